"""Benchmark: the engine's exact isosurface against VTK's own route to one, vtkTessellatorFilter
(ParaView's Tessellate: chord error, subdivision levels) followed by vtkContourFilter, on the
default dataset (Data/twisted_tube.vtu, 8 tri-quadratic rational patches, temperature = 0) as
`igaview render` frames it, or zoomed in by --zoom.

Times: the engine's frame (vtkIGAIsosurfaceImage, all hardware threads, the median of five
camera positions a few degrees apart) against the tessellation and the contour (VTK's filters
run on one thread), at each level asked.

Accuracy: every pixel's centre ray is cast at the contour's triangles (vtkCellLocator, in double
precision: what a rasteriser shows, without its depth buffer's rounding) and its nearest
hit set against the engine's exact hit on the same ray: the distance from the triangle's hit to
the exact surface's tangent plane there, in pixels at that depth. Reported: the pixels covered by
the contour, the share of them within half a pixel of the exact surface (a pixel the exact
surface does not cover counts as not within), and the pixels only one of the two covers.

Usage: PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 bench-tessellate-contour.py \
           DATA_DIR [--size N] [--zoom Z] [--levels L ...] [--chord-error E] [--json FILE]
Prints a table on stderr and one JSON document on stdout (or FILE). No X server needed."""
import argparse
import json
import math
import os
import statistics
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import reference
from vtkmodules.vtkCommonDataModel import vtkCellLocator
from vtkmodules.vtkFiltersCore import vtkContourFilter
from vtkmodules.vtkFiltersGeneral import vtkTessellatorFilter
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.vtkRenderingCore import vtkCamera

from igaview import vtkIGAIsosurfaceImage

ARRAY, ISOVALUE = "temperature", 0.0
# igaview render's default view: from the front right and above, z up, 30 degrees.
DIRECTION, VIEW_UP, VIEW_ANGLE = (-0.55, 0.65, -0.5), (0.0, 0.0, 1.0), 30.0


def framing_camera(bounds, zoom, azimuth=0.0):
    """A camera looking along DIRECTION (turned by `azimuth` degrees about z) at the bounds'
    centre, their bounding sphere just inside the view angle as vtkRenderer::ResetCamera frames
    it, then zoomed by `zoom` as vtkCamera::Zoom does (the view angle narrowed)."""
    centre = [(bounds[2 * a] + bounds[2 * a + 1]) / 2 for a in range(3)]
    radius = 0.5 * math.sqrt(sum((bounds[2 * a + 1] - bounds[2 * a]) ** 2 for a in range(3)))
    distance = radius / math.sin(math.radians(VIEW_ANGLE / 2))
    turn = math.radians(azimuth)
    d = (DIRECTION[0] * math.cos(turn) - DIRECTION[1] * math.sin(turn),
         DIRECTION[0] * math.sin(turn) + DIRECTION[1] * math.cos(turn), DIRECTION[2])
    length = math.sqrt(sum(c * c for c in d))
    camera = vtkCamera()
    camera.SetFocalPoint(centre)
    camera.SetPosition([centre[a] - distance * d[a] / length for a in range(3)])
    camera.SetViewUp(VIEW_UP)
    camera.SetViewAngle(VIEW_ANGLE)
    camera.Zoom(zoom)
    camera.SetClippingRange(0.5 * (distance - radius), distance + 2 * radius)
    return camera


def exact_frames(grid, size, zoom):
    """The engine's first hits at the default view (point arrays of vtkIGAIsosurfaceImage) and
    its frame times (ms) over five views a few degrees apart, the default last."""
    image = vtkIGAIsosurfaceImage()
    image.SetInputData(grid)
    image.SetImageSize(size, size)
    mapper = image.GetMapper()
    mapper.SetSurfaceArrayName(ARRAY)
    mapper.SetNumberOfIsovalues(1)
    mapper.SetIsovalue(0, ISOVALUE)
    bounds = grid.GetBounds()
    engine, whole = [], []
    for azimuth in (4.0, -4.0, 2.0, -2.0, 0.0):
        image.SetCamera(framing_camera(bounds, zoom, azimuth))
        start = time.perf_counter()
        image.Update()
        whole.append(1000 * (time.perf_counter() - start))
        engine.append(mapper.GetLastEngineTime())
    data = image.GetOutput().GetPointData()
    hits = {name: vtk_to_numpy(data.GetArray(name)) for name in ("Depth", "Position", "Normal")}
    return hits, engine, whole


def pixel_rays(camera, size, points):
    """The centre ray of each pixel that may see `points` (their projections' bounding box, the
    triangles lying in front of the eye) as two points: the eye and one beyond the far plane."""
    eye = np.array(camera.GetPosition())
    forward = np.array(camera.GetDirectionOfProjection())
    up = np.array(camera.GetViewUp())
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half = math.tan(math.radians(camera.GetViewAngle() / 2))
    far = camera.GetClippingRange()[1] * 2
    relative = points - eye
    depth = relative @ forward
    pixel = lambda along: (along / (depth * half) + 1) * size / 2 - 0.5
    columns, rows = pixel(relative @ right), pixel(relative @ up)
    first = [max(0, int(math.floor(c.min()))) for c in (columns, rows)]
    last = [min(size - 1, int(math.ceil(c.max()))) for c in (columns, rows)]
    for j in range(first[1], last[1] + 1):
        for i in range(first[0], last[0] + 1):
            x = (2 * (i + 0.5) / size - 1) * half
            y = (2 * (j + 0.5) / size - 1) * half
            yield j * size + i, eye, eye + far * (forward + x * right + y * up)


