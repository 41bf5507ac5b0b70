#!/usr/bin/env bash
# Configures and builds IGAView in ./build (override with BUILD_DIR). CUDA sources are compiled
# when nvcc is found (also in /usr/local/cuda/bin); set CUDA_ARCHITECTURES to override 90.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
args=(-G Ninja -DCMAKE_BUILD_TYPE=Release)
if [ -n "${CUDA_ARCHITECTURES:-}" ]; then
  args+=("-DCMAKE_CUDA_ARCHITECTURES=$CUDA_ARCHITECTURES")
fi
cmake -S "$root" -B "$build" "${args[@]}" >/dev/null
cmake --build "$build" -j "$(nproc)"
