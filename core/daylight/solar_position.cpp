#include "core/daylight/solar_position.h"

#include <cmath>
#include <iomanip>
#include <numbers>
#include <ostream>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>

// The steps follow section 3 of Reda & Andreas (2004/2008), "Solar position algorithm for solar
// radiation applications", NREL/TP-560-34302; equation numbers are the report's. NREL's spa.c was not
// consulted. The periodic-term tables are the report's Tables A4.2 (Earth periodic terms, from
// VSOP87, Bretagnon & Francou 1988) and A4.3 (nutation, from Meeus 1998 ch. 22), transcribed here
// from pvlib-python's pvlib/spa.py (BSD-3-Clause; github.com/pvlib/pvlib-python, commit 6382338),
// which carries the same tables; term counts checked against the report (L0 64 ... R4 1; 63 nutation
// rows).

namespace ilp {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kJ2000 = 2451545.0;              // JD of 2000-01-01 12:00 TT
constexpr double kSunRadius_deg = 0.26667;        // the paper's apparent solar radius (eq. 42's cutoff)
constexpr double kEarthRadius_m = 6378140.0;      // equatorial radius used by eqs. 35-36
constexpr double kEarthFlattening = 0.99664719;   // b/a of the reference ellipsoid (eqs. 34, 36)

double rad(double angle_deg) { return angle_deg * kPi / 180.0; }
double deg(double angle_rad) { return angle_rad * 180.0 / kPi; }

// Limits an angle to [0, 360) (the paper's "limit to the range 0 to 360").
double limit_degrees(double a) {
  double r = std::fmod(a, 360.0);
  if (r < 0.0) r += 360.0;
  return r >= 360.0 ? 0.0 : r;
}

// One row A cos(B + C x) of an Earth periodic-term series (Table A4.2): A in 1e-8 rad (L, B) or
// 1e-8 AU (R), B in rad, C in rad per Julian ephemeris millennium.
struct PeriodicTerm {
  double a, b, c;
};

// One row of Table A4.3: the multiples Y0..Y4 of X0..X4 (eqs. 15-19) and the coefficients of
// Δψ = (a + b JCE) sin(Σ X_j Y_j) and Δε = (c + d JCE) cos(Σ X_j Y_j), in 0.0001 arcsec.
struct NutationTerm {
  int y[5];
  double a, b, c, d;
};

constexpr PeriodicTerm kL0[] = {
    {175347046.0, 0.0, 0.0}, {3341656.0, 4.6692568, 6283.07585}, {34894.0, 4.6261, 12566.1517},
    {3497.0, 2.7441, 5753.3849}, {3418.0, 2.8289, 3.5231}, {3136.0, 3.6277, 77713.7715},
    {2676.0, 4.4181, 7860.4194}, {2343.0, 6.1352, 3930.2097}, {1324.0, 0.7425, 11506.7698},
    {1273.0, 2.0371, 529.691}, {1199.0, 1.1096, 1577.3435}, {990.0, 5.233, 5884.927},
    {902.0, 2.045, 26.298}, {857.0, 3.508, 398.149}, {780.0, 1.179, 5223.694}, {753.0, 2.533, 5507.553},
    {505.0, 4.583, 18849.228}, {492.0, 4.205, 775.523}, {357.0, 2.92, 0.067}, {317.0, 5.849, 11790.629},
    {284.0, 1.899, 796.298}, {271.0, 0.315, 10977.079}, {243.0, 0.345, 5486.778},
    {206.0, 4.806, 2544.314}, {205.0, 1.869, 5573.143}, {202.0, 2.458, 6069.777},
    {156.0, 0.833, 213.299}, {132.0, 3.411, 2942.463}, {126.0, 1.083, 20.775}, {115.0, 0.645, 0.98},
    {103.0, 0.636, 4694.003}, {102.0, 0.976, 15720.839}, {102.0, 4.267, 7.114}, {99.0, 6.21, 2146.17},
    {98.0, 0.68, 155.42}, {86.0, 5.98, 161000.69}, {85.0, 1.3, 6275.96}, {85.0, 3.67, 71430.7},
    {80.0, 1.81, 17260.15}, {79.0, 3.04, 12036.46}, {75.0, 1.76, 5088.63}, {74.0, 3.5, 3154.69},
    {74.0, 4.68, 801.82}, {70.0, 0.83, 9437.76}, {62.0, 3.98, 8827.39}, {61.0, 1.82, 7084.9},
    {57.0, 2.78, 6286.6}, {56.0, 4.39, 14143.5}, {56.0, 3.47, 6279.55}, {52.0, 0.19, 12139.55},
    {52.0, 1.33, 1748.02}, {51.0, 0.28, 5856.48}, {49.0, 0.49, 1194.45}, {41.0, 5.37, 8429.24},
    {41.0, 2.4, 19651.05}, {39.0, 6.17, 10447.39}, {37.0, 6.04, 10213.29}, {37.0, 2.57, 1059.38},
    {36.0, 1.71, 2352.87}, {36.0, 1.78, 6812.77}, {33.0, 0.59, 17789.85}, {30.0, 0.44, 83996.85},
    {30.0, 2.74, 1349.87}, {25.0, 3.16, 4690.48},
};
constexpr PeriodicTerm kL1[] = {
    {628331966747.0, 0.0, 0.0}, {206059.0, 2.678235, 6283.07585}, {4303.0, 2.6351, 12566.1517},
    {425.0, 1.59, 3.523}, {119.0, 5.796, 26.298}, {109.0, 2.966, 1577.344}, {93.0, 2.59, 18849.23},
    {72.0, 1.14, 529.69}, {68.0, 1.87, 398.15}, {67.0, 4.41, 5507.55}, {59.0, 2.89, 5223.69},
    {56.0, 2.17, 155.42}, {45.0, 0.4, 796.3}, {36.0, 0.47, 775.52}, {29.0, 2.65, 7.11},
    {21.0, 5.34, 0.98}, {19.0, 1.85, 5486.78}, {19.0, 4.97, 213.3}, {17.0, 2.99, 6275.96},
    {16.0, 0.03, 2544.31}, {16.0, 1.43, 2146.17}, {15.0, 1.21, 10977.08}, {12.0, 2.83, 1748.02},
    {12.0, 3.26, 5088.63}, {12.0, 5.27, 1194.45}, {12.0, 2.08, 4694.0}, {11.0, 0.77, 553.57},
    {10.0, 1.3, 6286.6}, {10.0, 4.24, 1349.87}, {9.0, 2.7, 242.73}, {9.0, 5.64, 951.72},
    {8.0, 5.3, 2352.87}, {6.0, 2.65, 9437.76}, {6.0, 4.67, 4690.48},
};
constexpr PeriodicTerm kL2[] = {
    {52919.0, 0.0, 0.0}, {8720.0, 1.0721, 6283.0758}, {309.0, 0.867, 12566.152}, {27.0, 0.05, 3.52},
    {16.0, 5.19, 26.3}, {16.0, 3.68, 155.42}, {10.0, 0.76, 18849.23}, {9.0, 2.06, 77713.77},
    {7.0, 0.83, 775.52}, {5.0, 4.66, 1577.34}, {4.0, 1.03, 7.11}, {4.0, 3.44, 5573.14},
    {3.0, 5.14, 796.3}, {3.0, 6.05, 5507.55}, {3.0, 1.19, 242.73}, {3.0, 6.12, 529.69},
    {3.0, 0.31, 398.15}, {3.0, 2.28, 553.57}, {2.0, 4.38, 5223.69}, {2.0, 3.75, 0.98},
};
constexpr PeriodicTerm kL3[] = {
    {289.0, 5.844, 6283.076}, {35.0, 0.0, 0.0}, {17.0, 5.49, 12566.15}, {3.0, 5.2, 155.42},
    {1.0, 4.72, 3.52}, {1.0, 5.3, 18849.23}, {1.0, 5.97, 242.73},
};
constexpr PeriodicTerm kL4[] = {
    {114.0, 3.142, 0.0}, {8.0, 4.13, 6283.08}, {1.0, 3.84, 12566.15},
};
constexpr PeriodicTerm kL5[] = {
    {1.0, 3.14, 0.0},
};
constexpr PeriodicTerm kB0[] = {
    {280.0, 3.199, 84334.662}, {102.0, 5.422, 5507.553}, {80.0, 3.88, 5223.69}, {44.0, 3.7, 2352.87},
    {32.0, 4.0, 1577.34},
};
constexpr PeriodicTerm kB1[] = {
    {9.0, 3.9, 5507.55}, {6.0, 1.73, 5223.69},
};
constexpr PeriodicTerm kR0[] = {
    {100013989.0, 0.0, 0.0}, {1670700.0, 3.0984635, 6283.07585}, {13956.0, 3.05525, 12566.1517},
    {3084.0, 5.1985, 77713.7715}, {1628.0, 1.1739, 5753.3849}, {1576.0, 2.8469, 7860.4194},
    {925.0, 5.453, 11506.77}, {542.0, 4.564, 3930.21}, {472.0, 3.661, 5884.927},
    {346.0, 0.964, 5507.553}, {329.0, 5.9, 5223.694}, {307.0, 0.299, 5573.143},
    {243.0, 4.273, 11790.629}, {212.0, 5.847, 1577.344}, {186.0, 5.022, 10977.079},
    {175.0, 3.012, 18849.228}, {110.0, 5.055, 5486.778}, {98.0, 0.89, 6069.78}, {86.0, 5.69, 15720.84},
    {86.0, 1.27, 161000.69}, {65.0, 0.27, 17260.15}, {63.0, 0.92, 529.69}, {57.0, 2.01, 83996.85},
    {56.0, 5.24, 71430.7}, {49.0, 3.25, 2544.31}, {47.0, 2.58, 775.52}, {45.0, 5.54, 9437.76},
    {43.0, 6.01, 6275.96}, {39.0, 5.36, 4694.0}, {38.0, 2.39, 8827.39}, {37.0, 0.83, 19651.05},
    {37.0, 4.9, 12139.55}, {36.0, 1.67, 12036.46}, {35.0, 1.84, 2942.46}, {33.0, 0.24, 7084.9},
    {32.0, 0.18, 5088.63}, {32.0, 1.78, 398.15}, {28.0, 1.21, 6286.6}, {28.0, 1.9, 6279.55},
    {26.0, 4.59, 10447.39},
};
constexpr PeriodicTerm kR1[] = {
    {103019.0, 1.10749, 6283.07585}, {1721.0, 1.0644, 12566.1517}, {702.0, 3.142, 0.0},
    {32.0, 1.02, 18849.23}, {31.0, 2.84, 5507.55}, {25.0, 1.32, 5223.69}, {18.0, 1.42, 1577.34},
    {10.0, 5.91, 10977.08}, {9.0, 1.42, 6275.96}, {9.0, 0.27, 5486.78},
};
constexpr PeriodicTerm kR2[] = {
    {4359.0, 5.7846, 6283.0758}, {124.0, 5.579, 12566.152}, {12.0, 3.14, 0.0}, {9.0, 3.63, 77713.77},
    {6.0, 1.87, 5573.14}, {3.0, 5.47, 18849.23},
};
constexpr PeriodicTerm kR3[] = {
    {145.0, 4.273, 6283.076}, {7.0, 3.92, 12566.15},
};
constexpr PeriodicTerm kR4[] = {
    {4.0, 2.56, 6283.08},
};
constexpr NutationTerm kNutation[] = {
    {{0, 0, 0, 0, 1}, -171996.0, -174.2, 92025.0, 8.9},
    {{-2, 0, 0, 2, 2}, -13187.0, -1.6, 5736.0, -3.1},
    {{0, 0, 0, 2, 2}, -2274.0, -0.2, 977.0, -0.5},
    {{0, 0, 0, 0, 2}, 2062.0, 0.2, -895.0, 0.5},
    {{0, 1, 0, 0, 0}, 1426.0, -3.4, 54.0, -0.1},
    {{0, 0, 1, 0, 0}, 712.0, 0.1, -7.0, 0.0},
    {{-2, 1, 0, 2, 2}, -517.0, 1.2, 224.0, -0.6},
    {{0, 0, 0, 2, 1}, -386.0, -0.4, 200.0, 0.0},
    {{0, 0, 1, 2, 2}, -301.0, 0.0, 129.0, -0.1},
    {{-2, -1, 0, 2, 2}, 217.0, -0.5, -95.0, 0.3},
    {{-2, 0, 1, 0, 0}, -158.0, 0.0, 0.0, 0.0},
    {{-2, 0, 0, 2, 1}, 129.0, 0.1, -70.0, 0.0},
    {{0, 0, -1, 2, 2}, 123.0, 0.0, -53.0, 0.0},
    {{2, 0, 0, 0, 0}, 63.0, 0.0, 0.0, 0.0},
    {{0, 0, 1, 0, 1}, 63.0, 0.1, -33.0, 0.0},
    {{2, 0, -1, 2, 2}, -59.0, 0.0, 26.0, 0.0},
    {{0, 0, -1, 0, 1}, -58.0, -0.1, 32.0, 0.0},
    {{0, 0, 1, 2, 1}, -51.0, 0.0, 27.0, 0.0},
    {{-2, 0, 2, 0, 0}, 48.0, 0.0, 0.0, 0.0},
    {{0, 0, -2, 2, 1}, 46.0, 0.0, -24.0, 0.0},
    {{2, 0, 0, 2, 2}, -38.0, 0.0, 16.0, 0.0},
    {{0, 0, 2, 2, 2}, -31.0, 0.0, 13.0, 0.0},
    {{0, 0, 2, 0, 0}, 29.0, 0.0, 0.0, 0.0},
    {{-2, 0, 1, 2, 2}, 29.0, 0.0, -12.0, 0.0},
    {{0, 0, 0, 2, 0}, 26.0, 0.0, 0.0, 0.0},
    {{-2, 0, 0, 2, 0}, -22.0, 0.0, 0.0, 0.0},
    {{0, 0, -1, 2, 1}, 21.0, 0.0, -10.0, 0.0},
    {{0, 2, 0, 0, 0}, 17.0, -0.1, 0.0, 0.0},
    {{2, 0, -1, 0, 1}, 16.0, 0.0, -8.0, 0.0},
    {{-2, 2, 0, 2, 2}, -16.0, 0.1, 7.0, 0.0},
    {{0, 1, 0, 0, 1}, -15.0, 0.0, 9.0, 0.0},
    {{-2, 0, 1, 0, 1}, -13.0, 0.0, 7.0, 0.0},
    {{0, -1, 0, 0, 1}, -12.0, 0.0, 6.0, 0.0},
    {{0, 0, 2, -2, 0}, 11.0, 0.0, 0.0, 0.0},
    {{2, 0, -1, 2, 1}, -10.0, 0.0, 5.0, 0.0},
    {{2, 0, 1, 2, 2}, -8.0, 0.0, 3.0, 0.0},
    {{0, 1, 0, 2, 2}, 7.0, 0.0, -3.0, 0.0},
    {{-2, 1, 1, 0, 0}, -7.0, 0.0, 0.0, 0.0},
    {{0, -1, 0, 2, 2}, -7.0, 0.0, 3.0, 0.0},
    {{2, 0, 0, 2, 1}, -7.0, 0.0, 3.0, 0.0},
    {{2, 0, 1, 0, 0}, 6.0, 0.0, 0.0, 0.0},
    {{-2, 0, 2, 2, 2}, 6.0, 0.0, -3.0, 0.0},
    {{-2, 0, 1, 2, 1}, 6.0, 0.0, -3.0, 0.0},
    {{2, 0, -2, 0, 1}, -6.0, 0.0, 3.0, 0.0},
    {{2, 0, 0, 0, 1}, -6.0, 0.0, 3.0, 0.0},
    {{0, -1, 1, 0, 0}, 5.0, 0.0, 0.0, 0.0},
    {{-2, -1, 0, 2, 1}, -5.0, 0.0, 3.0, 0.0},
    {{-2, 0, 0, 0, 1}, -5.0, 0.0, 3.0, 0.0},
    {{0, 0, 2, 2, 1}, -5.0, 0.0, 3.0, 0.0},
    {{-2, 0, 2, 0, 1}, 4.0, 0.0, 0.0, 0.0},
    {{-2, 1, 0, 2, 1}, 4.0, 0.0, 0.0, 0.0},
    {{0, 0, 1, -2, 0}, 4.0, 0.0, 0.0, 0.0},
    {{-1, 0, 1, 0, 0}, -4.0, 0.0, 0.0, 0.0},
    {{-2, 1, 0, 0, 0}, -4.0, 0.0, 0.0, 0.0},
    {{1, 0, 0, 0, 0}, -4.0, 0.0, 0.0, 0.0},
    {{0, 0, 1, 2, 0}, 3.0, 0.0, 0.0, 0.0},
    {{0, 0, -2, 2, 2}, -3.0, 0.0, 0.0, 0.0},
    {{-1, -1, 1, 0, 0}, -3.0, 0.0, 0.0, 0.0},
    {{0, 1, 1, 0, 0}, -3.0, 0.0, 0.0, 0.0},
    {{0, -1, 1, 2, 2}, -3.0, 0.0, 0.0, 0.0},
    {{2, -1, -1, 2, 2}, -3.0, 0.0, 0.0, 0.0},
    {{0, 0, 3, 2, 2}, -3.0, 0.0, 0.0, 0.0},
    {{2, -1, 0, 2, 2}, -3.0, 0.0, 0.0, 0.0},
};

// ---- Input checks ---------------------------------------------------------------------------

std::string text(double v) {
  std::ostringstream s;
  s << std::setprecision(12) << v;
  return s.str();
}

void require(bool ok, const char* field, const std::string& value, const char* rule) {
  if (!ok) throw std::invalid_argument(std::string("solar_position: ") + field + " = " + value + ": " + rule);
}

void require_in(double v, double lo, double hi, const char* field, const char* rule) {
  require(std::isfinite(v) && v >= lo && v <= hi, field, text(v), rule);
}

// Gregorian from 1582-10-15 on, Julian before (the date as given, so that a time zone carrying the
// instant across midnight of the reform cannot switch calendars).
bool is_gregorian(int year, int month, int day) {
  if (year != 1582) return year > 1582;
  return month > 10 || (month == 10 && day >= 15);
}

int days_in_month(int year, int month) {
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (month != 2) return kDays[month - 1];
  const bool gregorian = is_gregorian(year, 3, 1);
  const bool leap = gregorian ? (year % 4 == 0 && (year % 100 != 0 || year % 400 == 0)) : year % 4 == 0;
  return leap ? 29 : 28;
}

void check_instant(const SolarInstant& t) {
  require(t.year >= -2000 && t.year <= 6000, "SolarInstant::year", std::to_string(t.year),
          "must be in [-2000, 6000], the algorithm's range of validity");
  require(t.month >= 1 && t.month <= 12, "SolarInstant::month", std::to_string(t.month), "must be in [1, 12]");
  require(t.day >= 1 && t.day <= days_in_month(t.year, t.month), "SolarInstant::day", std::to_string(t.day),
          "must be in [1, days of the month]");
  require(!(t.year == 1582 && t.month == 10 && t.day > 4 && t.day < 15), "SolarInstant::day",
          std::to_string(t.day), "1582-10-05..14 do not exist (the Gregorian reform)");
  require(t.hour >= 0 && t.hour <= 24, "SolarInstant::hour", std::to_string(t.hour), "must be in [0, 24]");
  require(t.minute >= 0 && t.minute <= 59, "SolarInstant::minute", std::to_string(t.minute),
          "must be in [0, 59]");
  require(std::isfinite(t.second) && t.second >= 0.0 && t.second < 60.0, "SolarInstant::second",
          text(t.second), "must be in [0, 60)");
  require(t.hour < 24 || (t.minute == 0 && t.second == 0.0), "SolarInstant::hour", std::to_string(t.hour),
          "24 only as 24:00:00");
  require_in(t.timezone_h, -18.0, 18.0, "SolarInstant::timezone_h", "must be in [-18, 18] h east of UTC");
  require_in(t.delta_t_s, -86400.0, 86400.0, "SolarInstant::delta_t_s", "must be finite, |TT - UT1| <= 86400 s");
}

void check_site(const SolarSite& s, double refraction_deg) {
  require_in(s.latitude_deg, -90.0, 90.0, "SolarSite::latitude_deg", "must be in [-90, 90]");
  require_in(s.longitude_deg, -180.0, 180.0, "SolarSite::longitude_deg", "must be in [-180, 180], east positive");
  require(std::isfinite(s.elevation_m) && s.elevation_m > -kEarthRadius_m, "SolarSite::elevation_m",
          text(s.elevation_m), "must be finite and > -6378140 m");
  require_in(s.pressure_mbar, 0.0, 2000.0, "SolarSite::pressure_mbar", "must be in [0, 2000] mbar (not Pa)");
  require(std::isfinite(s.temperature_c) && s.temperature_c > -273.0 && s.temperature_c <= 100.0,
          "SolarSite::temperature_c", text(s.temperature_c), "must be in (-273, 100] °C");
  // Above 4° the cutoff -(0.26667° + refraction) would reach eq. 42's pole at e0 = -5.11°.
  require_in(refraction_deg, 0.0, 4.0, "atmospheric_refraction_deg", "must be in [0, 4]");
}

// ---- 3.1 Time scales ------------------------------------------------------------------------

// Eq. 4 (Meeus 1998 ch. 7): the Julian day of a UT date whose day carries the time as a fraction.
// INT is truncation; B = 2 - A + INT(A / 4) for Gregorian dates, 0 for Julian ones.
double julian_day(const SolarInstant& t) {
  const double day = t.day + (t.hour + t.minute / 60.0 + t.second / 3600.0 - t.timezone_h) / 24.0;
  int y = t.year, m = t.month;
  if (m <= 2) {
    y -= 1;
    m += 12;
  }
  double b = 0.0;
  if (is_gregorian(t.year, t.month, t.day)) {
    const int a = y / 100;  // y >= 1582 here, so truncation is the floor
    b = 2 - a + a / 4;
  }
  return std::trunc(365.25 * (y + 4716)) + std::trunc(30.6001 * (m + 1)) + day + b - 1524.5;
}

// ---- 3.2-3.3 Earth heliocentric, sun geocentric ---------------------------------------------

// Eq. 9-10: Σ A cos(B + C JME) over one table.
double periodic_sum(std::span<const PeriodicTerm> terms, double jme) {
  double s = 0.0;
  for (const PeriodicTerm& p : terms) s += p.a * std::cos(p.b + p.c * jme);
  return s;
}

// Eq. 11: (X0 + X1 JME + X2 JME² + ...) / 1e8, by Horner's rule.
double earth_series(std::span<const std::span<const PeriodicTerm>> tables, double jme) {
  double s = 0.0;
  for (auto it = tables.rbegin(); it != tables.rend(); ++it) s = s * jme + periodic_sum(*it, jme);
  return s / 1e8;
}

struct Heliocentric {
  double longitude_deg;  // L, limited to [0, 360)
  double latitude_deg;   // B
  double radius_au;      // R
};

Heliocentric earth_heliocentric(double jme) {
  static constexpr std::span<const PeriodicTerm> kL[] = {kL0, kL1, kL2, kL3, kL4, kL5};
  static constexpr std::span<const PeriodicTerm> kB[] = {kB0, kB1};
  static constexpr std::span<const PeriodicTerm> kR[] = {kR0, kR1, kR2, kR3, kR4};
  return {limit_degrees(deg(earth_series(kL, jme))), deg(earth_series(kB, jme)), earth_series(kR, jme)};
}

// ---- 3.4-3.5 Nutation and the obliquity of the ecliptic -------------------------------------

struct Nutation {
  double longitude_deg;  // Δψ
  double obliquity_deg;  // Δε
};

// Eqs. 15-23: X0..X4 (degrees) from the Julian ephemeris century, then the 63 rows of Table A4.3.
Nutation nutation(double jce) {
  const double x[5] = {
      297.85036 + jce * (445267.111480 + jce * (-0.0019142 + jce / 189474.0)),  // mean elongation of the moon
      357.52772 + jce * (35999.050340 + jce * (-0.0001603 - jce / 300000.0)),   // mean anomaly of the sun
      134.96298 + jce * (477198.867398 + jce * (0.0086972 + jce / 56250.0)),    // mean anomaly of the moon
      93.27191 + jce * (483202.017538 + jce * (-0.0036825 + jce / 327270.0)),   // moon's argument of latitude
      125.04452 + jce * (-1934.136261 + jce * (0.0020708 + jce / 450000.0)),    // moon's ascending node
  };
  double psi = 0.0, eps = 0.0;
  for (const NutationTerm& n : kNutation) {
    double arg = 0.0;
    for (int j = 0; j < 5; ++j) arg += x[j] * n.y[j];
    psi += (n.a + n.b * jce) * std::sin(rad(arg));
    eps += (n.c + n.d * jce) * std::cos(rad(arg));
  }
  return {psi / 36000000.0, eps / 36000000.0};
}

// Eq. 24: the mean obliquity ε0 in arcseconds, U = JME / 10 (Laskar 1986, valid |U| < 1).
double mean_obliquity_arcsec(double jme) {
  static constexpr double kC[] = {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67,
                                  -39.05,    7.12,     27.87, 5.79,    2.45};
  const double u = jme / 10.0;
  double s = 0.0;
  for (int i = 10; i >= 0; --i) s = s * u + kC[i];
  return s;
}

// ---- 3.6-3.10 The geocentric sun ------------------------------------------------------------

struct GeocentricSun {
  double right_ascension_deg;  // α, [0, 360)
  double declination_deg;      // δ
  double sidereal_time_deg;    // ν, apparent sidereal time at Greenwich
  double radius_au;            // R, for the parallax
};

GeocentricSun geocentric_sun(double jd, double jde) {
  const double jc = (jd - kJ2000) / 36525.0;    // eq. 6
  const double jce = (jde - kJ2000) / 36525.0;  // eq. 7
  const double jme = jce / 10.0;                // eq. 8
  const Heliocentric h = earth_heliocentric(jme);
  const double theta = limit_degrees(h.longitude_deg + 180.0);  // eq. 13
  const double beta = -h.latitude_deg;                          // eq. 14
  const Nutation n = nutation(jce);
  const double epsilon = mean_obliquity_arcsec(jme) / 3600.0 + n.obliquity_deg;  // eq. 25
  const double aberration = -20.4898 / (3600.0 * h.radius_au);                   // eq. 26
  const double lambda = theta + n.longitude_deg + aberration;                    // eq. 27
  const double nu0 = limit_degrees(280.46061837 + 360.98564736629 * (jd - kJ2000) + 0.000387933 * jc * jc -
                                   jc * jc * jc / 38710000.0);  // eq. 28
  const double nu = nu0 + n.longitude_deg * std::cos(rad(epsilon));  // eq. 29
  const double l = rad(lambda), e = rad(epsilon), b = rad(beta);
  const double alpha = deg(std::atan2(std::sin(l) * std::cos(e) - std::tan(b) * std::sin(e), std::cos(l)));  // eq. 30
  const double delta = deg(std::asin(std::sin(b) * std::cos(e) + std::cos(b) * std::sin(e) * std::sin(l)));  // eq. 31
  return {limit_degrees(alpha), delta, nu, h.radius_au};
}

// ---- 3.11-3.15 The topocentric sun ----------------------------------------------------------

struct Topocentric {
  double declination_deg;  // δ'
  double hour_angle_deg;   // H', west of south
};

// Eqs. 32-40: the hour angle and the parallax of the observer's position on the ellipsoid shifts α and δ.
Topocentric topocentric(const GeocentricSun& g, const SolarSite& site) {
  const double hour_angle = limit_degrees(g.sidereal_time_deg + site.longitude_deg - g.right_ascension_deg);  // eq. 32
  const double xi = rad(8.794 / (3600.0 * g.radius_au));  // eq. 33, equatorial horizontal parallax
  const double phi = rad(site.latitude_deg);
  const double u = std::atan(kEarthFlattening * std::tan(phi));                            // eq. 34
  const double x = std::cos(u) + site.elevation_m / kEarthRadius_m * std::cos(phi);             // eq. 35
  const double y = kEarthFlattening * std::sin(u) + site.elevation_m / kEarthRadius_m * std::sin(phi);  // eq. 36
  const double h = rad(hour_angle), delta = rad(g.declination_deg);
  const double denom = std::cos(delta) - x * std::sin(xi) * std::cos(h);
  const double d_alpha = std::atan2(-x * std::sin(xi) * std::sin(h), denom);                     // eq. 37
  const double delta_p = std::atan2((std::sin(delta) - y * std::sin(xi)) * std::cos(d_alpha), denom);  // eq. 39
  return {deg(delta_p), hour_angle - deg(d_alpha)};  // eq. 40
}

// Eq. 42 (Saemundsson's formula in the paper's form), degrees, applied only while some of the disc
// can be above the horizon (the 2008 revision's condition on e0).
double refraction_correction_deg(double e0_deg, const SolarSite& site, double refraction_deg) {
  if (e0_deg < -(kSunRadius_deg + refraction_deg)) return 0.0;
  return site.pressure_mbar / 1010.0 * 283.0 / (273.0 + site.temperature_c) * 1.02 /
         (60.0 * std::tan(rad(e0_deg + 10.3 / (e0_deg + 5.11))));
}

}  // namespace

