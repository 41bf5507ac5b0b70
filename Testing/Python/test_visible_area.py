"""The README's Python examples with no X server (DISPLAY unset by the test): its snippet, as
written, run from the source folder, and Python/examples/visible_area.py: the visible area of the
collapsed-axis cylinder's disk height = 1 (radius 1, facing the camera) and of its part where
radius > 0.5, against pi and 3 pi / 4."""
import math
import os
import sys

assert "DISPLAY" not in os.environ, "this test runs without an X server"
import numpy as np  # noqa: E402

source = sys.argv[1]
examples, data = os.path.join(source, "Python", "examples"), os.path.join(source, "Data")
readme = open(os.path.join(source, "README.md"), encoding="utf-8").read()
snippet = readme.split("## Python\n", 1)[1].split("```python\n", 1)[1].split("```", 1)[0]
os.chdir(source)
scope = {}
exec(snippet, scope)
radius = scope["radius"]
print(f"README snippet: {np.isfinite(radius).sum()} pixels hit, radius up to {np.nanmax(radius)}")
assert np.isfinite(radius).sum() > 60000 and np.nanmax(radius) <= 1 + 1e-12

sys.path.insert(0, examples)
from visible_area import visible_areas  # noqa: E402

total, above = visible_areas(os.path.join(data, "collapsed_axis_cylinder.vtu"), "height", 1.0,
                             "radius", 0.5)
print(f"disk {total:.6f} (pi {math.pi:.6f}), radius > 0.5: {above:.6f} "
      f"(3 pi / 4 {0.75 * math.pi:.6f})")
assert abs(total / math.pi - 1) < 2e-3, total
assert abs(above / (0.75 * math.pi) - 1) < 2e-3, above
