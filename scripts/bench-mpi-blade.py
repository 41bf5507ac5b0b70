"""pvbatch benchmark: the SST paper's wind blade (igaview-generate-data --blade N: N Bézier
patches in pieces of 100k, read by ParaView's parallel .pvtu reader, which deals the pieces out
to the ranks) drawn by the "IGA Isosurface" representation, its strain's isosurface, at 512x512,
with the ranks' images composited by IceT. Run it with 1 rank and with several.

Per frame (wall time of the render call on the client): the first (reading, the mapper's
extraction of the patches and the engine's checks), a sweep of isovalues, and small camera moves.
Per rank: peak resident memory (VmHWM of every pvbatch process of this run); the pixels the
composited image covers (a run that drew nothing fails). With
PARAVIEW_LOG_RENDERING_VERBOSITY=INFO set by the caller, ParaView's render-pass log on stderr
holds IceT's compositing time per rank.

Usage: mpiexec -np N pvbatch bench-mpi-blade.py PLUGIN GENERATOR WORK_DIR [PATCHES [JSON]]
(PATCHES: 800000 by default; the blade's files are made once in WORK_DIR and kept.)"""
# Spelled builtins.*: pvbatch's script namespace gets numpy_interface's sum/max/min, which are
# MPI reductions that only rank 0 would enter here.
import builtins
import json
import os
import statistics
import subprocess
import sys
import time

from paraview import servermanager, simple

plugin, generator, work_dir = sys.argv[1:4]
patches = int(sys.argv[4]) if len(sys.argv) > 4 else 800000
json_file = sys.argv[5] if len(sys.argv) > 5 else None
SIZE = [512, 512]
ISOVALUES = [0.1, 0.2, 0.3, 0.4, 0.5]

simple.LoadPlugin(plugin)
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
blade_dir = os.path.join(work_dir, f"blade-{patches}")
pvtu = os.path.join(blade_dir, "wind_blade.pvtu")
if not os.path.exists(pvtu):
    os.makedirs(blade_dir, exist_ok=True)
    subprocess.run([generator, blade_dir, "--blade", str(patches)], check=True)


def timed_render(view):
    start = time.perf_counter()
    simple.Render(view)
    return 1000 * (time.perf_counter() - start)


def peak_memory_per_rank():
    """VmHWM (MB) of every pvbatch process running this script, by process id."""
    peaks = {}
    script = os.path.basename(__file__)
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                command = f.read().split(b"\0")
            if not any(b"pvbatch" in part for part in command[:1]) or not any(
                    script.encode() in part for part in command):
                continue
            with open(f"/proc/{pid}/status") as f:
                for line in f:
                    if line.startswith("VmHWM:"):
                        peaks[int(pid)] = int(line.split()[1]) / 1024
        except OSError:
            continue
    return peaks


view = simple.CreateRenderView()
view.ViewSize = SIZE
view.OrientationAxesVisibility = 0
reader = simple.XMLPartitionedUnstructuredGridReader(FileName=[pvtu])
display = simple.Show(reader, view)
display.SetRepresentationType("IGA Isosurface")
display.IGASurfaceArray = ["POINTS", "strain"]
display.IGAIsovalues = [ISOVALUES[2]]
simple.ColorBy(display, None)
view.ResetCamera()
first = timed_render(view)
sweep = []
for isovalue in ISOVALUES:
    display.IGAIsovalues = [isovalue]
    sweep.append(timed_render(view))
display.IGAIsovalues = [ISOVALUES[2]]
simple.Render(view)
camera = view.GetActiveCamera()
moves = []
for step in range(5):
    camera.Azimuth(2.0)
    moves.append(timed_render(view))

def covered_pixels():
    """Pixels of the composited image that differ from the background: the blade was drawn."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    shot = os.path.join(work_dir, f"blade-{patches}-{ranks}.png")
    simple.SaveScreenshot(shot, view, ImageResolution=SIZE, TransparentBackground=0)
    png = vtkPNGReader()
    png.SetFileName(shot)
    png.Update()
    pixels = png.GetOutput().GetPointData().GetScalars()
    corner = pixels.GetTuple(0)
    return builtins.sum(1 for p in range(pixels.GetNumberOfTuples()) if pixels.GetTuple(p) != corner)


result = {
    "ranks": ranks, "patches": patches, "width": SIZE[0], "height": SIZE[1],
    "coveredPixels": covered_pixels(),
    "firstFrameMs": first, "isovalueFramesMs": sweep, "cameraFramesMs": moves,
    "isovalueMedianMs": statistics.median(sweep), "cameraMedianMs": statistics.median(moves),
    "peakMBPerRank": sorted(peak_memory_per_rank().values()),
}
# Every rank's memory found, and an image that shows the blade: else the figures mean nothing.
assert len(result["peakMBPerRank"]) == ranks, result
assert result["coveredPixels"] > 0, result
print(json.dumps(result))
if json_file:
    with open(json_file, "w") as out:
        json.dump(result, out, indent=1)
