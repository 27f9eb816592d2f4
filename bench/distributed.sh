#!/usr/bin/env bash
# MPI overhead on one machine (docs/performance.md, "Distributed bakes"): the same bake as
# 2 ranks x 1 thread and as 1 process x 2 threads, alternating in one session, for a shadowed
# and an inter-reflected (2 bounces) bunny. Prints, per mode, each run's bake time (the bake's
# own secondsTotal: passes and exchanges, not loading or the BVH) and wall time (the whole
# command, mpirun's start-up included), the medians, and the parallel efficiency
# T(1 x 2 threads) / T(2 ranks x 1 thread); then the bytes each bounce pass exchanged.
# Usage: bench/distributed.sh [BUILD_DIR] [REPEATS]   (mpirun, Open MPI; as root it sets
# OMPI_ALLOW_RUN_AS_ROOT)
set -euo pipefail
build=${1:-build}
repeats=${2:-5}
prt=$(cd "$build" && pwd)/prt
mesh=${PRT_BENCH_MESH:-/usr/share/glmark2/models/bunny.obj}
[[ -f $mesh ]] || { echo "no $mesh (Debian: glmark2-data)" >&2; exit 1; }
command -v mpirun > /dev/null || { echo "mpirun not found (Debian: openmpi-bin)" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mpi="mpirun --oversubscribe --bind-to none -np 2"

bake_seconds() {  # the transfer's bake time from prt bake's report line "MODE: N rays in T"
  python3 - "$1" <<'PY'
import re, sys
t = re.findall(r"^\w+: \d+ rays in ([\d.]+) (ms|s)", open(sys.argv[1]).read(), re.M)
v, unit = t[-1]
print(float(v) / (1000 if unit == "ms" else 1))
PY
}

run() {  # LABEL LAUNCH THREADS ARGS... -> "bake wall" seconds
  local launch=$1 threads=$2; shift 2
  local start end
  start=$(date +%s.%N)
  $launch "$prt" bake "$mesh" "$@" -j "$threads" -o "$tmp/out.glb" 2> "$tmp/err.txt"
  end=$(date +%s.%N)
  echo "$(bake_seconds "$tmp/err.txt") $(echo "$end - $start" | bc)"
}

echo "machine: $(nproc) cores, $(uname -m); load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for mode in "shadowed --samples 1024" "interreflected --bounces 2 --samples 512"; do
  read -r -a args <<< "--mode $mode"
  one=() two=()
  for ((i = 0; i < repeats; i++)); do
    one+=("$(run "" 2 "${args[@]}")")
    two+=("$(run "$mpi" 1 "${args[@]}")")
  done
  grep -E "pass [0-9]+ '" "$tmp/err.txt" | sed 's/^/  /' > "$tmp/passes.txt" || true
  python3 - "$mode" "${one[@]}" -- "${two[@]}" <<'PY'
import statistics, sys
mode = sys.argv[1]
rest = sys.argv[2:]
cut = rest.index("--")
one = [tuple(map(float, r.split())) for r in rest[:cut]]
two = [tuple(map(float, r.split())) for r in rest[cut + 1:]]
mb = lambda xs, k: statistics.median(x[k] for x in xs)
print(f"\n{mode}")
print("  1 process x 2 threads, bake s:", " ".join(f"{x[0]:.2f}" for x in one), f"(wall {' '.join(f'{x[1]:.2f}' for x in one)})")
print("  2 ranks x 1 thread,    bake s:", " ".join(f"{x[0]:.2f}" for x in two), f"(wall {' '.join(f'{x[1]:.2f}' for x in two)})")
e = mb(one, 0) / mb(two, 0)
ew = mb(one, 1) / mb(two, 1)
pairs = statistics.median(a[0] / b[0] for a, b in zip(one, two))
print(f"  medians: bake {mb(one,0):.3f} s vs {mb(two,0):.3f} s -> parallel efficiency {e:.3f} "
      f"(median of the pairs' ratios {pairs:.3f}); wall {mb(one,1):.2f} s vs {mb(two,1):.2f} s -> {ew:.3f}")
PY
  echo "  last 2-rank run's passes:"; cat "$tmp/passes.txt"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
