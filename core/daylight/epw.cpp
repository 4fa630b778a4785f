#include "core/daylight/epw.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <ostream>
#include <sstream>
#include <string_view>

#include "core/base/error.h"

namespace ilp {

namespace {

constexpr int kTypicalYearHours = 8760;
constexpr int kLeapYearHours = 8784;
constexpr int kHeaderLines = 8;
constexpr std::size_t kLocationFields = 10;  // LOCATION, city .. elevation
constexpr std::size_t kRowFields = 19;       // through diffuse horizontal illuminance, the last field read
// An hourly EPW file is 1.5-2 MB; far more is not one (and is not read into memory).
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{64} << 20;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

constexpr std::array<int, 12> kDaysInMonth = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
constexpr std::array<const char*, 12> kMonthNames = {"Jan", "Feb", "Mar", "Apr", "May", "Jun",
                                                     "Jul", "Aug", "Sep", "Oct", "Nov", "Dec"};
constexpr std::array<std::string_view, kHeaderLines> kHeaderKeywords = {
    "LOCATION",         "DESIGN CONDITIONS", "TYPICAL/EXTREME PERIODS", "GROUND TEMPERATURES",
    "HOLIDAYS/DAYLIGHT SAVINGS", "COMMENTS 1", "COMMENTS 2",              "DATA PERIODS"};
constexpr std::string_view kLocationLayout =
    "LOCATION,city,region,country,source,WMO station,latitude,longitude,time zone,elevation";

// A data field ilp reads: where it is, what it is called, its missing-value code (values at
// or above it mean missing, as the EPW data dictionary has it) and the range of a value.
struct FieldRule {
  std::size_t field;     // 1-based position on the row
  const char* name;
  const char* unit;
  double missing_from;   // values >= this are the missing-value code
  bool required;         // missing is an error (ilp needs it); else NaN
  double min, max;       // a value present lies in [min, max], or (min, max) when `open`
  bool open;
  double WeatherHour::*member;
};

constexpr std::array<FieldRule, 9> kRules = {{
    {7, "dry bulb temperature", "°C", 99.9, false, -70, 70, true, &WeatherHour::dry_bulb_c},
    {8, "dew point temperature", "°C", 99.9, true, -70, 70, true, &WeatherHour::dew_point_c},
    {10, "atmospheric station pressure", "Pa", 999999, false, 31000, 120000, true, &WeatherHour::pressure_pa},
    {14, "global horizontal irradiance", "Wh/m²", 9999, false, 0, kInf, false,
     &WeatherHour::global_horizontal_w_per_m2},
    {15, "direct normal irradiance", "Wh/m²", 9999, true, 0, kInf, false, &WeatherHour::direct_normal_w_per_m2},
    {16, "diffuse horizontal irradiance", "Wh/m²", 9999, true, 0, kInf, false,
     &WeatherHour::diffuse_horizontal_w_per_m2},
    {17, "global horizontal illuminance", "lux", 999900, false, 0, kInf, false, &WeatherHour::global_horizontal_lux},
    {18, "direct normal illuminance", "lux", 999900, false, 0, kInf, false, &WeatherHour::direct_normal_lux},
    {19, "diffuse horizontal illuminance", "lux", 999900, false, 0, kInf, false,
     &WeatherHour::diffuse_horizontal_lux},
}};

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::toupper(static_cast<unsigned char>(x)) == std::toupper(static_cast<unsigned char>(y));
         });
}

bool istarts_with(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() && iequals(text.substr(0, prefix.size()), prefix);
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

// `text` as it may appear in a message: quoted, control characters escaped, shortened.
std::string quoted(std::string_view text, std::size_t max_chars = 60) {
  std::string out = "'";  // (not "'" + ...: GCC 12 warns falsely on operator+(const char*, string&&))
  return out.append(printable(shortened(text, max_chars))).append("'");
}

std::string format_number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string date_text(int month, int day, int hour) {
  const bool known = month >= 1 && month <= 12;
  return std::to_string(day) + " " + (known ? kMonthNames[month - 1] : "month " + std::to_string(month)) + " hour " +
         std::to_string(hour);
}

[[noreturn]] void fail(const std::string& path, int line, const std::string& message) {
  throw ConfigError(located(FileLoc{path, line, 0}, message));
}

// A finite number written in full (surrounding blanks and a leading '+' allowed).
bool parse_number(std::string_view token, double& out) {
  token = trim(token);
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  double value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value)) return false;
  out = value;
  return true;
}

