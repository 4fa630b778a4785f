#include "core/daylight/sky_models.h"

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

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

Eigen::Vector3d unit(const Eigen::Vector3d& v, const char* what) {
  const double length = v.norm();
  require(std::isfinite(length) && length > 0.0, std::string(what) + " must be finite and non-zero");
  return v / length;
}

// ---- CIE S 011/E:2003 table (DAYLIGHT.md 1.4: LightingToolbox ciesky.m, DigitalRune, Darula &
// Kittler 2002 agree) -----------------------------------------------------------------------------
constexpr CieGeneralSkyType kCieSkies[] = {
    {1, "I", 1, 4.0, -0.70, 0.0, -1.0, 0.00, "CIE standard overcast, steep gradation, azimuthal uniformity"},
    {2, "I", 2, 4.0, -0.70, 2.0, -1.5, 0.15, "overcast, steep gradation, slight brightening toward the sun"},
    {3, "II", 1, 1.1, -0.80, 0.0, -1.0, 0.00, "overcast, moderate gradation, azimuthal uniformity"},
    {4, "II", 2, 1.1, -0.80, 2.0, -1.5, 0.15, "overcast, moderate gradation, slight brightening toward the sun"},
    {5, "III", 1, 0.0, -1.00, 0.0, -1.0, 0.00, "sky of uniform luminance"},
    {6, "III", 2, 0.0, -1.00, 2.0, -1.5, 0.15, "partly cloudy, no gradation, slight brightening toward the sun"},
    {7, "III", 3, 0.0, -1.00, 5.0, -2.5, 0.30, "partly cloudy, no gradation, brighter circumsolar region"},
    {8, "III", 4, 0.0, -1.00, 10.0, -3.0, 0.45, "partly cloudy, no gradation, distinct solar corona"},
    {9, "IV", 2, -1.0, -0.55, 2.0, -1.5, 0.15, "partly cloudy, obscured sun"},
    {10, "IV", 3, -1.0, -0.55, 5.0, -2.5, 0.30, "partly cloudy, brighter circumsolar region"},
    {11, "IV", 4, -1.0, -0.55, 10.0, -3.0, 0.45, "white-blue sky, distinct solar corona"},
    {12, "V", 4, -1.0, -0.32, 10.0, -3.0, 0.45, "CIE standard clear sky, low atmospheric turbidity"},
    {13, "V", 5, -1.0, -0.32, 16.0, -3.0, 0.30, "CIE standard clear sky, polluted atmosphere"},
    {14, "VI", 5, -1.0, -0.15, 16.0, -3.0, 0.30, "cloudless turbid sky, broad solar corona"},
    {15, "VI", 6, -1.0, -0.15, 24.0, -2.8, 0.15, "white-blue turbid sky, broad solar corona"},
};

double cie_gradation(const CieGeneralSkyType& s, double cos_zenith) {
  return cos_zenith > 0.0 ? 1.0 + s.a * std::exp(s.b / cos_zenith) : 1.0;
}

double cie_indicatrix(const CieGeneralSkyType& s, double chi_rad) {
  const double cos_chi = std::cos(chi_rad);
  return 1.0 + s.c * (std::exp(s.d * chi_rad) - std::exp(s.d * kPi / 2.0)) + s.e * cos_chi * cos_chi;
}

double angle_between(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return std::acos(std::clamp(u.dot(v), -1.0, 1.0));
}

// ---- Perez 1990 (gendaymtx SkyClearCat, DiffuseLumEff, DirectLumEff: Perez et al. 1990 tables 1
// and 4) ------------------------------------------------------------------------------------------
constexpr double kClearnessBinLower[kPerezBins + 1] = {1.000, 1.065, 1.230, 1.500, 1.950,
                                                       2.800, 4.500, 6.200, 12.01};
constexpr double kClearnessMax = 11.9, kBrightnessMin = 0.01, kBrightnessMax = 0.6;  // gendaymtx's limits
constexpr double kClearnessKappa = 1.041;  // per rad³
constexpr double kNightThreshold_w_per_m2 = 1e-4;

