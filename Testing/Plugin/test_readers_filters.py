"""pvpython: the IGAView plugin's readers and deformation filters as ParaView proxies: file
dialog extensions, Bezier cells out, numbered files as a time series for the animation toolbar,
deformations that undo each other, exact parameter attributes on a rational file, and a NURBS file
drawn by the "IGA Isosurface" representation.

Usage: pvpython test_readers_filters.py PLUGIN DATA_DIR WORK_DIR"""
import builtins  # pvpython scripts see numpy_interface's sum/max in their namespace
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import servermanager, simple  # noqa: E402

import iga_scene  # noqa: E402

plugin, data_dir, work_dir = sys.argv[1:4]
os.makedirs(work_dir, exist_ok=True)
simple.LoadPlugin(plugin)
VTK_BEZIER_HEXAHEDRON = 79

# The file dialog offers the readers for their extensions.
factory = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
filters = factory.GetSupportedFileTypes(servermanager.ActiveConnection.Session)
assert "G+Smo NURBS geometry (*.xml)" in filters, filters
assert "GeoPDEs NURBS geometry (*.txt)" in filters, filters
assert "MFEM NURBS mesh (*.mesh)" in filters, filters

# OpenDataFile picks our readers for their own files, and ParaView's for other .xml and .txt.
csv = os.path.join(work_dir, "table.txt")
with open(csv, "w") as f:
    f.write("x,y\n1,2\n3,4\n")
other_xml = os.path.join(work_dir, "other.xml")
with open(other_xml, "w") as f:
    f.write('<?xml version="1.0"?>\n<CityModel></CityModel>\n')
for path, expected in ((os.path.join(data_dir, "gismo_quarter_ring.xml"), "AAIGAGismoReader"),
                       (os.path.join(data_dir, "geopdes_quarter_ring.txt"), "AAIGAGeoPDEsReader"),
                       (os.path.join(data_dir, "mfem_quarter_ring.mesh"), "AAIGAMFEMReader"),
                       (csv, "CSVReader"), (other_xml, "CityGML Reader")):
    opened = simple.OpenDataFile(path)
    assert opened.GetXMLName() == expected, (path, opened.GetXMLName())
    simple.Delete(opened)

# The same quarter ring (radii 1..2, height 1) in both formats.
gismo = simple.IGAGSmoReader(FileName=os.path.join(data_dir, "gismo_quarter_ring.xml"))
geopdes = simple.IGAGeoPDEsReader(FileName=os.path.join(data_dir, "geopdes_quarter_ring.txt"))
for reader in (gismo, geopdes):
    reader.UpdatePipeline()
    grid = servermanager.Fetch(reader)
    assert grid.GetNumberOfCells() > 0
    assert all(grid.GetCellType(c) == VTK_BEZIER_HEXAHEDRON for c in range(grid.GetNumberOfCells()))
    bounds = reader.GetDataInformation().GetBounds()
    # The quarter ring spans x, y in [0, 2] (control points reach the corner (2, 2)), z in [0, 1].
    assert [round(b, 12) for b in bounds] == [0.0, 2.0, 0.0, 2.0, 0.0, 1.0], bounds
    assert "z" in reader.PointData.keys(), reader.PointData.keys()

# The readers' memory limit: the ring's one cell fits a megabyte, not a kilobyte.
limited = simple.IGAGeoPDEsReader(FileName=os.path.join(data_dir, "geopdes_quarter_ring.txt"))
assert limited.MemoryLimitMB == 0.0, limited.MemoryLimitMB
limited.MemoryLimitMB = 0.001
limited.UpdatePipeline()
assert servermanager.Fetch(limited).GetNumberOfCells() == 0
limited.MemoryLimitMB = 1
limited.UpdatePipeline()
assert servermanager.Fetch(limited).GetNumberOfCells() > 0
simple.Delete(limited)

# ExactParameters: the rational ring's cell one degree higher (36 points, not 12), and the field's
# range of parameter_u its parameter's, 0 .. 1.
exact = simple.IGAGSmoReader(FileName=os.path.join(data_dir, "gismo_quarter_ring.xml"))
assert exact.ExactParameters == 0, exact.ExactParameters
assert servermanager.Fetch(exact).GetNumberOfPoints() == 12
exact.ExactParameters = 1
exact.UpdatePipeline()
assert servermanager.Fetch(exact).GetNumberOfPoints() == 36
u_range = exact.PointData["parameter_u"].GetRange()
assert abs(u_range[0]) < 1e-5 and abs(u_range[1] - 1) < 1e-5, u_range
simple.Delete(exact)

