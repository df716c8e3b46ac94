#!/usr/bin/env bash
# Installs what m4mesh needs to build and test on Debian (run as root).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends \
  g++ make cmake pkg-config ccache clang libclang-rt-14-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  libcli11-dev libssl-dev libcgal-dev nlohmann-json3-dev libdraco-dev libeigen3-dev \
  libpng-dev libgif-dev python3-dev pybind11-dev python3-matplotlib python3-numpy python3-pytest \
  > /dev/null
