"""vtkIGAIsosurfaceProbeLine from Python, with no X server: a segment's hits on an isosurface,
solved exactly, against the analytic sphere (the gallery's f = r^2 - 1 = 0, and the rational
Marsden sphere's), nearest first, with their distances, normals facing the segment's start and
attributes evaluated at the hits; MaximumHits; a segment that misses; a segment of no length; the
probe's frame written as a deep OpenEXR file by the mapper.

Usage: python3 test_probe_line.py DATA_DIR WORK_DIR"""
import math
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

from igaview import vtkIGAAlgebraicSource, vtkIGAIsosurfaceMapper, vtkIGAIsosurfaceProbeLine

data, work_dir = sys.argv[1:3]
os.makedirs(work_dir, exist_ok=True)


def probe(producer, array, start, end, hits=16):
    line = vtkIGAIsosurfaceProbeLine()
    line.SetInputConnection(producer.GetOutputPort())
    line.SetSurfaceArrayName(array)
    line.SetIsovalue(0.0)
    line.SetPoint1(start)
    line.SetPoint2(end)
    line.SetMaximumHits(hits)
    line.Update()
    return line.GetOutput()


def column(output, name):
    return vtk_to_numpy(output.GetPointData().GetArray(name))


# The gallery sphere: the line y = 0.3, z = 0.1 meets it at x = -+sqrt(0.9).
sphere = vtkIGAAlgebraicSource()
sphere.SetGallerySurfaceByName("sphere")
start, end = np.array([-2.0, 0.3, 0.1]), np.array([2.0, 0.3, 0.1])
out = probe(sphere, "f", start, end)
assert out.GetNumberOfPoints() == 2, out.GetNumberOfPoints()
x = math.sqrt(0.9)
points = vtk_to_numpy(out.GetPoints().GetData())
assert np.allclose(points, [[-x, 0.3, 0.1], [x, 0.3, 0.1]], atol=1e-12), points
assert np.allclose(column(out, "Distance"), [2 - x, 2 + x], atol=1e-12), column(out, "Distance")
assert np.all(np.abs(column(out, "f")) < 1e-12), column(out, "f")
normals = column(out, "Normal")
assert np.allclose(np.linalg.norm(normals, axis=1), 1, atol=1e-12)
assert np.all(normals @ (end - start) < 0), normals  # facing the segment's start
assert list(column(out, "Cell")) == [0, 0]
assert probe(sphere, "f", start, end, hits=1).GetNumberOfPoints() == 1
assert probe(sphere, "f", [-2.0, 1.1, 0.0], [2.0, 1.1, 0.0]).GetNumberOfPoints() == 0

# The rational Marsden sphere (degree 3): its hits lie on the unit sphere.
reader = vtkXMLUnstructuredGridReader()
reader.SetFileName(os.path.join(data, "marsden_sphere_p3.vtu"))
out = probe(reader, "sphere", [0.2, -3.0, 0.4], [0.2, 3.0, 0.4])
points = vtk_to_numpy(out.GetPoints().GetData())
assert out.GetNumberOfPoints() == 2, out.GetNumberOfPoints()
assert np.allclose(np.linalg.norm(points, axis=1), 1, atol=1e-9), points
assert np.all(np.abs(column(out, "sphere")) < 1e-9), column(out, "sphere")

# A segment of no length is refused with an error, and nothing is put out.
errors = []
line = vtkIGAIsosurfaceProbeLine()
line.SetInputConnection(sphere.GetOutputPort())
line.SetPoint1(0, 0, 0)
line.SetPoint2(0, 0, 0)
line.AddObserver("ErrorEvent", lambda obj, event: errors.append(event))
line.Update()
assert errors and line.GetOutput().GetNumberOfPoints() == 0, errors
# The probe's frame (one pixel, its two hits) as a deep OpenEXR file through the mapper; a mapper
# with no frame refuses.
line = vtkIGAIsosurfaceProbeLine()
line.SetInputConnection(sphere.GetOutputPort())
line.SetSurfaceArrayName("f")
line.SetIsovalue(0.0)
line.SetPoint1(start)
line.SetPoint2(end)
line.Update()
deep = os.path.join(work_dir, "probe-deep.exr")
assert line.GetMapper().WriteDeepEXR(deep)
with open(deep, "rb") as f:
    head = f.read(4096)
assert head[:4] == b"\x76\x2f\x31\x01" and b"deepscanline" in head, head[:64]
assert not vtkIGAIsosurfaceMapper().WriteDeepEXR(os.path.join(work_dir, "none.exr"))
print("probe line: sphere hits at -+%.12f, Marsden sphere hits on r = 1" % x)
