#!/usr/bin/env bash
# On a GPU machine without VTK (the device tool's machines): build the VTK-free Kernels with
# CUDA, run the GPU tests (CUDA engine against the CPU engine) and the GPU benchmark, then, where
# the CUDA toolkit has them, compute-sanitizer's memcheck over the GPU tests and an Nsight
# Systems profile of the deforming 10k blade. Results go to $OUT (or ./gpu-results).
#
# Device time is scarce (one call, minutes), so every phase runs under a share of one deadline
# (GPU_CHECK_SECONDS, default 540) and leaves its log in $OUT even when it times out;
# phases.txt lists each phase's exit status and seconds. A failure is remembered, not fatal:
# the checks after a failing test matter most. The build keeps to the targets run here.
#
# GoogleTest sources must be in .deps/googletest and GLM's headers in .deps/glm (git-ignored;
# copy them there and pass .deps through the device tool's `carry`):
#   mkdir -p .deps && cp -r /usr/src/googletest /usr/include/glm .deps/   # once, here
#   scripts/gpu-check.sh [--quick]        # the options go to igaBenchmark --gpu
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${OUT:-$root/gpu-results}"
build="${BUILD_DIR:-$root/build-gpu}"
deadline=$((SECONDS + ${GPU_CHECK_SECONDS:-540}))
export PATH="$PATH:/usr/local/cuda/bin"
mkdir -p "$out"
rm -f "$out"/*.log
failed=0

# phase NAME LIMIT COMMAND...: COMMAND's output appended to $out/NAME.log (or $out/$log.log when
# `log` is set), run for at most LIMIT seconds and never past the deadline; its status and time
# appended to phases.txt.
phase()
{
  local name="$1" limit="$2" file="$out/${log:-$1}.log"
  shift 2
  local left=$((deadline - SECONDS))
  ((left < limit)) && limit=$left
  if ((limit < 5)); then
    echo "$name skipped: deadline reached" | tee -a "$out/phases.txt"
    failed=1
    return 1
  fi
  local start=$SECONDS status=0
  timeout --kill-after=5 "$limit" "$@" >> "$file" 2>&1 || status=$?
  echo "$name exit $status after $((SECONDS - start)) s (limit $limit s)" | tee -a "$out/phases.txt"
  ((status == 0)) || failed=1
  return "$status"
}

# The device tool brings back few files: the device goes at the top of phases.txt, the
# configure step's output into build.log.
nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv \
  > "$out/phases.txt" 2>&1 || true
log=build phase configure 60 cmake -S "$root/Kernels" -B "$build" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES="${CUDA_ARCHITECTURES:-90}" || exit 1
phase build 300 cmake --build "$build" -j "$(nproc)" --target igaBenchmark igaCudaEngineTests \
  igaKernelsCudaTests || { tail -50 "$out/build.log"; exit 1; }
# Registers, stack and shared memory of every kernel (what limits occupancy), a line each.
if command -v cuobjdump > /dev/null; then
  cuobjdump --dump-resource-usage "$build/CMakeFiles/igaEngine.dir/src/CudaEngine.cu.o" 2>&1 |
    grep -E "Function|REG" | sed -E 's/^[[:space:]]+//' | paste - - | sort -u \
    > "$out/resource-usage.txt" || true
fi
phase gpu-tests 200 ctest --test-dir "$build" -L cuda -j 4 --no-tests=error --output-on-failure
tail -3 "$out/gpu-tests.log"
phase benchmark 200 "$build/igaBenchmark" --gpu "$@" --json "$out/benchmark-gpu.json"
if command -v compute-sanitizer > /dev/null; then
  phase memcheck 150 compute-sanitizer --tool memcheck --error-exitcode 99 \
    "$build/Testing/igaCudaEngineTests"
  tail -3 "$out/memcheck.log"
else
  echo "memcheck skipped: compute-sanitizer not installed" | tee -a "$out/phases.txt"
fi
if command -v nsys > /dev/null; then
  # The report stays in the build folder (large); its summaries go to $OUT.
  phase nsys 90 nsys profile --force-overwrite true --stats=true -o "$build/blade-10k" \
    "$build/igaBenchmark" --gpu --only blade-10008-deforming --json "$out/profiled.json"
else
  echo "nsys skipped: not installed" | tee -a "$out/phases.txt"
fi
cat "$out/phases.txt"
exit "$failed"
