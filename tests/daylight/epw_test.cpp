// read_epw: the real Chicago TMY3 file checked against its text, and every bad input a
// clear ConfigError naming file, line and field.
#include "core/daylight/epw.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "tests/test_support.h"

#ifndef ILP_SHARED_DIR
#define ILP_SHARED_DIR "/work/shared"
#endif

namespace ilp {
namespace {

using test::error_of;
using test::expect_message;

const std::string kChicago = std::string(ILP_SHARED_DIR) + "/weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw";

// The file's numbers are written with at most 2 decimals; parsing them is exact to this.
constexpr double kParseTol = 1e-9;

// ------------------------------------------------------------------ the real file

class ChicagoEpw : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kChicago)) GTEST_SKIP() << kChicago << " absent";
  }
};

TEST_F(ChicagoEpw, SiteMatchesTheLocationLine) {
  // LOCATION,Chicago Ohare Intl Ap,IL,USA,TMY3,725300,41.98,-87.92,-6.0,201.0
  const WeatherFile w = read_epw(kChicago);
  EXPECT_EQ(w.path, kChicago);
  EXPECT_EQ(w.site.city, "Chicago Ohare Intl Ap");
  EXPECT_EQ(w.site.region, "IL");
  EXPECT_EQ(w.site.country, "USA");
  EXPECT_EQ(w.site.source, "TMY3");
  EXPECT_EQ(w.site.station_id, "725300");
  EXPECT_NEAR(w.site.latitude_deg, 41.98, kParseTol);
  EXPECT_NEAR(w.site.longitude_deg, -87.92, kParseTol);
  EXPECT_NEAR(w.site.timezone_h, -6.0, kParseTol);
  EXPECT_NEAR(w.site.elevation_m, 201.0, kParseTol);
  std::ostringstream os;
  os << w.site;
  EXPECT_EQ(os.str(), "Chicago Ohare Intl Ap, IL, USA (TMY3 725300): 41.98° N, 87.92° W, UTC-6, 201 m");
}

TEST_F(ChicagoEpw, HasTheHoursOfATypicalYearInOrder) {
  const WeatherFile w = read_epw(kChicago);
  ASSERT_EQ(w.hours.size(), 8760u);
  EXPECT_EQ(w.hours.front().month, 1);
  EXPECT_EQ(w.hours.front().day, 1);
  EXPECT_EQ(w.hours.front().hour, 1);
  EXPECT_EQ(w.hours.back().month, 12);
  EXPECT_EQ(w.hours.back().day, 31);
  EXPECT_EQ(w.hours.back().hour, 24);
  for (std::size_t i = 0; i < w.hours.size(); ++i) ASSERT_EQ(w.hours[i].hour, static_cast<int>(i % 24) + 1) << i;
}

void expect_hour(const WeatherHour& h, int month, int day, int hour, const std::vector<double>& v) {
  SCOPED_TRACE(::testing::Message() << h);
  EXPECT_EQ(h.month, month);
  EXPECT_EQ(h.day, day);
  EXPECT_EQ(h.hour, hour);
  const double got[] = {h.dry_bulb_c,
                        h.dew_point_c,
                        h.pressure_pa,
                        h.global_horizontal_w_per_m2,
                        h.direct_normal_w_per_m2,
                        h.diffuse_horizontal_w_per_m2,
                        h.global_horizontal_lux,
                        h.direct_normal_lux,
                        h.diffuse_horizontal_lux};
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_NEAR(got[i], v[i], kParseTol) << "value " << i;
}