struct EfficacyCoefficients {
  double a, b, c, d;
};
constexpr EfficacyCoefficients kDiffuseEfficacy[kPerezBins] = {
    {97.24, -0.46, 12.00, -8.91},   {107.22, 1.15, 0.59, -3.95},    {104.97, 2.96, -5.53, -8.77},
    {102.39, 5.59, -13.95, -13.90}, {100.71, 5.94, -22.75, -23.74}, {106.42, 3.83, -36.15, -28.83},
    {141.88, 1.90, -53.24, -14.03}, {152.23, 0.35, -45.27, -7.98},
};
constexpr EfficacyCoefficients kDirectEfficacy[kPerezBins] = {
    {57.20, -4.55, -2.98, 117.12}, {98.99, -3.46, -1.21, 12.38},  {109.83, -4.90, -1.71, -8.81},
    {110.34, -5.84, -1.99, -4.56}, {106.36, -3.97, -1.75, -6.16}, {107.19, -1.25, -1.51, -26.73},
    {105.75, 0.77, -1.26, -34.44}, {101.18, 1.58, -1.10, -8.29},
};

// ---- Perez 1993 table 1 (gendaymtx PerezCoeff, gendaylit coeff_perez): per bin a1..a4 b1..b4
// c1..c4 d1..d4 e1..e4 -------------------------------------------------------------------------
constexpr double kPerezLuminance[kPerezBins][20] = {
    {1.3525, -0.2576, -0.2690, -1.4366, -0.7670, 0.0007, 1.2734, -0.1233, 2.8000, 0.6004, 1.2375, 1.0000, 1.8734,
     0.6297, 0.9738, 0.2809, 0.0356, -0.1246, -0.5718, 0.9938},
    {-1.2219, -0.7730, 1.4148, 1.1016, -0.2054, 0.0367, -3.9128, 0.9156, 6.9750, 0.1774, 6.4477, -0.1239, -1.5798,
     -0.5081, -1.7812, 0.1080, 0.2624, 0.0672, -0.2190, -0.4285},
    {-1.1000, -0.2515, 0.8952, 0.0156, 0.2782, -0.1812, -4.5000, 1.1766, 24.7219, -13.0812, -37.7000, 34.8438,
     -5.0000, 1.5218, 3.9229, -2.6204, -0.0156, 0.1597, 0.4199, -0.5562},
    {-0.5484, -0.6654, -0.2672, 0.7117, 0.7234, -0.6219, -5.6812, 2.6297, 33.3389, -18.3000, -62.2500, 52.0781,
     -3.5000, 0.0016, 1.1477, 0.1062, 0.4659, -0.3296, -0.0876, -0.0329},
    {-0.6000, -0.3566, -2.5000, 2.3250, 0.2937, 0.0496, -5.6812, 1.8415, 21.0000, -4.7656, -21.5906, 7.2492, -3.5000,
     -0.1554, 1.4062, 0.3988, 0.0032, 0.0766, -0.0656, -0.1294},
    {-1.0156, -0.3670, 1.0078, 1.4051, 0.2875, -0.5328, -3.8500, 3.3750, 14.0000, -0.9999, -7.1406, 7.5469, -3.4000,
     -0.1078, -1.0750, 1.5702, -0.0672, 0.4016, 0.3017, -0.4844},
    {-1.0000, 0.0211, 0.5025, -0.5119, -0.3000, 0.1922, 0.7023, -1.6317, 19.0000, -5.0000, 1.2438, -1.9094, -4.0000,
     0.0250, 0.3844, 0.2656, 1.0468, -0.3788, -2.4517, 1.4656},
    {-1.0500, 0.0289, 0.4260, 0.3590, -0.3250, 0.1156, 0.7781, 0.0025, 31.0625, -14.5000, -46.1148, 55.3750, -7.2312,
     0.4050, 13.3500, 0.6234, 1.5000, -0.6426, 1.8564, 0.5636},
};
constexpr double kPerezMinCosZeta = 0.01;  // perezlum.cal's floor on Dz in the gradation term
// The normalisation's quadrature: 1° altitude × 2° azimuth cells (90 × 180): within 2e-4 of a
// 0.125° × 0.125° rule over a dozen skies (worst with the sun at 3° zenith), about 0.5 ms a sky.
constexpr int kNormalisationAltitudeSteps = 90;

