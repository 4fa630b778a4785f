// EnergyPlus weather files (EPW: the EnergyPlus "Auxiliary Programs" manual, chapter
// "Weather Converter Program", its EPW data dictionary): the site from the LOCATION line
// and the 8760 hourly rows of a typical year, with the irradiance and illuminance a sky
// model needs (the fields Radiance's gendaymtx reads from an EPW: direct normal and diffuse
// horizontal irradiance, dew point). Depends on core/base only (errors with file locations).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace ilp {

// The LOCATION line (first line of the file), as written: text fields trimmed.
struct WeatherSite {
  std::string city, region, country;  // region: state, province or region ("IL")
  std::string source;                 // the data set ("TMY3", "IWEC", ...)
  std::string station_id;             // WMO station number, kept as text ("725300")
  double latitude_deg = 0.0;          // [-90, 90], north positive
  double longitude_deg = 0.0;         // [-180, 180], east positive (the EPW convention)
  double timezone_h = 0.0;            // [-12, 14], hours east of UTC (Chicago: -6)
  double elevation_m = 0.0;           // above sea level, [-1000, 9999.9)
};

// One hourly row. `hour` h covers the hour ending at h:00 local standard time (hour 1 is
// 00:00-01:00). Irradiances are the hour's energy per m² (Wh/m², the same number as the
// hour's mean W/m²); illuminances are the hour's mean.
//
// Direct normal and diffuse horizontal irradiance and the dew point are always values (a
// missing one is an error); the other fields are NaN where the file has the EPW
// missing-value code (dry bulb >= 99.9, pressure >= 999999, global horizontal irradiance
// >= 9999, illuminances >= 999900). Every value present is in the data dictionary's range:
// temperatures in (-70, 70) °C, pressure in (31000, 120000) Pa, irradiance and
// illuminance >= 0.
struct WeatherHour {
  int month = 1, day = 1, hour = 1;  // 1..12, 1..days in the month (no 29 February), 1..24
  double dry_bulb_c = 0.0, dew_point_c = 0.0;
  double pressure_pa = 0.0;  // station pressure
  double global_horizontal_w_per_m2 = 0.0, direct_normal_w_per_m2 = 0.0, diffuse_horizontal_w_per_m2 = 0.0;
  double global_horizontal_lux = 0.0, direct_normal_lux = 0.0, diffuse_horizontal_lux = 0.0;
};

// A weather file read whole.
struct WeatherFile {
  std::string path;              // as given to read_epw
  WeatherSite site;
  std::vector<WeatherHour> hours;  // 8760: 1 January hour 1 to 31 December hour 24, in file order
};

// Reads the EPW file at `path`: 8 header lines (LOCATION, DESIGN CONDITIONS,
// TYPICAL/EXTREME PERIODS, GROUND TEMPERATURES, HOLIDAYS/DAYLIGHT SAVINGS, COMMENTS 1,
// COMMENTS 2, DATA PERIODS with 1 record per hour), then exactly 8760 hourly rows of at
// least 19 comma-separated fields, in calendar order with no 29 February. LF or CRLF line
// ends, a UTF-8 byte order mark and empty lines at the end are accepted.
//
// Throws ConfigError on anything else, its message "FILE:LINE: field N (NAME): what is
// wrong" (N counts from 1 on the line; "FILE: ..." for the file as a whole): a missing,
// unreadable or special file; another format (WEA, CSV, binary); a header line out of
// place; a LOCATION line with too few fields or a latitude, longitude, time zone or
// elevation out of range; a row with too few fields, a field that is not a finite number,
// the missing-value code in direct normal or diffuse horizontal irradiance or dew point, a
// value out of range (negative irradiance); a month, day or hour out of range or out of
// order; fewer or more than 8760 rows (8784: a leap year).
WeatherFile read_epw(const std::string& path);

// "Chicago Ohare Intl Ap, IL, USA (TMY3 725300): 41.98° N, 87.92° W, UTC-6, 201 m".
std::ostream& operator<<(std::ostream& os, const WeatherSite& site);
// "1/1 hour 12: 364 W/m² global, 521 direct normal, 144 diffuse; -3.3 °C".
std::ostream& operator<<(std::ostream& os, const WeatherHour& hour);

}  // namespace ilp