bool parse_integer(std::string_view token, int& out) {
  token = trim(token);
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  int value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size()) return false;
  out = value;
  return true;
}

// One line split into its fields, for reading them with messages that name line and field.
struct Line {
  const std::string& path;
  int number = 0;  // 1-based
  std::vector<std::string_view> fields;

  std::string_view text(std::size_t field) const { return fields[field - 1]; }

  [[noreturn]] void fail_field(std::size_t field, std::string_view name, const std::string& what) const {
    fail(path, number, "field " + std::to_string(field) + " (" + std::string(name) + "): " + what);
  }

  double number_at(std::size_t field, std::string_view name) const {
    double value = 0;
    if (parse_number(text(field), value)) return value;
    if (trim(text(field)).empty()) fail_field(field, name, "is empty; a number is needed here");
    fail_field(field, name, quoted(text(field)) + " is not a number");
  }

  int integer_at(std::size_t field, std::string_view name) const {
    int value = 0;
    if (parse_integer(text(field), value)) return value;
    if (trim(text(field)).empty()) fail_field(field, name, "is empty; a whole number is needed here");
    fail_field(field, name, quoted(text(field)) + " is not a whole number");
  }
};

// ------------------------------------------------------------------------ the file's lines

std::string read_text(const std::string& path) {
  if (const std::string why = not_a_regular_file(path, "weather (EPW)"); !why.empty()) throw ConfigError(why);
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) {
    const int err = errno;
    if (err == ENOENT) throw ConfigError(path + ": no such file (an EnergyPlus weather file, .epw, was expected)");
    throw ConfigError(path + ": cannot open the weather file: " + std::strerror(err));
  }
  std::string text;
  char buffer[1 << 16];
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, file.get())) > 0;) {
    text.append(buffer, got);
    if (text.size() > kMaxFileBytes)
      throw ConfigError(path + ": more than " + std::to_string(kMaxFileBytes >> 20) +
                        " MB, far more than an hourly EPW file (about 1.6 MB): not a weather file");
  }
  if (std::ferror(file.get())) throw ConfigError(path + ": cannot read the weather file: " + std::strerror(errno));
  return text;
}

// The lines of `text` without their line ends (LF or CRLF), a UTF-8 byte order mark and
// blank lines at the end dropped.
std::vector<std::string_view> split_lines(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  while (!lines.empty() && trim(lines.back()).empty()) lines.pop_back();
  return lines;
}

// Throws unless the first line is a LOCATION line, saying what the file looks like.
void check_format(const std::string& path, std::string_view text, const std::vector<std::string_view>& lines) {
  const std::string epw_start = "an EPW file starts with " + std::string(kLocationLayout);
  if (lines.empty()) throw ConfigError(path + ": is empty (or blank); " + epw_start);
  const std::string_view first_line = lines.front();
  if (iequals(trim(first_line.substr(0, first_line.find(','))), "LOCATION")) return;
  std::string looks;
  if (text.substr(0, 4096).find('\0') != std::string_view::npos)
    looks = "looks like a binary file, not EPW text";
  else if (istarts_with(first_line, "place "))
    looks = "looks like a Radiance/DAYSIM WEA file (first line " + quoted(first_line) +
            "); ilp reads the EnergyPlus weather file (.epw) it was made from";
  else if (first_line.find(',') != std::string_view::npos)
    looks = "looks like a CSV file (first line " + quoted(first_line) + "), not an EPW file";
  else
    looks = "first line " + quoted(first_line) + " is not a LOCATION line";
  fail(path, 1, looks + "; " + epw_start);
}

