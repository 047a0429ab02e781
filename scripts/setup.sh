#!/usr/bin/env bash
# Installs every Debian package fibrenet needs and builds it in build/ (Release).
# Usage: scripts/setup.sh            (idempotent; re-run after pulling changes)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake git pkg-config
  libeigen3-dev libnlopt-cxx-dev libsqlite3-dev libsqlitecpp-dev sqlite3
  libopenmpi-dev openmpi-bin libhdf5-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  python3 python3-matplotlib python3-numpy python3-h5py
)
source scripts/install_packages.sh
install_packages "${packages[@]}"

cmake -S . -B build -DCMAKE_BUILD_TYPE="${FIBRENET_BUILD_TYPE:-Release}" > /dev/null
cmake --build build -j "$(nproc)"
