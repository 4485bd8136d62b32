#!/usr/bin/env bash
# Quick start, step 1: install what is missing (Debian 12 packages only), build Tyndall, and render
# the built-in default scene to tyndall.png. Idempotent: with everything installed and built it
# only re-renders. Usage: scripts/setup.sh [--no-render]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  g++ cmake make pkg-config
  libembree-dev libtbb-dev libopenvdb-dev libboost-iostreams-dev
  libopenimageio-dev openimageio-tools libtinygltf-dev nlohmann-json3-dev libcli11-dev
  libglfw3-dev libegl1-mesa-dev libgl1-mesa-dri libosmesa6-dev
  libgtest-dev libbenchmark-dev gnuplot-nox
  clang libclang-rt-14-dev
  libopenmpi-dev openmpi-bin xvfb xauth
  libimgui-dev libstb-dev libhwy-dev xdotool x11-apps x11-utils libx11-dev imagemagick
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${#missing[@]} missing packages: ${missing[*]}"
  sudo=""
  if [ "$(id -u)" != 0 ]; then
    command -v sudo >/dev/null || { echo "setup: need root or sudo to install packages" >&2; exit 1; }
    sudo="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all packages present"
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$jobs"

if [ "${1:-}" != "--no-render" ]; then
  ./build/app/tyndall render -o tyndall.png
  echo "setup: wrote tyndall.png (the default scene); run the tests with: ctest --test-dir build --output-on-failure"
fi
