#!/usr/bin/env bash
# The main job on a default scene: installs what it needs (Debian packages, plus the Stanford
# bunny from glmark2-data and CC0 Poly Haven environments from blender-data), builds prtkit, then
# bakes, relights, renders and validates into demo-out/ (open demo-out/index.html).
# Usage: scripts/demo.sh [prt demo options]   e.g. scripts/demo.sh --env studio.exr -o out
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh" --with-assets
"$root/scripts/build.sh"
cd "$root"
args=("$@")
if [[ " ${args[*]-} " != *" -o "* && " ${args[*]-} " != *" --output "* ]]; then args+=(-o demo-out); fi
"$root/build/prt" demo "${args[@]}"
echo "demo: prt is $root/build/prt; for the README's tour put it on PATH:" \
     "export PATH=\"$root/build:\$PATH\" (or cmake --install build)" >&2
