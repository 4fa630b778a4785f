#include "core/light/opening_axis.h"

#include <gtest/gtest.h>

#include <iostream>

namespace ilp {
namespace {

const std::string kShared = std::string(ILP_SOURCE_DIR) + "/../shared/photometry/";

TEST(OpeningAxisScratch, Print) {
  for (const char* f : {"lidrs/iesna2002_example_typec.ies", "luxcore/ASA_15M_R2.ies", "radiance/examp1.ies",
                        "renderpipeline/area_light.ies", "renderpipeline/bollard.ies", "renderpipeline/defined_diffuse.ies",
                        "renderpipeline/medium_scatter.ies", "renderpipeline/overhead.ies", "renderpipeline/star_focused.ies",
                        "eulumdat-analysis/sample_01.ldt", "eulumdat-analysis/sample_03.ldt", "eulumdat-analysis/sample_14.ldt",
                        "eulumdat-analysis/sample_17.ldt", "eulumdat-analysis/sample_18.ldt", "eulumdat-analysis/sample_20.ldt",
                        "lidrs/example.ldt"}) {
    const Photometry p = load_photometry(kShared + f);
    const CurveEvidence e = curve_evidence(p);
    const PhotometricOpening o = photometric_opening(p);
    std::cout << f << " L " << p.opening.length_m << " W " << p.opening.width_m << " shape " << int(p.opening.shape)
              << " ax0 " << e.asymmetry_along_c0 << " ax90 " << e.asymmetry_along_c90 << " s0 " << e.spread_c0_c180
              << " s90 " << e.spread_c90_c270 << " -> " << o.length_axis_c_deg << " : " << o.reason << "\n";
  }
}

}  // namespace
}  // namespace ilp
