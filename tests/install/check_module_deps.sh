#!/usr/bin/env bash
# The architecture's rule, checked on the build's own dependency graph (cmake --graphviz): the
# modules that read, hold and relight transfer — prt_transfer, prt_relight, prt_io — reach
# neither the ray tracer (embree, prt_raytrace), nor the bake (prt_transport), nor the CPCA
# fitting (prt_compress), directly or transitively; and no header under include/prt/transfer,
# include/prt/relight or include/prt/io includes raytrace/.
# Usage: check_module_deps.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --graphviz="$tmp/deps.dot" "$build" > /dev/null
status=0
for module in prt_transfer prt_relight prt_io; do
  # Breadth-first over the edges "nodeA" -> "nodeB" from the module's node.
  reached=$(awk -v start="$module" '
    /\[ label = / {
      id = $1; gsub(/"/, "", id)
      lbl = $0; sub(/.*label = "/, "", lbl); sub(/(\\n|").*/, "", lbl)
      name[id] = lbl
      if (lbl == start) root = id
    }
    / -> / {
      a = $1; b = $3; gsub(/"/, "", a); gsub(/"/, "", b)
      edges[a] = edges[a] " " b
    }
    END {
      if (root == "") { print "MISSING"; exit }
      queue[0] = root; seen[root] = 1; head = 0; tail = 1
      while (head < tail) {
        n = queue[head++]
        split(edges[n], next_, " ")
        for (k in next_) if (next_[k] != "" && !seen[next_[k]]) {
          seen[next_[k]] = 1; queue[tail++] = next_[k]
        }
      }
      for (n in seen) if (n != root) print name[n]
    }' "$tmp/deps.dot")
  if [[ "$reached" == "MISSING" ]]; then
    echo "$module: not in the dependency graph" >&2
    status=1
    continue
  fi
  for forbidden in embree prt_raytrace prt_transport prt_compress Eigen3::Eigen; do
    if grep -qx "$forbidden" <<< "$reached"; then
      echo "$module reaches $forbidden (it must not: docs/architecture.md)" >&2
      status=1
    fi
  done
done
if grep -rn '#include "prt/raytrace/' "$src/include/prt/transfer" "$src/include/prt/relight" \
     "$src/include/prt/io"; then
  echo "a header of transfer, relight or io includes the ray tracer" >&2
  status=1
fi
[[ $status -eq 0 ]] && echo "prt_transfer, prt_relight and prt_io reach no ray tracer, bake or CPCA fitting"
exit $status
