#!/usr/bin/env bash
# Builds the libFuzzer targets with clang, AddressSanitizer and UBSan in ./build-fuzz (override
# with FUZZ_BUILD_DIR) and runs each, seeded from Data/ and ../shared/data, for SECONDS
# (default 60) or, with RUNS set, that many executions. Corpora grow in the build directory;
# a crash leaves its input there (crash-*) and fails the script.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FUZZ_BUILD_DIR:-$root/build-fuzz}"
seconds="${1:-60}"
flags="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize=vptr -fno-omit-frame-pointer"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DBUILD_TESTING=OFF -DIGAVIEW_FUZZ=ON -DIGAVIEW_ENABLE_CUDA=OFF \
  "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_C_FLAGS=$flags" >/dev/null
targets=(igaFuzzVTU igaFuzzGismo igaFuzzGeoPDEs igaFuzzMFEM igaFuzzSeries igaFuzzEngine igaFuzzCsg
  igaFuzzAlgebraic)
cmake --build "$build" -j "$(nproc)" --target "${targets[@]}"

shared="$root/../shared/data"
seed() { # corpus directory, then seed files (missing ones skipped)
  local corpus="$1"
  shift
  mkdir -p "$corpus"
  for f in "$@"; do
    [ -f "$f" ] && cp -n "$f" "$corpus/" || true
  done
}
seed "$build/corpus/vtu" "$root"/Data/*.vtu "$root"/Testing/Fuzz/regressions/*.vtu
seed "$build/corpus/gismo" "$root"/Data/gismo_*.xml "$root"/Testing/Fuzz/gismo/*.xml "$shared"/gismo/*.xml
seed "$build/corpus/geopdes" "$root"/Data/geopdes_*.txt "$shared"/geopdes/*.txt
seed "$build/corpus/mfem" "$root"/Data/mfem_*.mesh "$root"/Data/mfem_*.gf "$root"/Testing/Data/mfem/*.mesh \
  "$shared"/mfem/*.mesh
seed "$build/corpus/series" "$root"/Testing/Fuzz/series/*.pvd
seed "$build/corpus/engine" "$root"/Testing/Fuzz/engine/*
seed "$build/corpus/csg" "$root"/Testing/Fuzz/csg/*.txt
seed "$build/corpus/algebraic" "$root"/Testing/Fuzz/algebraic/*.txt

# UBSan findings are errors; leaks of VTK's singletons at exit are not ours to judge.
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export ASAN_OPTIONS="detect_leaks=0"
# A fixed seed makes a short run (CI's) repeat itself; FUZZ_SEED=0 draws one.
limit=(-max_total_time="$seconds" -seed="${FUZZ_SEED:-1}")
if [ -n "${RUNS:-}" ]; then
  limit=(-runs="$RUNS" -seed="${FUZZ_SEED:-1}")
fi
run() { # target, corpus, dictionary (optional)
  local dict=() status=0
  [ -n "${3:-}" ] && dict=(-dict="$3")
  echo "fuzz: $1 on $2"
  (cd "$build" && "./bin/$1" "${limit[@]}" -rss_limit_mb=2048 -timeout=30 -max_len=65536 \
    -print_final_stats=1 "${dict[@]}" "$2" >"$build/$1.log" 2>&1) || status=$?
  grep -E "^stat::(number_of_executed_units|peak_rss_mb)|^#[0-9]+ +DONE" "$build/$1.log" || true
  if [ "$status" -ne 0 ]; then
    tail -n 80 "$build/$1.log" >&2
    echo "fuzz: $1 failed (exit $status); its input and log are in $build" >&2
    exit 1
  fi
}
run igaFuzzVTU "$build/corpus/vtu" "$root/Testing/Fuzz/xml.dict"
run igaFuzzGismo "$build/corpus/gismo" "$root/Testing/Fuzz/xml.dict"
run igaFuzzGeoPDEs "$build/corpus/geopdes" "$root/Testing/Fuzz/geopdes.dict"
run igaFuzzMFEM "$build/corpus/mfem" "$root/Testing/Fuzz/mfem.dict"
run igaFuzzSeries "$build/corpus/series" "$root/Testing/Fuzz/xml.dict"
run igaFuzzEngine "$build/corpus/engine"
run igaFuzzCsg "$build/corpus/csg" "$root/Testing/Fuzz/csg.dict"
run igaFuzzAlgebraic "$build/corpus/algebraic"
