#!/bin/sh
# ctest readme-tour: check_readme_tour.sh SOURCE_DIR BUILD_DIR WORK_DIR — runs the README's tour
# (the first ```sh block under "## A tour of `prt`") as pasted, from a copy of the clone's root
# whose build/ and examples/ are the real ones, stopping at the first command that fails.
# Left out, and said so: the windowed `prt view` lines (they wait for a person to close the
# window) and `prt demo` (scripts/demo.sh runs it). Exits 77 (skipped) without the tour's assets.
src=$1 build=$2 work=$3
for f in /usr/share/glmark2/models/bunny.obj \
         /usr/share/blender/datafiles/studiolights/world/courtyard.exr; do
  if [ ! -f "$f" ]; then
    echo "skipped: $f missing (scripts/setup.sh --with-assets installs glmark2-data and blender-data)"
    exit 77
  fi
done
rm -rf "$work" && mkdir -p "$work" || exit 1
ln -s "$build" "$work/build" && ln -s "$src/examples" "$work/examples" || exit 1
awk '/^## A tour of `prt`/ {tour = 1} tour && /^```sh$/ {inside = 1; next}
     inside && /^```$/ {exit} inside {print}' "$src/README.md" > "$work/tour.sh"
[ -s "$work/tour.sh" ] || { echo "no tour block in $src/README.md"; exit 1; }
# Windowed viewer lines (no --headless) and the demo: left out, and counted.
awk '(/^prt view/ && !/--headless/) || /^prt demo/ {left++; next} {print}
     END {print "left out: " left " windowed view / demo line(s)" > "/dev/stderr"}' \
    "$work/tour.sh" > "$work/run.sh"
cd "$work" && exec sh -e -x ./run.sh
