#!/bin/sh
# Builds the libFuzzer targets of the particle-file parsers with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer, and runs each for a fixed number of inputs from the seeds in
# tests/fuzz/corpus/. Exit status non-zero on any crash, leak, sanitizer report or timeout.
#   tests/fuzz/run_fuzzers.sh BUILD_DIR [RUNS]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$1
runs=${2:-200000}
clangxx=$(command -v clang++ || command -v clang++-14 || true)
if [ -z "$clangxx" ]; then
  echo "clang++ not found (Debian packages clang and libclang-rt-14-dev; scripts/test installs them)" >&2
  exit 1
fi
mkdir -p "$build"
for target in dump ss gzip; do
  exe="$build/fuzz_$target"
  echo "== building fuzz_$target"
  "$clangxx" -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -I "$root/Solvers" "$root/Solvers/io/DumpColumns.cpp" "$root/Solvers/io/DumpIndex.cpp" \
    "$root/Solvers/io/DumpRowParser.cpp" "$root/Solvers/io/DumpWriter.cpp" \
    "$root/Solvers/io/PkdgravSs.cpp" \
    "$root/Solvers/io/FileBytes.cpp" "$root/Solvers/common/ParticleSet.cpp" \
    "$here/fuzz_$target.cpp" -lz -o "$exe"
  work="$build/corpus_$target"
  rm -rf "$work"
  mkdir -p "$work"
  cp "$here/corpus/$target/"* "$work/"
  echo "== running fuzz_$target for $runs inputs"
  status=0
  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    "$exe" -runs="$runs" -seed=1 -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$build/crash_${target}_" "$work" > "$build/fuzz_$target.log" 2>&1 || status=$?
  if [ "$status" -ne 0 ]; then
    cat "$build/fuzz_$target.log"
    echo "fuzz_$target found a problem (exit $status); the input is in $build/crash_${target}_*" >&2
    exit 1
  fi
  tail -n 1 "$build/fuzz_$target.log"
done
echo "all fuzz targets ran $runs inputs without a finding"