TEST_F(ChicagoEpw, RowsMatchTheirText) {
  const WeatherFile w = read_epw(kChicago);
  ASSERT_EQ(w.hours.size(), 8760u);
  // Fields 2-4, 7, 8, 10, 14-19 of the lines (sed -n 'Np' | cut -d, -f...):
  // line 9:    1986,1,1,1,0,...,-12.2,-16.1,73,99500,0,0,218,0,0,0,0,0,0
  expect_hour(w.hours[0], 1, 1, 1, {-12.2, -16.1, 99500, 0, 0, 0, 0, 0, 0});
  // line 20:   1986,1,1,12,0,...,-3.3,-9.4,63,99300,591,1415,236,364,521,144,38026,50467,16854
  expect_hour(w.hours[11], 1, 1, 12, {-3.3, -9.4, 99300, 364, 521, 144, 38026, 50467, 16854});
  // line 4124: 1979,6,21,12,0,...,30.6,13.3,35,99000,1247,1322,405,876,703,211,94400,72200,26100
  expect_hour(w.hours[4115], 6, 21, 12, {30.6, 13.3, 99000, 876, 703, 211, 94400, 72200, 26100});
  // line 8768: 1981,12,31,24,0,...,-6.1,-8.9,81,98300,0,0,253,0,0,0,0,0,0
  expect_hour(w.hours[8759], 12, 31, 24, {-6.1, -8.9, 98300, 0, 0, 0, 0, 0, 0});
}

TEST_F(ChicagoEpw, AnnualGlobalHorizontalMatchesAnIndependentSum) {
  // awk -F, 'NR>8 {g += $14} END {print g}' USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw
  //   -> 1406646 Wh/m² = 1406.646 kWh/(m²·a); DNI ($15) 1294257, DHI ($16) 660253.
  const WeatherFile w = read_epw(kChicago);
  double global = 0, direct = 0, diffuse = 0;
  for (const WeatherHour& h : w.hours) {
    global += h.global_horizontal_w_per_m2;
    direct += h.direct_normal_w_per_m2;
    diffuse += h.diffuse_horizontal_w_per_m2;
  }
  EXPECT_NEAR(global / 1000.0, 1406.646, 1e-6);  // integers summed in double: exact
  EXPECT_NEAR(direct / 1000.0, 1294.257, 1e-6);
  EXPECT_NEAR(diffuse / 1000.0, 660.253, 1e-6);
}

TEST_F(ChicagoEpw, DiffuseNeverExceedsGlobalAndNightsAreDark) {
  // Diffuse horizontal is part of global horizontal: DHI <= GHI up to the file's rounding
  // to whole Wh/m². Hours 1-3 and 23-24 (22:00-03:00 standard time) are dark in Chicago
  // all year (earliest sunrise about 04:10 CST, latest sunset about 19:30 CST).
  constexpr double kRoundingTol = 1.0;  // Wh/m², one unit of the file's last digit
  const WeatherFile w = read_epw(kChicago);
  int day_rows = 0;
  for (const WeatherHour& h : w.hours) {
    SCOPED_TRACE(::testing::Message() << h);
    EXPECT_FALSE(std::isnan(h.global_horizontal_w_per_m2 + h.global_horizontal_lux + h.direct_normal_lux +
                            h.diffuse_horizontal_lux + h.dry_bulb_c + h.pressure_pa));  // nothing missing
    if (h.global_horizontal_w_per_m2 > 0) {
      ++day_rows;
      EXPECT_LE(h.diffuse_horizontal_w_per_m2, h.global_horizontal_w_per_m2 + kRoundingTol);
    }
    if (h.hour <= 3 || h.hour >= 23) {
      EXPECT_EQ(h.global_horizontal_w_per_m2 + h.direct_normal_w_per_m2 + h.diffuse_horizontal_w_per_m2, 0.0);
      EXPECT_EQ(h.global_horizontal_lux + h.direct_normal_lux + h.diffuse_horizontal_lux, 0.0);
    }
  }
  EXPECT_GT(day_rows, 4000);  // about half the year's hours are sunlit
  EXPECT_LT(day_rows, 4800);
}

// ------------------------------------------------------------------ synthetic files

const char* const kHeader[] = {
    "LOCATION,Testville,TS,XYZ,TEST,123456,41.98,-87.92,-6.0,201.0",
    "DESIGN CONDITIONS,0",
    "TYPICAL/EXTREME PERIODS,0",
    "GROUND TEMPERATURES,0",
    "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0",
    "COMMENTS 1,synthetic",
    "COMMENTS 2,for epw_test",
    "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31",
};
constexpr int kDaysInMonth[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};

