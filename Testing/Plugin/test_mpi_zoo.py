"""pvbatch under MPI: the degenerate zoo (igaview-generate-data --zoo: a collapsed edge, a patch
collapsed to a point, an inverted patch, weights over 1e-3 .. 1e3, a constant field, degree 16
and a self-intersecting patch next to the regular sphere) drawn with its patches spread over the ranks gives the image of
all of them on rank 0, pixel for pixel: each rank draws the same hits for its patches, and IceT
keeps the nearer of them.

Usage: mpiexec -np N pvbatch test_mpi_zoo.py PLUGIN GENERATOR WORK_DIR"""
import os
import subprocess
import sys
# Spelled builtins.*: pvbatch's script namespace gets numpy_interface's sum/max/min, which are
# MPI reductions that only rank 0 would enter here.
import builtins

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import servermanager, simple  # noqa: E402

import iga_scene  # noqa: E402

plugin, generator, work_dir = sys.argv[1:4]
os.makedirs(work_dir, exist_ok=True)
simple.LoadPlugin(plugin)
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
assert ranks >= 2, f"run with mpiexec -np 2 or more (have {ranks} rank)"
# The script runs on rank 0 only; the other ranks read the file it writes.
subprocess.run([generator, work_dir, "--zoo"], check=True, stdout=subprocess.DEVNULL)
zoo_file = os.path.join(work_dir, "degenerate_zoo.vtu")

SIZE = [384, 48]
# The eight members in a row along x, 4 apart: about 19 pixels each (the degree-16 sphere
# dominates the time).
CAMERA = ([14.0, -9.5, 0.0], [14.0, 0.0, 0.0], [0.0, 0.0, 1.0])

view = simple.CreateRenderView()
view.ViewSize = SIZE
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = iga_scene.BACKGROUND


def render_alone(source, name):
    for shown in simple.GetSources().values():
        simple.Hide(shown, view)
    display = iga_scene.show_surface(source, view, "sphere", 0.0)
    display.IGANumberOfThreads = 1  # one a rank: the ranks share the machine's cores
    simple.ColorBy(display, None)
    iga_scene.place_camera(view, CAMERA)
    png = os.path.join(work_dir, name + ".png")
    simple.SaveScreenshot(png, view, ImageResolution=SIZE, TransparentBackground=0)
    return png


def cells_on_rank0(source):
    source.UpdatePipeline()
    total = source.GetDataInformation().GetNumberOfCells()
    rank0 = simple.Threshold(Input=simple.ProcessIdScalars(Input=source, CellScalars=1),
                             Scalars=["CELLS", "ProcessId"], LowerThreshold=0, UpperThreshold=0)
    rank0.UpdatePipeline()
    return rank0.GetDataInformation().GetNumberOfCells(), total


reader = simple.XMLUnstructuredGridReader(FileName=[zoo_file])
spread = simple.RedistributeDataSet(Input=reader)
on_rank0 = [cells_on_rank0(source) for source in (reader, spread)]
assert on_rank0[0] == (8, 8), on_rank0
assert 0 < on_rank0[1][0] < 8 and on_rank0[1][1] == 8, on_rank0

(size, whole), (size_spread, split) = (iga_scene.read_rgb(render_alone(s, name))
                                       for s, name in ((reader, "zoo_whole"),
                                                       (spread, "zoo_spread")))
assert size == size_spread == tuple(SIZE), (size, size_spread)
background = tuple(round(255 * c) for c in iga_scene.BACKGROUND)
pixels = [(i, j) for j in range(size[1]) for i in range(size[0])]
covered = [p for p in pixels if whole(*p) != background]
differing = [p for p in pixels if whole(*p) != split(*p)]
assert len(covered) > 1500, len(covered)
assert not differing, (len(differing), differing[:10])
print(f"{ranks} ranks, degenerate zoo: {on_rank0[1][0]} of 8 patches on rank 0 when spread; "
      f"{len(covered)} pixels covered, {len(differing)} differing from all on rank 0")
