#include "core/daylight/sky_patches.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>

namespace ilp {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRadPerDeg = kPi / 180.0;

// Tregenza's patches per 12° row from the horizon up (tregenza.cal, gendaymtx rh_init's tnaz);
// MF:n repeats each row n times with n times as many patches.
constexpr int kTregenzaRows = 7;
constexpr int kTregenzaPatchesPerRow[kTregenzaRows] = {30, 30, 24, 24, 18, 12, 6};

int patches_in_row(int mf, int row) { return mf * kTregenzaPatchesPerRow[row / mf]; }

void append_row(SkySubdivision& sky, int row) {
  const double alpha = sky.row_width_deg;
  const double lo = alpha * row, hi = alpha * (row + 1);
  const int n = patches_in_row(sky.mf, row);
  const double width_deg = 360.0 / n;
  const double solid_angle = 2.0 * kPi * (std::sin(hi * kRadPerDeg) - std::sin(lo * kRadPerDeg)) / n;
  for (int j = 0; j < n; ++j) {
    const double centre_azi = width_deg * j;
    sky.patches.push_back({lo, hi, centre_azi - 0.5 * width_deg, centre_azi + 0.5 * width_deg,
                           sky_direction(0.5 * (lo + hi), centre_azi), solid_angle});
  }
}

// The unit direction, or std::invalid_argument.
Eigen::Vector3d unit_direction(const Eigen::Vector3d& direction, const char* function) {
  const double length = direction.norm();
  if (!std::isfinite(length) || length <= 0.0)
    throw std::invalid_argument(std::string(function) + ": the direction must be finite and non-zero");
  return direction / length;
}

}  // namespace

Eigen::Vector3d sky_direction(double altitude_deg, double azimuth_deg) {
  const double alt = altitude_deg * kRadPerDeg, azi = azimuth_deg * kRadPerDeg;
  return {std::cos(alt) * std::sin(azi), std::cos(alt) * std::cos(azi), std::sin(alt)};
}

SkySubdivision sky_subdivision(int mf) {
  if (mf < 1 || mf > kMaxReinhartMf)
    throw std::invalid_argument("sky_subdivision: mf = " + std::to_string(mf) + ": must be in [1, " +
                                std::to_string(kMaxReinhartMf) + "]");
  SkySubdivision sky;
  sky.mf = mf;
  sky.row_width_deg = 90.0 / (kTregenzaRows * mf + 0.5);
  sky.patches.reserve(144 * mf * mf + 1);
  for (int row = 0; row < kTregenzaRows * mf; ++row) {
    sky.row_start.push_back(static_cast<int>(sky.patches.size()));
    append_row(sky, row);
  }
  sky.row_start.push_back(static_cast<int>(sky.patches.size()));
  const double cap_lo = 90.0 - 0.5 * sky.row_width_deg;
  sky.patches.push_back({cap_lo, 90.0, 0.0, 360.0, Eigen::Vector3d::UnitZ(),
                         2.0 * kPi * (1.0 - std::cos(0.5 * sky.row_width_deg * kRadPerDeg))});
  sky.row_start.push_back(static_cast<int>(sky.patches.size()));
  return sky;
}

int sky_patch_of(const SkySubdivision& sky, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d d = unit_direction(direction, "sky_patch_of");
  if (d.z() < 0.0) throw std::invalid_argument("sky_patch_of: the direction is below the horizon (z < 0)");
  const int rows = kTregenzaRows * sky.mf;
  const double alt_deg = std::asin(std::min(d.z(), 1.0)) / kRadPerDeg;
  const int row = static_cast<int>(std::floor(alt_deg / sky.row_width_deg));
  if (row >= rows) return sky.row_start[rows];  // the zenith cap
  double azi_deg = std::atan2(d.x(), d.y()) / kRadPerDeg;
  if (azi_deg < 0.0) azi_deg += 360.0;
  const int n = patches_in_row(sky.mf, row);
  const double width_deg = 360.0 / n;
  const int j = static_cast<int>(std::floor((azi_deg + 0.5 * width_deg) / width_deg)) % n;
  return sky.row_start[row] + j;
}

int radiance_bin_of(const SkySubdivision& sky, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d d = unit_direction(direction, "radiance_bin_of");
  return d.z() < 0.0 ? kGroundBin : sky_patch_of(sky, d) + 1;
}

std::ostream& operator<<(std::ostream& os, const SkyPatch& p) {
  const Eigen::Vector3d& c = p.centre_direction;
  return os << "altitude [" << p.altitude_lo_deg << ", " << p.altitude_hi_deg << ")° azimuth [" << p.azimuth_lo_deg
            << ", " << p.azimuth_hi_deg << ")° centre (" << c.x() << ", " << c.y() << ", " << c.z() << ") "
            << p.solid_angle_sr << " sr";
}

}  // namespace ilp