// A 35-field row: sunlit 07:00-17:00 (hours 8..17) with 300 W/m² global, 400 direct
// normal, 100 diffuse; illuminance 110 lm/W of each.
std::string row(int month, int day, int hour) {
  const bool sun = hour >= 8 && hour <= 17;
  const int g = sun ? 300 : 0, dn = sun ? 400 : 0, dh = sun ? 100 : 0;
  std::ostringstream os;
  os << "2001," << month << ',' << day << ',' << hour << ",0,?9?9?9?9E0?9?9?9?9,10.0,5.0,70,101325,0,0,300," << g
     << ',' << dn << ',' << dh << ',' << 110 * g << ',' << 110 * dn << ',' << 110 * dh
     << ",0,180,3.0,5,5,20.0,77777,9,999999999,10,0.1000,0,88,0.200,0.0,0.0";
  return os.str();
}

// The lines of a valid file: 8 header lines, then the 8760 rows.
std::vector<std::string> valid_lines() {
  std::vector<std::string> lines(std::begin(kHeader), std::end(kHeader));
  for (int m = 1; m <= 12; ++m)
    for (int d = 1; d <= kDaysInMonth[m - 1]; ++d)
      for (int h = 1; h <= 24; ++h) lines.push_back(row(m, d, h));
  return lines;
}

std::string joined(const std::vector<std::string>& lines, const std::string& end = "\n") {
  std::string text;
  for (const std::string& line : lines) text += line + end;
  return text;
}

// The 1-based line of a date's row in valid_lines().
int line_of(int month, int day, int hour) {
  int index = 0;
  for (int m = 1; m < month; ++m) index += kDaysInMonth[m - 1] * 24;
  return 8 + index + (day - 1) * 24 + hour;
}

// The row at `line` (1-based) with field `field` (1-based) set to `value`.
void set_field(std::vector<std::string>& lines, int line, int field, const std::string& value) {
  std::string& text = lines[line - 1];
  std::size_t start = 0;
  for (int f = 1; f < field; ++f) start = text.find(',', start) + 1;
  const std::size_t end = text.find(',', start);
  text.replace(start, end == std::string::npos ? std::string::npos : end - start, value);
}

class EpwFile : public ::testing::Test {
 protected:
  // Writes `text` as NAME and returns read_epw's ConfigError message ("" and a failure
  // when it reads or throws something else).
  std::string error_reading(const std::string& text, const std::string& name = "weather.epw") {
    const std::string path = dir_.write(name, text);
    return error_of<ConfigError>([&] { (void)read_epw(path); }, "read_epw(" + name + ")");
  }
  std::string error_reading(const std::vector<std::string>& lines) { return error_reading(joined(lines)); }
  // "PATH:LINE: " of weather.epw.
  std::string at(int line) const { return dir_.file("weather.epw") + ":" + std::to_string(line) + ": "; }
  // Line `line` with field `field` set to `value`: the message names both and the value.
  void expect_field_error(int line, int field, const std::string& value, const std::vector<std::string>& parts) {
    std::vector<std::string> lines = valid_lines();
    set_field(lines, line, field, value);
    SCOPED_TRACE("line " + std::to_string(line) + " field " + std::to_string(field) + " = '" + value + "'");
    std::vector<std::string> all = parts;
    all.push_back("field " + std::to_string(field) + " (");
    expect_message(error_reading(lines), at(line), all);
  }

  test::TempDir dir_;
};

TEST_F(EpwFile, ReadsAValidFileWithLfOrCrlfAndTrailingBlankLines) {
  const std::vector<std::string> lines = valid_lines();
  const std::string lf = dir_.write("lf.epw", joined(lines));
  const std::string crlf = dir_.write("crlf.epw", joined(lines, "\r\n") + "\r\n");
  const std::string bom = dir_.write("bom.epw", "\xEF\xBB\xBF" + joined(lines) + "\n  \n");
  const std::string no_end = dir_.write("no_end.epw", joined(lines).substr(0, joined(lines).size() - 1));
  for (const std::string& path : {lf, crlf, bom, no_end}) {
    SCOPED_TRACE(path);
    const WeatherFile w = read_epw(path);
    ASSERT_EQ(w.hours.size(), 8760u);
    EXPECT_EQ(w.site.city, "Testville");
    EXPECT_EQ(w.site.station_id, "123456");
    const WeatherHour& noon = w.hours[11];
    EXPECT_EQ(noon.global_horizontal_w_per_m2, 300);
    EXPECT_EQ(noon.direct_normal_w_per_m2, 400);
    EXPECT_EQ(noon.diffuse_horizontal_w_per_m2, 100);
    EXPECT_EQ(noon.diffuse_horizontal_lux, 11000);
    EXPECT_EQ(w.hours[8759].pressure_pa, 101325);
  }
}

