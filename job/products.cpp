// From the job's luminaires.products to the variants a search tries.
#include "job/config.h"
#include "job/products.h"

#include <iomanip>
#include <sstream>

#include "core/base/error.h"
#include "core/light/opening_axis.h"
#include "core/light/photometry.h"

namespace ilp {
namespace {

std::string format(double v) {
  std::ostringstream os;
  os << std::setprecision(6) << v;
  return os.str();
}

}  // namespace

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
    v.type = photometric_luminaire_type(p.name, photometry, p.length_axis_c_deg);
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
  if (v.type.shape == OutlineShape::rectangle)
    v.notes.push_back("product '" + p.name + "': opening " + photometric_opening(*photometry).reason);
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

ProductVariant product_base(const ProductSetting& p) {
  ProductVariant base = p.photometry_path.empty() ? panel_base(p) : photometric_base(p);
  base.dim_min = p.dim_min;
  base.dim_max = p.dim_max;
  base.maintenance_factor = p.maintenance_factor;
  base.mount_offset_m = p.mount_offset_m;
  base.mount_offset_loc = p.mount_offset_loc;
  return base;
}

std::vector<ProductVariant> product_variants(const std::vector<ProductSetting>& products, bool wall_mounted) {
  std::vector<ProductVariant> out;
  for (const ProductSetting& p : products) {
    const ProductVariant base = product_base(p);
    std::vector<double> rotations = p.rotations_deg;
    if (rotations.empty())
      rotations = rotationally_symmetric(base.type) || wall_mounted ? std::vector<double>{0.0} : std::vector<double>{0.0, 90.0};
    for (double r : rotations) {
      ProductVariant v = base;
      v.rotation_deg = r;
      v.tilt_deg = p.tilt_deg;
      out.push_back(std::move(v));
    }
  }
  return out;
}

}  // namespace ilp
