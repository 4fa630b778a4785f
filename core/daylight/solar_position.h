// The sun's position by NREL's Solar Position Algorithm (SPA): Reda & Andreas, "Solar position
// algorithm for solar radiation applications", Solar Energy 76(5):577-589, 2004 (NREL/TP-560-34302,
// revised 2008), written from the paper. Topocentric zenith and azimuth to about ±0.0003° for the
// years -2000..6000, given the observer's site and TT - UT1. Depends on the standard library and
// Eigen (the direction vector) only; docs: ../shared/DAYLIGHT.md section 4.
#pragma once

#include <iosfwd>

#include <Eigen/Core>

namespace ilp {

// Where the observer stands, and the air the sunlight crosses (for the refraction correction).
struct SolarSite {
  double latitude_deg;             // geodetic, north positive, in [-90, 90]
  double longitude_deg;            // east positive (Greenwich 0, Denver -105), in [-180, 180]
  double elevation_m = 0.0;        // above the reference ellipsoid, > -6378140 (the Earth's radius)
  double pressure_mbar = 1013.25;  // local annual mean air pressure, in [0, 2000] (0: no refraction)
  double temperature_c = 12.0;     // local annual mean air temperature, in (-273, 100]
};

// A local civil time. The calendar is the Julian one before 1582-10-15 and the Gregorian one from
// then on (the paper's and Meeus's convention); years count astronomically (1 BC = year 0).
struct SolarInstant {
  int year;                 // in [-2000, 6000], the paper's range of validity
  int month;                // in [1, 12]
  int day;                  // in [1, days of the month]; 1582-10-05..14 do not exist
  int hour;                 // in [0, 23], or 24 with minute = second = 0 (the next day's 00:00)
  int minute;               // in [0, 59]
  double second = 0.0;      // in [0, 60)
  double timezone_h;        // hours east of UTC (Mountain Standard Time: -7), in [-18, 18]
  double delta_t_s = 69.0;  // ΔT = TT - UT1 in seconds, |ΔT| <= 86400 (about 69 s in 2020-2025)
};

struct SolarPosition {
  double zenith_deg;            // topocentric, refracted (where the sunlight comes from), [0, 180]
  double geometric_zenith_deg;  // topocentric, without the refraction correction, [0, 180]
  double azimuth_deg;           // topocentric, east of north (navigators'), in [0, 360)
  double declination_deg;       // geocentric apparent declination δ of the sun (paper eq. 31)
  double julian_day;            // JD of the instant in UT (paper eq. 4), not the ephemeris day
};

// The sun's position at `t` seen from `site`. `atmospheric_refraction_deg` is the refraction at
// sunrise and sunset, in [0, 4]: the paper's refraction correction is applied only while the
// geometric elevation is at least -(0.26667° sun radius + atmospheric_refraction_deg), i.e. while
// some of the disc can be seen. Throws std::invalid_argument naming the field and its value when an
// input is non-finite or outside its range above.
SolarPosition solar_position(const SolarInstant& t, const SolarSite& site,
                             double atmospheric_refraction_deg = 0.5667);

// The unit vector toward the sun (refracted zenith and azimuth) in a right-handed z-up frame with
// +x east and +y north: (sin A sin Z, cos A sin Z, cos Z) for azimuth A and zenith Z. Its z is
// negative when the sun is below the horizon.
Eigen::Vector3d sun_direction(const SolarPosition& p);

// "zenith 50.11162° (geometric 50.12795°), azimuth 194.34024°, declination -9.31434°, JD ..."
std::ostream& operator<<(std::ostream& os, const SolarPosition& p);

}  // namespace ilp
