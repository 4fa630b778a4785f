#include "core/luminaire_product.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "core/error.h"

namespace ilp {
namespace {

constexpr double kPointSourceDiameterM = 0.1;

std::string format(double v) {
  std::ostringstream os;
  os << std::setprecision(6) << v;
  return os.str();
}

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
  // gamma from nadir, C counter-clockwise from +x (core/photometry.h).
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

LuminaireType photometric_luminaire_type(const std::string& name, std::shared_ptr<const Photometry> photometry) {
  LuminaireType t;
  t.name = name;
  const LuminousOpening& o = photometry->opening;
  const bool flat_rectangle = o.shape == OpeningShape::rectangle && o.length_m > 0.0 && o.width_m > 0.0;
  if (flat_rectangle) {
    t.shape = OutlineShape::rectangle;
    t.length_m = o.length_m;
    t.width_m = o.width_m;
  } else {
    t.shape = OutlineShape::disc;
    const double d = std::max(o.length_m, o.width_m);
    t.length_m = t.width_m = d > 0.0 ? d : kPointSourceDiameterM;
  }
  t.distribution = std::make_shared<PhotometricDistribution>(std::move(photometry));
  return t;
}

namespace {

ProductVariant photometric_base(const ProductSetting& p) {
  std::shared_ptr<const Photometry> photometry;
  try {
    photometry = std::make_shared<const Photometry>(load_photometry(p.photometry_path));
  } catch (const IlpError& e) {
    throw ConfigError(located(p.photometry_loc, "luminaires.products '" + p.name + "'.photometry: " + e.what()));
  }
  ProductVariant v;
  v.product = p.name;
  v.source = p.photometry_path;
  try {
    v.type = photometric_luminaire_type(p.name, photometry);
  } catch (const IlpError& e) {
    throw ConfigError(located(p.photometry_loc, "luminaires.products '" + p.name + "'.photometry: " + e.what()));
  }
  v.rated_flux_lm = p.flux_lm.value_or(photometry->luminaire_flux_lm);
  if (p.power_w) {
    v.power_w = *p.power_w;
  } else if (photometry->input_power_w > 0.0) {
    // The file's watts belong to its own output: scale them with an overridden flux.
    v.power_w = photometry->input_power_w * v.rated_flux_lm / photometry->luminaire_flux_lm;
  } else {
    throw ConfigError(located(p.loc, "luminaires.products '" + p.name + "': " + p.photometry_path +
                                         " gives no input watts: add power_w"));
  }
  v.notes.push_back("product '" + p.name + "': " + p.photometry_path + " (" +
                    (photometry->luminaire.empty() ? "no luminaire name" : photometry->luminaire) + "), " +
                    format(photometry->luminaire_flux_lm) + " lm from the candela values" +
                    (p.flux_lm ? ", rated " + format(*p.flux_lm) + " lm as given" : "") + ", " + format(v.power_w) +
                    " W, " + format(100.0 * photometry->upward_fraction) + " % upward, opening " +
                    format(v.type.length_m) + " x " + format(v.type.width_m) + " m " +
                    (v.type.shape == OutlineShape::disc ? "round" : "rectangular"));
  for (const std::string& w : photometry->warnings) v.notes.push_back("warning: " + w);
  return v;
}

ProductVariant panel_base(const ProductSetting& p) {
  ProductVariant v;
  v.product = p.name;
  v.source = "square_lambertian";
  v.type = LuminaireType::square_lambertian(p.size_m);
  v.type.name = p.name;
  v.rated_flux_lm = *p.flux_lm;
  v.power_w = *p.power_w;
  v.notes.push_back("product '" + p.name + "': square Lambertian panel " + format(p.size_m) + " m, " +
                    format(v.rated_flux_lm) + " lm, " + format(v.power_w) + " W");
  return v;
}

bool rotationally_symmetric(const LuminaireType& type) {
  const auto* d = dynamic_cast<const PhotometricDistribution*>(type.distribution.get());
  const bool symmetric_light = !d || d->photometry().symmetry == PhotometricSymmetry::rotational;
  return symmetric_light && (type.shape == OutlineShape::disc || type.length_m == type.width_m);
}

}  // namespace

std::vector<ProductVariant> product_variants(const LuminaireSearch& search) {
  std::vector<ProductVariant> out;
  for (const ProductSetting& p : search.products) {
    ProductVariant base = p.photometry_path.empty() ? panel_base(p) : photometric_base(p);
    base.dim_min = p.dim_min;
    base.dim_max = p.dim_max;
    base.maintenance_factor = p.maintenance_factor;
    base.mount_offset_m = p.mount_offset_m;
    base.mount_offset_loc = p.mount_offset_loc;
    std::vector<double> rotations = p.rotations_deg;
    if (rotations.empty()) rotations = rotationally_symmetric(base.type) ? std::vector<double>{0.0} : std::vector<double>{0.0, 90.0};
    for (double r : rotations) {
      ProductVariant v = base;
      v.rotation_deg = r;
      out.push_back(std::move(v));
    }
  }
  return out;
}

JobConfig job_for_variant(const JobConfig& job, const ProductVariant& variant) {
  JobConfig out = job;
  LuminaireSearch& s = *out.search;
  s.type = variant.type;
  s.rotation_deg = variant.rotation_deg;
  s.product = variant.product;
  s.uniform_output = true;
  s.flux_min_lm = variant.dim_min * variant.rated_flux_lm;
  s.flux_max_lm = variant.dim_max * variant.rated_flux_lm;
  s.efficacy_lm_per_w = variant.rated_flux_lm / variant.power_w;
  // Maintained values depend on the product's own depreciation when it states it.
  if (variant.maintenance_factor) out.maintenance_factor = *variant.maintenance_factor;
  if (variant.mount_offset_m) {
    s.mount_offset_m = *variant.mount_offset_m;
    s.offset_loc = variant.mount_offset_loc;
  }
  return out;
}

}  // namespace ilp
