"""pvpython: the "IGA Isosurface" representation of the IGAView plugin draws the bundled tube's
temperature = 0 sheet coloured by radius; the image matches the baseline and its pixels show
the surface where the sheet is and the background elsewhere. The engine's properties (backend,
subdivision depth cap, memory budget) reach the mapper: CUDA falls back to the same CPU image
with one warning, the caps leave unresolved pixels reported once, and the engine's progress
reaches ParaView's progress handler as the representation's.

Usage: pvpython test_isosurface_representation.py PLUGIN DATA_DIR BASELINE_DIR WORK_DIR"""
import os
import sys
# Spelled builtins.*: pvbatch's script namespace gets numpy_interface's sum/max/min, which are
# MPI reductions that only rank 0 would enter here.
import builtins

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import simple  # noqa: E402
from vtkmodules.util.misc import calldata_type  # noqa: E402
from vtkmodules.util.vtkConstants import VTK_STRING  # noqa: E402
from vtkmodules.vtkCommonCore import vtkOutputWindow  # noqa: E402

import iga_scene  # noqa: E402

# The mapper's warnings and plain messages, as ParaView's output messages receive them.
mapper_messages = []


@calldata_type(VTK_STRING)
def on_message(obj, event, text):
    if "vtkIGAIsosurfaceMapper" in text:
        mapper_messages.append((event, text))


for event in ("WarningEvent", "ErrorEvent", "TextEvent"):
    vtkOutputWindow.GetInstance().AddObserver(event, on_message)


def count_messages(part, event="WarningEvent"):
    return builtins.sum(1 for e, text in mapper_messages if e == event and part in text)


plugin, data_dir, baseline_dir, work_dir = sys.argv[1:5]
os.makedirs(work_dir, exist_ok=True)
simple.LoadPlugin(plugin)

# Offered for unstructured grids, not for poly data (the representation's input domain).
sphere_display = simple.Show(simple.Sphere())
assert "IGA Isosurface" not in sphere_display.Representation.Available
simple.Delete(sphere_display)

reader = simple.XMLUnstructuredGridReader(FileName=[os.path.join(data_dir, "twisted_tube.vtu")])
view = iga_scene.make_view()
display = iga_scene.show_isosurface(reader, view)
assert "IGA Isosurface" in display.Representation.Available

# The isovalue range offered by the panel is the surface array's range in the data.
domain = display.GetProperty("IGAIsovalues").SMProperty.GetDomain("scalar_range")
data_range = reader.PointData["temperature"].GetRange()
assert (domain.GetMinimum(0), domain.GetMaximum(0)) == tuple(data_range), data_range
assert data_range[0] < 0.0 < data_range[1], data_range

shot, difference = iga_scene.check_image(view, baseline_dir, iga_scene.BASELINE, work_dir)
(width, height), pixel = iga_scene.read_rgb(shot)
assert (width, height) == tuple(iga_scene.SIZE), (width, height)
background = tuple(round(255 * c) for c in iga_scene.BACKGROUND)
for corner in [(0, 0), (width - 1, 0), (0, height - 1), (width - 1, height - 1)]:
    assert pixel(*corner) == background, (corner, pixel(*corner))
