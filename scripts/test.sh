#!/usr/bin/env bash
# Command (2) of the README: install what is missing, build, and run the whole test suite,
# then the sanitizer build's unit tests and a short fuzz run.
# GPU tests report SKIPPED where no CUDA device is present.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-dependencies.sh"
"$root/scripts/build.sh"
build="${BUILD_DIR:-$root/build}"
cd "$build"
xvfb-run -a -s "-screen 0 1280x1024x24" ctest --output-on-failure -j "$(nproc)"
# The Kernels' tests under AddressSanitizer and UBSan, and a short run of every fuzz target.
"$root/scripts/sanitize.sh"
"$root/scripts/fuzz.sh" 30
