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

// The table's steps per step of the file's own web, and their bounds in degrees.
constexpr double kTableStepsPerNode = 16.0;
constexpr double kFinestGammaStepDeg = 0.125, kCoarsestGammaStepDeg = 0.5;
constexpr double kFinestCStepDeg = 0.5, kCoarsestCStepDeg = 2.0;

// The smallest gap between consecutive angles (degrees); `fallback` for fewer than two.
double finest_step_deg(const std::vector<double>& angles_deg, double fallback) {
  double finest = fallback;
  for (std::size_t k = 1; k < angles_deg.size(); ++k)
    if (const double gap = angles_deg[k] - angles_deg[k - 1]; gap > 0.0) finest = std::min(finest, gap);
  return finest;
}

// Intervals over `span_deg` of about a sixteenth of the file's step, within the bounds.
int table_steps(double span_deg, double file_step_deg, double finest_deg, double coarsest_deg) {
  const double step = std::clamp(file_step_deg / kTableStepsPerNode, finest_deg, coarsest_deg);
  return static_cast<int>(std::ceil(span_deg / step - 1e-9));
}

}  // namespace

PhotometricDistribution::PhotometricDistribution(std::shared_ptr<const Photometry> photometry)
    : photometry_(std::move(photometry)) {
  if (!(photometry_->luminaire_flux_lm > 0.0))
    throw PhotometryError(photometry_->path + ": the candela values integrate to no light (0 lm)");
  const double per_lm = 1.0 / photometry_->luminaire_flux_lm;
  const Photometry& p = *photometry_;
  gamma_steps_ = table_steps(180.0, finest_step_deg(p.gamma_angles_deg, 180.0), kFinestGammaStepDeg, kCoarsestGammaStepDeg);
  // One C plane (a rotational web): the intensity does not depend on C.
  c_steps_ = p.c_angles_deg.size() < 2
                 ? 1
                 : table_steps(360.0, finest_step_deg(p.c_angles_deg, 360.0), kFinestCStepDeg, kCoarsestCStepDeg);
  table_.resize(static_cast<std::size_t>((c_steps_ + 1) * (gamma_steps_ + 1)));
  for (int c = 0; c <= c_steps_; ++c)
    for (int g = 0; g <= gamma_steps_; ++g)
      table_[static_cast<std::size_t>(c * (gamma_steps_ + 1) + g)] =
          static_cast<float>(p.intensity_cd(360.0 * c / c_steps_, 180.0 * g / gamma_steps_) * per_lm);
}

double PhotometricDistribution::cd_per_lm(const Eigen::Vector3d& d) const {
  const double norm = d.norm();
  if (!(norm > 0.0)) return 0.0;
  // gamma from nadir, C counter-clockwise from +x (core/light/photometry.h).
  const double gamma = std::acos(std::clamp(-d.z() / norm, -1.0, 1.0)) * (gamma_steps_ / std::numbers::pi);
  double c = std::atan2(d.y(), d.x()) * (c_steps_ / (2.0 * std::numbers::pi));
  if (c < 0.0) c += c_steps_;
  const int ci = std::min(static_cast<int>(c), c_steps_ - 1), gi = std::min(static_cast<int>(gamma), gamma_steps_ - 1);
  const double u = c - ci, v = gamma - gi;
  const float* row0 = &table_[static_cast<std::size_t>(ci * (gamma_steps_ + 1) + gi)];
  const float* row1 = row0 + (gamma_steps_ + 1);
  return (1.0 - u) * ((1.0 - v) * row0[0] + v * row0[1]) + u * ((1.0 - v) * row1[0] + v * row1[1]);
}

std::string PhotometricDistribution::key() const {
  const Photometry& p = *photometry_;
  std::ostringstream os;
  os << std::setprecision(17) << "photometric " << p.path << " flux " << p.luminaire_flux_lm << " candela sum "
     << p.candela_cd.sum() << " webs " << p.c_angles_deg.size() << "x" << p.gamma_angles_deg.size() << " table "
     << c_steps_ << "x" << gamma_steps_ << " float";
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
