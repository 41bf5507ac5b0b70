"""The scene shared by the plugin's image tests: the bundled twisted tube's temperature = 0
sheet drawn by the "IGA Isosurface" representation, coloured by radius, with a fixed camera.
Serial (pvpython) and MPI (pvbatch) runs compare against the same baseline image."""
import os

from paraview import simple

SIZE = [300, 240]
BACKGROUND = [0.1, 0.1, 0.15]
BASELINE = "PluginIsosurfaceTemperature"


def make_view():
    view = simple.CreateRenderView()
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = BACKGROUND
    return view


CAMERA = ([2.4, -3.0, 2.6], [0.2, 0.0, 1.0], [0.0, 0.0, 1.0])


def place_camera(view, camera=CAMERA):
    """camera: (position, focal point, view up)."""
    # After a first render, which would otherwise reset the camera to the data's bounds.
    simple.Render(view)
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = camera
    view.CameraViewAngle = 30


def show_surface(source, view, array, isovalue):
    """source drawn by the "IGA Isosurface" representation: point array `array` = isovalue."""
    display = simple.Show(source, view)
    display.SetRepresentationType("IGA Isosurface")
    display.IGASurfaceArray = ["POINTS", array]
    display.IGAIsovalues = [isovalue]
    return display


def show_isosurface(source, view, camera=CAMERA):
    display = show_surface(source, view, "temperature", 0.0)
    display.Specular = 0.3
    display.SpecularPower = 30.0
    simple.ColorBy(display, ("POINTS", "radius"))
    lut = simple.GetColorTransferFunction("radius")
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(0.5, 1.0)
    place_camera(view, camera)
    return display


def check_image(view, baseline_dir, name, work_dir):
    """Saves the view and compares it with `name`.png under baseline_dir (VTK's regression
    image difference, threshold 10), or writes the baseline when IGAVIEW_WRITE_BASELINES is
    set. Returns (path of the screenshot, image difference)."""
    shot = os.path.join(work_dir, name + ".png")
    simple.SaveScreenshot(shot, view, ImageResolution=SIZE, TransparentBackground=0)
    baseline = os.path.join(baseline_dir, name + ".png")
    if os.environ.get("IGAVIEW_WRITE_BASELINES"):
        simple.SaveScreenshot(baseline, view, ImageResolution=SIZE, TransparentBackground=0)
        print("wrote", baseline)
        return shot, 0.0
    return shot, compare_images(shot, baseline, work_dir)


def compare_images(test_png, valid_png, work_dir):
    """VTK's regression comparison of two PNG files; raises when they differ."""
    from vtkmodules.vtkTestingRendering import vtkTesting

    testing = vtkTesting()
    for arg in ("-V", valid_png, "-T", work_dir):
        testing.AddArgument(arg)
    result = testing.RegressionTest(test_png, 10)
    difference = testing.GetImageDifference()
    assert result == vtkTesting.PASSED, f"{test_png} differs from {valid_png}: {difference}"
    return difference


def read_rgb(png):
    """The PNG's pixels as {(i, j): (r, g, b)} accessor, row 0 at the bottom (VTK's order)."""
    from vtkmodules.vtkIOImage import vtkPNGReader

    reader = vtkPNGReader()
    reader.SetFileName(png)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    width = image.GetDimensions()[0]

    def pixel(i, j):
        return tuple(int(scalars.GetComponent(j * width + i, c)) for c in range(3))

    return image.GetDimensions()[:2], pixel