void require_bin(int bin) {
  require(bin >= 0 && bin < kPerezBins, "Perez clearness bin = " + std::to_string(bin) + ": must be in [0, 7]");
}

// The sun's zenith as gendaymtx's ComputeSky limits it: 90° below the horizon, >= 3°.
double limited_sun_zenith_rad(const Eigen::Vector3d& sun) {
  const double altitude = std::asin(std::clamp(sun.z(), -1.0, 1.0));
  if (altitude <= 0.0) return 90.0 * kRadPerDeg;
  if (altitude >= 87.0 * kRadPerDeg) return 3.0 * kRadPerDeg;
  return 0.5 * kPi - altitude;
}

double clearness_of(double dni, double dhi, double zenith_rad) {
  if (dhi <= 0.0) return kClearnessMax;
  const double kz3 = kClearnessKappa * zenith_rad * zenith_rad * zenith_rad;
  return std::clamp(((dhi + dni) / dhi + kz3) / (1.0 + kz3), 1.0, kClearnessMax);
}

// ∫ lv cos ζ dω over the upper hemisphere, midpoint rule on kAltitudeSteps × 2 kAltitudeSteps
// (altitude × azimuth) cells; the gradation is evaluated once per ring of constant altitude.
double perez_horizontal_integral(const PerezLuminanceCoefficients& k, const Eigen::Vector3d& sun, int altitude_steps) {
  const int azimuth_steps = 2 * altitude_steps;
  const double d_alt = 0.5 * kPi / altitude_steps, d_azi = 2.0 * kPi / azimuth_steps;
  double sum = 0.0;
  for (int i = 0; i < altitude_steps; ++i) {
    const double alt = (i + 0.5) * d_alt, ca = std::cos(alt), sa = std::sin(alt);
    const double gradation = 1.0 + k.a * std::exp(k.b / std::max(sa, kPerezMinCosZeta));
    double ring = 0.0;
    for (int j = 0; j < azimuth_steps; ++j) {
      const double azi = (j + 0.5) * d_azi;
      const double cos_gamma = std::clamp(ca * std::sin(azi) * sun.x() + ca * std::cos(azi) * sun.y() + sa * sun.z(),
                                          -1.0, 1.0);
      const double indicatrix = 1.0 + k.c * std::exp(k.d * std::acos(cos_gamma)) + k.e * cos_gamma * cos_gamma;
      ring += std::max(0.0, gradation * indicatrix);
    }
    sum += ring * sa * ca;
  }
  return sum * d_alt * d_azi;
}

// The mean of `f` over samples² equal-solid-angle cells of the patch (midpoints).
double patch_mean(const SkyPatch& p, const SkyLuminance& f, int samples) {
  const double z0 = std::sin(p.altitude_lo_deg * kRadPerDeg), z1 = std::sin(p.altitude_hi_deg * kRadPerDeg);
  const double a0 = p.azimuth_lo_deg * kRadPerDeg, a1 = p.azimuth_hi_deg * kRadPerDeg;
  double sum = 0.0;
  for (int s = 0; s < samples; ++s) {
    const double z = z0 + (s + 0.5) * (z1 - z0) / samples, r = std::sqrt(std::max(0.0, 1.0 - z * z));
    for (int t = 0; t < samples; ++t) {
      const double azi = a0 + (t + 0.5) * (a1 - a0) / samples;
      sum += f(Eigen::Vector3d(r * std::sin(azi), r * std::cos(azi), z));
    }
  }
  return sum / (samples * samples);
}

}  // namespace

// ---- Uniform and overcast ---------------------------------------------------------------------

SkyLuminance uniform_sky(double luminance_cd_per_m2) {
  return [luminance_cd_per_m2](const Eigen::Vector3d& d) { return d.z() < 0.0 ? 0.0 : luminance_cd_per_m2; };
}