# Drawn by the representation: the isosurface z = 0.5 of the G+Smo file covers pixels.
view = simple.CreateRenderView(ViewSize=[200, 160])
iga_scene.show_surface(gismo, view, "z", 0.5)
simple.ResetCamera(view)
shot = os.path.join(work_dir, "gismo_quarter_ring.png")
simple.SaveScreenshot(shot, view, ImageResolution=[200, 160], TransparentBackground=0)
(width, height), pixel = iga_scene.read_rgb(shot)
background = pixel(0, 0)
covered = builtins.sum(1 for j in range(height) for i in range(width) if pixel(i, j) != background)
assert covered > 500, covered

# A composite input (both G+Smo files grouped) goes to the mapper as it is: from the same
# camera it covers what the ring alone covers, and more.
blocks = simple.IGAGSmoReader(FileName=os.path.join(data_dir, "gismo_two_blocks.xml"))
group = simple.GroupDatasets(Input=[gismo, blocks])
simple.Hide(gismo, view)


def coverage(source, name):
    for shown in (gismo, group):
        simple.Hide(shown, view)
    iga_scene.show_surface(source, view, "z", 0.5)
    png = os.path.join(work_dir, name + ".png")
    simple.SaveScreenshot(png, view, ImageResolution=[200, 160], TransparentBackground=0)
    (w, h), px = iga_scene.read_rgb(png)
    return {(i, j) for j in range(h) for i in range(w) if px(i, j) != background}


simple.Show(group, view)
simple.ResetCamera(view)
grouped, ring_alone = coverage(group, "grouped"), coverage(gismo, "ring_alone")
assert len(ring_alone) > 100, len(ring_alone)
assert len(grouped) > len(ring_alone) + 100, (len(grouped), len(ring_alone))
assert len(ring_alone - grouped) < 0.01 * len(ring_alone), len(ring_alone - grouped)

# A synthetic deformation is a time series for the animation toolbar; time 0 is the input.
source = simple.IGATwistedTube()
bend = simple.IGASyntheticDeformation(Input=source, Mode="Bend", GenerateDisplacement=1)
steps = list(bend.TimestepValues)
assert len(steps) == 11 and all(abs(t - i / 10) < 1e-15 for i, t in enumerate(steps)), steps
bend.UpdatePipeline(0.0)
assert bend.GetDataInformation().GetBounds() == source.GetDataInformation().GetBounds()
bend.UpdatePipeline(1.0)
bent = bend.GetDataInformation().GetBounds()
assert bent != source.GetDataInformation().GetBounds(), bent
# Displacing the control points back by the generated displacement restores the input.
back = simple.IGADisplaceControlPoints(Input=bend, ScaleFactor=-1.0)
back.Displacement = ["POINTS", "Displacement"]
back.UpdatePipeline(1.0)
restored = back.GetDataInformation().GetBounds()
original = source.GetDataInformation().GetBounds()
assert builtins.max(abs(a - b) for a, b in zip(restored, original)) < 1e-12, (restored, original)
# The boundary of the two G+Smo blocks (3 Bezier cells, 2 of their 18 faces shared twice) as
# Bezier quadrilaterals, which ParaView draws as a surface.
boundary = simple.IGABoundarySurface(Input=blocks)
faces = servermanager.Fetch(boundary)
VTK_BEZIER_QUADRILATERAL = 77
assert faces.GetNumberOfCells() == 14, faces.GetNumberOfCells()
assert builtins.all(faces.GetCellType(c) == VTK_BEZIER_QUADRILATERAL for c in range(14))
assert faces.GetBounds() == servermanager.Fetch(blocks).GetBounds(), faces.GetBounds()
assert faces.GetPointData().GetRationalWeights() is not None
assert faces.GetCellData().GetArray("BoundaryFace") is not None


def drawn_alone(show, name):
    """Pixels off the background when `show` alone shows something in the view."""
    for shown in simple.GetSources().values():
        simple.Hide(shown, view)
    show()
    simple.ResetCamera(view)
    png = os.path.join(work_dir, name + ".png")
    simple.SaveScreenshot(png, view, ImageResolution=[200, 160], TransparentBackground=0)
    (w, h), px = iga_scene.read_rgb(png)
    return builtins.sum(1 for j in range(h) for i in range(w) if px(i, j) != background)


boundary_pixels = drawn_alone(
    lambda: simple.Show(boundary, view).SetRepresentationType("Surface"), "boundary_surface")
assert boundary_pixels > 1000, boundary_pixels

