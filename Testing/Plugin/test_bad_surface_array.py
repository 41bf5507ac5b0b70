"""pvpython: a surface array the mapper cannot draw (the rational weights) is reported as one
clear error naming it, in ParaView's output messages (stderr here), and nothing crashes.

Usage: pvpython test_bad_surface_array.py PLUGIN DATA_DIR"""
import os
import sys

from paraview import simple

plugin, data_dir = sys.argv[1:3]
simple.LoadPlugin(plugin)
reader = simple.XMLUnstructuredGridReader(FileName=[os.path.join(data_dir, "twisted_tube.vtu")])
view = simple.CreateRenderView(ViewSize=[100, 80])
display = simple.Show(reader, view)
display.SetRepresentationType("IGA Isosurface")
display.IGASurfaceArray = ["POINTS", "RationalWeights"]
display.IGAIsovalues = [0.9]
simple.Render(view)
print("rendered after the bad array")
