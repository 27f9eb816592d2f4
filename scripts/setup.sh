#!/usr/bin/env bash
# Installs every Debian package prtkit's build, tests, benchmarks and demo need.
# Idempotent: when everything is present it only checks (a second or two) and exits.
# Usage: scripts/setup.sh [--with-assets | --with-fuzzing]   (the demo's real assets; clang-14 and
# libFuzzer for scripts/fuzz.sh)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libembree-dev libtbb-dev libeigen3-dev
  libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libtinyexr-dev libopenexr-dev zlib1g-dev
  libcli11-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # viewer (prt view): window, UI, GL loader; EGL + Mesa (llvmpipe) headless; Xvfb for its window test
  libglfw3-dev libimgui-dev libepoxy-dev libgl-dev libegl-dev libegl-mesa0 libgl1-mesa-dri xvfb xauth
)
assets=(glmark2-data blender-data)
# scripts/fuzz.sh: libFuzzer with clang 14 (ASan + UBSan)
fuzzing=(clang-14 libclang-rt-14-dev)

want=("${packages[@]}")
if [[ "${1:-}" == "--with-assets" ]]; then want+=("${assets[@]}"); fi
if [[ "${1:-}" == "--with-fuzzing" ]]; then want+=("${fuzzing[@]}"); fi

missing=()
for p in "${want[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#want[@]} packages present" >&2
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done" >&2