TEST_F(EpwFile, MissingOptionalFieldsAreNan) {
  std::vector<std::string> lines = valid_lines();
  const int noon = line_of(3, 1, 12);
  set_field(lines, noon, 7, "99.9");     // dry bulb
  set_field(lines, noon, 10, "999999");  // pressure
  set_field(lines, noon, 14, "9999");    // global horizontal irradiance
  set_field(lines, noon, 17, "999999");  // illuminances
  set_field(lines, noon, 18, "999900");
  set_field(lines, noon, 19, "999999");
  const WeatherFile w = read_epw(dir_.write("weather.epw", joined(lines)));
  const WeatherHour& h = w.hours[noon - 9];
  EXPECT_TRUE(std::isnan(h.dry_bulb_c));
  EXPECT_TRUE(std::isnan(h.pressure_pa));
  EXPECT_TRUE(std::isnan(h.global_horizontal_w_per_m2));
  EXPECT_TRUE(std::isnan(h.global_horizontal_lux));
  EXPECT_TRUE(std::isnan(h.direct_normal_lux));
  EXPECT_TRUE(std::isnan(h.diffuse_horizontal_lux));
  EXPECT_EQ(h.direct_normal_w_per_m2, 400);
  EXPECT_EQ(h.dew_point_c, 5.0);
}

// ------------------------------------------------------------------ the file as a whole

TEST_F(EpwFile, MissingFileOrFolderIsAnError) {
  const std::string missing = dir_.file("nowhere.epw");
  expect_message(error_of<ConfigError>([&] { (void)read_epw(missing); }), missing + ": ", {"no such file"});
  const std::string folder = dir_.file("");
  expect_message(error_of<ConfigError>([&] { (void)read_epw(folder); }), folder, {"is a folder"});
}

TEST_F(EpwFile, AnotherFormatSaysWhatItLooksLike) {
  const std::string wea = "place Chicago_IL\nlatitude 41.98\nlongitude 87.92\ntime_zone 90\nsite_elevation 201\n"
                          "weather_data_file_units 1\n1 1 0.5 0 0\n";
  expect_message(error_reading(wea), at(1), {"WEA file", "'place Chicago_IL'", "LOCATION,city"});
  expect_message(error_reading("Date,Time,GHI,DNI,DHI\n01/01/2001,01:00,0,0,0\n"), at(1),
                 {"looks like a CSV file", "'Date,Time,GHI,DNI,DHI'"});
  expect_message(error_reading(std::string("\x7f" "ELF\x02\x01\x00\x00", 8)), at(1), {"binary file"});
  expect_message(error_reading("hello\n"), at(1), {"'hello' is not a LOCATION line"});
  expect_message(error_reading(""), dir_.file("weather.epw") + ": ", {"is empty"});
  expect_message(error_reading("\n\r\n  \n"), dir_.file("weather.epw") + ": ", {"is empty"});
}

TEST_F(EpwFile, CrOnlyLineEndsAreAnError) {
  expect_message(error_reading(joined(valid_lines(), "\r")), at(1), {"carriage return inside the line"});
}

// ------------------------------------------------------------------ the header

TEST_F(EpwFile, LocationLineWithTooFewFieldsIsAnError) {
  std::vector<std::string> lines = valid_lines();
  lines[0] = "LOCATION,Chicago,IL,USA,TMY3,725300,41.98,-87.92";
  expect_message(error_reading(lines), at(1), {"LOCATION line has 8 fields, 10 are needed"});
}

