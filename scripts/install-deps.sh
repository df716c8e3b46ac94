#!/usr/bin/env bash
# Installs what m4mesh needs to build and test on Debian (run as root).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends \
  g++ make cmake pkg-config ccache clang libclang-rt-14-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  libcli11-dev libssl-dev libcgal-dev nlohmann-json3-dev libdraco-dev libeigen3-dev \
  libpng-dev libgif-dev libimagequant-dev libtinygltf-dev blender python3-dev pybind11-dev python3-matplotlib python3-numpy python3-pytest \
  python3-venv python3-pip python3-setuptools python3-wheel python3-build \
  libcpp-httplib-dev emscripten nodejs chromium time \
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev ffmpeg opencv-doc \
  > /dev/null
# npm comes with some Node.js builds (NodeSource's); Debian's comes apart.
command -v npm > /dev/null || apt-get install -y -qq --no-install-recommends npm > /dev/null
# three.js for the web player, playwright-core to drive Chromium in the browser tests, gltfpack, meshoptimizer and draco3d for scripts/anchor_bench.mjs (web/package-lock.json).
npm ci --prefix "$(dirname "$0")/../web" --no-audit --no-fund --loglevel=error