double cie_overcast_relative_luminance(const Eigen::Vector3d& direction) {
  const Eigen::Vector3d d = unit(direction, "cie_overcast_relative_luminance: the direction");
  return d.z() < 0.0 ? 0.0 : (1.0 + 2.0 * d.z()) / 3.0;
}

SkyLuminance cie_overcast_sky(double zenith_luminance_cd_per_m2) {
  return [zenith_luminance_cd_per_m2](const Eigen::Vector3d& d) {
    return zenith_luminance_cd_per_m2 * cie_overcast_relative_luminance(d);
  };
}

// ---- CIE general skies ------------------------------------------------------------------------

std::span<const CieGeneralSkyType> cie_general_sky_types() { return kCieSkies; }

const CieGeneralSkyType& cie_general_sky_type(int type) {
  require(type >= 1 && type <= 15, "CIE general sky type = " + std::to_string(type) + ": must be in [1, 15]");
  return kCieSkies[type - 1];
}

double cie_general_sky_relative_luminance(const CieGeneralSkyType& sky, const Eigen::Vector3d& direction,
                                          const Eigen::Vector3d& sun_direction) {
  const Eigen::Vector3d d = unit(direction, "cie_general_sky_relative_luminance: the direction");
  const Eigen::Vector3d s = unit(sun_direction, "cie_general_sky_relative_luminance: the sun direction");
  require(s.z() >= 0.0, "cie_general_sky_relative_luminance: the sun is below the horizon (z < 0)");
  if (d.z() < 0.0) return 0.0;
  const double sun_zenith = std::acos(std::min(s.z(), 1.0));
  const double numerator = cie_indicatrix(sky, angle_between(d, s)) * cie_gradation(sky, d.z());
  return numerator / (cie_indicatrix(sky, sun_zenith) * cie_gradation(sky, 1.0));
}

SkyLuminance cie_general_sky(int type, const Eigen::Vector3d& sun_direction, double zenith_luminance_cd_per_m2) {
  const CieGeneralSkyType& sky = cie_general_sky_type(type);
  const Eigen::Vector3d s = unit(sun_direction, "cie_general_sky: the sun direction");
  require(s.z() >= 0.0, "cie_general_sky: the sun is below the horizon (z < 0)");
  return [&sky, s, zenith_luminance_cd_per_m2](const Eigen::Vector3d& d) {
    return zenith_luminance_cd_per_m2 * cie_general_sky_relative_luminance(sky, d, s);
  };
}

// ---- Perez 1990 -------------------------------------------------------------------------------

int perez_clearness_bin(double clearness) {
  require(clearness >= kClearnessBinLower[0] && clearness < kClearnessBinLower[kPerezBins],
          "Perez sky clearness = " + std::to_string(clearness) + ": must be in [1, 12.01)");
  int bin = 0;
  while (clearness >= kClearnessBinLower[bin + 1]) ++bin;
  return bin;
}

double precipitable_water_cm(double dew_point_c) { return std::exp(0.07 * dew_point_c - 0.075); }

double kasten_air_mass(double sun_zenith_rad) {
  return 1.0 / (std::cos(sun_zenith_rad) + 0.15 * std::pow(93.885 - sun_zenith_rad / kRadPerDeg, -1.253));
}

double eccentricity_correction(int day_of_year) {
  require(day_of_year >= 1 && day_of_year <= 366, "day of year = " + std::to_string(day_of_year) +
                                                      ": must be in [1, 366]");
  const double g = (day_of_year - 1.0) * 2.0 * kPi / 365.0;
  return 1.00011 + 0.034221 * std::cos(g) + 0.00128 * std::sin(g) + 0.000719 * std::cos(2.0 * g) +
         0.000077 * std::sin(2.0 * g);
}

double perez_diffuse_efficacy_lm_per_w(int bin, double w_cm, double sun_zenith_rad, double brightness) {
  require_bin(bin);
  require(brightness > 0.0, "Perez sky brightness = " + std::to_string(brightness) + ": must be > 0");
  const EfficacyCoefficients& k = kDiffuseEfficacy[bin];
  return k.a + k.b * w_cm + k.c * std::cos(sun_zenith_rad) + k.d * std::log(brightness);
}

