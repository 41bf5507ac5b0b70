"""pvpython as a client of a pvserver it starts: the plugin loaded on both sides, the bundled
tube's isosurface drawn by the "IGA Isosurface" representation on the server (the representation
requires distributed rendering, so the client receives only the image) matches the serial
baseline.

Usage: pvpython test_client_server.py PVSERVER PLUGIN DATA_DIR BASELINE_DIR WORK_DIR"""
import os
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview import simple  # noqa: E402
from paraview import servermanager  # noqa: E402

import iga_scene  # noqa: E402

pvserver, plugin, data_dir, baseline_dir, work_dir = sys.argv[1:6]
os.makedirs(work_dir, exist_ok=True)

with socket.socket() as probe:  # a free port
    probe.bind(("localhost", 0))
    port = probe.getsockname()[1]
server_log = os.path.join(work_dir, "pvserver.log")
with open(server_log, "w") as log:
    server = subprocess.Popen(
        [pvserver, f"--server-port={port}", "--force-offscreen-rendering"],
        stdout=log, stderr=subprocess.STDOUT)
try:
    for _ in range(600):
        with open(server_log) as log:
            if "Accepting connection" in log.read():
                break
        assert server.poll() is None, "pvserver exited: " + open(server_log).read()
        time.sleep(0.1)
    else:
        raise RuntimeError("pvserver did not accept connections within a minute")
    assert simple.Connect("localhost", port) is not None, "no connection to pvserver"
    assert servermanager.ActiveConnection.IsRemote()
    simple.LoadPlugin(plugin, remote=True)
    simple.LoadPlugin(plugin, remote=False)

    reader = simple.XMLUnstructuredGridReader(
        FileName=[os.path.join(data_dir, "twisted_tube.vtu")])
    view = iga_scene.make_view()
    # Even with a threshold that would deliver small geometry to the client, the view renders
    # on the server.
    simple.GetSettingsProxy("RenderViewSettings").RemoteRenderThreshold = 1000.0
    iga_scene.show_isosurface(reader, view)
    shot, difference = iga_scene.check_image(view, baseline_dir, iga_scene.BASELINE, work_dir)
    assert view.GetClientSideObject().GetUseDistributedRenderingForRender(), "rendered locally"
    print(f"client-server: rendered on the server, image difference to the serial baseline "
          f"{difference:.3f} (threshold 10)")
    simple.Disconnect()
except Exception:
    # The server's own words (e.g. xvfb refusing its render window) belong in the test's output,
    # where the retry on "bad X server connection" looks for them.
    with open(server_log) as log:
        sys.stderr.write("pvserver output:\n" + log.read())
    raise
finally:
    server.terminate()
    try:
        server.wait(timeout=20)
    except subprocess.TimeoutExpired:
        server.kill()
