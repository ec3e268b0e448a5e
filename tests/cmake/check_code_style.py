#!/usr/bin/env python3
"""Fails on code that departs from the project's style: a C++ file that clang-format
(.clang-format at the root) would change, a line over 100 columns (characters, not bytes), or a
Solvers/ include not written from Solvers/ ("dem/DemSolver.h", never "../dem/DemSolver.h" or a
bare "DemSolver.h" of another folder).

    check_code_style.py SOURCE_DIR [CLANG_FORMAT]
"""

import glob
import os
import re
import subprocess
import sys

PATTERNS = ["Solvers/**/*.h", "Solvers/**/*.cpp", "Filters/*.h", "Filters/*.cxx", "Readers/*.h",
            "Readers/*.cxx", "Bridge/*.h", "tests/unit/*.cpp", "tests/fuzz/*.cpp", "benchmarks/**/*.cpp"]


def main(root, clang_format=None):
    files = sorted({f for p in PATTERNS for f in glob.glob(os.path.join(root, p), recursive=True)})
    if not files:
        print(f"no sources found under {root}")
        return 1
    problems = []
    for path in files:
        rel = os.path.relpath(path, root)
        with open(path, encoding="utf-8") as f:
            for n, line in enumerate(f, 1):
                width = len(line.rstrip("\n"))
                if width > 100:
                    problems.append(f"{rel}:{n}: {width} columns (at most 100)")
                m = re.match(r'\s*#\s*include\s*"([^"]+)"', line)
                if m and rel.startswith("Solvers/") and "/" not in m.group(1):
                    problems.append(f"{rel}:{n}: include \"{m.group(1)}\" as \"folder/Name.h\" (from Solvers/)")
                elif m and m.group(1).startswith("../"):
                    problems.append(f"{rel}:{n}: include \"{m.group(1)}\" from Solvers/, not ../")
    if clang_format:
        p = subprocess.run([clang_format, "--dry-run", "--Werror", "--style=file"] + files, cwd=root,
                           capture_output=True, text=True)
        if p.returncode != 0:
            changed = sorted(set(re.findall(r"^(\S+?):\d+:\d+: (?:warning|error)", p.stderr, re.M)))
            problems.append("clang-format would change (run clang-format -i on them): " + " ".join(
                os.path.relpath(c, root) if os.path.isabs(c) else c for c in changed))
    for p in problems:
        print(p)
    print(f"{len(files)} files checked: {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 and sys.argv[2] else None))
