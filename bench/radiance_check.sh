#!/usr/bin/env bash
# Re-checks ilp with Radiance, the reference simulator: builds Radiance's oconv, rtrace
# and rcalc from its public source (not part of this repository), runs an ilp job with
# the Radiance export, traces the export's grid points and compares each grid's average
# illuminance Em with the verified (initial) Em of result.json.
#
#   RADIANCE_SRC=/path/to/Radiance bash bench/radiance_check.sh [CONFIG ...]
#
# RADIANCE_SRC: a checkout of github.com/LBNL-ETA/Radiance (branch master). The tools are
# built once into build-radiance/ (headless, Release). CONFIG defaults to
# configs/office.yaml configs/office_products.yaml. RTRACE_OPTIONS overrides the rtrace
# settings below (6 ambient bounces with Radiance's ambient cache: minutes per grid here).
# Prints per grid: points, Em by ilp and by Radiance and their difference in %.
set -euo pipefail
cd "$(dirname "$0")/.."
: "${RADIANCE_SRC:?set RADIANCE_SRC to a Radiance source tree (github.com/LBNL-ETA/Radiance)}"
configs=("$@")
[ ${#configs[@]} -gt 0 ] || configs=(configs/office.yaml configs/office_products.yaml)
rtrace_options="${RTRACE_OPTIONS:--ab 6 -ad 1024 -as 256 -aa 0.08 -ar 256 -lw 1e-5}"

rad_build="$PWD/build-radiance"
if [ ! -x "$rad_build/bin/rtrace" ]; then
  mkdir -p "$RADIANCE_SRC/test"  # its CMakeLists copies test/, which a partial checkout may lack
  cmake -S "$RADIANCE_SRC" -B "$rad_build" -DBUILD_HEADLESS=ON -DCMAKE_BUILD_TYPE=Release > "$rad_build.log" 2>&1
  cmake --build "$rad_build" -j"$(nproc)" --target oconv rtrace rcalc >> "$rad_build.log" 2>&1
fi
RAYPATH=".:$RADIANCE_SRC/src/rt:$RADIANCE_SRC/src/cv:$RADIANCE_SRC/lib"  # rayinit.cal, source.cal
export RAYPATH
ilp=build/ilp

for config in "${configs[@]}"; do
  work="$(mktemp -d)"
  # The job as written, with the Radiance export added to its formats.
  sed -E 's/^(  formats: \[)/\1radiance, /' "$config" > "$work/job.yaml"
  sed -i -E "s#(mesh|photometry): \.\./#\1: $PWD/#" "$work/job.yaml"
  "$ilp" run "$work/job.yaml" --out "$work/out" -q > "$work/run.log" 2>&1 || { [ $? -eq 2 ] || { cat "$work/run.log"; exit 1; }; }
  (cd "$work/out" && "$rad_build/bin/oconv" radiance_scene.rad > scene.oct)
  python3 - "$work/out" "$config" "$rad_build/bin" "$rtrace_options" <<'EOF'
import json, subprocess, sys, os, time
out, config, bin_dir, options = sys.argv[1:5]
result = json.load(open(os.path.join(out, "result.json")))
for grid in result["grids"]:
    pts = os.path.join(out, "radiance_" + "".join(c if c.isalnum() or c in "-_" else "_" for c in grid["name"]) + ".pts")
    start = time.time()
    rgb = subprocess.run([os.path.join(bin_dir, "rtrace"), "-h", "-I+", "-w"] + options.split() + ["scene.oct"],
                         stdin=open(pts), capture_output=True, text=True, cwd=out, check=True).stdout.split()
    lux = [179.0 * (0.265 * float(rgb[k]) + 0.670 * float(rgb[k + 1]) + 0.065 * float(rgb[k + 2]))
           for k in range(0, len(rgb), 3)]
    em_radiance = sum(lux) / len(lux)
    em_ilp = grid["initial"]["average_lux"]
    print(f"{config}: grid {grid['name']}: {len(lux)} points, Em ilp {em_ilp:.2f} lx (verified, initial), "
          f"Radiance {em_radiance:.2f} lx, difference {100 * (em_radiance - em_ilp) / em_ilp:+.2f} % "
          f"(rtrace {time.time() - start:.1f} s)")
EOF
  rm -rf "$work"
done
