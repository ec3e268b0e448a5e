"""Small helpers for CraterKit's pvbatch tests."""

import contextlib
import subprocess
import time


class Checker:
    """Collects failed checks so that one run reports all of them; exit code 1 if any."""

    def __init__(self, name):
        self.name = name
        self.failures = []
        self.passed = 0

    def check(self, condition, message):
        if condition:
            self.passed += 1
        else:
            self.failures.append(message)
            print(f"FAIL: {message}", flush=True)

    def close(self):
        print(f"{self.name}: {self.passed} passed, {len(self.failures)} failed", flush=True)
        return 1 if self.failures else 0


def timed_run(args, **kwargs):
    """Runs ARGS, capturing its output as text, and prints the command with its seconds and exit
    status; returns the CompletedProcess (keyword arguments go to subprocess.run)."""
    start = time.time()
    done = subprocess.run(args, capture_output=True, text=True, **kwargs)
    print(f"$ {' '.join(args)}  ({time.time() - start:.1f} s, exit {done.returncode})", flush=True)
    return done


def check_tree_paths(check, top, build_dir, source_dir, shown=lambda rel: rel):
    """Checks, with CHECK, that nothing below TOP (an install prefix or an unpacked package)
    points into the build or source tree: every ELF has RUNPATH $ORIGIN alone, no file holds the
    build folder's path and no text file names the source tree (SHOWN turns a path relative to
    TOP into the one the messages give). Returns the number of ELF files."""
    import os
    elf = 0
    for folder, _, files in os.walk(top):
        for name in files:
            path = os.path.join(folder, name)
            if os.path.islink(path):
                continue
            data = open(path, "rb").read()
            rel = shown(os.path.relpath(path, top))
            check(build_dir.encode() not in data, f"{rel} holds the build folder's path {build_dir}")
            if data[:4] == b"\x7fELF":
                elf += 1
                dyn = timed_run(["readelf", "-d", path]).stdout
                runpaths = [line.split("[", 1)[1].rstrip("]") for line in dyn.splitlines()
                            if "(RUNPATH)" in line or "(RPATH)" in line]
                check(runpaths == ["$ORIGIN"], f"{rel}: RUNPATH {runpaths}, not [$ORIGIN]")
            elif data[:8] != b"!<arch>\n":
                check(source_dir.encode() not in data, f"{rel} names the source tree {source_dir}")
    return elf


@contextlib.contextmanager
def captured_vtk_messages():
    """Captures VTK error and warning text (pvbatch routes print() through the same window,
    so nothing printed inside the block is shown)."""
    from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
    original = vtkOutputWindow.GetInstance()
    original.Register(None)
    window = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(window)
    box = {"text": ""}
    try:
        yield box
    finally:
        box["text"] = window.GetOutput()
        vtkOutputWindow.SetInstance(original)
        original.UnRegister(None)


def run_script(path, args, capture=False):
    """Runs the Python script at PATH in this interpreter with ARGS as its command line; returns
    (exit code, stdout, stderr), the two texts empty unless `capture`."""
    import contextlib
    import io
    import runpy
    import sys
    sys.argv = [path] + list(args)
    out, err = io.StringIO(), io.StringIO()
    code = 0
    with contextlib.ExitStack() as stack:
        if capture:
            stack.enter_context(contextlib.redirect_stdout(out))
            stack.enter_context(contextlib.redirect_stderr(err))
        try:
            runpy.run_path(path, run_name="__main__")
        except SystemExit as stop:
            code = stop.code or 0
    return code, out.getvalue(), err.getvalue()


def run_example(source_dir, name, args):
    """Runs examples/NAME.py in this interpreter with ARGS; returns its exit code."""
    import os
    return run_script(os.path.join(source_dir, "examples", name + ".py"), args)[0]
