// libFuzzer harness for the photometric readers: any byte string fed to parse_ies and
// parse_eulumdat must either give a usable web or throw PhotometryError. Anything else (a
// crash, a sanitizer report, another exception, a web that breaks its invariants) is a bug.
// Build and run: scripts/fuzz_photometry.sh [seconds].
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "core/light/photometry.h"

namespace {

void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "photometry invariant broken: %s\n", what);
    std::abort();
  }
}

void check(const ilp::Photometry& p) {
  require(std::isfinite(p.luminaire_flux_lm) && p.luminaire_flux_lm > 0, "flux finite and > 0");
  require(p.upward_fraction >= 0 && p.upward_fraction <= 1, "upward fraction in [0, 1]");
  require(p.c_angles_deg.size() == static_cast<std::size_t>(p.candela_cd.rows()), "one row per C angle");
  require(p.gamma_angles_deg.size() == static_cast<std::size_t>(p.candela_cd.cols()), "one column per gamma");
  require(p.c_angles_deg.size() == 1 || p.c_angles_deg.back() == 360.0, "C grid closes at 360");
  for (double c : {0.0, 33.3, 90.0, 181.5, 359.99, -45.0}) {
    for (double g : {0.0, 10.0, 45.5, 89.9, 90.0, 135.0, 180.0}) {
      const double i = p.intensity_cd(c, g);
      require(std::isfinite(i) && i >= 0, "intensity finite and >= 0");
    }
  }
  const double i = p.intensity_cd(Eigen::Vector3d(0.3, -0.4, -0.8));
  require(std::isfinite(i) && i >= 0, "intensity toward a direction finite and >= 0");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    check(ilp::parse_ies(text, "fuzz.ies"));
  } catch (const ilp::PhotometryError&) {
  }
  try {
    check(ilp::parse_eulumdat(text, "fuzz.ldt"));
  } catch (const ilp::PhotometryError&) {
  }
  return 0;
}
