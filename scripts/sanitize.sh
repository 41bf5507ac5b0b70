#!/usr/bin/env bash
# Builds the VTK-free Kernels (math, engine) and their unit tests with AddressSanitizer and UBSan
# in ./build-sanitize (override with SANITIZE_BUILD_DIR) and runs them.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SANITIZE_BUILD_DIR:-$root/build-sanitize}"
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# Without the device driver's Thrust host build: Thrust's own headers bind a reference to null
# (thrust/detail/reference.h) under UBSan. The loop it runs is the CPU driver's, tested here.
cmake -S "$root/Kernels" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DIGAVIEW_ENABLE_CUDA=OFF "-DCMAKE_IGNORE_PATH=/usr/local/cuda/include/cccl;/usr/local/cuda/include" \
  "-DCMAKE_CXX_FLAGS=$flags" >/dev/null
cmake --build "$build" -j "$(nproc)"
cd "$build"
ASAN_OPTIONS="detect_leaks=1" UBSAN_OPTIONS="print_stacktrace=1" \
  ctest --output-on-failure -j "$(nproc)"