def contour_hits(surface, camera, size):
    """The nearest hit of every pixel's centre ray on the triangles (NaN where none)."""
    locator = vtkCellLocator()
    locator.SetDataSet(surface)
    locator.BuildLocator()
    found = np.full((size * size, 3), np.nan)
    t, hit, pcoords, sub = reference(0.0), [0.0] * 3, [0.0] * 3, reference(0)
    corners = vtk_to_numpy(surface.GetPoints().GetData()).astype(float)
    for pixel, start, end in pixel_rays(camera, size, corners):
        if locator.IntersectWithLine(tuple(start), tuple(end), 1e-12, t, hit, pcoords, sub):
            found[pixel] = hit
    return found


def accuracy(hits, exact, camera, size):
    """Pixels the contour covers, the share within half a pixel of the exact surface, the
    pixels only one covers and the largest distance (pixels) where both cover."""
    covered = ~np.isnan(hits[:, 0])
    exact_covered = ~np.isnan(exact["Depth"])
    both = covered & exact_covered
    pixel_size = 2 * exact["Depth"][both] * math.tan(math.radians(camera.GetViewAngle() / 2)) / size
    offset = np.abs(np.sum((hits[both] - exact["Position"][both]) * exact["Normal"][both], axis=1))
    distance = offset / pixel_size
    within = int(np.count_nonzero(distance <= 0.5))
    return {
        "contourPixels": int(np.count_nonzero(covered)),
        "exactPixels": int(np.count_nonzero(exact_covered)),
        "withinHalfPixel": within / max(1, int(np.count_nonzero(covered))),
        "contourOnlyPixels": int(np.count_nonzero(covered & ~exact_covered)),
        "exactOnlyPixels": int(np.count_nonzero(exact_covered & ~covered)),
        "largestDistancePixels": float(distance.max()) if distance.size else 0.0,
        "meanDistancePixels": float(distance.mean()) if distance.size else 0.0,
    }


def tessellated_contour(grid, level, chord_error):
    """Tessellate (chord error, `level` subdivisions) then Contour, with each one's time (ms)."""
    tessellate = vtkTessellatorFilter()
    tessellate.SetInputData(grid)
    tessellate.SetChordError(chord_error)
    tessellate.SetMaximumNumberOfSubdivisions(level)
    tessellate.SetOutputDimension(3)
    contour = vtkContourFilter()
    contour.SetInputConnection(tessellate.GetOutputPort())
    contour.SetInputArrayToProcess(0, 0, 0, 0, ARRAY)
    contour.SetValue(0, ISOVALUE)
    start = time.perf_counter()
    tessellate.Update()
    tessellated = time.perf_counter()
    contour.Update()
    contoured = time.perf_counter()
    return (contour.GetOutput(), tessellate.GetOutput().GetNumberOfCells(),
            1000 * (tessellated - start), 1000 * (contoured - tessellated))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("data_dir")
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--levels", type=int, nargs="+", default=[3, 4, 5])
    parser.add_argument("--chord-error", type=float, default=1e-3)
    parser.add_argument("--zoom", type=float, default=1.0)
    parser.add_argument("--json")
    args = parser.parse_args()
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(args.data_dir, "twisted_tube.vtu"))
    reader.Update()
    grid = reader.GetOutput()
    exact, engine, whole = exact_frames(grid, args.size, args.zoom)
    camera = framing_camera(grid.GetBounds(), args.zoom)
    result = {
        "dataset": "twisted_tube.vtu", "array": ARRAY, "isovalue": ISOVALUE,
        "width": args.size, "height": args.size, "zoom": args.zoom,
        "chordError": args.chord_error,
        "engineMs": statistics.median(engine), "engineFramesMs": engine,
        "imageFilterMs": statistics.median(whole), "levels": [],
    }
    print(f"engine: {result['engineMs']:.1f} ms a frame (vtkIGAIsosurfaceImage "
          f"{result['imageFilterMs']:.1f} ms), {int(np.count_nonzero(~np.isnan(exact['Depth'])))}"
          " pixels", file=sys.stderr)
    for level in args.levels:
        surface, cells, tessellate_ms, contour_ms = tessellated_contour(
            grid, level, args.chord_error)
        entry = {"level": level, "tessellatedCells": cells,
                 "triangles": surface.GetNumberOfCells(),
                 "tessellateMs": tessellate_ms, "contourMs": contour_ms,
                 "overEngine": (tessellate_ms + contour_ms) / result["engineMs"]}
        entry.update(accuracy(contour_hits(surface, camera, args.size), exact, camera, args.size))
        result["levels"].append(entry)
        print(f"level {level}: {cells} cells, {entry['triangles']} triangles, tessellate "
              f"{tessellate_ms:.0f} ms + contour {contour_ms:.0f} ms = "
              f"{entry['overEngine']:.0f}x the engine; {100 * entry['withinHalfPixel']:.1f}% of "
              f"{entry['contourPixels']} pixels within half a pixel (largest "
              f"{entry['largestDistancePixels']:.2f} px), {entry['contourOnlyPixels']} / "
              f"{entry['exactOnlyPixels']} pixels covered by the contour / the exact surface "
              "alone", file=sys.stderr)
    document = json.dumps(result, indent=1)
    if args.json:
        with open(args.json, "w") as out:
            out.write(document + "\n")
    else:
        print(document)


if __name__ == "__main__":
    main()