# The camera looks at (0.2, 0, 1), on the tube's axis inside its hole (inner radius 0.5): the
# centre shows the background through the hole, the sheet lies left and right of it.
centre = pixel(width // 2, height // 2)
assert centre == background, centre
left, right = pixel(45, 139), pixel(240, 89)
for side in (left, right):
    assert builtins.max(abs(a - b) for a, b in zip(side, background)) > 100, side
# Coloured through the lookup table: the sheet spans the radii 0.5 (blue) to 1 (red).
pixels = [pixel(i, j) for j in range(0, height, 2) for i in range(0, width, 2)]
bluish = builtins.sum(1 for r, g, b in pixels if b > r + 60)
reddish = builtins.sum(1 for r, g, b in pixels if r > b + 60)
covered = builtins.sum(1 for p in pixels if p != background)
assert bluish > 50 and reddish > 50, (bluish, reddish)
print(f"IGA Isosurface representation: image difference {difference:.3f} (threshold 10), "
      f"{covered} of {len(pixels)} sampled pixels covered, {bluish} bluish, {reddish} reddish, "
      f"centre {centre}")

# A second isovalue adds a second sheet: more pixels covered.
display.IGAIsovalues = [0.0, 0.5]
simple.Render(view)
two = os.path.join(work_dir, "two_isovalues.png")
simple.SaveScreenshot(two, view, ImageResolution=iga_scene.SIZE, TransparentBackground=0)
_, pixel2 = iga_scene.read_rgb(two)
covered2 = builtins.sum(1 for j in range(0, height, 2) for i in range(0, width, 2)
                        if pixel2(i, j) != background)
assert covered2 > covered, (covered2, covered)
print(f"two isovalues: {covered2} sampled pixels covered (one: {covered})")

# While interacting with LOD on (threshold 0: always), the view draws the outline instead: far
# fewer pixels than the surfaces, but some.
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter  # noqa: E402


def covered_now():
    grab = vtkWindowToImageFilter()
    grab.SetInput(view.GetRenderWindow())
    grab.ShouldRerenderOff()
    grab.ReadFrontBufferOff()
    grab.Update()
    scalars = grab.GetOutput().GetPointData().GetScalars()
    return builtins.sum(1 for i in range(scalars.GetNumberOfTuples())
                        if scalars.GetTuple(i)[:3] != background)


view.LODThreshold = 0.0
simple.Render(view)
still = covered_now()
view.InteractiveRender()
interactive = covered_now()
assert view.GetClientSideObject().GetUsedLODForLastRender()
assert 0 < interactive < 0.5 * still, (interactive, still)
print(f"LOD while interacting: outline covers {interactive} pixels, the surfaces {still}")

# The engine's properties (advanced, group "IGA Isosurface") and their defaults.
display.IGAIsovalues = [0.0]
assert display.IGABackend == "Automatic", display.IGABackend
assert display.GetProperty("IGABackend").Available == ["Automatic", "CPU", "CUDA"]
assert display.IGAMaximumSubdivisionDepth == 22, display.IGAMaximumSubdivisionDepth
assert display.IGAMemoryBudget == 4096, display.IGAMemoryBudget
assert display.IGAFrameDeadline == 0, display.IGAFrameDeadline
# Without CUDA the automatic choice says so once, as a plain message (no warning).
without_cuda = count_messages("built without CUDA", "TextEvent") == 1
assert count_messages("CUDA") == 0, mapper_messages

# ParaView's progress handler sees the representation's progress while the engine runs.
handler = simple.servermanager.ActiveConnection.Session.GetProgressHandler()
# The handler drops the events that come sooner than its interval after the last one it passed;
# the interval is clamped to 0.01 s at least, which a small frame's rounds may all be.
handler.SetProgressInterval(0)
progress = []


def on_progress(obj, event):
    progress.append((obj.GetLastProgressText(), obj.GetLastProgress()))


handler.AddObserver("ProgressEvent", on_progress)


def screenshot(name):
    path = os.path.join(work_dir, name + ".png")
    simple.SaveScreenshot(path, view, ImageResolution=iga_scene.SIZE, TransparentBackground=0)
    return path


def same_pixels(a, b):
    (size_a, pixel_a), (size_b, pixel_b) = iga_scene.read_rgb(a), iga_scene.read_rgb(b)
    return size_a == size_b and builtins.all(
        pixel_a(i, j) == pixel_b(i, j) for j in range(size_a[1]) for i in range(size_a[0]))


def covered_in(path):
    (w, h), pixel = iga_scene.read_rgb(path)
    return builtins.sum(1 for j in range(h) for i in range(w) if pixel(i, j) != background)


def turn_and_back():
    """Renders from a slightly different camera (the engine runs again), then the test's."""
    view.CameraPosition = [2.5, -2.9, 2.6]
    simple.Render(view)
    iga_scene.place_camera(view)


# CUDA asked for: without a GPU build the same image as the CPU's, and one warning over two
# frames computed.
display.IGABackend = "CUDA"
cuda_shot = screenshot("backend_cuda")
turn_and_back()
if without_cuda:
    assert same_pixels(cuda_shot, shot), "CUDA fallback differs from the CPU image"
    assert count_messages("CUDA asked for, but") == 1, mapper_messages
else:
    iga_scene.compare_images(cuda_shot, shot, work_dir)

# A frame large enough that its rounds take longer than the handler's interval: its progress
# reaches the handler between 0 and 100.
progress.clear()
view.CameraPosition = [2.5, -2.9, 2.6]
simple.SaveScreenshot(os.path.join(work_dir, "progress.png"), view, ImageResolution=[1500, 1200],
                      TransparentBackground=0)
iga_scene.place_camera(view)
engine_progress = [p for text, p in progress if text == "IGA Isosurface" and 0 < p < 100]
assert engine_progress, progress
print(f"Backend CUDA: {'CPU fallback, same image' if without_cuda else 'GPU'}; progress seen "
      f"by ParaView's handler: {engine_progress}")

# Two subdivision levels leave pixels unresolved (not drawn), warned about once.
display.IGABackend = "Automatic"
display.IGAMaximumSubdivisionDepth = 2
shallow = screenshot("depth_2")
turn_and_back()
assert count_messages("pixels left unresolved at the subdivision depth cap "
                      "(MaximumSubdivisionDepth 2:") == 1, mapper_messages
shallow_covered, full_covered = covered_in(shallow), covered_in(shot)
assert shallow_covered < full_covered, (shallow_covered, full_covered)

# The image takes 365 bytes a pixel of the budget (26 MiB at 300 x 240): 16 MiB draws nothing,
# said once; 41 MiB leaves the subdivision 16, not enough at this size either.
display.IGAMaximumSubdivisionDepth = 22
display.IGAMemoryBudget = 16
assert covered_in(screenshot("budget_16")) == 0
turn_and_back()
assert count_messages("nothing drawn: a 300x240 image needs 26 MiB (365 bytes a pixel), more "
                      "than the memory budget (MemoryBudgetMB 16)", "ErrorEvent") == 1, \
    mapper_messages
display.IGAMemoryBudget = 41
budget_shot = screenshot("budget_41")
turn_and_back()
assert count_messages("at the memory budget (MemoryBudgetMB 41:") == 1, mapper_messages
assert covered_in(budget_shot) < full_covered

# A deadline passed before the first subdivision round: nothing is found, said once.
display.IGAMemoryBudget = 4096
display.IGAFrameDeadline = 1e-9
late_shot = screenshot("deadline")
turn_and_back()
assert count_messages("the frame stopped at its deadline (FrameDeadline 1e-09 s)") == 1, \
    mapper_messages
assert covered_in(late_shot) == 0

# The defaults again: the baseline image.
display.IGAFrameDeadline = 0
assert same_pixels(screenshot("defaults_again"), shot)
assert count_messages("pixels left unresolved") == 3, mapper_messages
print(f"MaximumSubdivisionDepth 2: {shallow_covered} pixels covered, MemoryBudget 41 MB: "
      f"{covered_in(budget_shot)}, defaults: {full_covered}; each cap warned about once")
