#!/usr/bin/env bash
# Per-pixel relighting cost in the desktop viewer (issue 18; docs/performance.md, "Per-pixel
# relighting"): the frame time of prt view drawing per-texel transfer (relit per pixel in the
# fragment shader: four texel rows fetched and relit, then blended) against per-vertex transfer
# of the same scene (relit per vertex), at the same window size, interleaved in rounds so that
# the machine's load falls on every configuration alike. Headless (EGL, no X): on a machine
# without a GPU that is Mesa's llvmpipe, a CPU rasteriser, and the figures are its — a GPU's
# would be orders of magnitude shorter. Not a test (not in ctest).
#
# Usage: scripts/texel_relight_cost.sh [PRT] [OUTDIR] [SIZE] [FRAMES] [ROUNDS]
#   PRT     the prt binary (default build/prt)      OUTDIR  scratch folder (default a temp dir)
#   SIZE    the window, WxH (default 1024x1024)     FRAMES  frames per run (default 20)
#   ROUNDS  interleaved rounds (default 2)
# The bakes (a few seconds each on 2 cores): the builtin Cornell box, shadowed, 3 bands, scalar,
# 16 samples — per vertex, per texel over 1024² (1M texels, 36 MB of rows, 48 B per texel
# packed), the same compressed (CPCA K 16, N 3: 16 B per texel), per texel over 256², and RGB
# inter-reflected per texel over 512² (144 B per texel packed).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
prt=$(realpath "${1:-$root/build/prt}")
out=${2:-$(mktemp -d)}
size=${3:-1024x1024}
frames=${4:-20}
rounds=${5:-2}
mkdir -p "$out"
cd "$out"
scene='builtin:cornell?grid=8'
common=(-q bake "$scene" --bands 3 --samples 16)
[[ -f vertex.glb ]] || "$prt" "${common[@]}" --mode shadowed -o vertex.glb
[[ -f texels1024.glb ]] ||
  "$prt" "${common[@]}" --mode shadowed --domain texels --resolution 1024 -o texels1024.glb
[[ -f texels1024-cpca.glb ]] ||
  "$prt" -q compress texels1024.glb --clusters 16 --pca 3 -o texels1024-cpca.glb
[[ -f texels256.glb ]] ||
  "$prt" "${common[@]}" --mode shadowed --domain texels --resolution 256 -o texels256.glb
[[ -f texels512-rgb.glb ]] ||
  "$prt" "${common[@]}" --mode interreflected --domain texels --resolution 512 -o texels512-rgb.glb

# The median frame time (draw + glFinish) of one run, in ms.
frame() {
  "$prt" view "$1" --headless --size "$size" --frames "$frames" --stats |
    sed -n 's/^frame time (draw + glFinish): median \([0-9.]*\) ms.*/\1/p'
}
echo "prt view --headless --size $size --frames $frames --stats: median frame (draw + glFinish), ms"
echo "renderer: $("$prt" view vertex.glb --headless --size 64x64 --stats | sed -n 's/^renderer: //p')"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-8s %10s %12s %12s %12s %12s\n' round vertex texels1024 cpca1024 texels256 rgb512
for r in $(seq 1 "$rounds"); do
  printf '%-8s %10s %12s %12s %12s %12s\n' "$r" "$(frame vertex.glb)" "$(frame texels1024.glb)" \
    "$(frame texels1024-cpca.glb)" "$(frame texels256.glb)" "$(frame texels512-rgb.glb)"
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