// A carriage return left inside a line: CR-only line ends (classic Mac), which would run
// the whole file into one line.
void check_line_ends(const std::string& path, const std::vector<std::string_view>& lines) {
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].find('\r') != std::string_view::npos)
      fail(path, static_cast<int>(i) + 1,
           "a carriage return inside the line (CR-only line ends?); an EPW file has LF or CRLF line ends");
}

// ------------------------------------------------------------------------ the header

void check_range(const Line& line, std::size_t field, const char* name, double value, double min, double max,
                 const std::string& hint) {
  if (value >= min && value <= max) return;
  line.fail_field(field, name,
                  quoted(line.text(field)) + " is outside [" + format_number(min) + ", " + format_number(max) + "]" +
                      hint);
}

WeatherSite read_location(const std::string& path, std::string_view text) {
  const Line line{path, 1, split_fields(text)};
  if (line.fields.size() < kLocationFields)
    fail(path, 1,
         "the LOCATION line has " + std::to_string(line.fields.size()) + " fields, " +
             std::to_string(kLocationFields) + " are needed: " + std::string(kLocationLayout));
  WeatherSite site;
  site.city = trim(line.text(2));
  site.region = trim(line.text(3));
  site.country = trim(line.text(4));
  site.source = trim(line.text(5));
  site.station_id = trim(line.text(6));
  site.latitude_deg = line.number_at(7, "latitude");
  check_range(line, 7, "latitude", site.latitude_deg, -90, 90, " degrees (north positive)");
  site.longitude_deg = line.number_at(8, "longitude");
  check_range(line, 8, "longitude", site.longitude_deg, -180, 180, " degrees (east positive)");
  site.timezone_h = line.number_at(9, "time zone");
  const bool meridian = std::fmod(site.timezone_h, 15.0) == 0.0 && std::fabs(site.timezone_h) > 14;
  check_range(line, 9, "time zone", site.timezone_h, -12, 14,
              std::string(" hours east of UTC (Chicago: -6)") +
                  (meridian ? "; it looks like a meridian in degrees, which is 15 times the time zone" : ""));
  site.elevation_m = line.number_at(10, "elevation");
  if (!(site.elevation_m >= -1000 && site.elevation_m < 9999.9))
    line.fail_field(10, "elevation", quoted(line.text(10)) + " is outside [-1000, 9999.9) m above sea level");
  return site;
}

// Lines 2..8 carry their keywords; DATA PERIODS says 1 record per hour.
void check_header(const std::string& path, const std::vector<std::string_view>& lines) {
  for (int i = 1; i < kHeaderLines; ++i) {
    if (i >= static_cast<int>(lines.size()))
      fail(path, static_cast<int>(lines.size()),
           "the file ends after " + std::to_string(lines.size()) + " lines, inside the 8 header lines (no " +
               std::string(kHeaderKeywords[i]) + " line, no hourly rows)");
    const std::string_view keyword = trim(lines[i].substr(0, lines[i].find(',')));
    const bool ok = iequals(keyword, kHeaderKeywords[i]) || (i == 4 && iequals(keyword, "HOLIDAYS/DAYLIGHT SAVING"));
    if (!ok)
      fail(path, i + 1,
           "expected the " + std::string(kHeaderKeywords[i]) + " header line, found " + quoted(lines[i]) +
               " (an EPW file has 8 header lines: LOCATION, DESIGN CONDITIONS, TYPICAL/EXTREME PERIODS, GROUND "
               "TEMPERATURES, HOLIDAYS/DAYLIGHT SAVINGS, COMMENTS 1, COMMENTS 2, DATA PERIODS)");
  }
  const Line periods{path, kHeaderLines, split_fields(lines[kHeaderLines - 1])};
  if (periods.fields.size() < 3)
    fail(path, kHeaderLines, "the DATA PERIODS line has " + std::to_string(periods.fields.size()) +
                                 " fields; field 3 is the number of records per hour");
  const int per_hour = periods.integer_at(3, "records per hour");
  if (per_hour != 1)
    periods.fail_field(3, "records per hour",
                       quoted(periods.text(3)) + ": ilp reads hourly files (1 record per hour) only");
}

