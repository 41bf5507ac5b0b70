"""pvbatch under MPI: the "IGA Isosurface" representation draws each rank's own piece and IceT
composites the ranks' images by depth. With the bundled tube redistributed across the ranks by
RedistributeDataSet, the image equals the one with all cells on rank 0 and the serial baseline.

Usage: mpiexec -np N pvbatch test_mpi_isosurface.py PLUGIN DATA_DIR BASELINE_DIR WORK_DIR"""
import os
import sys
# Spelled builtins.*: pvbatch's script namespace gets numpy_interface's sum/max/min, which are
# MPI reductions that only rank 0 would enter here.
import builtins

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import servermanager, simple  # noqa: E402

import iga_scene  # noqa: E402

plugin, data_dir, baseline_dir, work_dir = sys.argv[1:5]
os.makedirs(work_dir, exist_ok=True)
simple.LoadPlugin(plugin)
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
assert ranks >= 2, f"run with mpiexec -np 2 or more (have {ranks} rank)"

RANK_SCRIPT = """
from vtkmodules.vtkCommonCore import vtkIntArray
from vtkmodules.vtkParallelCore import vtkMultiProcessController
output = self.GetOutput()
output.ShallowCopy(self.GetInput())
rank = vtkIntArray()
rank.SetName("rank")
rank.SetNumberOfTuples(output.GetNumberOfCells())
rank.Fill(vtkMultiProcessController.GetGlobalController().GetLocalProcessId())
output.GetCellData().AddArray(rank)
"""


def rank_pieces(source):
    """Each rank's cells alone (the others' are dropped): tag cells with the rank holding them,
    threshold per rank."""
    tagged = simple.ProgrammableFilter(Input=source, Script=RANK_SCRIPT)
    return [simple.Threshold(Input=tagged, Scalars=["CELLS", "rank"], LowerThreshold=rank,
                             UpperThreshold=rank) for rank in range(ranks)]


def cells_per_rank(source):
    counts = []
    for piece in rank_pieces(source):
        piece.UpdatePipeline()
        counts.append(piece.GetDataInformation().GetNumberOfCells())
    return counts


def coverage(png):
    """{pixel: colour} of the pixels showing something other than the background."""
    (width, height), pixel = iga_scene.read_rgb(png)
    background = tuple(round(255 * c) for c in iga_scene.BACKGROUND)
    colours = {(i, j): pixel(i, j) for j in range(height) for i in range(width)}
    return {p: c for p, c in colours.items() if c != background}


