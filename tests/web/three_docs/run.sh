#!/bin/sh
# ctest web.ThreeDocsFirstApp: run.sh PRT NODE BUILD WORKDIR — docs/three.md's first app as a
# reader makes it, in a fresh folder: the doc's named code blocks (doc_blocks.mjs: its install
# and bundle commands, index.html with the import map, bundled.html, main.js) run and written as
# they stand, the one change being /path/to/prtkit/build → BUILD. Offline: npm's registry is
# server.mjs, which serves three.js packed from web/node_modules (the doc's `npm install three`
# as written), and the pages over http (probe.js injected). Then each page — the import map's
# and the esbuild bundle's — in headless Chromium must draw the bake (≥ 2 % of the canvas lit,
# not one flat colour) with no error at all. Exits 77 (skipped, saying why) without node, npm,
# chromium, web/node_modules or the built package.
prt=$1 node=$2 build=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../../.." && pwd)
web="$src/web/node_modules"
skip() { echo "skipped: $*"; exit 77; }
[ -n "$node" ] && command -v "$node" >/dev/null 2>&1 || skip "no node here (apt-get install nodejs)"
command -v npm >/dev/null 2>&1 || skip "no npm here (apt-get install npm)"
chromium=${PRT_CHROMIUM:-}
for c in chromium chromium-browser google-chrome; do
  [ -n "$chromium" ] && break
  command -v "$c" >/dev/null 2>&1 && chromium=$c
done
[ -n "$chromium" ] || skip "no chromium here (apt-get install chromium)"
[ -f "$web/three/package.json" ] && [ -x "$web/.bin/esbuild" ] || skip "web/node_modules missing (run scripts/setup.sh)"
[ -f "$build/web/three/prtkit-three.js" ] || skip "$build/web/three/prtkit-three.js is not built (ninja prt_web_assets)"

rm -rf "$work" && mkdir -p "$work/app" || exit 1
work=$(cd "$work" && pwd)
app="$work/app"
doc=${PRT_THREE_DOC:-$src/docs/three.md}   # another copy of the doc, to check the check
"$node" "$here/doc_blocks.mjs" "$doc" "$app" > "$work/blocks.txt" || exit 1
for f in install.sh bundle.sh index.html bundled.html main.js; do
  grep -qx "$f" "$work/blocks.txt" || { echo "FAIL: docs/three.md has no block named ${f%.sh}"; exit 1; }
done

# The files main.js loads, as its comments say: a bake and a light.
"$prt" -q bake 'builtin:sphere-plane?subdiv=2' --mode interreflected --bands 3 --samples 16 \
  -o "$app/bunny.glb" || exit 1
"$prt" -q light builtin:sky --bands 3 -o "$app/sky.json" || exit 1

"$node" "$here/server.mjs" "$app" "$work/tarballs" "$work/port" "$web/three" "$web/esbuild" "$web"/@esbuild/* > "$work/server.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null' EXIT
i=0
while [ ! -s "$work/port" ]; do
  i=$((i + 1)); [ $i -gt 300 ] && { echo "FAIL: the local server did not start"; cat "$work/server.log"; exit 1; }
  kill -0 $server 2>/dev/null || { echo "FAIL: the local server stopped"; cat "$work/server.log"; exit 1; }
  sleep 0.1
done
port=$(cat "$work/port")

# npm as a reader's, but offline: the local registry (three and esbuild with its binary for
# this platform, from web/node_modules), a fresh cache, no user config.
: > "$work/npmrc"
export npm_config_registry="http://127.0.0.1:$port/" npm_config_cache="$work/npm-cache" \
  npm_config_userconfig="$work/npmrc" npm_config_audit=false npm_config_fund=false \
  npm_config_update_notifier=false npm_config_yes=true
cd "$app" || exit 1
for step in install bundle; do
  echo "--- docs/three.md, $step:"
  sed "s#/path/to/prtkit/build#$build#g" "$step.sh" | tee "$work/$step.run"
  sh -e "$work/$step.run" > "$work/$step.log" 2>&1 || { cat "$work/$step.log"; echo "FAIL: the doc's $step commands failed"; exit 1; }
done

# The check checked: the import map without its three/addons/ line must be caught (the module
# stops at that import: a blank page).
grep -v '"three/addons/"' index.html > no-addons.html
failures=0
for page in index.html bundled.html no-addons.html; do
  profile="$work/profile-$page"
  timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --use-angle=swiftshader --enable-unsafe-swiftshader --user-data-dir="$profile" \
    --window-size=480,360 --virtual-time-budget=60000 --dump-dom \
    "http://127.0.0.1:$port/$page" > "$work/$page.dom" 2> "$work/$page.log"
  "$node" -e '
    const dom = require("fs").readFileSync(process.argv[1], "utf8"), page = process.argv[2];
    const m = /<pre id="prt-test">([^<]*)<\/pre>/.exec(dom);
    if (!m) { console.log(`FAIL: ${page}: the page never reported (no #prt-test)`); process.exit(1); }
    const r = JSON.parse(m[1].replace(/&quot;/g, "\"").replace(/&lt;/g, "<").replace(/&gt;/g, ">").replace(/&amp;/g, "&"));
    console.log(`${page}: ${JSON.stringify(r)}`);
    const bad = [];
    if (r.errors.length) bad.push(`errors: ${r.errors.join(" | ")}`);
    if (!r.canvas) bad.push("no canvas on the page");
    else if (!(r.lit > 0.02 && r.colours > 8)) bad.push(`the canvas is blank (${(100 * (r.lit || 0)).toFixed(2)} % lit, ${r.colours} colours)`);
    if (bad.length) { console.log(`FAIL: ${page}: ${bad.join("; ")}`); process.exit(1); }
  ' "$work/$page.dom" "$page"
  ok=$?
  if [ "$page" = no-addons.html ]; then
    [ $ok -ne 0 ] && echo "(as it must: without three/addons/ the page is caught)" ||
      { echo "FAIL: an import map without three/addons/ passed the check"; failures=$((failures + 1)); }
  elif [ $ok -ne 0 ]; then
    failures=$((failures + 1))
  fi
done
[ $failures -eq 0 ] || exit 1
echo "docs/three.md's first app: installed, bundled and drawn (import map and bundle), no errors"
