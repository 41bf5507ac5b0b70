"""pvpython: the "IGA CSG" representation of the IGAView plugin. The bundled dice (a rounded
cube minus its pips) matches its baseline image; cutting it with a half-space and adding a
slice coloured by an attribute changes what is covered as the geometry says; an expression
that does not parse is refused and the image stays; the plane widget's plane, as a clip and as
a slice, covers what the typed half-space and slice cover, and as a clip it cuts the slices.

Usage: pvpython test_csg_representation.py PLUGIN DATA_DIR BASELINE_DIR WORK_DIR"""
import os
import sys
import builtins

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import simple  # noqa: E402

import iga_scene  # noqa: E402

plugin, data_dir, baseline_dir, work_dir = sys.argv[1:5]
os.makedirs(work_dir, exist_ok=True)
simple.LoadPlugin(plugin)


def covered_pixels(shot):
    (width, height), pixel = iga_scene.read_rgb(shot)
    background = tuple(round(255 * c) for c in iga_scene.BACKGROUND)
    return builtins.sum(1 for j in range(height) for i in range(width) if pixel(i, j) != background)


def screenshot(view, name):
    shot = os.path.join(work_dir, name + ".png")
    simple.Render(view)
    simple.SaveScreenshot(shot, view, ImageResolution=iga_scene.SIZE, TransparentBackground=0)
    return shot


dice = simple.XMLUnstructuredGridReader(FileName=[os.path.join(data_dir, "dice.vtu")])
view = iga_scene.make_view()
display = simple.Show(dice, view)
assert "IGA CSG" in display.Representation.Available, display.Representation.Available
display.SetRepresentationType("IGA CSG")
display.IGACsgExpression = "cube<0 - pips<0"
iga_scene.place_camera(view, ([3.2, -4.4, 3.6], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]))
shot, difference = iga_scene.check_image(view, baseline_dir, "PluginDiceCsg", work_dir)
whole = covered_pixels(shot)
assert whole > 15000, whole

# The dice's upper half (z >= 0) with its cut face, and the slice x = 0 through the lower half.
display.IGACsgExpression = "(cube<0 - pips<0) & plane(0, 0, 1, 0)"
display.IGASlices = [1.0, 0.0, 0.0, 0.0]
simple.ColorBy(display, ("POINTS", "cube"))
cut = covered_pixels(screenshot(view, "dice_cut"))
assert 0.3 * whole < cut < whole, (cut, whole)

# A bad expression is refused (an error naming the position) and the image stays.
display.IGACsgExpression = "cube<0 - (pips<0"
again = covered_pixels(screenshot(view, "dice_refused"))
assert again == cut, (again, cut)

# ParaView's plane widget. As a clip it cuts the solid as the typed half-space does, and the
# slices with it; as a slice it draws what the typed slice draws.
display.IGACsgExpression = "(cube<0 - pips<0) & plane(0, 0, 1, 0)"
display.IGASlices = []
typed_clip = covered_pixels(screenshot(view, "dice_typed_clip"))
display.IGACsgExpression = "cube<0 - pips<0"
display.IGAPlaneOrigin = [0.0, 0.0, 0.0]
display.IGAPlaneNormal = [0.0, 0.0, 1.0]
display.IGAPlaneUse = "Clip"
widget_clip = covered_pixels(screenshot(view, "dice_widget_clip"))
assert abs(widget_clip - typed_clip) <= 10 and typed_clip < whole, (widget_clip, typed_clip)
display.IGASlices = [1.0, 0.0, 0.0, 0.0]
clipped_slice = covered_pixels(screenshot(view, "dice_widget_clip_slice"))
# The slice is the volumes' section: in the upper half it shows beyond the rounded cube, in the
# lower half (shown uncut in `cut`, the same solid) it is gone.
assert widget_clip + 300 < clipped_slice < cut - 1000, (clipped_slice, widget_clip, cut)

display.IGACsgExpression = ""
display.IGAPlaneUse = "Off"
typed_slice = covered_pixels(screenshot(view, "dice_typed_slice"))
display.IGASlices = []
display.IGAPlaneNormal = [1.0, 0.0, 0.0]
display.IGAPlaneUse = "Slice"
widget_slice = covered_pixels(screenshot(view, "dice_widget_slice"))
assert 1000 < typed_slice and abs(widget_slice - typed_slice) <= 10, (widget_slice, typed_slice)
display.IGAPlaneUse = "Off"
assert covered_pixels(screenshot(view, "dice_nothing")) == 0
print(f"dice: {whole} pixels covered, cut open with a slice {cut}, image difference {difference}; "
      f"plane widget: clip {widget_clip} (typed {typed_clip}), with the slice cut {clipped_slice}, "
      f"slice {widget_slice} (typed {typed_slice})")
