"""vtkIGANurbsData from Python through its VTK-typed accessors: a reader's patches read back as
the file gives them (degrees, net sizes, knots, homogeneous control nets; the left-handed ring
not turned), the same patch rebuilt from those arrays gives the reader's Bézier cells value for
value, at a later step too, a trilinear cube built from numpy carries its field exactly
(f = x + 2y + 3z, range 0 .. 6), a second time step moves its cells, and bad input is refused
with a sentence naming the problem. No X server is needed.

Usage: python3 test_nurbs_data.py DATA_DIR"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkDataArrayCollection, vtkDoubleArray, vtkStringArray

from igaview import vtkIGAGismoReader, vtkIGANurbsData

data = sys.argv[1]
reader = vtkIGAGismoReader()
reader.SetFileName(os.path.join(data, "gismo_quarter_ring_solution.xml"))
reader.Update()
read = reader.GetNurbsData()
assert read.GetNumberOfPatches() == 1 and read.GetNumberOfTimeSteps() == 1
assert read.GetPatchDimension(0) == 3
degrees, size = [0, 0, 0], [0, 0, 0]
read.GetPatchDegrees(0, degrees)
read.GetPatchNetSize(0, size)
assert degrees == [2, 1, 1] and size == [3, 2, 2], (degrees, size)
knots = []
for direction in range(3):
    array = vtkDoubleArray()
    read.GetPatchKnots(0, direction, array)
    knots.append(array)
assert list(vtk_to_numpy(knots[0])) == [0, 0, 0, 1, 1, 1]
names = [read.GetAttributeName(i) for i in range(read.GetNumberOfAttributes())]
assert "temperature" in names, names
net = vtkDoubleArray()
read.GetPatchControlNet(0, 0, net)
assert net.GetNumberOfTuples() == 12 and net.GetNumberOfComponents() == 4 + len(names)

# The same patch rebuilt from the arrays: the same cells, value for value.
rebuilt = vtkIGANurbsData()
name_array = vtkStringArray()
for name in names:
    name_array.InsertNextValue(name)
assert rebuilt.SetAttributeNames(name_array) == ""
assert rebuilt.AddVolume(degrees, knots[0], knots[1], knots[2], net) == ""
# The ring is left-handed: read back as given, it is turned again when added, and so are nets
# of later steps.
assert read.IsVolumeReversed(0) and rebuilt.IsVolumeReversed(0)
nets = vtkDataArrayCollection()
nets.AddItem(net)
assert rebuilt.AddTimeStepNets(1.0, nets) == ""
assert np.array_equal(vtk_to_numpy(rebuilt.ToUnstructuredGrid(1).GetPoints().GetData()),
                      vtk_to_numpy(reader.GetOutput().GetPoints().GetData()))
mine, theirs = rebuilt.ToUnstructuredGrid(0), reader.GetOutput()
assert np.array_equal(vtk_to_numpy(mine.GetPoints().GetData()),
                      vtk_to_numpy(theirs.GetPoints().GetData()))
for name in names:
    assert np.array_equal(vtk_to_numpy(mine.GetPointData().GetArray(name)),
                          vtk_to_numpy(theirs.GetPointData().GetArray(name))), name

# A trilinear unit cube from numpy, f = x + 2y + 3z: the field is exact at its corners and
# its range is 0 .. 6.
cube = vtkIGANurbsData()
f_name = vtkStringArray()
f_name.InsertNextValue("f")
assert cube.SetAttributeNames(f_name) == ""
corners = np.array([[i & 1, i >> 1 & 1, i >> 2] for i in range(8)], dtype=float)
homogeneous = np.column_stack([corners, np.ones(8), corners @ [1.0, 2.0, 3.0]])
linear = numpy_to_vtk(np.array([0.0, 0.0, 1.0, 1.0]), deep=1)
cube_net = numpy_to_vtk(homogeneous, deep=1)
assert cube.AddVolume([1, 1, 1], linear, linear, linear, cube_net) == ""
grid = cube.ToUnstructuredGrid(0)
assert grid.GetNumberOfCells() == 1
points = vtk_to_numpy(grid.GetPoints().GetData())
f = vtk_to_numpy(grid.GetPointData().GetArray("f"))
assert np.allclose(f, points @ [1.0, 2.0, 3.0], atol=1e-15), (f, points)
assert grid.GetPointData().GetArray("f").GetRange(0) == (0.0, 6.0)

# A second time step: the cube moved by (1, 0, 0).
moved = homogeneous.copy()
moved[:, 0] += 1.0
nets = vtkDataArrayCollection()
nets.AddItem(numpy_to_vtk(moved, deep=1))
assert cube.AddTimeStepNets(0.5, nets) == ""
assert cube.GetNumberOfTimeSteps() == 2 and cube.GetTimeStep(1) == 0.5
assert cube.ToUnstructuredGrid(1).GetBounds() == (1.0, 2.0, 0.0, 1.0, 0.0, 1.0)

# Bad input: one sentence naming the problem, the contents kept.
problem = cube.AddVolume([1, 1, 1], linear, linear, linear, cube_net)
assert problem.startswith("patches are added while there is one time step"), problem
single = vtkIGANurbsData()
single.SetAttributeNames(f_name)
problem = single.AddVolume([1, 1, 1], linear, linear, linear, numpy_to_vtk(corners, deep=1))
assert "needs 5 components" in problem, problem
assert single.GetNumberOfPatches() == 0
negative = homogeneous.copy()
negative[3, 3] = -1.0
problem = single.AddVolume([1, 1, 1], linear, linear, linear, numpy_to_vtk(negative, deep=1))
assert "weight" in problem and single.GetNumberOfPatches() == 0, problem
assert single.AddVolume([1, 1, 1], linear, linear, linear, cube_net) == ""
assert "before the patches" in single.SetAttributeNames(f_name)
print("nurbs data: %d attributes read back, cube f range %s" % (len(names), str(grid.GetPointData().GetArray("f").GetRange(0))))
