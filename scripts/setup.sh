#!/usr/bin/env bash
# Installs the Debian packages ilp builds with (as root, on Debian 12), then
# configures and builds a Release tree in build/. Safe to run again: it installs
# only what is missing and rebuilds incrementally.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ cmake make pkg-config
          libeigen3-dev libembree-dev libnlopt-cxx-dev libnlopt-dev libopenmesh-dev libyaml-cpp-dev
          libtbb-dev libcli11-dev nlohmann-json3-dev libxxhash-dev libgtest-dev libbenchmark-dev
          librsvg2-dev fonts-dejavu-core libassimp-dev
          poppler-utils)  # pdftotext, pdffonts, pdftoppm: the report tests read report.pdf back
packages+=(libglpk-dev)  # GLPK: the output programme of three or more luminaire groups (optimizer/group_search.cpp)
packages+=(libdxflib-dev)  # tests: dxflib reads the DXF plan back (tests/data/import/README.md: assimp-utils remakes the converted office)
packages+=(libopenmpi-dev openmpi-bin)  # MPI: mpirun -np N ilp run (docs/cluster.md)
packages+=(clang)  # the libFuzzer harnesses (scripts/fuzz_photometry.sh)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup: installing packages needs root (run as root or with sudo)" >&2
    exit 1
  fi
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" > /dev/null
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON > /dev/null
cmake --build build -j"$(nproc)"
