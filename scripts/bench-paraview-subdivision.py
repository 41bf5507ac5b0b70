"""pvpython benchmark: ParaView's own drawing of Bezier quadrilaterals at Nonlinear Subdivision
Level 4 (its maximum: each cell tessellated into 2^4 x 2^4 quads) against the exact surface of
the "IGA Surface" representation, on the bundled teapot at 512x512 and 1920x1080: frame times
(the first frame after a change, which includes ParaView's tessellation or the engine's frame,
and a redraw after a camera move) and how far ParaView's silhouette lies from the exact one
(pixels covered by one and not the other, and the largest distance of such a pixel from the
exact silhouette). One JSON document on stdout.

Usage: pvpython bench-paraview-subdivision.py PLUGIN DATA_DIR WORK_DIR"""
import json
import math
import os
import sys
import time

from paraview import simple

plugin, data_dir, work_dir = sys.argv[1:4]
os.makedirs(work_dir, exist_ok=True)
simple.LoadPlugin(plugin)
CAMERA = ([5.5, -9.0, 6.0], [0.2, 0.0, 1.2], [0.0, 0.0, 1.0])


def mask(view, size, name):
    """Which pixels the (white, unlit) surface covers on the black background."""
    from vtkmodules.vtkIOImage import vtkPNGReader

    shot = os.path.join(work_dir, name + ".png")
    simple.SaveScreenshot(shot, view, ImageResolution=size, TransparentBackground=0)
    reader = vtkPNGReader()
    reader.SetFileName(shot)
    reader.Update()
    scalars = reader.GetOutput().GetPointData().GetScalars()
    return [scalars.GetComponent(p, 0) > 127 for p in range(size[0] * size[1])]


def silhouette_error(exact, other, width, height):
    """Pixels that differ, and the largest distance (pixel centres) of one from the nearest pixel
    of the exact mask's other side."""
    differing = [p for p in range(width * height) if exact[p] != other[p]]
    edge = [p for p in range(width * height)
            if any(0 <= q < width * height and exact[q] != exact[p]
                   for q in (p - 1, p + 1, p - width, p + width))]
    farthest = 0.0
    for p in differing:
        i, j = p % width, p // width
        nearest = min((math.hypot(i - q % width, j - q // width) for q in edge
                       if exact[q] != exact[p]), default=0.0)
        farthest = max(farthest, nearest)
    return len(differing), farthest


def timed_render(view):
    start = time.perf_counter()
    simple.Render(view)
    return 1000 * (time.perf_counter() - start)


def measure(size):
    view = simple.CreateRenderView()
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0, 0, 0]
    view.EnableRenderOnInteraction = 0
    teapot = simple.XMLUnstructuredGridReader(FileName=[os.path.join(data_dir, "teapot.vtu")])
    display = simple.Show(teapot, view)
    simple.ColorBy(display, None)
    display.AmbientColor = display.DiffuseColor = [1, 1, 1]
    display.Ambient, display.Diffuse, display.Specular = 1.0, 0.0, 0.0
    simple.Render(view)
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = CAMERA
    view.CameraViewAngle = 30
    result = {"width": size[0], "height": size[1]}
    for kind in ("IGA Surface", "Surface"):
        display.SetRepresentationType(kind)
        if kind == "Surface":
            display.NonlinearSubdivisionLevel = 4
        first = timed_render(view)
        view.CameraPosition = [CAMERA[0][0] + 0.3, CAMERA[0][1], CAMERA[0][2]]
        moved = timed_render(view)
        view.CameraPosition = CAMERA[0]
        simple.Render(view)
        key = "exact" if kind == "IGA Surface" else "subdivision4"
        result[key] = {"firstFrameMs": first, "cameraMoveMs": moved,
                       "mask": mask(view, size, key + "-%dx%d" % tuple(size))}
    differing, farthest = silhouette_error(result["exact"]["mask"],
                                           result["subdivision4"]["mask"], *size)
    result["subdivision4"]["differingPixels"] = differing
    result["subdivision4"]["largestSilhouetteDistancePx"] = farthest
    result["exact"]["coveredPixels"] = sum(result["exact"].pop("mask"))
    result["subdivision4"]["coveredPixels"] = sum(result["subdivision4"].pop("mask"))
    simple.Delete(display)
    simple.Delete(teapot)
    simple.Delete(view)
    return result


print(json.dumps({"dataset": "teapot (32 bicubic Bezier quadrilaterals)",
                  "frames": [measure([512, 512]), measure([1920, 1080])]}, indent=2))