# A numbered series of files opened together is a time series, a step a file, as ParaView's own
# readers make one: the G+Smo ring 1, 2 and 3 high, its animation steps drawn taller and taller.
with open(os.path.join(data_dir, "gismo_quarter_ring.xml")) as f:
    ring_text = f.read()
coefs = re.search(r"<coefs[^>]*>(.*?)</coefs>", ring_text, re.S)
rows = [[float(v) for v in line.split()] for line in coefs.group(1).strip().splitlines()]
ring_files = []
for k in range(3):
    ring_files.append(os.path.join(work_dir, f"ring_{k:03d}.xml"))
    net = "".join(f"   {x!r} {y!r} {z * (k + 1)!r}\n" for x, y, z in rows)
    with open(ring_files[-1], "w") as f:
        f.write(ring_text[:coefs.start(1)] + "\n" + net + "  " + ring_text[coefs.end(1):])
ring_series = simple.OpenDataFile(ring_files)
assert ring_series.GetXMLName() == "AAIGAGismoReader", ring_series.GetXMLName()
steps = list(ring_series.TimestepValues)
assert steps == [0.0, 1.0, 2.0], steps
for k, t in enumerate(steps):
    ring_series.UpdatePipeline(t)
    top = ring_series.GetDataInformation().GetBounds()[5]
    assert abs(top - (k + 1)) < 1e-12, (t, top)
for shown in simple.GetSources().values():
    simple.Hide(shown, view)
series_display = simple.Show(ring_series, view)
series_display.SetRepresentationType("IGA Surface")
iga_scene.place_camera(view, ([8.0, -8.0, 3.0], [1.0, 1.0, 1.5], [0.0, 0.0, 1.0]))
scene = simple.GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
series_pixels = []
for t in steps:
    scene.AnimationTime = t
    png = os.path.join(work_dir, f"ring_series_{int(t)}.png")
    simple.SaveScreenshot(png, view, ImageResolution=[200, 160], TransparentBackground=0)
    (w, h), px = iga_scene.read_rgb(png)
    series_pixels.append(builtins.sum(1 for j in range(h) for i in range(w) if px(i, j) != background))
assert series_pixels[0] > 500 and series_pixels[0] < series_pixels[1] < series_pixels[2], series_pixels
# GeoPDEs files make a series the same way.
geopdes_files = []
for k in range(2):
    geopdes_files.append(os.path.join(work_dir, f"ring_{k:03d}.txt"))
    with open(os.path.join(data_dir, "geopdes_quarter_ring.txt")) as src, \
            open(geopdes_files[-1], "w") as dst:
        dst.write(src.read())
geopdes_series = simple.OpenDataFile(geopdes_files)
assert geopdes_series.GetXMLName() == "AAIGAGeoPDEsReader", geopdes_series.GetXMLName()
assert list(geopdes_series.TimestepValues) == [0.0, 1.0], list(geopdes_series.TimestepValues)

print(f"boundary of the two blocks: 14 Bezier quadrilaterals, {boundary_pixels} pixels")
print(f"numbered G+Smo series: steps {steps}, pixels covered {series_pixels}")

# MFEM: the quarter ring with a GridFunction, the field a point array named after its file, its
# isosurface pressure = 3 (the plane 3x - 2z = 2 through the ring) drawn.
mfem = simple.IGAMFEMReader(FileName=os.path.join(data_dir, "mfem_quarter_ring.mesh"),
                            GridFunctionFileNames=[os.path.join(data_dir,
                                                                "mfem_quarter_ring_pressure.gf")])
mfem.UpdatePipeline()
assert "mfem_quarter_ring_pressure" in mfem.PointData.keys(), mfem.PointData.keys()
pressure_range = mfem.PointData["mfem_quarter_ring_pressure"].GetRange()
assert pressure_range == (-1.0, 7.0), pressure_range  # 3x - 2z + 1 at the control points
mfem_pixels = drawn_alone(
    lambda: iga_scene.show_surface(mfem, view, "mfem_quarter_ring_pressure", 3.0), "mfem_field")
assert mfem_pixels > 300, mfem_pixels
print(f"MFEM quarter ring: pressure over the control points {pressure_range}, isosurface 3 "
      f"covers {mfem_pixels} pixels")
print(f"readers: quarter ring bounds {bounds}; isosurface z = 0.5 covers {covered} pixels; "
      f"grouped with the two blocks {len(grouped)}, the ring alone then {len(ring_alone)}; "
      f"bend at time 1 bounds {bent}, displaced back to {restored}")
