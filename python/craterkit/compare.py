"""Image comparison for render tests (vtkImageDifference, as VTK's regression tests)."""


def image_difference(test_png, baseline_png):
    """Thresholded error between two PNGs (0 for identical; VTK's usual limit is ~10)."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.vtkImagingCore import vtkImageDifference
    readers = []
    for path in (test_png, baseline_png):
        reader = vtkPNGReader()
        reader.SetFileName(path)
        reader.Update()
        readers.append(reader)
    a, b = (r.GetOutput().GetDimensions() for r in readers)
    if a != b:
        raise AssertionError(f"image sizes differ: {test_png} {a} vs {baseline_png} {b}")
    diff = vtkImageDifference()
    diff.SetInputConnection(readers[0].GetOutputPort())
    diff.SetImageConnection(readers[1].GetOutputPort())
    diff.Update()
    return diff.GetThresholdedError()
