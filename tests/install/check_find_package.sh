#!/usr/bin/env bash
# Installs the built prtkit into a scratch prefix and builds and runs an outside project that
# uses it through find_package(prtkit) — the exported targets and the package config.
# Usage: check_find_package.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" > /dev/null
cmake -S "$src/tests/install/consumer" -B "$tmp/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$tmp/prefix" > /dev/null
cmake --build "$tmp/consumer" > /dev/null
"$tmp/consumer/consumer"
"$tmp/consumer/readme_example"
# The README shows exactly the example that was just built and run: its C++ block under
# "## Using the library" is the text between the markers.
sed -n '/^\/\/ readme-begin$/,/^\/\/ readme-end$/p' "$src/tests/install/consumer/readme_example.cpp" |
  sed '1d;$d' > "$tmp/example.cpp"
awk '/^## Using the library/{section=1} section && /^```cpp$/{on=1; next}
     on && /^```$/{exit} on{print}' "$src/README.md" > "$tmp/readme.cpp"
if ! diff -u "$tmp/example.cpp" "$tmp/readme.cpp"; then
  echo "README.md: the 'Using the library' example differs from" \
    "tests/install/consumer/readme_example.cpp (copy it between the readme markers)" >&2
  exit 1
fi
