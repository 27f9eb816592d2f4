#!/usr/bin/env bash
# MPI overhead on one machine (docs/performance.md, "Distributed bakes"): the same bake as
# 2 ranks x 1 thread and as 1 process x 2 threads, alternating in one session, for a shadowed
# and an inter-reflected (2 bounces) bunny. Prints, per mode, each run's bake time (the bake's
# own secondsTotal: passes and exchanges, not loading or the BVH) and wall time (the whole
# command, mpirun's start-up included), the medians, and the parallel efficiency
# T(1 x 2 threads) / T(2 ranks x 1 thread), and the CPU time of both (on a machine shared with
# other work the wall times are noisy, the CPU times much less); then the bytes each pass
# exchanged and a model of 8 and 64 ranks.
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

run() {  # LAUNCH THREADS ARGS... -> "bake wall cpu" seconds (cpu: user + system, all processes)
  local launch=$1 threads=$2; shift 2
  local times
  times=$(python3 -c '
import resource, subprocess, sys, time
t = time.monotonic()
with open(sys.argv[1], "w") as err:
    subprocess.run(sys.argv[2:], stderr=err, check=True)
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print(f"{time.monotonic() - t:.3f} {r.ru_utime + r.ru_stime:.3f}")' "$tmp/err.txt" $launch "$prt" bake "$mesh" "$@" -j "$threads" -o "$tmp/out.glb")
  echo "$(bake_seconds "$tmp/err.txt") $times"
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
  cp "$tmp/err.txt" "$tmp/err-mpi.txt"
  run "" 2 "${args[@]}" > /dev/null  # once more in one process, for its per-pass seconds
  cp "$tmp/err.txt" "$tmp/err-one.txt"
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
print("  CPU seconds (all processes, loading and BVH included):", " ".join(f"{x[2]:.2f}" for x in one), "vs", " ".join(f"{x[2]:.2f}" for x in two))
e = mb(one, 0) / mb(two, 0)
ew = mb(one, 1) / mb(two, 1)
pairs = statistics.median(a[0] / b[0] for a, b in zip(one, two))
print(f"  medians: bake {mb(one,0):.3f} s vs {mb(two,0):.3f} s -> parallel efficiency {e:.3f} "
      f"(median of the pairs' ratios {pairs:.3f}); wall {mb(one,1):.2f} s vs {mb(two,1):.2f} s -> {ew:.3f}; "
      f"CPU {mb(one,2):.2f} s vs {mb(two,2):.2f} s -> {mb(one,2) / mb(two,2):.3f}")
PY
  echo "  last 2-rank run's passes:"; cat "$tmp/passes.txt"
  python3 - "$tmp/err-one.txt" "$tmp/err-mpi.txt" <<'PY'
# A model of the speed-up at N ranks of one thread each, from the measured per-pass work
# (the one-process run's pass seconds x 2 threads), chunks and exchanged bytes:
#   T(N) = sum over passes k of  W_k/N + c_k/2 + x_k(N),
#   c_k = W_k / C_k the mean chunk time (the last chunks leave ranks idle by about half a
#   chunk), x_k(N) = N broadcasts of log2(N) latencies a + (N-1)/N S_k / b received per rank
#   (all-gathered passes; the last one is gathered to rank 0: S_k / b at rank 0), and
#   2a per chunk handed out (C_k/N per rank).
# Loading and the BVH (every rank, at once) are left out: they do not shrink with N.
import math, re, sys
one, mpi = (open(f).read() for f in sys.argv[1:3])
m = re.search(r"^\w+: \d+ rays in [\d.]+ m?s \([^)]*\); direct ([\d.]+) (ms|s)(.*)$", one, re.M)
sec = lambda v, u: float(v) / (1000 if u == "ms" else 1)
passes = [sec(m.group(1), m.group(2))] + [sec(v, u) for v, u in re.findall(r"bounce \d+ ([\d.]+) (ms|s)", m.group(3))]
W = [2 * p for p in passes]
info = re.findall(r"pass \d+ '[^']*': (\d+) chunks .*?the pass's (\d+) B", mpi)
C = [int(c) for c, _ in info]
S = [int(b) for _, b in info]
for name, a, b in (("InfiniBand (a = 2 us, b = 10 GB/s)", 2e-6, 10e9), ("10 GbE TCP (a = 30 us, b = 1 GB/s)", 30e-6, 1e9)):
    t1 = sum(W)
    out = []
    for N in (2, 8, 64):
        t = 0
        for k, (w, c, s) in enumerate(zip(W, C, S)):
            last = k == len(W) - 1
            x = (s / b) if last else (N * math.log2(N) * a + (N - 1) / N * s / b)
            t += w / N + (w / c) / 2 + x + (c / N) * 2 * a
        out.append(f"N={N}: {t1 / t:.1f}x ({t1 / t / N:.2f} efficiency)")
    print(f"  model, {name}: one rank {t1:.2f} s of work; " + "; ".join(out))
PY
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
