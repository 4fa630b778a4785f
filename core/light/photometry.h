// Photometric files of real luminaires: IES LM-63 (.ies, 1986/1991/1995/2002, type C) and
// EULUMDAT (.ldt, every Isym), read into one candela web with its luminous opening, lumens
// and watts. See docs/photometry.md for the conventions, what is refused and why.
//
// Frame (the luminaire's own, metres): z up, the luminaire hangs facing -z. Type C angles:
// gamma 0 = nadir (straight down, -z), 90 = horizontal, 180 = straight up; C is measured
// counter-clockwise from +x seen from above, so C0 = +x, C90 = +y, C180 = -x, C270 = -y.
// The file's length runs along C0-C180 (IES, LM-63) or the axis photometric_opening
// (core/light/opening_axis.h) finds for an EULUMDAT linear luminaire.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/error.h"

namespace ilp {

// A photometric file that cannot be read or breaks the format. The message reads
// "FILE:LINE: field NAME: what is wrong" (LINE is 1-based; the line holding the token).
class PhotometryError : public IlpError {
 public:
  using IlpError::IlpError;
};

enum class PhotometryFormat { ies, eulumdat };

// The symmetry the file states (IES: from its horizontal angles; EULUMDAT: Isym).
enum class PhotometricSymmetry {
  rotational,         // one plane: I does not depend on C
  quadrant,           // I(C) = I(180-C) = I(180+C) = I(360-C)   (IES 0..90, EULUMDAT Isym 4)
  bilateral_c0_c180,  // mirror about the C0-C180 plane: I(C) = I(360-C)   (IES 0..180, Isym 2)
  bilateral_c90_c270, // mirror about the C90-C270 plane: I(C) = I(180-C)  (IES 90..270, Isym 3)
  none,               // full web (IES 0..360 or 0..>180 closed periodically, Isym 0)
};

// line: one of length and width is 0 (a bare tube or LED strip), the other > 0.
enum class OpeningShape { point, rectangle, disc, cylinder, line };

// The luminous opening, metres, in the luminaire's frame, centred on its origin.
struct LuminousOpening {
  OpeningShape shape = OpeningShape::point;
  double length_m = 0;  // the file's length (IES length; EULUMDAT field 16): along C0-C180 unless
                        // photometric_opening lays it along C90-C270
  double width_m = 0;   // the file's width, across the length; disc/cylinder: the diameter
  double height_m = 0;  // luminous sides (rectangle) or the cylinder's height; 0 for a flat opening
};

// One EULUMDAT lamp set (field 26a-f); an IES file yields one set.
struct LampSet {
  int count = 0;            // number of lamps; negative = absolute photometry (EULUMDAT)
  std::string type;         // lamp designation
  double flux_lm = 0;       // total lamp flux of the set (absolute photometry: luminaire flux)
  std::string colour;       // colour temperature / appearance as written
  std::string colour_rendering;
  double power_w = 0;       // including ballast
};

// IES TILT=INCLUDE data: kept for the record, never applied (the web is at the tested tilt).
struct TiltTable {
  int geometry = 0;  // 1 vertical base-up/down, 2 horizontal in the C0 plane, 3 in the C90 plane
  std::vector<double> angles_deg;
  std::vector<double> factors;
};

struct Photometry {
  std::string path;
  PhotometryFormat format = PhotometryFormat::ies;
  std::string luminaire, manufacturer, catalogue;  // IES [LUMINAIRE] [MANUFAC] [LUMCAT]; EULUMDAT 9, 1, 10
  std::string version;  // IES id line ("IESNA:LM-63-2002", "" for 1986 files); EULUMDAT ""

  double luminaire_flux_lm = 0;  // integrate_flux_lm(*this): what leaves the luminaire
  double lamp_flux_lm = 0;       // stated lamps x lm/lamp (IES) or lamp set 1 (EULUMDAT);
                                 // absolute photometry: = luminaire_flux_lm
  bool absolute = false;         // IES lm/lamp = -1, EULUMDAT negative lamp count
  double input_power_w = 0;      // IES input watts / EULUMDAT lamp set 1 W (0 if not given)
  double upward_fraction = 0;    // share of luminaire_flux_lm with gamma > 90, in [0, 1]
  LuminousOpening opening;
  std::vector<LampSet> lamp_sets;  // EULUMDAT: all sets in file order (set 1 is used); IES: one
  std::optional<TiltTable> tilt;   // IES TILT=INCLUDE only
  // EULUMDAT header figures, percent (NaN for IES): light output ratio (23), downward flux (22).
  double stated_lor_percent = std::numeric_limits<double>::quiet_NaN();
  double stated_dff_percent = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> warnings;  // "FILE: ..." e.g. header DFF disagrees with the data

  // The candela web, expanded over the symmetry to the whole circle.
  PhotometricSymmetry symmetry = PhotometricSymmetry::rotational;
  std::vector<double> gamma_angles_deg;  // strictly increasing, within [0, 180] (the file's own)
  // Strictly increasing from 0; the last is 360 (its row repeats C0 unless the file gave its
  // own 360 plane). Rotational: the single angle 0.
  std::vector<double> c_angles_deg;
  Eigen::MatrixXd candela_cd;  // #c_angles by #gamma_angles, absolute cd (all scale factors applied)

  // Absolute intensity (cd) toward (C, gamma) in degrees, any C (taken modulo 360). On each
  // plane a monotone piecewise-cubic Hermite in gamma (PCHIP, Fritsch-Carlson slopes: no
  // overshoot at sharp cut-offs); across the four neighbouring planes a cubic Hermite in C with
  // three-point parabola slopes (periodic, linear in the data). C1 in both angles, reproduces
  // the nodes, clamped >= 0. 0 outside [gamma_front, gamma_back] of the file.
  double intensity_cd(double c_deg, double gamma_deg) const;
  // Same, toward `direction_local` in the luminaire frame (z up; need not be unit length;
  // the zero vector gives 0).
  double intensity_cd(const Eigen::Vector3d& direction_local) const;
};

// Reads `path`: by extension (.ies / .ldt, case-insensitive), else by content (an "IESNA" or
// "IES:" first line or a TILT= line means IES). Throws PhotometryError.
Photometry load_photometry(const std::string& path);
// Parse text already in memory; `path_for_messages` names it in errors and warnings.
Photometry parse_ies(std::string_view text, const std::string& path_for_messages);
Photometry parse_eulumdat(std::string_view text, const std::string& path_for_messages);

// Luminous flux (lm) of the web: trapezoid rule of I sin(gamma) over the file's gamma angles,
// then trapezoid rule over the expanded C angles 0..360 (rotational: x 2 pi). This is the rule
// ../shared/photometry/summarize.py calls "trap". Intensity outside the gamma range counts 0.
double integrate_flux_lm(const Photometry& p);
// The part of that flux with gamma >= 90 (the interval holding 90 split linearly).
double integrate_upward_flux_lm(const Photometry& p);

// "(C, gamma)" in degrees of a direction in the luminaire frame (z up): gamma = acos(-z/|d|),
// C = atan2(y, x) in [0, 360).
Eigen::Vector2d direction_to_c_gamma_deg(const Eigen::Vector3d& direction_local);
// The unit direction toward (C, gamma), the inverse of direction_to_c_gamma_deg.
Eigen::Vector3d c_gamma_to_direction(double c_deg, double gamma_deg);

}  // namespace ilp
