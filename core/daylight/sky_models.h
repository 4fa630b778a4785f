// Sky luminance distributions and their integration over a sky subdivision: the uniform sky,
// the CIE standard overcast sky (Moon & Spencer 1942), the 15 CIE standard general skies
// (CIE S 011/E:2003 = ISO 15469:2004), the Perez 1990 sky parameters and luminous efficacies
// and the Perez 1993 all-weather luminance model, normalised as Radiance's gendaymtx does
// (LBNL-ETA/Radiance src/gen/gendaymtx.c: followed, not copied). Luminances in cd/m² (or
// relative to the zenith, L/Lz). Frame of sky_patches.h: z up, +y north, +x east. Depends on
// Eigen and sky_patches.h; ../shared/DAYLIGHT.md section 1 gives the formulas and tables.
#pragma once

#include <functional>
#include <iosfwd>
#include <span>
#include <string_view>

#include <Eigen/Core>

#include "core/daylight/sky_patches.h"

namespace ilp {

// A sky's luminance (cd/m², or relative) toward a unit direction; 0 below the horizon (z < 0).
using SkyLuminance = std::function<double(const Eigen::Vector3d& direction)>;

// ---- Uniform and CIE standard overcast -------------------------------------------------------

// L everywhere above the horizon: E_h = π L.
SkyLuminance uniform_sky(double luminance_cd_per_m2);

// Moon & Spencer: L/Lz = (1 + 2 cos Z) / 3 (Z = zenith angle of `direction`, any length > 0);
// 0 below the horizon. E_h = 7π/9 Lz.
double cie_overcast_relative_luminance(const Eigen::Vector3d& direction);
SkyLuminance cie_overcast_sky(double zenith_luminance_cd_per_m2);

// ---- CIE standard general skies (CIE S 011/E:2003, ISO 15469:2004) ----------------------------

// One of the standard's 15 types: gradation φ(Z) = 1 + a exp(b / cos Z) and scattering
// indicatrix f(χ) = 1 + c [exp(d χ) - exp(d π/2)] + e cos² χ.
struct CieGeneralSkyType {
  int type;                      // 1..15
  std::string_view gradation;    // gradation group I..VI
  int indicatrix;                // indicatrix group 1..6
  double a, b, c, d, e;
  std::string_view description;  // the standard's wording, shortened
};

// The standard's table, types 1..15 in order (DAYLIGHT.md 1.4).
std::span<const CieGeneralSkyType> cie_general_sky_types();
// The row of `type`; throws std::invalid_argument unless 1 <= type <= 15.
const CieGeneralSkyType& cie_general_sky_type(int type);

// L/Lz = f(χ) φ(Z) / (f(Z_s) φ(0)) for the element toward `direction` (zenith angle Z, angle χ
// to the sun) and the sun toward `sun_direction` (zenith angle Z_s), both any length > 0. The
// horizon has φ = 1; 0 below it. Throws std::invalid_argument for a zero or non-finite vector or
// a sun below the horizon (the standard covers Z_s in [0, 90°]).
double cie_general_sky_relative_luminance(const CieGeneralSkyType& sky, const Eigen::Vector3d& direction,
                                          const Eigen::Vector3d& sun_direction);
SkyLuminance cie_general_sky(int type, const Eigen::Vector3d& sun_direction, double zenith_luminance_cd_per_m2);

// ---- Perez 1990: sky clearness, brightness, luminous efficacy ---------------------------------

inline constexpr double kSolarConstant_w_per_m2 = 1367.0;  // gendaymtx DC_SolarConstantE
inline constexpr int kPerezBins = 8;

// The clearness bin of ε (0-based; bounds 1, 1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2, 12.01, each
// lower bound inclusive, as gendaymtx's GetCategoryIndex). Throws std::invalid_argument for ε
// outside [1, 12.01).
int perez_clearness_bin(double clearness);
// W = exp(0.07 T_d - 0.075) cm (Perez 1990 eq. 3).
double precipitable_water_cm(double dew_point_c);
// Kasten 1966: m = 1 / (cos Z + 0.15 (93.885 - Z°)^-1.253), Z in [0, π/2].
double kasten_air_mass(double sun_zenith_rad);
// E_0 = 1.00011 + 0.034221 cos Γ + 0.00128 sin Γ + 0.000719 cos 2Γ + 0.000077 sin 2Γ,
// Γ = 2π (J - 1) / 365; day_of_year J in [1, 366].
double eccentricity_correction(int day_of_year);
// K_d = a + b W + c cos Z + d ln Δ (Perez 1990 table 4, eq. 7), lm/W; bin 0..7, Δ > 0.
double perez_diffuse_efficacy_lm_per_w(int bin, double precipitable_water_cm, double sun_zenith_rad,
                                       double brightness);
// K_b = max(0, a + b W + c exp(5.73 Z - 5) + d Δ) (Perez 1990 table 4, eq. 8), lm/W.
double perez_direct_efficacy_lm_per_w(int bin, double precipitable_water_cm, double sun_zenith_rad,
                                      double brightness);

// One hour of weather, as gendaymtx reads it from an EPW (WEA type 1).
struct PerezSkyInputs {
  double direct_normal_w_per_m2 = 0.0;        // DNI, >= 0
  double diffuse_horizontal_w_per_m2 = 0.0;   // DHI, >= 0
  Eigen::Vector3d sun_direction = Eigen::Vector3d::UnitZ();  // toward the sun, any length > 0
  double dew_point_c = 11.0;                  // gendaymtx's default when missing; finite
  int day_of_year = 1;                        // J in [1, 366], for E_0
};

// The sky's state as gendaymtx's ComputeSky derives it.
struct PerezSkyConditions {
  double sun_zenith_rad = 0.0;  // the sun's, limited to [3°, 90°] (90° with the sun below)
  double sun_azimuth_deg = 0.0; // east of north, in [0, 360)
  double air_mass = 0.0;        // Kasten, at the limited zenith
  double precipitable_water_cm = 0.0;
  // ε = ((DHI + DNI)/DHI + κ Z³) / (1 + κ Z³), κ = 1.041, limited to [1, 11.9]; DHI = 0 gives
  // ε = 11.9 (gendaymtx's infinity, limited).
  double clearness = 1.0;
  double brightness = 0.01;     // Δ = DHI m / (1367 E_0), limited to [0.01, 0.6]
  int bin = 0;                  // perez_clearness_bin(ε)
  double diffuse_efficacy_lm_per_w = 0.0;
  double direct_efficacy_lm_per_w = 0.0;
};

// Throws std::invalid_argument naming the input out of its range above.
PerezSkyConditions perez_sky_conditions(const PerezSkyInputs& in);

// ---- Perez 1993 all-weather luminance ---------------------------------------------------------

// lv(ζ, γ) = [1 + a exp(b / cos ζ)] [1 + c exp(d γ) + e cos² γ].
struct PerezLuminanceCoefficients {
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0, e = 0.0;
};

// a..e from Perez 1993 table 1 (gendaymtx PerezCoeff): x = x1 + x2 Z + Δ (x3 + x4 Z); in bin 0
// c = exp((Δ (c1 + c2 Z))^c3) - c4 and d = -exp(Δ (d1 + d2 Z)) + d3 + Δ d4. As gendaymtx's
// CalcPerezParam, Δ is raised to 0.2 when 1.065 < ε < 2.8. Z = sun zenith (rad).
PerezLuminanceCoefficients perez_luminance_coefficients(int bin, double clearness, double brightness,
                                                        double sun_zenith_rad);

// lv at element zenith angle ζ and angle γ to the sun (rad), clipped to >= 0 (gendaymtx). cos ζ
// is floored at 0.01 in the gradation term, as Radiance's perezlum.cal does, so the horizon
// stays finite when b > 0.
double perez_relative_luminance(const PerezLuminanceCoefficients& k, double zeta_rad, double gamma_rad);

// A Perez sky with its absolute scale: L = scale × lv, where the scale makes the horizontal
// illuminance of the sky (the continuous integral ∫ L cos ζ dω over the hemisphere, 1° × 2°
// midpoint rule, within 2e-4) equal K_d × DHI. gendaymtx normalises by its patch-centre sum instead
// (horizontal_illuminance_lux of the centre-sampled sky vector); the two differ by the
// subdivision's discretisation error. If lv vanishes everywhere the sky is uniform (gendaymtx's
// fallback).
struct PerezSky {
  PerezSkyConditions conditions;
  PerezLuminanceCoefficients coefficients;
  Eigen::Vector3d sun_direction = Eigen::Vector3d::UnitZ();  // as modelled: the limited zenith
  double luminance_scale_cd_per_m2 = 0.0;     // L = scale × lv
  bool uniform_fallback = false;              // lv was 0 everywhere: L = scale
  double diffuse_horizontal_illuminance_lux = 0.0;  // K_d × DHI
  double direct_normal_illuminance_lux = 0.0;       // K_b × DNI, for the sun placed elsewhere
  // L in cd/m² toward `direction` (unit); 0 below the horizon.
  double luminance_cd_per_m2(const Eigen::Vector3d& direction) const;
};

// Throws std::invalid_argument as perez_sky_conditions. Night (DNI + DHI <= 1e-4 W/m², gendaymtx's
// threshold) gives a black sky.
PerezSky perez_sky(const PerezSkyInputs& in);
SkyLuminance as_sky_luminance(const PerezSky& sky);

// ---- The sky vector ---------------------------------------------------------------------------

struct SkyVectorOptions {
  // Each patch's luminance is the mean over samples_per_side² cells of equal solid angle
  // (uniform in sin altitude and in azimuth; the zenith cap likewise over 0..360°), each
  // evaluated at its midpoint. In [1, 64].
  int samples_per_side = 8;
  // Evaluate each patch at its centre only, as gendaymtx does (samples_per_side is ignored).
  bool patch_centres_only = false;
};

// The luminance of each patch of `sky` (size sky.patches.size(), Radiance's order, the ground
// not included: element i is bin i + 1). Throws std::invalid_argument for samples_per_side
// outside [1, 64].
Eigen::VectorXd sky_vector(const SkySubdivision& sky, const SkyLuminance& luminance,
                           const SkyVectorOptions& options = {});

// Σ L_i cos θ_i Ω_i with θ_i the zenith angle of patch i's centre (gendaymtx's CalcRelHorzIllum),
// lux for L in cd/m². `luminance`: #patches. Throws std::invalid_argument on a size mismatch.
double horizontal_illuminance_lux(const SkySubdivision& sky, const Eigen::VectorXd& luminance);

// "ε 7.96 (bin 7), Δ 0.0815, Z 30°, K_d 124.3 lm/W, K_b 94.1 lm/W"
std::ostream& operator<<(std::ostream& os, const PerezSkyConditions& c);

}  // namespace ilp
