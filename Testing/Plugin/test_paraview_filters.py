"""pvpython: ParaView's own filters on the cells IGAView writes. Contour, Clip and Integrate
Variables run on the default tube, the collapsed-axis cylinder and a generated wind blade (whose
left-handed cells once crashed Contour); the volumes come out positive and the cylinder's
radius-0.5 contour lies on that radius.

Usage: pvpython test_paraview_filters.py GENERATOR DATA_DIR WORK_DIR"""
import math
import os
import subprocess
import sys

from paraview import servermanager, simple

generator, data_dir, work_dir = sys.argv[1:4]
os.makedirs(work_dir, exist_ok=True)
subprocess.run([generator, work_dir, "--blade", "3000"], check=True, stdout=subprocess.DEVNULL)

files = {
    "twisted_tube": os.path.join(data_dir, "twisted_tube.vtu"),
    "collapsed_axis_cylinder": os.path.join(data_dir, "collapsed_axis_cylinder.vtu"),
    "wind_blade": os.path.join(work_dir, "wind_blade", "wind_blade_000.vtu"),
}
for name, path in files.items():
    reader = simple.XMLUnstructuredGridReader(FileName=[path])
    reader.UpdatePipeline()
    cells = reader.GetDataInformation().GetNumberOfCells()
    array = [a for a in reader.PointData.keys() if a != "RationalWeights"][0]
    low, high = reader.PointData[array].GetRange()
    contour = simple.Contour(
        Input=reader, ContourBy=["POINTS", array], Isosurfaces=[0.5 * (low + high)])
    contour.UpdatePipeline()
    triangles = contour.GetDataInformation().GetNumberOfCells()
    assert triangles > 0, (name, "contour is empty")
    clip = simple.Clip(Input=reader, ClipType="Plane")
    clip.ClipType.Origin = reader.GetDataInformation().GetBounds()[0::2]
    clip.ClipType.Normal = [1.0, 0.3, 0.1]
    clip.UpdatePipeline()
    volume = servermanager.Fetch(simple.IntegrateVariables(Input=reader))
    volume = volume.GetCellData().GetArray("Volume").GetValue(0)
    assert volume > 0, (name, "Integrate Variables gives volume", volume)
    print(f"{name}: {cells} cells, contour of {array} {triangles} triangles, volume {volume:.6g}")

cylinder = simple.XMLUnstructuredGridReader(FileName=[files["collapsed_axis_cylinder"]])
ring = servermanager.Fetch(
    simple.Contour(Input=cylinder, ContourBy=["POINTS", "radius"], Isosurfaces=[0.5]))
assert ring.GetNumberOfPoints() > 0
radii = [math.hypot(*ring.GetPoint(p)[:2]) for p in range(ring.GetNumberOfPoints())]
assert max(abs(r - 0.5) for r in radii) < 1e-9, (min(radii), max(radii))
print("ParaView's filters ran on all cells")
