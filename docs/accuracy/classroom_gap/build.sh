#!/bin/bash
# Builds the probes of docs/accuracy.md ("Classroom: a grid point against a chair back")
# against a Release build in ./build (cmake + make ilp first), with ilp's own link line.
# Not part of the CMake build: one-off measurements, kept so the figures can be re-taken.
set -euo pipefail
root=$(cd "$(dirname "$0")/../../.." && pwd)
link=$(sed 's/.*-o \.\.\/ilp//' "$root/build/apps/CMakeFiles/ilp.dir/link.txt")
out=${1:-/tmp/classroom_gap}
mkdir -p "$out"
cd "$root/build/apps"
for p in point_light sweep_y exact_direct clearance; do
  g++ -O2 -std=gnu++20 -I"$root" -isystem /usr/include/eigen3 "$root/docs/accuracy/classroom_gap/$p.cpp" -o "$out/$p" $link
done
echo "built in $out"