TEST_F(EpwFile, LocationOutOfRangeNamesTheField) {
  expect_field_error(1, 7, "95", {"(latitude): '95' is outside [-90, 90]"});
  expect_field_error(1, 7, "-90.5", {"(latitude): '-90.5' is outside [-90, 90]"});
  expect_field_error(1, 8, "-200", {"(longitude): '-200' is outside [-180, 180]"});
  expect_field_error(1, 9, "90", {"(time zone): '90' is outside [-12, 14]", "meridian"});
  expect_field_error(1, 9, "-13", {"(time zone): '-13' is outside [-12, 14]"});
  expect_field_error(1, 9, "UTC-6", {"(time zone): 'UTC-6' is not a number"});
  expect_field_error(1, 10, "12000", {"(elevation): '12000' is outside"});
  expect_field_error(1, 7, "", {"(latitude): is empty"});
}

TEST_F(EpwFile, HeaderLineOutOfPlaceIsAnError) {
  std::vector<std::string> lines = valid_lines();
  lines.erase(lines.begin() + 2);  // no TYPICAL/EXTREME PERIODS
  expect_message(error_reading(lines), at(3), {"expected the TYPICAL/EXTREME PERIODS header line", "'GROUND"});
  expect_message(error_reading(std::string(kHeader[0]) + "\n" + row(1, 1, 1) + "\n"), at(2),
                 {"expected the DESIGN CONDITIONS header line", "'2001,1,1,1"});
  expect_message(error_reading(std::string(kHeader[0]) + "\n" + kHeader[1] + "\n"), at(2),
                 {"ends after 2 lines, inside the 8 header lines"});
}

TEST_F(EpwFile, SubHourlyDataPeriodsIsAnError) {
  expect_field_error(8, 3, "4", {"(records per hour): '4': ilp reads hourly files"});
}

// ------------------------------------------------------------------ the rows

TEST_F(EpwFile, RowWithTooFewFieldsIsAnError) {
  std::vector<std::string> lines = valid_lines();
  const int l = line_of(5, 10, 13);
  lines[l - 1] = "2001,5,10,13,0,?9,10.0,5.0,70,101325,0,0";
  expect_message(error_reading(lines), at(l), {"an hourly row of 12 fields", "first 19"});
  lines = valid_lines();
  lines.back().resize(40);  // a file cut inside its last row
  expect_message(error_reading(lines), at(8768), {"fields", "last line: is the file truncated?"});
}

TEST_F(EpwFile, NonNumericFieldIsAnError) {
  const int l = line_of(2, 3, 10);
  expect_field_error(l, 7, "abc", {"(dry bulb temperature): 'abc' is not a number"});
  expect_field_error(l, 15, "", {"(direct normal irradiance): is empty"});
  expect_field_error(l, 16, "nan", {"(diffuse horizontal irradiance): 'nan' is not a number"});
  expect_field_error(l, 14, "inf", {"(global horizontal irradiance): 'inf' is not a number"});
  expect_field_error(l, 10, "1e999", {"(atmospheric station pressure): '1e999' is not a number"});
  expect_field_error(l, 4, "10.5", {"(hour): '10.5' is not a whole number"});
  expect_field_error(l, 2, "Feb", {"(month): 'Feb' is not a whole number"});
}

TEST_F(EpwFile, MissingNeededValueSaysWhich) {
  const int l = line_of(7, 4, 12);
  expect_field_error(l, 15, "9999", {"(direct normal irradiance): '9999' is the missing-value code"});
  expect_field_error(l, 16, "9999", {"(diffuse horizontal irradiance): '9999' is the missing-value code"});
  expect_field_error(l, 16, "12345", {"'12345' is at or above the missing-value code 9999"});
  expect_field_error(l, 8, "99.9", {"(dew point temperature): '99.9' is the missing-value code"});
}

TEST_F(EpwFile, ValueOutOfRangeIsAnError) {
  const int l = line_of(7, 4, 12);
  expect_field_error(l, 15, "-5", {"(direct normal irradiance): '-5' is negative; must be >= 0 Wh/m²"});
  expect_field_error(l, 16, "-0.5", {"(diffuse horizontal irradiance): '-0.5' is negative"});
  expect_field_error(l, 14, "-1", {"(global horizontal irradiance): '-1' is negative"});
  expect_field_error(l, 17, "-1", {"(global horizontal illuminance): '-1' is negative; must be >= 0 lux"});
  expect_field_error(l, 7, "85", {"(dry bulb temperature): '85' is outside (-70, 70) °C"});
  expect_field_error(l, 10, "20000", {"(atmospheric station pressure): '20000' is outside (31000, 120000) Pa"});
}

