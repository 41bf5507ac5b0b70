"""pvpython: the IGAView plugin loads and its default source delivers Bezier hexahedra."""
import sys

from paraview import simple, servermanager

simple.LoadPlugin(sys.argv[1], ns=globals())
source = IGATwistedTube()  # noqa: F821 (defined by LoadPlugin from the proxy label)
source.Time = 0.0
simple.UpdatePipeline(proxy=source)
assert list(source.TimestepValues) == [0.1 * i for i in range(11)], source.TimestepValues

grid = servermanager.Fetch(source)
VTK_BEZIER_HEXAHEDRON = 79
assert grid.GetNumberOfCells() == 8, grid.GetNumberOfCells()
assert all(grid.GetCellType(c) == VTK_BEZIER_HEXAHEDRON for c in range(8))
assert grid.GetPointData().GetRationalWeights() is not None
# Degree 2 in every direction: VTK infers it from the 27 points, and no cell array is written
# (VTK 9.2's Contour and Clip of higher-order cells read cell data out of bounds).
assert grid.GetCellData().GetNumberOfArrays() == 0
assert all(grid.GetCellSize(c) == 27 for c in range(8))
info = source.GetDataInformation()
assert info.GetNumberOfCells() == 8
bounds = info.GetBounds()
assert abs(bounds[5] - 2.0) < 1e-12, bounds
print("plugin test passed: 8 Bezier hexahedra, 11 time steps")
