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