// ------------------------------------------------------------------------ the rows

// The first row of 29 February (by its month and day fields), or -1.
int find_leap_day(const std::vector<std::string_view>& lines) {
  for (std::size_t i = kHeaderLines; i < lines.size(); ++i) {
    const std::vector<std::string_view> f = split_fields(lines[i]);
    int month = 0, day = 0;
    if (f.size() >= 3 && parse_integer(f[1], month) && parse_integer(f[2], day) && month == 2 && day == 29)
      return static_cast<int>(i) + 1;
  }
  return -1;
}

// Throws unless there are 8760 rows, none of them blank.
void check_row_count(const std::string& path, const std::vector<std::string_view>& lines) {
  for (std::size_t i = kHeaderLines; i < lines.size(); ++i)
    if (trim(lines[i]).empty()) fail(path, static_cast<int>(i) + 1, "an empty line among the hourly rows");
  const int rows = static_cast<int>(lines.size()) - kHeaderLines;
  if (rows == kTypicalYearHours) return;
  const std::string span = std::to_string(rows) + " hourly rows (lines " + std::to_string(kHeaderLines + 1) + " to " +
                           std::to_string(lines.size()) + ")";
  if (rows < kTypicalYearHours)
    fail(path, static_cast<int>(lines.size()),
         "the file ends after " + (rows == 0 ? std::string("the header, with no hourly rows") : span) +
             "; a typical year has 8760: is the file truncated?");
  if (rows == kLeapYearHours) {
    const int leap = find_leap_day(lines);
    const std::string where = leap > 0 ? "field 3 (day): 29 Feb (lines " + std::to_string(leap) + " to " +
                                             std::to_string(leap + 23) + "): " : "";
    fail(path, leap > 0 ? leap : static_cast<int>(lines.size()),
         where + "the file has " + span + ", a leap year; ilp needs a typical year of 8760 hours: drop the 24 rows "
                 "of 29 February");
  }
  fail(path, kHeaderLines + kTypicalYearHours + 1,
       "the file has " + span + "; a typical year has 8760, one row per hour (sub-hourly data, or extra lines?)");
}

double read_value(const Line& line, const FieldRule& rule) {
  const double v = line.number_at(rule.field, rule.name);
  if (v >= rule.missing_from) {
    if (!rule.required) return kNaN;
    const std::string code = format_number(rule.missing_from);
    line.fail_field(rule.field, rule.name,
                    quoted(line.text(rule.field)) +
                        (v == rule.missing_from ? " is the missing-value code" : " is at or above the missing-value code " + code) +
                        " (" + code + " and above mean missing); ilp needs every hour's " + rule.name +
                        ": fill the gaps (e.g. with the EnergyPlus Weather Converter) or take another file");
  }
  const bool inside = rule.open ? (v > rule.min && v < rule.max) : (v >= rule.min && v <= rule.max);
  if (inside) return v;
  if (rule.min == 0 && !rule.open)
    line.fail_field(rule.field, rule.name, quoted(line.text(rule.field)) + " is negative; must be >= 0 " + rule.unit);
  line.fail_field(rule.field, rule.name,
                  quoted(line.text(rule.field)) + " is outside (" + format_number(rule.min) + ", " +
                      format_number(rule.max) + ") " + rule.unit + ", the EPW data dictionary's range");
}

// Month, day and hour in range (no 29 February).
void check_date_fields(const Line& line, const WeatherHour& h) {
  if (h.month < 1 || h.month > 12) line.fail_field(2, "month", quoted(line.text(2)) + " is outside 1..12");
  const int days = kDaysInMonth[h.month - 1];
  if (h.month == 2 && h.day == 29)
    line.fail_field(3, "day", "29 Feb, a leap day; ilp needs a typical year of 365 days (8760 hours) without "
                              "29 February");
  if (h.day < 1 || h.day > days)
    line.fail_field(3, "day", quoted(line.text(3)) + " is outside 1.." + std::to_string(days) + " (" +
                                  kMonthNames[h.month - 1] + ")");
  if (h.hour < 1 || h.hour > 24)
    line.fail_field(4, "hour", quoted(line.text(4)) +
                                   " is outside 1..24 (hour h is the hour ending at h:00; hour 1 is 00:00-01:00)");
}

