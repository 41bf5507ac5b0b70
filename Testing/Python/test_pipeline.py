"""IGAView's wrapped classes in a plain VTK pipeline from Python: the G+Smo reader, the mapper in
a render window and the offscreen image filter on the same camera. The filter's image covers the
pixels the window shows, in the same colours; the mapper's probe gives the filter's arrays; the
reader's exact attribute x equals the hit's x."""
import math
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkFieldData
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow, vtkWindowToImageFilter
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)

from igaview import vtkIGAGismoReader, vtkIGAIsosurfaceImage, vtkIGAIsosurfaceMapper

data = sys.argv[1]
reader = vtkIGAGismoReader()
reader.SetFileName(os.path.join(data, "gismo_quarter_ring.xml"))

mapper = vtkIGAIsosurfaceMapper()
mapper.SetInputConnection(reader.GetOutputPort())
mapper.SetDrawModeToSurfaces()
mapper.SelectColorArray("z")
mapper.SetScalarModeToUsePointFieldData()
mapper.SetScalarRange(0, 1)
actor = vtkActor()
actor.SetMapper(mapper)
renderer = vtkRenderer()
renderer.AddActor(actor)
window = vtkRenderWindow()
window.SetOffScreenRendering(1)
window.SetMultiSamples(0)
window.AddRenderer(renderer)
width, height = 240, 180
window.SetSize(width, height)
renderer.GetActiveCamera().Elevation(35)
renderer.GetActiveCamera().Azimuth(20)
renderer.ResetCamera()
window.Render()
grab = vtkWindowToImageFilter()
grab.SetInput(window)
grab.SetInputBufferTypeToRGB()
grab.Update()
shown = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).astype(int)

image = vtkIGAIsosurfaceImage()
image.SetInputConnection(reader.GetOutputPort())
image.GetMapper().SetDrawModeToSurfaces()
image.GetMapper().SelectColorArray("z")
image.GetMapper().SetScalarModeToUsePointFieldData()
image.GetMapper().SetScalarRange(0, 1)
image.SetCamera(renderer.GetActiveCamera())
image.SetImageSize(width, height)
image.Update()
pixels = image.GetOutput().GetPointData()
hits = vtk_to_numpy(pixels.GetArray("HitCount"))
rgba = vtk_to_numpy(pixels.GetArray("RGBA")).astype(int)
covered = hits > 0
drawn = shown.sum(axis=1) > 0
print(f"covered {covered.sum()} pixels, the window shows {drawn.sum()}")
assert covered.sum() > 0.2 * width * height, covered.sum()
assert np.array_equal(covered, drawn), np.count_nonzero(covered != drawn)
colour_error = np.abs(rgba[covered, :3] - shown[covered]).max()
print(f"largest colour difference {colour_error} of 255")
assert colour_error <= 2, colour_error

position = vtk_to_numpy(pixels.GetArray("Position"))
uvw = vtk_to_numpy(pixels.GetArray("UVW"))
cells = vtk_to_numpy(pixels.GetArray("Cell"))
x = vtk_to_numpy(pixels.GetArray("x"))
assert np.abs(x[covered] - position[covered, 0]).max() < 1e-9
assert np.isnan(x[~covered]).all() and (cells[~covered] == -1).all()
probed = 0
for j in range(0, height, 7):
    for i in range(0, width, 7):
        p = j * width + i
        point, parameter, attributes = [0.0] * 3, [0.0] * 3, vtkFieldData()
        cell = mapper.ProbePixel(i, j, point, parameter, attributes)
        assert cell == cells[p], (i, j, cell, cells[p])
        if cell < 0:
            continue
        probed += 1
        assert np.allclose(point, position[p], rtol=0, atol=1e-12), (point, position[p])
        assert np.allclose(parameter, uvw[p], rtol=0, atol=1e-12), (parameter, uvw[p])
        assert abs(attributes.GetArray("x").GetValue(0) - x[p]) < 1e-12
        assert abs(attributes.GetArray("z").GetValue(0) - point[2]) < 1e-9
print(f"probed {probed} pixels")
assert probed > 100, probed

# The exact range of x over the ring, 0 .. the outer radius, next to the control points' bounds.
x_range = [0.0, 0.0]
assert mapper.GetAttributeRange("x", x_range)
bounds = reader.GetOutput().GetBounds()
print(f"x takes {x_range}, control points span {bounds[0:2]}")
assert abs(x_range[0] - bounds[0]) < 1e-12 and abs(x_range[1] - bounds[1]) < 1e-12, (x_range, bounds)
assert not mapper.GetAttributeRange("no such array", x_range)

# The hits behind the first: the ring's surfaces with every layer kept, two layers asked for.
image.GetMapper().AllLayersOn()
image.SetLayers(2)
image.Update()
pixels = image.GetOutput().GetPointData()
hits = vtk_to_numpy(pixels.GetArray("HitCount"))
depth = vtk_to_numpy(pixels.GetArray("Depth"))
depth_behind = vtk_to_numpy(pixels.GetArray("Depth_1"))
behind = hits >= 2
print(f"{behind.sum()} pixels with a hit behind the first")
assert behind.sum() > 0.1 * width * height, behind.sum()
assert (depth_behind[behind] >= depth[behind]).all()
assert np.isnan(depth_behind[hits < 2]).all()
assert pixels.GetArray("x_1") is not None and pixels.GetArray("Depth_2") is None
