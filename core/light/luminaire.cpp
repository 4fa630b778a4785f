#include "core/light/luminaire.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/base/key_hash.h"

namespace ilp {
namespace {

constexpr int kDiscSides = 24;

}  // namespace

double LambertianDistribution::cd_per_lm(const Eigen::Vector3d& direction_local) const {
  return std::max(0.0, -direction_local.z()) / std::numbers::pi;
}

bool LuminaireType::lambertian() const {
  return dynamic_cast<const LambertianDistribution*>(distribution.get()) != nullptr;
}

double LuminaireType::opening_area_m2() const {
  if (shape == OutlineShape::rectangle) return length_m * width_m;
  return 0.25 * std::numbers::pi * length_m * width_m;
}

std::vector<Eigen::Vector3d> LuminaireType::outline_local() const {
  std::vector<Eigen::Vector3d> out;
  if (shape == OutlineShape::rectangle) {
    const double a = 0.5 * length_m, b = 0.5 * width_m;
    out = {{-a, -b, 0.0}, {a, -b, 0.0}, {a, b, 0.0}, {-a, b, 0.0}};
    return out;
  }
  // A regular polygon whose area equals the ellipse's: radius scaled by
  // sqrt((pi / n) / sin(pi / n) / cos(pi / n)).
  const double n = kDiscSides;
  const double scale = std::sqrt((std::numbers::pi / n) / (std::sin(std::numbers::pi / n) * std::cos(std::numbers::pi / n)));
  for (int k = 0; k < kDiscSides; ++k) {
    const double t = 2.0 * std::numbers::pi * k / n;
    out.emplace_back(0.5 * length_m * scale * std::cos(t), 0.5 * width_m * scale * std::sin(t), 0.0);
  }
  return out;
}

Eigen::Vector2d LuminaireType::half_footprint_m(double rotation_deg, double tilt_deg) const {
  const Eigen::Matrix3d r = luminaire_rotation(rotation_deg, tilt_deg);
  Eigen::Vector2d half = Eigen::Vector2d::Zero();
  for (const Eigen::Vector3d& v : outline_local()) half = half.cwiseMax((r * v).head<2>().cwiseAbs());
  return half;
}

std::string LuminaireType::key() const {
  std::ostringstream os;
  os << std::setprecision(17) << "luminaire " << name << " " << (shape == OutlineShape::rectangle ? "rect" : "disc")
     << " " << length_m << " x " << width_m << " " << distribution->key();
  return os.str();
}

LuminaireType LuminaireType::square_lambertian(double size_m) {
  LuminaireType t;
  t.length_m = t.width_m = size_m;
  return t;
}

Eigen::Matrix3d luminaire_rotation(double rotation_deg, double tilt_deg) {
  if (!std::isfinite(rotation_deg) || !(tilt_deg >= 0.0 && tilt_deg <= 90.0))
    throw std::invalid_argument("luminaire rotation " + std::to_string(rotation_deg) + " deg, tilt " +
                                std::to_string(tilt_deg) + " deg: the rotation must be finite, the tilt in [0, 90]");
  constexpr double kRad = std::numbers::pi / 180.0;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(rotation_deg * kRad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  if (tilt_deg == 0.0) return turn;  // bit for bit what an untilted luminaire always had
  return turn * Eigen::AngleAxisd(-tilt_deg * kRad, Eigen::Vector3d::UnitY()).toRotationMatrix();
}

Eigen::Matrix3d luminaire_rotation(const LuminairePlacement& at) { return luminaire_rotation(at.rotation_deg, at.tilt_deg); }

std::vector<Eigen::Vector3d> luminaire_outline_m(const LuminaireType& type, const LuminairePlacement& at) {
  const Eigen::Matrix3d r = luminaire_rotation(at);
  std::vector<Eigen::Vector3d> out = type.outline_local();
  for (Eigen::Vector3d& v : out) v = at.position_m + r * v;
  return out;
}

static_assert(field_count<LuminairePlacement>() == 3, "LuminairePlacement changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const LuminairePlacement& p) {
  k.field("position_m", p.position_m).field("rotation_deg", p.rotation_deg).field("tilt_deg", p.tilt_deg);
}

static_assert(field_count<LuminaireType>() == 5, "LuminaireType changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const LuminaireType& t) {
  k.field("name", t.name).field("shape", t.shape).field("length_m", t.length_m).field("width_m", t.width_m);
  k.field("distribution", t.distribution ? t.distribution->key() : std::string("none"));
}

}  // namespace ilp