double perez_direct_efficacy_lm_per_w(int bin, double w_cm, double sun_zenith_rad, double brightness) {
  require_bin(bin);
  const EfficacyCoefficients& k = kDirectEfficacy[bin];
  return std::max(0.0, k.a + k.b * w_cm + k.c * std::exp(5.73 * sun_zenith_rad - 5.0) + k.d * brightness);
}

PerezSkyConditions perez_sky_conditions(const PerezSkyInputs& in) {
  const double dni = in.direct_normal_w_per_m2, dhi = in.diffuse_horizontal_w_per_m2;
  require(std::isfinite(dni) && dni >= 0.0, "Perez sky: direct normal irradiance = " + std::to_string(dni) +
                                                " W/m²: must be finite and >= 0");
  require(std::isfinite(dhi) && dhi >= 0.0, "Perez sky: diffuse horizontal irradiance = " + std::to_string(dhi) +
                                                " W/m²: must be finite and >= 0");
  require(std::isfinite(in.dew_point_c), "Perez sky: the dew point must be finite");
  const Eigen::Vector3d sun = unit(in.sun_direction, "Perez sky: the sun direction");
  PerezSkyConditions c;
  c.sun_zenith_rad = limited_sun_zenith_rad(sun);
  c.sun_azimuth_deg = std::atan2(sun.x(), sun.y()) / kRadPerDeg;
  if (c.sun_azimuth_deg < 0.0) c.sun_azimuth_deg += 360.0;
  c.air_mass = kasten_air_mass(c.sun_zenith_rad);
  c.precipitable_water_cm = precipitable_water_cm(in.dew_point_c);
  c.clearness = clearness_of(dni, dhi, c.sun_zenith_rad);
  const double brightness = dhi * c.air_mass / (kSolarConstant_w_per_m2 * eccentricity_correction(in.day_of_year));
  c.brightness = std::clamp(brightness, kBrightnessMin, kBrightnessMax);
  c.bin = perez_clearness_bin(c.clearness);
  c.diffuse_efficacy_lm_per_w =
      perez_diffuse_efficacy_lm_per_w(c.bin, c.precipitable_water_cm, c.sun_zenith_rad, c.brightness);
  c.direct_efficacy_lm_per_w =
      perez_direct_efficacy_lm_per_w(c.bin, c.precipitable_water_cm, c.sun_zenith_rad, c.brightness);
  return c;
}

// ---- Perez 1993 -------------------------------------------------------------------------------

PerezLuminanceCoefficients perez_luminance_coefficients(int bin, double clearness, double brightness,
                                                        double sun_zenith_rad) {
  require_bin(bin);
  const double delta = (clearness > 1.065 && clearness < 2.8) ? std::max(brightness, 0.2) : brightness;
  const double z = sun_zenith_rad;
  const double* x = kPerezLuminance[bin];
  auto linear = [&](int i) { return x[4 * i] + x[4 * i + 1] * z + delta * (x[4 * i + 2] + x[4 * i + 3] * z); };
  PerezLuminanceCoefficients k{linear(0), linear(1), linear(2), linear(3), linear(4)};
  if (bin == 0) {
    k.c = std::exp(std::pow(delta * (x[8] + x[9] * z), x[10])) - x[11];
    k.d = -std::exp(delta * (x[12] + x[13] * z)) + x[14] + delta * x[15];
  }
  return k;
}

double perez_relative_luminance(const PerezLuminanceCoefficients& k, double zeta_rad, double gamma_rad) {
  const double cos_zeta = std::max(std::cos(zeta_rad), kPerezMinCosZeta);
  const double cos_gamma = std::cos(gamma_rad);
  const double lv = (1.0 + k.a * std::exp(k.b / cos_zeta)) *
                    (1.0 + k.c * std::exp(k.d * gamma_rad) + k.e * cos_gamma * cos_gamma);
  return std::max(lv, 0.0);
}