SolarPosition solar_position(const SolarInstant& t, const SolarSite& site, double atmospheric_refraction_deg) {
  check_instant(t);
  check_site(site, atmospheric_refraction_deg);
  const double jd = julian_day(t);
  const double jde = jd + t.delta_t_s / 86400.0;  // eq. 5
  const GeocentricSun g = geocentric_sun(jd, jde);
  const Topocentric tp = topocentric(g, site);
  const double phi = rad(site.latitude_deg), dp = rad(tp.declination_deg), hp = rad(tp.hour_angle_deg);
  // Eq. 41: the topocentric elevation without refraction.
  const double e0 = deg(std::asin(std::sin(phi) * std::sin(dp) + std::cos(phi) * std::cos(dp) * std::cos(hp)));
  const double e = e0 + refraction_correction_deg(e0, site, atmospheric_refraction_deg);  // eq. 43
  // Eq. 44-46: the astronomers' azimuth Γ (west of south), turned to east of north.
  const double gamma = deg(std::atan2(std::sin(hp), std::cos(hp) * std::sin(phi) - std::tan(dp) * std::cos(phi)));
  SolarPosition p;
  p.zenith_deg = 90.0 - e;
  p.geometric_zenith_deg = 90.0 - e0;
  p.azimuth_deg = limit_degrees(gamma + 180.0);
  p.declination_deg = g.declination_deg;
  p.julian_day = jd;
  return p;
}

Eigen::Vector3d sun_direction(const SolarPosition& p) {
  const double z = rad(p.zenith_deg), a = rad(p.azimuth_deg);
  return {std::sin(a) * std::sin(z), std::cos(a) * std::sin(z), std::cos(z)};
}

std::ostream& operator<<(std::ostream& os, const SolarPosition& p) {
  const std::ios_base::fmtflags flags = os.flags();
  const std::streamsize precision = os.precision();
  os << std::fixed << std::setprecision(6) << "zenith " << p.zenith_deg << "° (geometric " << p.geometric_zenith_deg
     << "°), azimuth " << p.azimuth_deg << "°, declination " << p.declination_deg << "°, JD " << p.julian_day;
  os.flags(flags);
  os.precision(precision);
  return os;
}

}  // namespace ilp
