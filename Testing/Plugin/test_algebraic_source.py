"""pvpython: the "IGA Algebraic Surface" source delivers the exact Bernstein volume of a gallery
surface or of an expression over a box, the "IGA Isosurface" representation draws its f = 0 by
ray composition (the mapper says which path its patches took), the same pixels as the shared
subdivision tree and every root finder, a bad expression is one error naming its position (and
a good one draws again), ParaView takes the field's range (not the control values'), the IGA
Probe Line filter finds a segment's exact hits, colouring by curvature_mean colours the sphere by
its 1/r, and the representation's Antialiasing blends the silhouette's pixels with the background
in quarters.

Usage: pvpython test_algebraic_source.py PLUGIN WORK_DIR"""
import os
import sys
import builtins

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import servermanager, simple  # noqa: E402
from vtkmodules.util.misc import calldata_type  # noqa: E402
from vtkmodules.util.vtkConstants import VTK_STRING  # noqa: E402
from vtkmodules.vtkCommonCore import vtkOutputWindow  # noqa: E402

import iga_scene  # noqa: E402

errors = []


@calldata_type(VTK_STRING)
def on_error(obj, event, text):
    errors.append(text)


vtkOutputWindow.GetInstance().AddObserver("ErrorEvent", on_error)

plugin, work_dir = sys.argv[1:3]
os.makedirs(work_dir, exist_ok=True)
simple.LoadPlugin(plugin, ns=globals())

source = IGAAlgebraicSurface()  # noqa: F821 (defined by LoadPlugin from the proxy label)
source.GallerySurface = "kummer"
simple.UpdatePipeline(proxy=source)
grid = servermanager.Fetch(source)
assert grid.GetNumberOfCells() == 1, grid.GetNumberOfCells()
assert grid.GetNumberOfPoints() == 125, grid.GetNumberOfPoints()  # degree 4 per direction
assert grid.GetPointData().GetArray("f") is not None
assert all(abs(b - e) < 1e-12 for b, e in zip(grid.GetBounds(), [-2.5, 2.5] * 3)), grid.GetBounds()

# An ABS field of the same surface: the elements the surface crosses, 64 points each (cubic).
source.SplineCells = 12
simple.UpdatePipeline(proxy=source)
abs_grid = servermanager.Fetch(source)
assert 100 < abs_grid.GetNumberOfCells() < 12 ** 3, abs_grid.GetNumberOfCells()
assert abs_grid.GetNumberOfPoints() == 64 * abs_grid.GetNumberOfCells()
source.SplineCells = 0

# Ranges are the field's, not its control values': the sphere's f = r^2 - 1 over [-1.2, 1.2]^3
# takes -1 .. 3.32 (its control values reach -5.32). ParaView's data information, a colour map
# rescaled to the data and the IGA Isosurface's default isovalue (the middle) all take it.
source.GallerySurface = "sphere"
simple.UpdatePipeline(proxy=source)
f_range = source.PointData["f"].GetRange()
assert abs(f_range[0] + 1) < 1e-4 and abs(f_range[1] - 3.32) < 1e-4, f_range
range_view = simple.CreateRenderView()
range_display = simple.Show(source, range_view)
simple.ColorBy(range_display, ("POINTS", "f"))
range_display.RescaleTransferFunctionToDataRange(False, True)
lut_points = simple.GetColorTransferFunction("f").RGBPoints
assert abs(lut_points[0] + 1) < 1e-4 and abs(lut_points[-4] - 3.32) < 1e-4, lut_points
range_display.SetRepresentationType("IGA Isosurface")
assert abs(range_display.IGAIsovalues[0] - 1.16) < 1e-4, range_display.IGAIsovalues
simple.Delete(range_display)
simple.Delete(range_view)

# IGA Probe Line: its defaults come from the data (the field's middle 1.16, the bounds' corners);
# the segment y = 0.3, z = 0.1 meets f = 0 at x = -+sqrt(0.9), where f is 0.
probe = IGAProbeLine(Input=source)  # noqa: F821 (defined by LoadPlugin)
assert list(probe.SurfaceArray) == ["POINTS", "f"], probe.SurfaceArray
assert abs(probe.Isovalue - 1.16) < 1e-4 and list(probe.Point2) == [1.2, 1.2, 1.2]
probe.Isovalue = 0.0
probe.Point1 = [-2.0, 0.3, 0.1]
probe.Point2 = [2.0, 0.3, 0.1]
probe.UpdatePipeline()
probed = servermanager.Fetch(probe)
assert probed.GetNumberOfPoints() == 2, probed.GetNumberOfPoints()
for k, sign in enumerate((-1, 1)):
    hit = probed.GetPoint(k)
    assert abs(hit[0] - sign * 0.9 ** 0.5) < 1e-12 and abs(hit[1] - 0.3) < 1e-12, hit
    assert abs(probed.GetPointData().GetArray("f").GetValue(k)) < 1e-12
simple.Delete(probe)
source.GallerySurface = "kummer"

view = iga_scene.make_view()
display = iga_scene.show_surface(source, view, "f", 0.0)
iga_scene.place_camera(view, ([-8.0, -10.0, 6.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]))


def paths():
    """(patches drawn by ray composition, by the SST) in the last frame, as the panel says."""
    display.UpdatePropertyInformation()
    return (display.GetProperty("IGALastRayCompositionPatches").GetElement(0),
            display.GetProperty("IGALastSstPatches").GetElement(0))



