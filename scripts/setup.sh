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
  python3 python3-matplotlib python3-numpy
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -q
  $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE="${FIBRENET_BUILD_TYPE:-Release}" > /dev/null
cmake --build build -j "$(nproc)"
