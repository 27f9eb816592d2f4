#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang-14, ASan + UBSan + coverage) into build-fuzz/, writes
# their seed corpora, and runs every target for SECONDS (default 20) one after another. Stops at
# the first finding (the crashing input is left in build-fuzz/findings/TARGET/) and exits non-zero.
#
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]     (targets: hdr exr ldr obj ply off gltf bake
#                                                   light_json haar_light_json light_txt transport_txt material reference_json)
# The growing corpora stay in build-fuzz/corpus/TARGET/, so later runs continue where earlier
# ones stopped; the committed regression inputs (fuzz/corpus/TARGET/) join the seeds. This is a
# separate check, not part of ctest (ctest replays the seeds and the regression inputs with the
# ordinary compiler, label fuzz-replay): see docs/robustness.md.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-20}
shift || true
all=(hdr exr ldr obj ply off gltf bake light_json haar_light_json light_txt transport_txt material reference_json)
[[ $# -gt 0 ]] && targets=("$@") || targets=("${all[@]}")
build="$root/build-fuzz"
jobs=${FUZZ_BUILD_JOBS:-2}

"$root/scripts/setup.sh" --with-fuzzing
cxx=${CXX_FUZZ:-clang++-14}
command -v "$cxx" >/dev/null || { echo "fuzz.sh: $cxx not found (apt-get install clang-14 libclang-rt-14-dev)" >&2; exit 2; }
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER="$cxx" "${launcher[@]}" -DPRT_BUILD_FUZZERS=ON -DPRT_BUILD_TESTS=OFF \
  -DPRT_BUILD_BENCH=OFF -DPRT_BUILD_VIEWER=OFF >/dev/null
nice -n 10 ninja -C "$build" -j "$jobs" make_seeds $(printf 'fuzz_%s ' "${targets[@]}")

# Seeds: tiny files from our own writers (make_seeds: images, meshes, lights, transport, bakes in
# every representation, material specs), plus the committed regression inputs.
seeds="$build/seeds"
rm -rf "$seeds"
ASAN_OPTIONS=detect_leaks=0 "$build/fuzz/make_seeds" "$seeds"
for t in "${targets[@]}"; do
  [[ -d "$root/fuzz/corpus/$t" ]] && cp "$root/fuzz/corpus/$t"/* "$seeds/$t/"
done

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0:malloc_limit_mb=2048}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
status=0
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  findings="$build/findings/$t"
  mkdir -p "$corpus" "$findings"
  echo "fuzz.sh: $t for ${seconds}s"
  # -rss_limit_mb / -malloc_limit_mb: an input that makes us allocate more than this is a finding
  # (the limits in fuzz_common.hpp keep legal inputs far below it). -timeout: a hang is a finding.
  if ! nice -n 10 "$build/fuzz/fuzz_$t" "$corpus" "$seeds/$t" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=65536 \
      -artifact_prefix="$findings/" -print_final_stats=1 >"$build/fuzz_$t.log" 2>&1; then
    echo "fuzz.sh: $t FOUND A PROBLEM: see $build/fuzz_$t.log and $findings/" >&2
    tail -n 30 "$build/fuzz_$t.log" >&2
    status=1
    break
  fi
  grep -E "stat::number_of_executed_units|cov:" "$build/fuzz_$t.log" | tail -n 2 || true
done
exit $status
