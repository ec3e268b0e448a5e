"""Small helpers for CraterKit's pvbatch tests."""

import contextlib


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


def run_example(source_dir, name, args):
    """Runs examples/NAME.py in this interpreter with ARGS; returns its exit code."""
    import os
    import runpy
    import sys
    sys.argv = [name + ".py"] + list(args)
    try:
        runpy.run_path(os.path.join(source_dir, "examples", name + ".py"), run_name="__main__")
        return 0
    except SystemExit as stop:
        return stop.code or 0
