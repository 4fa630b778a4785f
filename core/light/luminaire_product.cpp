#include "core/light/luminaire_product.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "core/base/error.h"
#include "core/light/opening_axis.h"

namespace ilp {
namespace {

constexpr double kPointSourceDiameterM = 0.1;

}  // namespace

PhotometricDistribution::PhotometricDistribution(std::shared_ptr<const Photometry> photometry)
    : photometry_(std::move(photometry)) {
  if (!(photometry_->luminaire_flux_lm > 0.0))
    throw PhotometryError(photometry_->path + ": the candela values integrate to no light (0 lm)");
  const double per_lm = 1.0 / photometry_->luminaire_flux_lm;
  table_.resize(static_cast<std::size_t>((kCSteps + 1) * (kGammaSteps + 1)));
  for (int c = 0; c <= kCSteps; ++c)
    for (int g = 0; g <= kGammaSteps; ++g)
      table_[static_cast<std::size_t>(c * (kGammaSteps + 1) + g)] =
          photometry_->intensity_cd(360.0 * c / kCSteps, 180.0 * g / kGammaSteps) * per_lm;
}

double PhotometricDistribution::cd_per_lm(const Eigen::Vector3d& d) const {
  const double norm = d.norm();
  if (!(norm > 0.0)) return 0.0;
  // gamma from nadir, C counter-clockwise from +x (core/light/photometry.h).
  const double gamma = std::acos(std::clamp(-d.z() / norm, -1.0, 1.0)) * (kGammaSteps / std::numbers::pi);
  double c = std::atan2(d.y(), d.x()) * (kCSteps / (2.0 * std::numbers::pi));
  if (c < 0.0) c += kCSteps;
  const int ci = std::min(static_cast<int>(c), kCSteps - 1), gi = std::min(static_cast<int>(gamma), kGammaSteps - 1);
  const double u = c - ci, v = gamma - gi;
  const double* row0 = &table_[static_cast<std::size_t>(ci * (kGammaSteps + 1) + gi)];
  const double* row1 = row0 + (kGammaSteps + 1);
  return (1.0 - u) * ((1.0 - v) * row0[0] + v * row0[1]) + u * ((1.0 - v) * row1[0] + v * row1[1]);
}

std::string PhotometricDistribution::key() const {
  const Photometry& p = *photometry_;
  std::ostringstream os;
  os << std::setprecision(17) << "photometric " << p.path << " flux " << p.luminaire_flux_lm << " candela sum "
     << p.candela_cd.sum() << " webs " << p.c_angles_deg.size() << "x" << p.gamma_angles_deg.size();
  return os.str();
}

LuminaireType photometric_luminaire_type(const std::string& name, std::shared_ptr<const Photometry> photometry,
                                         std::optional<double> length_axis_c_deg) {
  LuminaireType t;
  t.name = name;
  const LuminousOpening& o = photometry->opening;
  const bool flat_rectangle = o.shape == OpeningShape::rectangle && o.length_m > 0.0 && o.width_m > 0.0;
  if (flat_rectangle) {
    const PhotometricOpening laid = photometric_opening(*photometry, length_axis_c_deg);
    t.shape = OutlineShape::rectangle;
    t.length_m = laid.along_c0_m;  // LuminaireType: length along local x (C0)
    t.width_m = laid.along_c90_m;
  } else if (o.shape == OpeningShape::line) {  // a thin rectangle along its one size
    t.shape = OutlineShape::rectangle;
    t.length_m = o.length_m > 0.0 ? o.length_m : kLineSourceWidthM;
    t.width_m = o.width_m > 0.0 ? o.width_m : kLineSourceWidthM;
  } else {
    t.shape = OutlineShape::disc;
    const double d = std::max(o.length_m, o.width_m);
    t.length_m = t.width_m = d > 0.0 ? d : kPointSourceDiameterM;
  }
  t.distribution = std::make_shared<PhotometricDistribution>(std::move(photometry));
  return t;
}

}  // namespace ilp
