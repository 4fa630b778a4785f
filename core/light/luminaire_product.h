// A luminaire one can buy, as the search and the verification use it: its luminaire
// type (a photometric file's distribution and opening, or the square Lambertian
// panel) at one rotation, its rated lumens and watts, its dimming range and its own
// maintenance factor and suspension.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "core/light/luminaire.h"
#include "core/light/photometry.h"

namespace ilp {

// A photometric file's candela web as a luminaire distribution, per lumen of its flux.
// The file's smooth interpolant (Photometry::intensity_cd) is sampled once on a table
// that lookups read bilinearly: the direct light asks millions of times, and the table
// is ~20x cheaper than the cubic. Its steps are a sixteenth of the file's finest angle
// step (at least 0.125 and at most 0.5 degree of gamma, at least 0.5 and at most 2
// degrees of C, one step of C for a rotationally symmetric file), so that the bilinear
// reading is within about 0.05 % of the interpolant's change between the file's nodes,
// and the table stays small enough for the cores' own caches (a 18 x 5 degree
// EULUMDAT web: 321 x 577 floats, 0.7 MB; the finest, 721 x 1441 floats, 4 MB): a lookup
// that misses them costs more than the rest of a shadow ray's work.
class PhotometricDistribution final : public IntensityDistribution {
 public:
  explicit PhotometricDistribution(std::shared_ptr<const Photometry> photometry);
  double cd_per_lm(const Eigen::Vector3d& direction_local) const override;
  std::string key() const override;
  const Photometry& photometry() const { return *photometry_; }
  int c_steps() const { return c_steps_; }          // the table's intervals over 360 degrees of C
  int gamma_steps() const { return gamma_steps_; }  // and over 180 degrees of gamma

 private:
  std::shared_ptr<const Photometry> photometry_;
  int c_steps_ = 1, gamma_steps_ = 1;
  std::vector<float> table_;  // (c_steps_ + 1) x (gamma_steps_ + 1), cd per lm
};

// A line source's drawn, meshed and glaring width (a T5 tube is 16 mm).
inline constexpr double kLineSourceWidthM = 0.02;

// The luminaire type of a photometric file: its distribution and its luminous opening
// (a rectangle, or a disc for round, cylindrical and point openings; a point source
// gets a 0.1 m disc so that it has an outline that shades and can be drawn). The
// rectangle's length runs along the axis photometric_opening (core/light/opening_axis.h)
// decides, `length_axis_c_deg` (0 or 90) overriding it for a product that says so, so
// that the outline lies the way the curves were measured.
LuminaireType photometric_luminaire_type(const std::string& name, std::shared_ptr<const Photometry> photometry,
                                         std::optional<double> length_axis_c_deg = std::nullopt);

struct ProductVariant {
  std::string product;     // the product's name
  std::string source;      // the photometric file, or "square_lambertian"
  LuminaireType type;
  double rotation_deg = 0.0;
  double tilt_deg = 0.0;       // aim (core/light/luminaire.h: LuminairePlacement::tilt_deg)
  double rated_flux_lm = 0.0;  // at full output
  double power_w = 0.0;        // at full output
  double dim_min = 1.0, dim_max = 1.0;  // the output range, fractions of rated_flux_lm
  std::optional<double> maintenance_factor;  // the product's own; replaces the job's when given
  std::optional<double> mount_offset_m;      // the product's own suspension; replaces the job's when given
  FileLoc mount_offset_loc;
  std::vector<std::string> notes;  // the file's warnings, what was taken from where
};

}  // namespace ilp
