// NREL's Solar Position Algorithm (core/daylight/solar_position.h) against the report's worked
// example (NREL/TP-560-34302, its table of results and the spa_tester case quoted in ../shared/DAYLIGHT.md),
// Meeus's Julian days (Astronomical Algorithms, 2nd ed., ch. 7, = the report's Table A4.1) and his
// example 25.b, the civil calendar of <chrono>, USNO's 2024 equinoxes and solstices, NOAA's
// approximate solar noon, closed forms (the pole, symmetry about transit), and the refused inputs.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/daylight/solar_position.h"

namespace ilp {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The report's stated accuracy of SPA against the full theory, ±0.0003° (abstract).
constexpr double kSpaAccuracy_deg = 3e-4;

// The report's example: Golden, Colorado (NREL's Solar Radiation Research Laboratory).
SolarSite golden() {
  return {.latitude_deg = 39.742476, .longitude_deg = -105.1786, .elevation_m = 1830.14, .pressure_mbar = 820.0,
          .temperature_c = 11.0};
}

SolarInstant utc(int year, int month, int day, int hour = 0, int minute = 0, double second = 0.0) {
  return {.year = year, .month = month, .day = day, .hour = hour, .minute = minute, .second = second,
          .timezone_h = 0.0, .delta_t_s = 69.0};
}

// Local civil time `seconds` after the midnight that opens the given date.
SolarInstant local_at(int year, int month, int day, double seconds, double timezone_h) {
  const int whole = static_cast<int>(std::floor(seconds));
  return {.year = year, .month = month, .day = day, .hour = whole / 3600, .minute = whole / 60 % 60,
          .second = seconds - whole + whole % 60, .timezone_h = timezone_h, .delta_t_s = 69.0};
}

// 2003-10-17 12:30:30 MST, ΔT = 67 s, refraction 0.5667° (the report's worked example and its table of
// intermediate results; the 6-decimal zenith is spa_tester's, as ../shared/DAYLIGHT.md quotes it).
// Measured: JD 2452930.3128472, zenith 50.1116220°, geometric zenith 50.1279541°, azimuth
// 194.3402405°, declination -9.3143401°, Δe 0.0163321° (each within 1e-6 of the report's digits).
TEST(SolarPosition, MatchesTheReportsWorkedExample) {
  const SolarInstant t{.year = 2003, .month = 10, .day = 17, .hour = 12, .minute = 30, .second = 30.0,
                       .timezone_h = -7.0, .delta_t_s = 67.0};
  const SolarPosition p = solar_position(t, golden(), 0.5667);
  EXPECT_NEAR(p.julian_day, 2452930.312847, 5e-7) << p;  // the report gives 6 decimals
  EXPECT_NEAR(p.zenith_deg, 50.11162, 5e-6) << p;         // the report: θ = 50.11162°
  EXPECT_NEAR(p.zenith_deg, 50.111622, 1e-6) << p;        // spa_tester: 50.111622°
  EXPECT_NEAR(p.geometric_zenith_deg, 90.0 - 39.872046, 1e-6) << p;  // e0 = 39.872046°
  EXPECT_NEAR(p.azimuth_deg, 194.340241, 1e-6) << p;       // Φ = 194.340241° (Γ = 14.340241°)
  EXPECT_NEAR(p.declination_deg, -9.31434, 5e-6) << p;     // δ = -9.31434°
  // Δe = 0.016332° (the report): the refraction lifts the sun, so the refracted zenith is smaller.
  EXPECT_NEAR(p.geometric_zenith_deg - p.zenith_deg, 0.016332, 1e-6) << p;
}

// The report's Table A4.1 = Meeus ch. 7's examples (2000 Jan 1.5 ... -1001 Aug 17.9); the instants
// are UT (timezone 0). -4712 Jan 1.5 = JD 0 lies outside the years the algorithm accepts.
// Measured: each exact (difference 0).
TEST(SolarPosition, JulianDaysMatchTheReportsTable) {
  struct Row {
    int year, month, day, hour, minute;
    double jd;
  };
  const Row rows[] = {
      {2000, 1, 1, 12, 0, 2451545.0}, {1999, 1, 1, 0, 0, 2451179.5},  {1987, 1, 27, 0, 0, 2446822.5},
      {1987, 6, 19, 12, 0, 2446966.0}, {1988, 1, 27, 0, 0, 2447187.5}, {1988, 6, 19, 12, 0, 2447332.0},
      {1900, 1, 1, 0, 0, 2415020.5},  {1600, 1, 1, 0, 0, 2305447.5},  {1600, 12, 31, 0, 0, 2305812.5},
      {837, 4, 10, 7, 12, 2026871.8},  {-123, 12, 31, 0, 0, 1676496.5}, {-122, 1, 1, 0, 0, 1676497.5},
      {-1000, 7, 12, 12, 0, 1356001.0}, {-1000, 2, 29, 0, 0, 1355866.5}, {-1001, 8, 17, 21, 36, 1355671.4},
  };
  for (const Row& r : rows) {
    const SolarPosition p = solar_position(utc(r.year, r.month, r.day, r.hour, r.minute), golden());
    EXPECT_NEAR(p.julian_day, r.jd, 1e-6) << r.year << "-" << r.month << "-" << r.day << " " << r.hour << ":"
                                          << r.minute;
  }
}

// Gregorian dates against <chrono>'s proleptic Gregorian calendar (Hinnant's days_from_civil):
// JD = 2440587.5 + days since 1970-01-01 (the Unix epoch's JD). The first of every month of every
// 7th year from 1583 to 6000. Measured: each exact (difference 0).
TEST(SolarPosition, GregorianJulianDaysMatchTheChronoCalendar) {
  using namespace std::chrono;
  for (int y = 1583; y <= 6000; y += 7) {
    for (unsigned m = 1; m <= 12; ++m) {
      const sys_days d{year{y} / month{m} / day{1}};
      const double expected = 2440587.5 + d.time_since_epoch().count();
      const double jd = solar_position(utc(y, static_cast<int>(m), 1), golden()).julian_day;
      ASSERT_NEAR(jd, expected, 1e-6) << y << "-" << m << "-01";
    }
  }
}

// Day after day the Julian day steps by exactly 1, across the Julian calendar's leap days (every 4th
// year), the Gregorian ones (not 1700, 1800, 1900; 2000) and the reform (1582-10-04 -> 10-15).
TEST(SolarPosition, JulianDaysStepByOneAcrossBothCalendarsAndTheReform) {
  const int ranges[][2] = {{-2000, -1996}, {1580, 1583}, {1699, 1701}, {1899, 1901}, {1999, 2001}, {5996, 6000}};
  auto days_in = [](int y, int m) {
    static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const bool leap = y < 1583 ? y % 4 == 0 : (y % 4 == 0 && (y % 100 != 0 || y % 400 == 0));
    return m == 2 && leap ? 29 : kDays[m - 1];
  };
  for (const auto& r : ranges) {
    double previous = std::numeric_limits<double>::quiet_NaN();
    for (int y = r[0]; y <= r[1]; ++y)
      for (int m = 1; m <= 12; ++m)
        for (int d = 1; d <= days_in(y, m); ++d) {
          if (y == 1582 && m == 10 && d > 4 && d < 15) continue;
          const double jd = solar_position(utc(y, m, d), golden()).julian_day;
          if (!std::isnan(previous)) {
            ASSERT_DOUBLE_EQ(jd - previous, 1.0) << y << "-" << m << "-" << d;
          }
          previous = jd;
        }
  }
}

// Meeus example 25.b (VSOP87, the full theory): 1992-10-13.0 TD, apparent δ = -7.783871°. With
// ΔT = 0 the UT instant is the TD one. Measured: -7.7838740° (3e-6° off).
TEST(SolarPosition, DeclinationMatchesMeeusExample25b) {
  SolarInstant t = utc(1992, 10, 13);
  t.delta_t_s = 0.0;
  const SolarPosition p = solar_position(t, golden());
  EXPECT_NEAR(p.julian_day, 2448908.5, 1e-9);
  EXPECT_NEAR(p.declination_deg, -7.783871, kSpaAccuracy_deg) << p;
}

// USNO's 2024 equinoxes and solstices (UT, to the minute): Mar 20 03:06, Jun 20 20:51, Sep 22 12:44,
// Dec 21 09:21. At an equinox δ = 0; at a solstice |δ| = the true obliquity (23.4361° mean in 2024,
// Laskar, + 0.0023° nutation) less 0.0002° of the sun's ecliptic latitude. A minute of time is
// 0.0003° of δ near an equinox. Measured: -0.0000024°, 23.438228°, 0.0000238°, -23.438382°.
TEST(SolarPosition, DeclinationAtTheEquinoxesAndSolstices) {
  EXPECT_NEAR(solar_position(utc(2024, 3, 20, 3, 6), golden()).declination_deg, 0.0, 1e-3);
  EXPECT_NEAR(solar_position(utc(2024, 6, 20, 20, 51), golden()).declination_deg, 23.44, 0.01);
  EXPECT_NEAR(solar_position(utc(2024, 9, 22, 12, 44), golden()).declination_deg, 0.0, 1e-3);
  EXPECT_NEAR(solar_position(utc(2024, 12, 21, 9, 21), golden()).declination_deg, -23.44, 0.01);
}

// Local seconds after midnight of 2024-06-20 (MST) at which the sun crosses the meridian at Golden
// (azimuth 180°: it culminates south of the zenith there), by bisection.
double transit_seconds_golden_june20() {
  double lo = 11.0 * 3600.0, hi = 13.5 * 3600.0;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double az = solar_position(local_at(2024, 6, 20, mid, -7.0), golden()).azimuth_deg;
    (az < 180.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// NOAA's approximate solar noon ("General Solar Position Calculations", Spencer 1971's equation of
// time, good to about half a minute): 720 - 4 λ - EoT minutes UTC, γ = 2π/365 (day of year - 1).
// On 2024-06-20 (day 172) at λ = -105.1786°: EoT = -1.33 min, noon = 12:02:03 MST.
// Measured: SPA's transit at 12:02:29 MST (26 s later).
TEST(SolarPosition, TransitMatchesNoaasApproximateSolarNoon) {
  const double gamma = 2.0 * kPi / 365.0 * (172 - 1);
  const double eot_min = 229.18 * (0.000075 + 0.001868 * std::cos(gamma) - 0.032077 * std::sin(gamma) -
                                   0.014615 * std::cos(2 * gamma) - 0.040849 * std::sin(2 * gamma));
  const double noon_local_s = (720.0 - 4.0 * golden().longitude_deg - eot_min) * 60.0 - 7.0 * 3600.0;
  EXPECT_NEAR(transit_seconds_golden_june20(), noon_local_s, 60.0) << "EoT " << eot_min << " min";
}

// On the solstice day the path is symmetric about transit: azimuths mirror about the meridian
// (A(t0 - Δ) + A(t0 + Δ) = 360°) and the zeniths agree. What breaks the symmetry is δ's drift: the
// transit (19:02 UT) comes 1.8 h before the solstice (20:51 UT), where δ moves 0.007°/day x 0.075 d
// per day, so by under 0.0003° across ±6.5 h. Measured: at most 0.00022°.
TEST(SolarPosition, AzimuthIsSymmetricAboutTransit) {
  const double t0 = transit_seconds_golden_june20();
  for (double dt_h : {0.5, 2.0, 4.0, 6.5}) {
    const SolarPosition am = solar_position(local_at(2024, 6, 20, t0 - dt_h * 3600.0, -7.0), golden());
    const SolarPosition pm = solar_position(local_at(2024, 6, 20, t0 + dt_h * 3600.0, -7.0), golden());
    EXPECT_NEAR(am.azimuth_deg + pm.azimuth_deg, 360.0, 1e-3) << dt_h << " h: " << am << " / " << pm;
    EXPECT_NEAR(am.zenith_deg, pm.zenith_deg, 1e-3) << dt_h << " h: " << am << " / " << pm;
    EXPECT_LT(am.azimuth_deg, 180.0);
  }
}

// At local midnight the sun is down, by no more than at its lower culmination (zenith 180° - |φ| -
// |δ|, plus up to ξ = 0.0025° of topocentric parallax), and without refraction (the correction stops
// once the whole disc is below the horizon). Golden at midsummer, then Sydney at hers.
// Measured: 116.8192° (bound 116.8199°), 122.6733° (bound 122.6954°).
TEST(SolarPosition, SunIsBelowTheHorizonAtLocalMidnight) {
  const SolarPosition g = solar_position(local_at(2024, 6, 21, 0.0, -7.0), golden());
  EXPECT_GT(g.zenith_deg, 90.0) << g;
  EXPECT_LE(g.zenith_deg, 180.0 - 39.742476 - g.declination_deg + 0.003) << g;
  EXPECT_EQ(g.zenith_deg, g.geometric_zenith_deg) << g;
  const SolarSite sydney{.latitude_deg = -33.8688, .longitude_deg = 151.2093};
  const SolarPosition s = solar_position(local_at(2024, 12, 21, 0.0, 10.0), sydney);
  EXPECT_GT(s.zenith_deg, 90.0) << s;
  EXPECT_LE(s.zenith_deg, 180.0 - 33.8688 + s.declination_deg + 0.003) << s;
  EXPECT_EQ(s.zenith_deg, s.geometric_zenith_deg) << s;
}

// Meeus's low-accuracy solar coordinates (Astronomical Algorithms, 2nd ed., ch. 25, "accuracy
// 0.01°"; the method of NOAA's solar calculator), an algorithm apart from SPA's VSOP87 series:
// the geocentric elevation and azimuth at `jd` (UT, ΔT ignored: 69 s moves the sun 0.0008°).
struct LowAccuracySun {
  double elevation_deg, azimuth_deg;
};

LowAccuracySun meeus_low_accuracy(double jd, double latitude_deg, double longitude_deg) {
  auto r = [](double d) { return d * kPi / 180.0; };
  const double t = (jd - 2451545.0) / 36525.0;
  const double l0 = 280.46646 + t * (36000.76983 + 0.0003032 * t);  // eq. 25.2
  const double m = r(357.52911 + t * (35999.05029 - 0.0001537 * t));  // eq. 25.3
  const double c = (1.914602 - t * (0.004817 + 0.000014 * t)) * std::sin(m) +
                   (0.019993 - 0.000101 * t) * std::sin(2 * m) + 0.000289 * std::sin(3 * m);
  const double omega = r(125.04 - 1934.136 * t);
  const double lambda = r(l0 + c - 0.00569 - 0.00478 * std::sin(omega));  // apparent longitude
  const double eps = r(23.0 + (26.0 + (21.448 - t * (46.815 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0 +
                       0.00256 * std::cos(omega));  // eqs. 22.2, 25.8
  const double ra = std::atan2(std::cos(eps) * std::sin(lambda), std::cos(lambda));
  const double dec = std::asin(std::sin(eps) * std::sin(lambda));
  const double gmst = r(280.46061837 + 360.98564736629 * (jd - 2451545.0));  // eq. 12.4
  const double h = gmst + r(longitude_deg) - ra, phi = r(latitude_deg);
  const double el = std::asin(std::sin(phi) * std::sin(dec) + std::cos(phi) * std::cos(dec) * std::cos(h));
  const double az = std::atan2(-std::sin(h), std::tan(dec) * std::cos(phi) - std::sin(phi) * std::cos(h));
  return {el * 180.0 / kPi, std::fmod(az * 180.0 / kPi + 360.0, 360.0)};
}

// Hourly (at :17 UT) on every third day of 2024 at Golden, while the sun is 5° or more up: SPA's
// geometric (topocentric) elevation and azimuth against Meeus's low-accuracy method. The topocentric
// parallax lowers SPA's elevation by up to ξ = 0.0025° more. Measured: 1332 instants, at most
// 0.0062° in elevation, 0.0077° in azimuth.
TEST(SolarPosition, AgreesWithMeeussLowAccuracyMethodThroughAYear) {
  int compared = 0;
  for (int month = 1; month <= 12; ++month)
    for (int day = 1; day <= 28; day += 3)
      for (int hour = 0; hour < 24; hour += 1) {
        const SolarPosition p = solar_position(utc(2024, month, day, hour, 17), golden());
        if (p.geometric_zenith_deg > 85.0) continue;
        const LowAccuracySun m = meeus_low_accuracy(p.julian_day, golden().latitude_deg, golden().longitude_deg);
        EXPECT_NEAR(90.0 - p.geometric_zenith_deg, m.elevation_deg, 0.01) << p;
        EXPECT_NEAR(p.azimuth_deg, m.azimuth_deg, 0.01) << p;
        ++compared;
      }
  EXPECT_GT(compared, 1000);
}

// Refraction only while some of the disc can be up: below e0 = -(0.26667° + refraction) the two
// zeniths agree; above it the refracted sun stands higher. Minute by minute through the evening.
TEST(SolarPosition, RefractionStopsBelowTheDiscsCutoff) {
  for (double refraction : {0.5667, 2.0}) {
    int above = 0, below = 0;
    for (int minute = 0; minute < 120; ++minute) {
      const SolarInstant t = local_at(2003, 10, 17, 16.5 * 3600.0 + 60.0 * minute, -7.0);
      const SolarPosition p = solar_position(t, golden(), refraction);
      const double e0 = 90.0 - p.geometric_zenith_deg;
      if (e0 < -(0.26667 + refraction)) {
        EXPECT_EQ(p.zenith_deg, p.geometric_zenith_deg) << p;
        ++below;
      } else {
        EXPECT_LT(p.zenith_deg, p.geometric_zenith_deg) << p;
        ++above;
      }
    }
    EXPECT_GT(above, 0);
    EXPECT_GT(below, 0);
  }
}

// At the North Pole the elevation is the (topocentric) declination at any hour: e0 = asin(sin δ').
// The parallax keeps δ' within ξ = 0.0025° of δ. Measured: at most 0.0023°.
TEST(SolarPosition, ElevationAtThePoleIsTheDeclination) {
  const SolarSite pole{.latitude_deg = 90.0, .longitude_deg = 0.0};
  for (int hour : {0, 6, 12, 18}) {
    const SolarPosition p = solar_position(utc(2024, 5, 1, hour), pole);
    EXPECT_NEAR(90.0 - p.geometric_zenith_deg, p.declination_deg, 0.003) << p;
  }
}

// The direction toward the sun: unit length, z = cos Z, and for the report's example (azimuth
// 194.34°, south-south-west) pointing south (-y) and a little west (-x).
TEST(SolarPosition, SunDirectionIsTheUnitVectorOfZenithAndAzimuth) {
  const SolarInstant t{.year = 2003, .month = 10, .day = 17, .hour = 12, .minute = 30, .second = 30.0,
                       .timezone_h = -7.0, .delta_t_s = 67.0};
  const SolarPosition p = solar_position(t, golden());
  const Eigen::Vector3d d = sun_direction(p);
  EXPECT_NEAR(d.norm(), 1.0, 1e-12);
  EXPECT_NEAR(d.z(), std::cos(p.zenith_deg * kPi / 180.0), 1e-12);
  EXPECT_NEAR(std::atan2(d.x(), d.y()) * 180.0 / kPi + 360.0, p.azimuth_deg, 1e-9);
  EXPECT_LT(d.y(), 0.0);
  EXPECT_LT(d.x(), 0.0);
  const SolarPosition east{.zenith_deg = 90.0, .geometric_zenith_deg = 90.0, .azimuth_deg = 90.0,
                           .declination_deg = 0.0, .julian_day = 0.0};
  EXPECT_TRUE(sun_direction(east).isApprox(Eigen::Vector3d(1.0, 0.0, 0.0), 1e-12));
}

TEST(SolarPosition, PrintsItsFields) {
  std::ostringstream s;
  s << SolarPosition{50.11162, 50.127954, 194.340241, -9.31434, 2452930.312847};
  EXPECT_EQ(s.str(),
            "zenith 50.111620° (geometric 50.127954°), azimuth 194.340241°, declination -9.314340°, JD "
            "2452930.312847");
}

// Each refused input throws std::invalid_argument whose message names the field and its value.
void expect_refused(const SolarInstant& t, const SolarSite& site, double refraction, const std::string& field,
                    const std::string& value) {
  try {
    solar_position(t, site, refraction);
    ADD_FAILURE() << "accepted " << field << " = " << value;
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(field + " = " + value), std::string::npos) << message;
  }
}

TEST(SolarPosition, RefusesEachBadInputNamingTheFieldAndValue) {
  const SolarInstant ok = utc(2024, 6, 21, 12);
  const SolarSite site = golden();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto with_site = [&](auto change) {
    SolarSite s = site;
    change(s);
    return s;
  };
  auto with_time = [&](auto change) {
    SolarInstant t = ok;
    change(t);
    return t;
  };
  expect_refused(ok, with_site([](SolarSite& s) { s.latitude_deg = 90.5; }), 0.5667, "latitude_deg", "90.5");
  expect_refused(ok, with_site([](SolarSite& s) { s.latitude_deg = -91; }), 0.5667, "latitude_deg", "-91");
  expect_refused(ok, with_site([&](SolarSite& s) { s.latitude_deg = nan; }), 0.5667, "latitude_deg", "nan");
  expect_refused(ok, with_site([](SolarSite& s) { s.longitude_deg = 181; }), 0.5667, "longitude_deg", "181");
  expect_refused(ok, with_site([](SolarSite& s) { s.longitude_deg = -180.25; }), 0.5667, "longitude_deg",
                 "-180.25");
  expect_refused(ok, with_site([&](SolarSite& s) { s.elevation_m = inf; }), 0.5667, "elevation_m", "inf");
  expect_refused(ok, with_site([](SolarSite& s) { s.pressure_mbar = 101325; }), 0.5667, "pressure_mbar", "101325");
  expect_refused(ok, with_site([](SolarSite& s) { s.pressure_mbar = -1; }), 0.5667, "pressure_mbar", "-1");
  expect_refused(ok, with_site([](SolarSite& s) { s.temperature_c = -300; }), 0.5667, "temperature_c", "-300");
  expect_refused(ok, site, -0.1, "atmospheric_refraction_deg", "-0.1");
  expect_refused(ok, site, nan, "atmospheric_refraction_deg", "nan");
  expect_refused(with_time([](SolarInstant& t) { t.year = -2001; }), site, 0.5667, "year", "-2001");
  expect_refused(with_time([](SolarInstant& t) { t.year = 6001; }), site, 0.5667, "year", "6001");
  expect_refused(with_time([](SolarInstant& t) { t.month = 0; }), site, 0.5667, "month", "0");
  expect_refused(with_time([](SolarInstant& t) { t.month = 13; }), site, 0.5667, "month", "13");
  expect_refused(with_time([](SolarInstant& t) { t.day = 0; }), site, 0.5667, "day", "0");
  expect_refused(with_time([](SolarInstant& t) { t.day = 31; }), site, 0.5667, "day", "31");  // June
  expect_refused(utc(2023, 2, 29), site, 0.5667, "day", "29");
  expect_refused(utc(1900, 2, 29), site, 0.5667, "day", "29");  // Gregorian: not a leap year
  expect_refused(utc(1582, 10, 10), site, 0.5667, "day", "10");  // dropped by the reform
  expect_refused(with_time([](SolarInstant& t) { t.hour = -1; }), site, 0.5667, "hour", "-1");
  expect_refused(with_time([](SolarInstant& t) { t.hour = 25; }), site, 0.5667, "hour", "25");
  expect_refused(utc(2024, 6, 21, 24, 30), site, 0.5667, "hour", "24");
  expect_refused(with_time([](SolarInstant& t) { t.minute = 60; }), site, 0.5667, "minute", "60");
  expect_refused(with_time([](SolarInstant& t) { t.minute = -1; }), site, 0.5667, "minute", "-1");
  expect_refused(with_time([](SolarInstant& t) { t.second = 60; }), site, 0.5667, "second", "60");
  expect_refused(with_time([](SolarInstant& t) { t.second = -0.5; }), site, 0.5667, "second", "-0.5");
  expect_refused(with_time([&](SolarInstant& t) { t.second = nan; }), site, 0.5667, "second", "nan");
  expect_refused(with_time([](SolarInstant& t) { t.timezone_h = 19; }), site, 0.5667, "timezone_h", "19");
  expect_refused(with_time([&](SolarInstant& t) { t.timezone_h = nan; }), site, 0.5667, "timezone_h", "nan");
  expect_refused(with_time([&](SolarInstant& t) { t.delta_t_s = inf; }), site, 0.5667, "delta_t_s", "inf");
}

// The edges of the ranges are accepted: the poles, the antimeridian, Julian 1500-02-29, the last day
// before the reform and the first after, 24:00:00, the years -2000 and 6000.
TEST(SolarPosition, AcceptsTheEdgesOfEachRange) {
  const SolarSite pole_south{.latitude_deg = -90.0, .longitude_deg = 180.0};
  const SolarSite pole_north{.latitude_deg = 90.0, .longitude_deg = -180.0};
  EXPECT_NO_THROW(solar_position(utc(2024, 6, 21, 12), pole_south));
  EXPECT_NO_THROW(solar_position(utc(2024, 6, 21, 12), pole_north));
  EXPECT_NO_THROW(solar_position(utc(1500, 2, 29), golden()));
  EXPECT_NO_THROW(solar_position(utc(-2000, 1, 1), golden()));
  EXPECT_NO_THROW(solar_position(utc(6000, 12, 31, 23, 59, 59.999), golden()));
  const double before = solar_position(utc(1582, 10, 4, 24), golden()).julian_day;
  const double after = solar_position(utc(1582, 10, 15), golden()).julian_day;
  EXPECT_DOUBLE_EQ(before, 2299160.5);  // 24:00 of Oct 4 (Julian) is 00:00 of Oct 15 (Gregorian)
  EXPECT_DOUBLE_EQ(after, 2299160.5);
}

}  // namespace
}  // namespace ilp
