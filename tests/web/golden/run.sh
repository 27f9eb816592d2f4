#!/bin/sh
# ctest web.GoldenVectors: run.sh HELPER NODE GENDIR WORKDIR — the library's outputs
# (prt_web_golden) against the page's JS (check.mjs) on the same inputs. Exits 77 (skipped,
# saying why) without node, web/node_modules or the generated constants (CMake makes them with
# the page: ninja prt_web_assets).
helper=$1 node=$2 gen=$3 work=$4
here=$(dirname "$0")
if [ -z "$node" ] || ! command -v "$node" >/dev/null 2>&1; then
  echo "skipped: no node here (apt-get install nodejs)"; exit 77
fi
if [ ! -f "$here/../../../web/node_modules/three/package.json" ]; then
  echo "skipped: web/node_modules missing (run scripts/setup.sh)"; exit 77
fi
if [ ! -f "$gen/constants.js" ]; then
  echo "skipped: $gen/constants.js missing (build the page: ninja prt_web_assets)"; exit 77
fi
rm -rf "$work" && mkdir -p "$work" || exit 1
"$helper" "$work" || exit 1
exec "$node" "$here/check.mjs" "$work/golden.json" "$gen"
