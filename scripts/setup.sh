#!/usr/bin/env bash
# Installs every Debian package prtkit's build, tests, benchmarks and demo need.
# Idempotent: when everything is present it only checks (a second or two) and exits.
# Usage: scripts/setup.sh [--with-assets | --with-fuzzing]   (the demo's real assets; clang-14 and
# libFuzzer for scripts/fuzz.sh)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libembree-dev libtbb-dev libeigen3-dev libspectra-dev
  libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libtinyexr-dev libopenexr-dev zlib1g-dev
  libpng-dev
  libcli11-dev libfmt-dev
  # MPI (mpirun -np N prt bake ...; docs/distributed.md): Open MPI, found by find_package(MPI)
  openmpi-bin libopenmpi-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # viewer (prt view): window, UI, GL loader; EGL + Mesa (llvmpipe) headless; Xvfb for its window test
  libglfw3-dev libimgui-dev libepoxy-dev libgl-dev libegl-dev libegl-mesa0 libgl1-mesa-dri xvfb xauth
  # browser viewer (prt web): node + npm bundle web/ (three.js, lil-gui, esbuild from npm, and the
  # Khronos glTF validator the tests run on every bake; pinned
  # by web/package-lock.json); chromium runs its tests headless (SwiftShader, no GPU needed)
  # (npm is added below only when no npm command exists: NodeSource's nodejs ships its own npm and
  # conflicts with Debian's npm package)
  nodejs chromium
  # the Python module (import prtkit): its build, numpy, the tests (pytest; tqdm for the progress
  # bar's), and `pip install --no-build-isolation .` offline (setuptools, wheel, pip, venv)
  python3-dev pybind11-dev python3-numpy python3-pytest python3-tqdm
  python3-setuptools python3-wheel python3-pip python3-venv
  # the tests of `prt completions` and `prt manpage`: zsh checks the script, groff the page
  zsh groff-base
  # the peer the light exports are checked against: Filament's cmgen (prt light --format cmgen)
  libfilament-tools
)
assets=(glmark2-data blender-data)
# scripts/fuzz.sh: libFuzzer with clang 14 (ASan + UBSan)
fuzzing=(clang-14 libclang-rt-14-dev)

want=("${packages[@]}")
if ! command -v npm >/dev/null 2>&1; then want+=(npm); fi
if [[ "${1:-}" == "--with-assets" ]]; then want+=("${assets[@]}"); fi
if [[ "${1:-}" == "--with-fuzzing" ]]; then want+=("${fuzzing[@]}"); fi

missing=()
for p in "${want[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# The browser viewer's npm packages, exactly as locked (web/package-lock.json), into
# web/node_modules; skipped when they are already there. Re-run cmake afterwards so the build
# bundles the page (target prt_web_assets).
web_packages() {
  local web
  web="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/web"
  # A worktree may link web/node_modules to another checkout's: npm ci would empty that folder
  # (it deletes node_modules through the link), so a link is used as it is, never reinstalled.
  if [[ -L "$web/node_modules" ]]; then
    [[ -f "$web/node_modules/three/package.json" ]] ||
      echo "setup: web/node_modules is a link to a folder without the packages; run npm ci where it points" >&2
    return 0
  fi
  if [[ -f "$web/node_modules/three/package.json" && -f "$web/node_modules/lil-gui/package.json" &&
        -f "$web/node_modules/esbuild/package.json" &&
        -f "$web/node_modules/gltf-validator/package.json" &&
        "$web/node_modules/.package-lock.json" -nt "$web/package-lock.json" ]]; then
    return 0
  fi
  echo "setup: installing the browser viewer's npm packages (web/package-lock.json)" >&2
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
}

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#want[@]} packages present" >&2
  web_packages
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
web_packages
echo "setup: done" >&2
