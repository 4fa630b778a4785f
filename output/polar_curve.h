// The polar intensity curve of a photometric file as a data sheet draws it: intensity
// in cd per 1000 lm of the luminaire's output in two planes, C0-C180 and C90-C270,
// gamma 0 (nadir) pointing down, light going up drawn above the centre. One standalone
// SVG document (pure: no library), which the PDF report places on the product's page.
#pragma once

#include <string>
#include <vector>

#include "core/light/photometry.h"

namespace ilp {

// One plane pair's curve: the intensity at gamma 0, step, ..., 180 degrees toward the
// first plane (drawn right of the vertical axis) and toward the opposite one (left).
struct PolarPlane {
  double c_deg = 0.0;                    // the first plane: 0 or 90 (its opposite + 180)
  std::vector<double> gamma_deg;         // 0 .. 180
  std::vector<double> cd_per_klm;        // toward c_deg
  std::vector<double> cd_per_klm_opposite;  // toward c_deg + 180
};

struct PolarCurve {
  PolarPlane c0_c180, c90_c270;
  double max_cd_per_klm = 0.0;           // over both planes
  double ring_step_cd_per_klm = 0.0;     // a 1-2-5 step, at most 5 rings up to the maximum
};

// Samples the file's intensity (Photometry::intensity_cd) every `gamma_step_deg` in both
// plane pairs, divided by its luminaire flux / 1000. Throws std::invalid_argument when
// the step is not in (0, 45] or the file's luminaire flux is not > 0.
PolarCurve polar_curve(const Photometry& photometry, double gamma_step_deg = 2.5);

// The diagram, `size_px` square (plus a legend line below): rings at the ring step
// labelled in cd/klm, spokes every 30 degrees labelled with gamma, the C0-C180 curve
// solid red and the C90-C270 curve dashed blue, each labelled in the legend. Its curves
// are <polyline> elements with class "c0_c180" and "c90_c270": point k of a curve is
// gamma_deg[k] on the first plane's side, then the opposite plane's side runs back up,
// at x = cx ± r sin(gamma), y = cy + r cos(gamma) (SVG y down), r = value x the scale.
std::string polar_curve_svg(const PolarCurve& curve, double size_px = 360.0);

}  // namespace ilp