TEST_F(EpwFile, DateOutOfRangeIsAnError) {
  const int l = line_of(4, 30, 5);
  expect_field_error(l, 2, "13", {"(month): '13' is outside 1..12"});
  expect_field_error(l, 3, "31", {"(day): '31' is outside 1..30 (Apr)"});
  expect_field_error(l, 3, "0", {"(day): '0' is outside 1..30"});
  expect_field_error(l, 4, "0", {"(hour): '0' is outside 1..24", "hour 1 is 00:00-01:00"});
  expect_field_error(l, 4, "25", {"(hour): '25' is outside 1..24"});
}

TEST_F(EpwFile, RowsOutOfOrderAreAnError) {
  std::vector<std::string> lines = valid_lines();
  const int l = line_of(1, 1, 3);
  std::swap(lines[l - 1], lines[l]);  // hour 4 before hour 3
  expect_message(error_reading(lines), at(l),
                 {"field 4 (hour): 1 Jan hour 4 is out of order: row 3 of the year is 1 Jan hour 3"});
  lines = valid_lines();
  const int first = line_of(3, 1, 1);
  lines.erase(lines.begin() + first - 1, lines.begin() + first + 23);  // no 1 March ...
  for (int h = 1; h <= 24; ++h) lines.push_back(row(12, 31, h));       // ... and 31 Dec twice
  expect_message(error_reading(lines), at(first), {"field 3 (day): 2 Mar hour 1 is out of order", "1 Mar hour 1"});
  lines = valid_lines();
  set_field(lines, 9, 2, "2");  // starts in February
  expect_message(error_reading(lines), at(9), {"field 2 (month): 1 Feb hour 1 is out of order", "1 Jan hour 1"});
}

TEST_F(EpwFile, LeapDayInATypicalYearIsAnError) {
  std::vector<std::string> lines = valid_lines();
  const int l = line_of(3, 1, 1);
  lines.erase(lines.end() - 24, lines.end());  // 31 December out, 29 February in: still 8760 rows
  for (int h = 24; h >= 1; --h) lines.insert(lines.begin() + l - 1, row(2, 29, h));
  expect_message(error_reading(lines), at(l), {"field 3 (day): 29 Feb, a leap day", "without 29 February"});
}

// ------------------------------------------------------------------ the number of rows

TEST_F(EpwFile, TruncatedFileSaysHowManyRows) {
  std::vector<std::string> lines = valid_lines();
  lines.resize(8 + 4000);
  expect_message(error_reading(lines), at(4008),
                 {"ends after 4000 hourly rows (lines 9 to 4008)", "8760", "truncated"});
  lines.resize(8);
  expect_message(error_reading(lines), at(8), {"ends after the header, with no hourly rows"});
}

TEST_F(EpwFile, LeapYearSaysToDropTheLeapDay) {
  std::vector<std::string> lines = valid_lines();
  const int l = line_of(3, 1, 1);
  for (int h = 24; h >= 1; --h) lines.insert(lines.begin() + l - 1, row(2, 29, h));
  ASSERT_EQ(lines.size(), 8u + 8784u);
  expect_message(error_reading(lines), at(l),
                 {"field 3 (day): 29 Feb (lines " + std::to_string(l) + " to " + std::to_string(l + 23) + ")",
                  "8784 hourly rows", "leap year", "typical year of 8760 hours", "drop the 24 rows of 29 February"});
}

TEST_F(EpwFile, TooManyRowsIsAnError) {
  std::vector<std::string> lines = valid_lines();
  lines.push_back(row(12, 31, 24));
  expect_message(error_reading(lines), at(8769), {"8761 hourly rows (lines 9 to 8769)", "typical year has 8760"});
}

TEST_F(EpwFile, EmptyLineAmongTheRowsIsAnError) {
  std::vector<std::string> lines = valid_lines();
  lines.insert(lines.begin() + 100, "");
  lines.pop_back();
  expect_message(error_reading(lines), at(101), {"an empty line among the hourly rows"});
}

}  // namespace
}  // namespace ilp
