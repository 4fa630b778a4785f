// Which C-plane a photometric file's luminous opening runs along (issue 19): the file
// gives a length and a width, the formats differ on where they lie, and a linear
// luminaire laid the wrong way turns a layout's rows by 90 degrees. See
// docs/photometry.md ("Which way the opening runs") for the documents and the rule.
#pragma once

#include <optional>
#include <string>

#include "core/light/photometry.h"

namespace ilp {

// What the file's curves say about its long axis (symmetries and widths of the web).
struct CurveEvidence {
  // Share of the light that differs between each direction and its mirror image
  // (sum |I - I_mirror| / sum (I + I_mirror), weighted by solid angle), in [0, 1]:
  // mirror x -> -x, I(C) against I(180 - C): 0 when the luminaire is symmetric end to
  // end along local x (C0-C180); mirror y -> -y, I(C) against I(360 - C), likewise along y.
  double asymmetry_along_c0 = 0.0;
  double asymmetry_along_c90 = 0.0;
  // Spread of the curve in each vertical plane: intensity-weighted mean of |sin gamma|
  // over both half-planes (0.5 for I = cos gamma below, 0.637 for a uniform half-plane).
  double spread_c0_c180 = 0.0;
  double spread_c90_c270 = 0.0;
};

// The evidence from the file's own interpolant (Photometry::intensity_cd), every 5
// degrees of C and 2.5 of gamma.
CurveEvidence curve_evidence(const Photometry& p);

// Where the file's luminous opening lies in the luminaire's frame.
struct PhotometricOpening {
  // The C angle (0 or 90) of the axis along which the file's "length" runs (IES
  // length, EULUMDAT field 16); its width runs along the other one.
  double length_axis_c_deg = 0.0;
  double along_c0_m = 0.0;   // the opening's extent along local x (C0-C180)
  double along_c90_m = 0.0;  // along local y (C90-C270)
  std::string reason;        // one sentence: the format, the dimensions, the curves, or the override
};

// The rule (docs/photometry.md): an override (a product's own, 0 or 90) wins; IES
// LM-63 fixes the length along the 0-180 plane; EULUMDAT does not say, so an
// linear rectangle (long side >= 3 x short) is laid along the axis the curves
// show to be its length (the luminaire symmetric end to end, else the narrower
// plane), and anything else keeps the length along C0. Throws std::invalid_argument
// for an override other than 0 or 90.
PhotometricOpening photometric_opening(const Photometry& p, std::optional<double> length_axis_c_deg = std::nullopt);

}  // namespace ilp