def covered():
    """The pixels of the view that show the surface."""
    simple.Render(view)
    shot = os.path.join(work_dir, "algebraic.png")
    simple.SaveScreenshot(shot, view, ImageResolution=iga_scene.SIZE, TransparentBackground=0)
    (width, height), pixel = iga_scene.read_rgb(shot)
    background = tuple(round(255 * c) for c in iga_scene.BACKGROUND)
    return {(i, j) for j in range(height) for i in range(width) if pixel(i, j) != background}


composed = covered()
assert paths() == (1, 0), paths()
assert len(composed) > 8000, len(composed)
display.IGAMethod = "Shared Subdivision Tree"
tree = covered()
assert paths() == (0, 1), paths()
# Silhouette pixels may differ where a ray grazes the surface.
assert len(composed ^ tree) <= len(composed) // 100, (len(composed), len(composed ^ tree))
display.IGAMethod = "Automatic"
for finder in display.GetProperty("IGARootFinder").Available:
    display.IGARootFinder = finder
    other = covered()
    assert len(composed ^ other) <= len(composed) // 200, (finder, len(composed ^ other))
display.IGARootFinder = "Bezier Point Insertion (Wei-Feng)"

# Frame coherency: the camera turned by a degree, seeded by the frame before, covers the same
# pixels as the cold frame of that camera.
camera = view.GetActiveCamera()
camera.Azimuth(1)
turned = covered()
camera.Azimuth(-1)
display.IGAFrameCoherency = 1
covered()
camera.Azimuth(1)
assert covered() == turned, len(turned ^ covered())
display.UpdatePropertyInformation()
seeded = display.GetProperty("IGALastSeededRays").GetElement(0)
assert seeded > len(turned) // 2, (seeded, len(turned))
display.IGAFrameCoherency = 0
camera.Azimuth(-1)

source.GallerySurface = "Expression over Box"
source.Expression = "x^2 + y^2 - z^2 - 0.1"
source.Box = [-1, 1, -1, 1, -1, 1]
iga_scene.place_camera(view, ([-3.0, -4.0, 2.5], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]))
cone = covered()
assert paths() == (1, 0), paths()
assert len(cone) > 8000, len(cone)

assert not errors, errors
source.Expression = "x + w^2"
simple.Render(view)
named = [e for e in errors if "expression, position 5: unknown variable 'w'" in e]
assert len(named) == 1, errors
print(f"algebraic source: kummer {len(composed)} pixels covered, the tree {len(tree)}, "
      f"the cone {len(cone)}")

# After the refused expression a good one draws again. Colour by the isosurface's curvature (not
# an array of the data: the mapper computes it at the hits): the unit sphere is mean 1 everywhere, so with a colour map from 0 (blue)
# to 2 (red) every surface pixel shows the map's middle.
source.Expression = "x^2 + y^2 + z^2 - 1"
source.Box = [-1.2, 1.2, -1.2, 1.2, -1.2, 1.2]
simple.UpdatePipeline(proxy=source)
display.ColorArrayName = ["POINTS", "curvature_mean"]
lut = simple.GetColorTransferFunction("curvature_mean")
lut.AutomaticRescaleRangeMode = "Never"
lut.RGBPoints = [0.0, 0.0, 0.0, 1.0, 2.0, 1.0, 0.0, 0.0]
lut.ColorSpace = "RGB"
display.LookupTable = lut
display.Ambient, display.Diffuse, display.Specular = 1.0, 0.0, 0.0
iga_scene.place_camera(view, ([0.0, -5.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]))
simple.Render(view)
shot = os.path.join(work_dir, "curvature.png")
simple.SaveScreenshot(shot, view, ImageResolution=iga_scene.SIZE, TransparentBackground=0)
(width, height), pixel = iga_scene.read_rgb(shot)
centre = pixel(width // 2, height // 2)
assert abs(centre[0] - centre[2]) < 12 and centre[0] > 90, centre
print(f"curvature colour at the sphere's centre: {centre}")

# Antialiasing: unlit in one colour, every pixel is the background, the surface's colour, or a
# blend of the two in quarters (four samples a silhouette pixel); without it, no blend (with
# ParaView's own screen-space FXAA, on by default, off).
def blends(path):
    (width, height), pixel = iga_scene.read_rgb(path)
    background = [round(255 * c) for c in iga_scene.BACKGROUND]
    channel = max(range(3), key=lambda c: abs(centre[c] - background[c]))
    quarters = 0
    for j in range(height):
        for i in range(width):
            p = pixel(i, j)
            alpha = (p[channel] - background[channel]) / (centre[channel] - background[channel])
            expected = [alpha * centre[c] + (1 - alpha) * background[c] for c in range(3)]
            assert all(abs(p[c] - expected[c]) <= 3 for c in range(3)), (i, j, p, alpha)
            assert abs(4 * alpha - round(4 * alpha)) < 0.1, (i, j, p, alpha)
            quarters += 0.1 < alpha < 0.9
    return quarters


view.UseFXAA = 0
simple.Render(view)
simple.SaveScreenshot(shot, view, ImageResolution=iga_scene.SIZE, TransparentBackground=0)
assert blends(shot) == 0
display.IGAAntialiasing = 1
simple.Render(view)
smooth = os.path.join(work_dir, "antialiased.png")
simple.SaveScreenshot(smooth, view, ImageResolution=iga_scene.SIZE, TransparentBackground=0)
display.UpdatePropertyInformation()
antialiased = display.GetProperty("IGALastAntialiasedPixels").GetElement(0)
blended = blends(smooth)
assert blended > 100 and antialiased > blended, (blended, antialiased)
print(f"antialiasing: {antialiased} pixels supersampled, {blended} blended with the background")
assert errors == named, errors  # the refused expression's error alone
