#!/bin/sh
# ctest web.ThreeModuleUnderNode: run.sh PRT NODE PACKAGE WORKDIR — the built prtkit-three
# package (PACKAGE = build/web/three) imported by name under node as an app imports it, with
# three.js from web/node_modules, against prt's own files (module_check.mjs; lightmap_check.mjs
# for the relit lightmaps exported as glTF). Exits 77 (skipped,
# saying why) without node, web/node_modules or the built package.
prt=$1 node=$2 pkg=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
three="$here/../../../web/node_modules/three"
if [ -z "$node" ] || ! command -v "$node" >/dev/null 2>&1; then
  echo "skipped: no node here (apt-get install nodejs)"; exit 77
fi
if [ ! -f "$three/package.json" ]; then
  echo "skipped: web/node_modules missing (run scripts/setup.sh)"; exit 77
fi
if [ ! -f "$pkg/prtkit-three.js" ]; then
  echo "skipped: $pkg/prtkit-three.js is not built (ninja prt_web_assets)"; exit 77
fi
rm -rf "$work" && mkdir -p "$work/node_modules" || exit 1
# The package copied as npm install copies it; three.js linked (node resolves a linked
# package's own imports from where it really is).
mkdir "$work/node_modules/prtkit-three" || exit 1
cp "$pkg/package.json" "$pkg/prtkit-three.js" "$pkg/README.md" "$work/node_modules/prtkit-three/" || exit 1
ln -s "$(cd "$three" && pwd)" "$work/node_modules/three" || exit 1
cp "$here/module_check.mjs" "$here/lightmap_check.mjs" "$work/" || exit 1
cd "$work" || exit 1
"$prt" -q bake 'builtin:cornell?grid=6' --mode shadowed --mode interreflected --bands 3 \
  --samples 16 -o cornell.glb || exit 1
"$prt" -q probes 'builtin:cornell?grid=6' --grid 3x2x2 --bands 3 --samples 16 -o probes.glb || exit 1
"$prt" -q light builtin:sky --bands 3 -o sky.json || exit 1
"$prt" -q light builtin:sky --bands 3 --rotate 30,-50,20 -o sky-turned.json || exit 1
"$prt" -q light builtin:sky --bands 3 --format threejs -o sky-three.json || exit 1
"$prt" -q light builtin:sky --bands 2 -o sky2.json || exit 1
"$prt" -q bake 'builtin:cornell?grid=6' --mode shadowed --basis haar --resolution 4 --terms 8 \
  -o haar.glb || exit 1
"$prt" -q light builtin:sky --basis haar --resolution 4 --terms 8 -o haar-sky.json || exit 1
"$prt" -q light builtin:sky --basis haar --resolution 8 --terms 8 -o haar-sky8.json || exit 1
"$prt" -q bake 'builtin:cornell?grid=6' --mode interreflected --domain texels --resolution 16 \
  --transfer matrix --bands 3 --samples 16 -o texels.glb || exit 1
"$prt" -q export texels.glb --format lightmap -o lm.glb || exit 1
"$prt" -q export texels.glb --format lightmap-sh --encoding l1 -o lm-l1.glb || exit 1
"$prt" -q export texels.glb --format lightmap-sh --encoding l2 -o lm-l2.glb || exit 1
"$node" module_check.mjs || exit 1
exec "$node" lightmap_check.mjs
