"""pvpython: the "IGA Surface" and "IGA Surface With Edges" representations of the IGAView plugin.
The bundled teapot (32 bicubic Bezier quadrilaterals) coloured by height with its element edges
matches its baseline image; the edges are drawn in the display's EdgeColor and disappear under
"IGA Surface"; a G+Smo volume read by the plugin's reader shows its boundary.

Usage: pvpython test_surface_representation.py PLUGIN DATA_DIR BASELINE_DIR WORK_DIR"""
import os
import sys
import builtins

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import simple  # noqa: E402

import iga_scene  # noqa: E402

plugin, data_dir, baseline_dir, work_dir = sys.argv[1:5]
os.makedirs(work_dir, exist_ok=True)
simple.LoadPlugin(plugin)

EDGE = (0, 255, 0)


def edge_pixels(shot):
    (width, height), pixel = iga_scene.read_rgb(shot)
    return builtins.sum(1 for j in range(height) for i in range(width)
                        if pixel(i, j)[1] > 200 and pixel(i, j)[0] < 60 and pixel(i, j)[2] < 60)


def covered_pixels(shot):
    (width, height), pixel = iga_scene.read_rgb(shot)
    background = tuple(round(255 * c) for c in iga_scene.BACKGROUND)
    return builtins.sum(1 for j in range(height) for i in range(width) if pixel(i, j) != background)


teapot = simple.XMLUnstructuredGridReader(FileName=[os.path.join(data_dir, "teapot.vtu")])
view = iga_scene.make_view()
display = simple.Show(teapot, view)
for kind in ("IGA Isosurface", "IGA Surface", "IGA Surface With Edges"):
    assert kind in display.Representation.Available, display.Representation.Available
display.SetRepresentationType("IGA Surface With Edges")
display.EdgeColor = [0.0, 1.0, 0.0]
simple.ColorBy(display, ("POINTS", "height"))
lut = simple.GetColorTransferFunction("height")
lut.ApplyPreset("Cool to Warm", True)
place = ([5.5, -9.0, 6.0], [0.2, 0.0, 1.2], [0.0, 0.0, 1.0])
iga_scene.place_camera(view, place)
shot, difference = iga_scene.check_image(view, baseline_dir, "PluginTeapotSurfaceWithEdges",
                                         work_dir)
with_edges, covered = edge_pixels(shot), covered_pixels(shot)
assert covered > 8000, covered
assert with_edges > 300, with_edges

display.SetRepresentationType("IGA Surface")
simple.Render(view)
plain = os.path.join(work_dir, "teapot_surface.png")
simple.SaveScreenshot(plain, view, ImageResolution=iga_scene.SIZE, TransparentBackground=0)
assert edge_pixels(plain) == 0, edge_pixels(plain)
assert abs(covered_pixels(plain) - covered) < 20, (covered_pixels(plain), covered)
simple.Hide(teapot, view)

# A geometry-only G+Smo volume: its boundary, without choosing an attribute or an isovalue.
gismo = simple.IGAGSmoReader(FileName=os.path.join(data_dir, "gismo_quarter_ring.xml"))
ring = simple.Show(gismo, view)
ring.SetRepresentationType("IGA Surface")
simple.ResetCamera(view)
simple.Render(view)
ring_shot = os.path.join(work_dir, "gismo_ring_surface.png")
simple.SaveScreenshot(ring_shot, view, ImageResolution=iga_scene.SIZE, TransparentBackground=0)
assert covered_pixels(ring_shot) > 5000, covered_pixels(ring_shot)

# With the light kit off (and no AdditionalLights) ParaView draws surfaces unlit, in full colour; so does
# the IGA representation, to the value of ParaView's own "Surface" of the same cells.
view.UseLight = 0
simple.ColorBy(ring, None)
ring.AmbientColor = ring.DiffuseColor = [0.9, 0.5, 0.1]
unlit = {}
for kind in ("IGA Surface", "Surface"):
    ring.SetRepresentationType(kind)
    simple.Render(view)
    shot_path = os.path.join(work_dir, f"gismo_ring_unlit_{kind.replace(' ', '_')}.png")
    simple.SaveScreenshot(shot_path, view, ImageResolution=iga_scene.SIZE,
                          TransparentBackground=0)
    (width, height), pixel = iga_scene.read_rgb(shot_path)
    background = tuple(round(255 * c) for c in iga_scene.BACKGROUND)
    colours = [pixel(i, j) for j in range(height) for i in range(width)
               if pixel(i, j) != background]
    unlit[kind] = max(set(colours), key=colours.count), len(colours)
    share = colours.count(unlit[kind][0]) / len(colours)
    assert share > 0.95, f"{kind}: {share:.3f} of the covered pixels in its most common colour"
assert unlit["IGA Surface"][1] > 5000, unlit
assert all(abs(a - b) <= 1 for a, b in zip(unlit["IGA Surface"][0], unlit["Surface"][0])), unlit
assert all(abs(a - round(255 * c)) <= 1 for a, c in zip(unlit["IGA Surface"][0], [0.9, 0.5, 0.1]))
print(f"teapot: {covered} pixels covered, {with_edges} edge pixels, image difference "
      f"{difference}; G+Smo ring boundary: {covered_pixels(ring_shot)} pixels, unlit in "
      f"{unlit['IGA Surface'][0]} (ParaView's Surface: {unlit['Surface'][0]})")
