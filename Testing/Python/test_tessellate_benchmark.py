"""scripts/bench-tessellate-contour.py at a small size, with no X server: its measurement of VTK's
Tessellate + Contour against the engine's exact hits must see a coarse tessellation's error and a
fine one's accuracy (if the camera of the ray cast and of the engine differed, or the distances
were measured wrongly, neither would hold), and its JSON must carry what docs/benchmarks.md
reports.

Usage: python3 test_tessellate_benchmark.py SCRIPT DATA_DIR WORK_DIR"""
import json
import os
import subprocess
import sys

script, data, work_dir = sys.argv[1:4]
os.makedirs(work_dir, exist_ok=True)
out = os.path.join(work_dir, "tessellate-contour.json")
subprocess.run([sys.executable, script, data, "--size", "128", "--zoom", "3", "--levels", "1", "3",
                "--json", out], check=True)
with open(out) as f:
    result = json.load(f)
coarse, fine = result["levels"]
exact = fine["exactPixels"]
print(json.dumps(result["levels"], indent=1))
assert result["engineMs"] > 0 and exact > 4000, result
# Three subdivisions under the chord error: nearly every pixel within half a pixel of the exact
# surface, the two covering nearly the same pixels.
assert fine["withinHalfPixel"] > 0.98, fine
assert fine["contourOnlyPixels"] + fine["exactOnlyPixels"] < 0.02 * exact, fine
assert abs(fine["contourPixels"] - exact) < 0.02 * exact, fine
# One subdivision: far fewer triangles, visibly off the exact surface.
assert coarse["triangles"] < fine["triangles"] / 4, (coarse, fine)
assert coarse["withinHalfPixel"] < fine["withinHalfPixel"] - 0.2, (coarse, fine)
assert coarse["largestDistancePixels"] > 1.0 > fine["largestDistancePixels"], (coarse, fine)
for level in result["levels"]:
    assert level["tessellateMs"] > 0 and level["contourMs"] > 0, level
    assert level["overEngine"] > 0, level
print("tessellate-contour benchmark: OK")
