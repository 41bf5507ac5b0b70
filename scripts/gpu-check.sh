#!/usr/bin/env bash
# On a GPU machine without VTK (the device tool's machines): build the VTK-free Kernels with
# CUDA, run the GPU tests (CUDA engine against the CPU engine) and the GPU benchmark.
# GoogleTest sources must be in .deps/googletest and GLM's headers in .deps/glm (git-ignored;
# copy them there and pass .deps through the device tool's `carry`). Results go to $OUT (or ./gpu-results).
# Where the CUDA toolkit has them, compute-sanitizer then checks the GPU tests for memory errors
# and Nsight Systems profiles the deforming 10k blade (kernel and transfer summaries), in the
# same call: the device machine is given back after half a minute idle, and a fresh one
# rebuilds.
#
#   mkdir -p .deps && cp -r /usr/src/googletest /usr/include/glm .deps/   # once, here
#   scripts/gpu-check.sh [--quick]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${OUT:-$root/gpu-results}"
build="${BUILD_DIR:-$root/build-gpu}"
mkdir -p "$out"
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv > "$out/device.csv" || true
cmake -S "$root/Kernels" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CUDA_ARCHITECTURES="${CUDA_ARCHITECTURES:-90}" > "$out/configure.log"
cmake --build "$build" -j "$(nproc)" > "$out/build.log" 2>&1 || { tail -50 "$out/build.log"; exit 1; }
# A failure is remembered, not fatal: the checks below matter most when a test fails.
failed=0
(cd "$build" && ctest -L "gpu|engine" --output-on-failure) 2>&1 | tee "$out/ctest.log" || failed=1
"$build/igaBenchmark" --gpu "$@" --json "$out/benchmark-gpu.json" 2>&1 |
  tee "$out/benchmark.log" || failed=1

export PATH="$PATH:/usr/local/cuda/bin"
if command -v compute-sanitizer > /dev/null; then
  status=0
  compute-sanitizer --tool memcheck --error-exitcode 99 "$build/Testing/igaCudaEngineTests" \
    > "$out/memcheck.log" 2>&1 || status=$?
  echo "compute-sanitizer memcheck: exit $status" | tee -a "$out/memcheck.log"
  [ "$status" -eq 0 ] || failed=1
else
  echo "compute-sanitizer: not installed" > "$out/memcheck.log"
fi
if command -v nsys > /dev/null; then
  # The report stays in the build folder (large); its summaries go to $OUT.
  nsys profile --force-overwrite true --stats=true -o "$build/blade-10k" \
    "$build/igaBenchmark" --gpu --only blade-10008-deforming --json "$out/profiled.json" \
    > "$out/nsys.log" 2>&1 || echo "nsys: exit $?" >> "$out/nsys.log"
else
  echo "nsys: not installed" > "$out/nsys.log"
fi
exit "$failed"
