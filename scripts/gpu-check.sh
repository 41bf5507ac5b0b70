#!/usr/bin/env bash
# On a GPU machine without VTK (the device tool's machines): build the VTK-free Kernels with
# CUDA, run the GPU tests (CUDA engine against the CPU engine) and the GPU benchmark.
# GoogleTest sources must be in .deps/googletest (git-ignored; copy /usr/src/googletest there
# and pass .deps through the device tool's `carry`). Results go to $OUT (or ./gpu-results).
#
#   mkdir -p .deps && cp -r /usr/src/googletest .deps/     # once, on the development machine
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
(cd "$build" && ctest -L "gpu|engine" --output-on-failure) 2>&1 | tee "$out/ctest.log"
"$build/igaBenchmark" --gpu "$@" --json "$out/benchmark-gpu.json" 2>&1 | tee "$out/benchmark.log"