// The row at `index` (0-based) of a typical year is that hour of the calendar.
void check_order(const Line& line, const WeatherHour& h, int index) {
  int day_of_year = index / 24, month = 0;
  while (day_of_year >= kDaysInMonth[month]) day_of_year -= kDaysInMonth[month++];
  const int day = day_of_year + 1, hour = index % 24 + 1;
  if (h.month == month + 1 && h.day == day && h.hour == hour) return;
  const std::size_t field = h.month != month + 1 ? 2 : h.day != day ? 3 : 4;
  const char* name = field == 2 ? "month" : field == 3 ? "day" : "hour";
  line.fail_field(field, name,
                  date_text(h.month, h.day, h.hour) + " is out of order: row " + std::to_string(index + 1) +
                      " of the year is " + date_text(month + 1, day, hour) +
                      "; ilp needs the 8760 hours from 1 Jan hour 1 in calendar order, one row each");
}

WeatherHour read_row(const std::string& path, std::string_view text, int line_number, bool last) {
  const Line line{path, line_number, split_fields(text)};
  if (line.fields.size() < kRowFields)
    fail(path, line_number,
         "an hourly row of " + std::to_string(line.fields.size()) + " fields; ilp reads the first " +
             std::to_string(kRowFields) + " (through field 19, diffuse horizontal illuminance) and an EPW row has 35" +
             (last ? "; it is the file's last line: is the file truncated?" : ""));
  WeatherHour h;
  h.month = line.integer_at(2, "month");
  h.day = line.integer_at(3, "day");
  h.hour = line.integer_at(4, "hour");
  check_date_fields(line, h);
  check_order(line, h, line_number - kHeaderLines - 1);
  for (const FieldRule& rule : kRules) h.*rule.member = read_value(line, rule);
  return h;
}

}  // namespace

WeatherFile read_epw(const std::string& path) {
  const std::string text = read_text(path);
  const std::vector<std::string_view> lines = split_lines(text);
  check_format(path, text, lines);
  check_line_ends(path, lines);
  WeatherFile weather;
  weather.path = path;
  weather.site = read_location(path, lines.front());
  check_header(path, lines);
  check_row_count(path, lines);
  weather.hours.reserve(kTypicalYearHours);
  for (int i = kHeaderLines; i < static_cast<int>(lines.size()); ++i)
    weather.hours.push_back(read_row(path, lines[i], i + 1, i + 1 == static_cast<int>(lines.size())));
  return weather;
}

std::ostream& operator<<(std::ostream& os, const WeatherSite& site) {
  const auto hemisphere = [](double v, const char* plus, const char* minus) {
    return format_number(std::fabs(v)) + "° " + (v < 0 ? minus : plus);
  };
  std::string utc = "UTC";
  if (site.timezone_h != 0) utc += (site.timezone_h > 0 ? "+" : "") + format_number(site.timezone_h);
  return os << printable(site.city) << ", " << printable(site.region) << ", " << printable(site.country) << " ("
            << printable(site.source) << " " << printable(site.station_id)
            << "): " << hemisphere(site.latitude_deg, "N", "S") << ", " << hemisphere(site.longitude_deg, "E", "W")
            << ", " << utc << ", " << format_number(site.elevation_m) << " m";
}

std::ostream& operator<<(std::ostream& os, const WeatherHour& h) {
  return os << date_text(h.month, h.day, h.hour) << ": " << h.global_horizontal_w_per_m2 << " W/m² global, "
            << h.direct_normal_w_per_m2 << " direct normal, " << h.diffuse_horizontal_w_per_m2 << " diffuse; "
            << h.dry_bulb_c << " °C";
}

}  // namespace ilp
