"""pvpython: a surface array the mapper cannot draw (the rational weights) is reported as one
clear error naming it, in ParaView's output messages (stderr here), and nothing crashes.

Usage: pvpython test_bad_surface_array.py PLUGIN DATA_DIR"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import simple  # noqa: E402

import iga_scene  # noqa: E402

plugin, data_dir = sys.argv[1:3]
simple.LoadPlugin(plugin)
reader = simple.XMLUnstructuredGridReader(FileName=[os.path.join(data_dir, "twisted_tube.vtu")])
view = simple.CreateRenderView(ViewSize=[100, 80])
iga_scene.show_surface(reader, view, "RationalWeights", 0.9)
simple.Render(view)
print("rendered after the bad array")