reader = simple.XMLUnstructuredGridReader(FileName=[os.path.join(data_dir, "twisted_tube.vtu")])
redistributed = simple.RedistributeDataSet(Input=reader)
# The single-piece file lands on rank 0; RedistributeDataSet spreads whole cells over all ranks.
whole_counts, split_counts = cells_per_rank(reader), cells_per_rank(redistributed)
# The bundled source answers piece requests itself: whole patches, disjoint per rank.
source_counts = cells_per_rank(simple.IGATwistedTube())
assert source_counts == [8 * (r + 1) // ranks - 8 * r // ranks for r in range(ranks)], source_counts
print("cells per rank: read", whole_counts, "redistributed", split_counts, "IGA Twisted Tube",
      source_counts)
assert whole_counts == [8] + [0] * (ranks - 1), whole_counts
assert builtins.sum(split_counts) == 8, split_counts
assert 0 < builtins.min(split_counts) and builtins.max(split_counts) < 8, split_counts

view = iga_scene.make_view()


def render_alone(source, name, camera=iga_scene.CAMERA, opacity=1.0):
    for shown in simple.GetSources().values():
        simple.Hide(shown, view)
    iga_scene.show_isosurface(source, view, camera).Opacity = opacity
    png = os.path.join(work_dir, name + ".png")
    simple.SaveScreenshot(png, view, ImageResolution=iga_scene.SIZE, TransparentBackground=0)
    return png


# The scene of the serial test: the split data gives its baseline and the all-on-rank-0 image.
iga_scene.show_isosurface(redistributed, view)
split_png, to_baseline = iga_scene.check_image(view, baseline_dir, iga_scene.BASELINE, work_dir)
to_whole = iga_scene.compare_images(split_png, render_alone(reader, "whole"), work_dir)

# Translucent (ordered compositing by the pieces' bounds): the same image as on one rank.
split_translucent = render_alone(redistributed, "split_translucent", opacity=0.5)
to_whole_translucent = iga_scene.compare_images(
    split_translucent, render_alone(reader, "whole_translucent", opacity=0.5), work_dir)
# ... and it is translucent: where the sheet is seen once, half its opaque colour over the
# background (the sheet folds, so some pixels see two layers).
opaque, translucent = coverage(split_png), coverage(split_translucent)
background = [round(255 * c) for c in iga_scene.BACKGROUND]
blended = [p for p, c in opaque.items() if p in translucent and builtins.all(
    abs(t - (o + b) / 2) <= 3 for t, o, b in zip(translucent[p], c, background))]
assert abs(len(translucent) - len(opaque)) <= 0.01 * len(opaque), (len(translucent), len(opaque))
assert len(blended) >= 0.5 * len(opaque), (len(blended), len(opaque))

# Looking (down) along the line between the two ranks' pieces, one hides the other: the composite is
# right only where IceT keeps, per pixel, the rank with the nearer depth.
pieces = rank_pieces(redistributed)
centres = []
for piece in pieces[:2]:
    piece.UpdatePipeline()
    b = piece.GetDataInformation().GetBounds()
    centres.append([(b[2 * d] + b[2 * d + 1]) / 2 for d in range(3)])
axis = [a - b for a, b in zip(centres[1], centres[0])]
norm = builtins.sum(a * a for a in axis) ** 0.5
focal = [(a + b) / 2 for a, b in zip(*centres)]
up = [0.0, 0.0, 1.0] if abs(axis[2]) < 0.9 * norm else [1.0, 0.0, 0.0]
# From a little above, to see the sheet rather than its edge.
along = ([f + 5 * a / norm + 0.5 * u for f, a, u in zip(focal, axis, up)], focal, up)
split_along = render_alone(redistributed, "split_along", along)
to_whole_along = iga_scene.compare_images(
    split_along, render_alone(reader, "whole_along", along), work_dir)

# Each rank's piece alone covers only part of that image; the parts overlap on screen, and
# together they cover the composite. Not quite exactly: alone, a piece has smaller bounds, hence
# another clipping range and projection, and a few pixels on patch seams between the ranks'
# pieces come out differently (bounded below).
covered = coverage(split_along)
parts = [coverage(render_alone(piece, f"rank{rank}_alone", along))
         for rank, piece in enumerate(pieces[:2])]
overlap = parts[0].keys() & parts[1].keys()
union = parts[0].keys() | parts[1].keys()
# Where both ranks draw different colours, a compositor ignoring depth would get some wrong.
contested = [p for p in overlap if parts[0][p] != parts[1][p]]
assert builtins.all(0 < len(part) < len(covered) for part in parts), [len(p) for p in parts]
assert len(contested) > 100, (len(contested), len(overlap))
assert len(union - covered.keys()) <= 0.005 * len(covered), sorted(union - covered.keys())[:20]
assert len(covered.keys() - union) <= 0.005 * len(covered), sorted(covered.keys() - union)[:20]
print(f"{ranks} ranks, serial test's camera: split image vs all on rank 0 {to_whole:.3f}, vs the "
      f"serial baseline {to_baseline:.3f}, at opacity 0.5 vs all on rank 0 "
      f"{to_whole_translucent:.3f}, {len(blended)} of {len(opaque)} pixels half over the "
      f"background (threshold 10)")
print(f"camera along the pieces' centres {centres[0]} -> {centres[1]}: split vs all on rank 0 "
      f"{to_whole_along:.3f}; {len(covered)} pixels covered, by each rank's piece alone "
      f"{[len(p) for p in parts]}, by both {len(overlap)} ({len(contested)} in different "
      f"colours), seam pixels differing {len(union ^ covered.keys())}")
