#!/usr/bin/env bash
# Command (1) of the README: install what is missing, build, and render the bundled default
# dataset to igaview.png. Extra arguments go to `igaview render`.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-dependencies.sh"
"$root/scripts/build.sh"
build="${BUILD_DIR:-$root/build}"
# VTK's render windows need an X server; xvfb-run provides one when there is no display.
if [ -n "${DISPLAY:-}" ]; then
  "$build/bin/igaview" render "$@"
else
  xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/igaview" render "$@"
fi
