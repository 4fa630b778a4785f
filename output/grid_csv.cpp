#include "output/grid_csv.h"

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/base/error.h"
#include "output/atomic_file.h"
#include "output/svg_plan_parts.h"

namespace ilp {
namespace {

constexpr const char* kHeader =
    "grid,point,x_m,y_m,z_m,direct_initial_lux,total_initial_lux,maintenance_factor,direct_maintained_lux,"
    "total_maintained_lux";
constexpr int kFields = 10;
constexpr int kMetreDecimals = 4, kLuxDecimals = 2, kFactorDecimals = 4;

// RFC 4180: a field with a comma, quote or line break is quoted, quotes doubled.
std::string quoted(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string number(double v, int decimals) { return svg::fixed(v, decimals); }

// Splits one record into fields (quotes as RFC 4180); `pos` moves past the record's
// line break. Returns false at the end of the text.
bool next_record(const std::string& text, std::size_t& pos, std::vector<std::string>& fields, int& line,
                 const std::string& source) {
  fields.clear();
  if (pos >= text.size()) return false;
  std::string field;
  bool in_quotes = false;
  const int start_line = line;
  for (; pos < text.size(); ++pos) {
    const char c = text[pos];
    if (in_quotes) {
      if (c == '"' && pos + 1 < text.size() && text[pos + 1] == '"') { field += '"'; ++pos; }
      else if (c == '"') in_quotes = false;
      else { if (c == '\n') ++line; field += c; }
    } else if (c == '"' && field.empty()) {
      in_quotes = true;
    } else if (c == ',') {
      fields.push_back(std::move(field));
      field.clear();
    } else if (c == '\n') {
      ++pos;
      break;
    } else if (c != '\r') {
      field += c;
    }
  }
  if (in_quotes) throw IlpError(source + ":" + std::to_string(start_line) + ": unterminated quoted field");
  fields.push_back(std::move(field));
  ++line;
  return true;
}

double parse_number(const std::string& field, const std::string& where, const char* column) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (ec != std::errc() || end != field.data() + field.size() || !std::isfinite(v))
    throw IlpError(where + ": " + column + " = '" + field + "' is not a finite number");
  return v;
}

}  // namespace

std::string grid_csv(const std::vector<GridCsvGrid>& grids) {
  std::string out = std::string(kHeader) + "\n";
  for (const GridCsvGrid& g : grids) {
    if (!(g.maintenance_factor > 0.0) || g.maintenance_factor > 1.0)
      throw std::invalid_argument("grid_csv: grid '" + g.name + "' has maintenance factor " +
                                  std::to_string(g.maintenance_factor) + ", not in (0, 1]");
    const std::string name = quoted(g.name), factor = number(g.maintenance_factor, kFactorDecimals);
    for (std::size_t k = 0; k < g.points.size(); ++k) {
      const GridCsvPoint& p = g.points[k];
      if (!p.position_m.allFinite() || !std::isfinite(p.direct_initial_lux) || !std::isfinite(p.total_initial_lux))
        throw std::invalid_argument("grid_csv: grid '" + g.name + "' point " + std::to_string(k) +
                                    " has a non-finite coordinate or value");
      out += name + ',' + std::to_string(k);
      for (int a = 0; a < 3; ++a) out += ',' + number(p.position_m[a], kMetreDecimals);
      out += ',' + number(p.direct_initial_lux, kLuxDecimals) + ',' + number(p.total_initial_lux, kLuxDecimals);
      out += ',' + factor;
      out += ',' + number(p.direct_initial_lux * g.maintenance_factor, kLuxDecimals);
      out += ',' + number(p.total_initial_lux * g.maintenance_factor, kLuxDecimals) + '\n';
    }
  }
  return out;
}

void write_grid_csv(const std::string& path, const std::vector<GridCsvGrid>& grids) {
  const std::string text = grid_csv(grids);  // checks first: nothing is written for bad input
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

std::vector<GridCsvGrid> parse_grid_csv(const std::string& text, const std::string& source) {
  std::size_t pos = 0;
  int line = 1;
  std::vector<std::string> fields;
  if (!next_record(text, pos, fields, line, source) || fields.size() != kFields) {
    throw IlpError(source + ":1: the header must be " + kHeader);
  }
  {
    std::string header;
    for (std::size_t k = 0; k < fields.size(); ++k) header += (k ? "," : "") + fields[k];
    if (header != kHeader) throw IlpError(source + ":1: the header must be " + kHeader);
  }
  std::vector<GridCsvGrid> grids;
  std::map<std::string, std::size_t> index;
  const double lux_rounding = 0.5 * std::pow(10.0, -kLuxDecimals), factor_rounding = 0.5 * std::pow(10.0, -kFactorDecimals);
  for (int record_line = line; next_record(text, pos, fields, line, source); record_line = line) {
    const std::string where = source + ":" + std::to_string(record_line);
    if (fields.size() == 1 && fields[0].empty()) continue;  // a blank line (e.g. at the end)
    if (fields.size() != kFields)
      throw IlpError(where + ": " + std::to_string(fields.size()) + " fields, expected " + std::to_string(kFields));
    auto [it, inserted] = index.try_emplace(fields[0], grids.size());
    if (inserted) grids.push_back({fields[0], 1.0, {}});
    GridCsvGrid& g = grids[it->second];
    const double point = parse_number(fields[1], where, "point");
    if (point != static_cast<double>(g.points.size()))
      throw IlpError(where + ": point = " + fields[1] + ", expected " + std::to_string(g.points.size()) +
                     " (the next point of grid '" + g.name + "')");
    GridCsvPoint p;
    p.position_m = {parse_number(fields[2], where, "x_m"), parse_number(fields[3], where, "y_m"),
                    parse_number(fields[4], where, "z_m")};
    p.direct_initial_lux = parse_number(fields[5], where, "direct_initial_lux");
    p.total_initial_lux = parse_number(fields[6], where, "total_initial_lux");
    g.maintenance_factor = parse_number(fields[7], where, "maintenance_factor");
    if (!(g.maintenance_factor > 0.0) || g.maintenance_factor > 1.0)
      throw IlpError(where + ": maintenance_factor = " + fields[7] + ": must be in (0, 1]");
    const double direct_m = parse_number(fields[8], where, "direct_maintained_lux");
    const double total_m = parse_number(fields[9], where, "total_maintained_lux");
    // Both sides were rounded: allow the rounding of the maintained value, plus that of
    // the initial value and of the factor carried through the product.
    const auto matches = [&](double initial, double maintained) {
      const double slack = lux_rounding * (1.0 + g.maintenance_factor) + factor_rounding * std::abs(initial) + 1e-9;
      return std::abs(initial * g.maintenance_factor - maintained) <= slack;
    };
    if (!matches(p.direct_initial_lux, direct_m) || !matches(p.total_initial_lux, total_m))
      throw IlpError(where + ": the maintained values are not the initial ones x maintenance_factor");
    g.points.push_back(p);
  }
  return grids;
}

}  // namespace ilp
