"""pvpython: the "IGA CSG" representation of the IGAView plugin. The bundled dice (a rounded
cube minus its pips) matches its baseline image; cutting it with a half-space and adding a
slice coloured by an attribute changes what is covered as the geometry says; an expression
that does not parse is refused and the image stays.

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
print(f"dice: {whole} pixels covered, cut open with a slice {cut}, image difference {difference}")
