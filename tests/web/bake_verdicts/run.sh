#!/bin/sh
# ctest web.BakeVerdicts: run.sh PRT NODE GENDIR WORKDIR CORPUS — one corpus of bakes, valid and
# malformed, through prt's reader (prt web) and the JS readers (the page's parseBake and
# prtkit-three's plugin, under node from their sources; verdicts.mjs): the same accept/refuse
# verdict for every file, every JS refusal one line naming the file. The corpus: the fuzz seeds
# in CORPUS (fuzz/corpus/bake) and the mutations make_cases.mjs writes of four small bakes made
# here (vertex and per-texel transfer, dense and CPCA, a probe grid, dense and CPCA, and Haar
# transfer per vertex, per texel, over a cube finer than the viewers take, and inter-reflected). Exits 77 (skipped, saying why) without node, web/node_modules or the generated constants.
prt=$1 node=$2 gen=$3 work=$4 corpus=$5
here=$(cd "$(dirname "$0")" && pwd)
if [ -z "$node" ] || ! command -v "$node" >/dev/null 2>&1; then
  echo "skipped: no node here (apt-get install nodejs)"; exit 77
fi
if [ ! -f "$here/../../../web/node_modules/three/package.json" ]; then
  echo "skipped: web/node_modules missing (run scripts/setup.sh)"; exit 77
fi
if [ ! -f "$gen/constants.js" ] || [ ! -d "$gen/three-shaders" ]; then
  echo "skipped: $gen/constants.js or three-shaders missing (build the page: ninja prt_web_assets)"; exit 77
fi
rm -rf "$work" && mkdir -p "$work/cases" || exit 1
cd "$work" || exit 1
"$prt" -q bake 'builtin:cornell?grid=2' --mode shadowed --mode interreflected --bands 2 --samples 4 \
  -o vertex.glb || exit 1
"$prt" -q compress vertex.glb --clusters 4 --pca 2 -o cpca.glb >/dev/null || exit 1
"$prt" -q bake 'builtin:cornell?grid=2' --mode shadowed --bands 2 --samples 4 --domain texels \
  --resolution 8 -o texel.glb || exit 1
"$prt" -q compress texel.glb --clusters 4 --pca 2 -o texel-cpca.glb >/dev/null || exit 1
"$prt" -q probes 'builtin:cornell?grid=2' --grid 2x2x2 --bands 2 --samples 4 -o probes.glb || exit 1
"$prt" -q compress probes.glb --clusters 2 --pca 1 -o probes-cpca.glb >/dev/null || exit 1
"$prt" -q bake 'builtin:cornell?grid=2' --mode shadowed --basis haar --resolution 4 --terms 8 -o haar.glb || exit 1
"$prt" -q bake 'builtin:cornell?grid=2' --mode shadowed --basis haar --domain texels --resolution 8 \
  --cube-resolution 4 --terms 8 -o haar-texel.glb || exit 1
"$prt" -q bake 'builtin:cornell?grid=2' --mode unshadowed --basis haar --resolution 128 --terms 4 \
  -o haar-128.glb || exit 1
"$prt" -q bake 'builtin:cornell?grid=2' --mode interreflected --bounces 1 --basis haar --resolution 4 \
  --terms 8 --bands 2 -o haar-ir.glb || exit 1
"$node" "$here/make_cases.mjs" cases vertex.glb texel.glb cpca.glb texel-cpca.glb probes.glb probes-cpca.glb \
  haar.glb haar-texel.glb haar-128.glb haar-ir.glb || exit 1
exec "$node" "$here/verdicts.mjs" "$prt" "$gen" "$work" "$corpus"/*.glb cases/*.glb
