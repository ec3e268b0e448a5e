"""Reports written by the examples: report.json (machine-readable, full precision) and report.md
(for people: numbers rounded to what they mean, what the run is, and where validation stands)."""

import json
import os
import subprocess


def rounded(value, digits=3):
    """VALUE to DIGITS significant figures, without an exponent (0.8346110545424051 -> '0.835',
    1234.5 -> '1230'); other types unchanged."""
    if isinstance(value, bool) or not isinstance(value, float):
        return value
    import numpy as np
    return np.format_float_positional(value, precision=digits, unique=False, fractional=False, trim="-")


def to_resolution(value, resolution):
    """VALUE to the decimal place of RESOLUTION (a length measured on grains of radius 0.039 m is
    given to 0.01 m: 0.98931 -> '0.99'), the digits a measurement with that resolution can claim;
    other types and a non-positive resolution: as rounded() gives them."""
    import math
    if isinstance(value, bool) or not isinstance(value, float) or not resolution > 0.0:
        return rounded(value)
    decimals = max(0, -math.floor(math.log10(resolution)))
    return f"{value:.{decimals}f}"


def validation_summary(path):
    """The rows of the validation table (tests/slow/validate.py) at PATH as markdown, with the
    sentence that says when they were run; or a sentence saying that none has been run."""
    if not os.path.exists(path):
        return ("No validation case has been run on this machine yet (`scripts/test -L slow` runs them "
                "and writes results/validation.md; docs/validation.md holds the recorded results).\n")
    with open(path) as f:
        rows = [line for line in f if line.startswith("|")]
    dates = sorted({cells[7].strip() for cells in (r.strip().strip("|").split("|") for r in rows[2:])
                    if len(cells) > 7})
    when = f"run {dates[0]}" + (f" to {dates[-1]}" if len(dates) > 1 else "") if dates else "not dated"
    return f"Latest validation results ({when}; from {path}):\n\n" + "".join(rows)


def git_commit(root=None):
    """The commit of the CraterKit source tree at ROOT (default: the one this package is in), as
    `git rev-parse --short HEAD` gives it, with "-dirty" when tracked files have changes; None
    when the package is installed, ROOT is not the top of a git clone, or git is missing."""
    from . import SOURCE_ROOT
    root = root or SOURCE_ROOT
    if not root:
        return None

    # GIT_OPTIONAL_LOCKS=0: `git status` leaves the index alone (no lock a commit could meet).
    env = dict(os.environ, GIT_OPTIONAL_LOCKS="0")

    def git(*args):
        done = subprocess.run(["git", "-C", root, *args], capture_output=True, text=True, timeout=60,
                              env=env)
        if done.returncode != 0:
            raise OSError(done.stderr.strip())
        return done.stdout.strip()

    try:
        if os.path.realpath(git("rev-parse", "--show-toplevel")) != os.path.realpath(root):
            return None
        commit = git("rev-parse", "--short", "HEAD")
        return commit + ("-dirty" if git("status", "--porcelain", "--untracked-files=no") else "")
    except (OSError, subprocess.SubprocessError):
        return None


def write_report(output_dir, title, image, report, about="", validation="", resolution=None):
    """Writes report.json with every entry and report.md with ABOUT (what the run is), the picture,
    the scalar entries rounded to three significant figures, and VALIDATION. Both also say which
    CraterKit wrote them: report.json's "craterkit_version" and "git_commit" (after "example"),
    a line under report.md's title. RESOLUTION maps entries to the resolution of their
    measurement (a crater's lengths: the grain radius); report.md gives them to its decimal place."""
    from . import __version__
    commit = git_commit()
    stamped = {}
    if "example" in report:
        stamped["example"] = report["example"]
    stamped["craterkit_version"] = __version__
    stamped["git_commit"] = commit
    stamped.update((k, v) for k, v in report.items() if k not in stamped)
    with open(os.path.join(output_dir, "report.json"), "w") as f:
        json.dump(stamped, f, indent=2)
    with open(os.path.join(output_dir, "report.md"), "w") as f:
        f.write(f"# CraterKit: {title}\n\n")
        f.write(f"CraterKit {__version__}" + (f", commit {commit}" if commit else "") + "\n\n")
        if about:
            f.write(about.strip() + "\n\n")
        f.write(f"![{title}]({image})\n\n| quantity | value |\n|---|---|\n")
        for key, value in report.items():
            if not isinstance(value, (list, dict)):
                shown = to_resolution(value, (resolution or {}).get(key, 0.0))
                f.write(f"| {key} | {shown} |\n")
        if validation:
            f.write("\n## Validation\n\n" + validation.strip() + "\n")
