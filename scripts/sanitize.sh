#!/usr/bin/env bash
# Builds the library, the command line and the tests with AddressSanitizer and
# UndefinedBehaviorSanitizer into build-asan/ and runs the suite there (the viewer and the
# benchmarks are left out). Slow (~15 minutes on 2 cores), so it is a developer check, not CI's.
# Usage: scripts/sanitize.sh [ctest args]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
flags="-fsanitize=address,undefined -fno-omit-frame-pointer"
cmake -S "$root" -B "$root/build-asan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPRT_BUILD_BENCH=OFF -DPRT_BUILD_VIEWER=OFF \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" >/dev/null
cmake --build "$root/build-asan" -j "$(nproc 2>/dev/null || echo 2)"
cd "$root/build-asan"
# The install test builds an outside project without the sanitizer runtime: skipped here.
# allocator_may_return_null: a refused huge allocation throws std::bad_alloc as in a normal
# build (the hardening tests check that it becomes one short line) instead of aborting.
ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" --timeout 900 -E install "$@"