double PerezSky::luminance_cd_per_m2(const Eigen::Vector3d& direction) const {
  if (direction.z() < 0.0) return 0.0;
  if (uniform_fallback) return luminance_scale_cd_per_m2;
  const double zeta = std::acos(std::min(direction.z(), 1.0));
  return luminance_scale_cd_per_m2 *
         perez_relative_luminance(coefficients, zeta, angle_between(direction, sun_direction));
}

PerezSky perez_sky(const PerezSkyInputs& in) {
  PerezSky sky;
  sky.conditions = perez_sky_conditions(in);
  const PerezSkyConditions& c = sky.conditions;
  sky.coefficients = perez_luminance_coefficients(c.bin, c.clearness, c.brightness, c.sun_zenith_rad);
  const double azi = c.sun_azimuth_deg * kRadPerDeg, sz = std::sin(c.sun_zenith_rad);
  sky.sun_direction = Eigen::Vector3d(sz * std::sin(azi), sz * std::cos(azi), std::cos(c.sun_zenith_rad));
  if (in.direct_normal_w_per_m2 + in.diffuse_horizontal_w_per_m2 <= kNightThreshold_w_per_m2) return sky;
  sky.diffuse_horizontal_illuminance_lux = c.diffuse_efficacy_lm_per_w * in.diffuse_horizontal_w_per_m2;
  sky.direct_normal_illuminance_lux = c.direct_efficacy_lm_per_w * in.direct_normal_w_per_m2;
  sky.luminance_scale_cd_per_m2 = 1.0;
  double relative = perez_horizontal_integral(sky.coefficients, sky.sun_direction, kNormalisationAltitudeSteps);
  if (relative <= 1e-9) {  // gendaymtx's zero-sky fallback: uniform
    sky.uniform_fallback = true;
    relative = kPi;
  }
  sky.luminance_scale_cd_per_m2 = sky.diffuse_horizontal_illuminance_lux / relative;
  return sky;
}

SkyLuminance as_sky_luminance(const PerezSky& sky) {
  return [sky](const Eigen::Vector3d& d) { return sky.luminance_cd_per_m2(d); };
}

// ---- The sky vector ---------------------------------------------------------------------------

Eigen::VectorXd sky_vector(const SkySubdivision& sky, const SkyLuminance& luminance,
                           const SkyVectorOptions& options) {
  const int samples = options.samples_per_side;
  require(options.patch_centres_only || (samples >= 1 && samples <= 64),
          "sky_vector: samples_per_side = " + std::to_string(samples) + ": must be in [1, 64]");
  Eigen::VectorXd result(static_cast<Eigen::Index>(sky.patches.size()));
  for (std::size_t i = 0; i < sky.patches.size(); ++i) {
    const SkyPatch& p = sky.patches[i];
    result[static_cast<Eigen::Index>(i)] =
        options.patch_centres_only ? luminance(p.centre_direction) : patch_mean(p, luminance, samples);
  }
  return result;
}

double horizontal_illuminance_lux(const SkySubdivision& sky, const Eigen::VectorXd& luminance) {
  require(luminance.size() == static_cast<Eigen::Index>(sky.patches.size()),
          "horizontal_illuminance_lux: the sky vector has " + std::to_string(luminance.size()) +
              " entries, the subdivision " + std::to_string(sky.patches.size()) + " patches");
  double sum = 0.0;
  for (std::size_t i = 0; i < sky.patches.size(); ++i) {
    const SkyPatch& p = sky.patches[i];
    sum += luminance[static_cast<Eigen::Index>(i)] * p.centre_direction.z() * p.solid_angle_sr;
  }
  return sum;
}

std::ostream& operator<<(std::ostream& os, const PerezSkyConditions& c) {
  return os << "ε " << c.clearness << " (bin " << c.bin << "), Δ " << c.brightness << ", Z "
            << c.sun_zenith_rad / kRadPerDeg << "°, K_d " << c.diffuse_efficacy_lm_per_w << " lm/W, K_b "
            << c.direct_efficacy_lm_per_w << " lm/W";
}

}  // namespace ilp
