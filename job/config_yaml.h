// Inside the job loader only (job/config*.cpp): the YAML values with their file
// locations and the checks every key shares (bounds, known keys, duplicates). yaml-cpp
// stays behind job/: no other module includes this.
#pragma once

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "job/config.h"

namespace ilp::config_yaml {

// Bounds on the numbers a user types, so that no later arithmetic overflows or
// loses the job (docs/reliability.md). Generous for real rooms and products.
constexpr double kMaxFlux_lm = 1e9;              // a stadium floodlight is ~2e5 lm
constexpr double kMaxExitance_lm_per_m2 = 1e9;   // the sun's disc ~1e5 lx on a surface
constexpr double kMaxLux = 1e7;                  // goal targets
constexpr double kMinLuminaireSize_m = 1e-3, kMaxLuminaireSize_m = 100.0;
constexpr double kMinPatchEdge_m = 1e-4, kMaxLength_m = 1e5;
constexpr double kMinSpacing_m = 1e-3;
constexpr double kMinScale = 1e-6, kMaxScale = 1e6;
constexpr double kMaxEfficacy_lm_per_w = 1000.0;  // 683 lm/W is the theoretical limit
constexpr double kMaxSeconds = 1e7;
// Bounds on the strings a user types: names and keywords (a 50 MB product name once
// ran for minutes and wrote a 200 MB result.json), paths, and how deep YAML may nest
// (yaml-cpp recurses per level).
constexpr std::size_t kMaxNameChars = 256;
constexpr std::size_t kMaxPathChars = 4096;  // PATH_MAX
constexpr std::size_t kMaxGridNameChars = 200;  // isolux_NAME_N.png within a file name's 255 bytes
constexpr int kMaxNestingLevels = 64;

// A YAML node with the dotted key that led to it, for messages that say where.
class Value {
 public:
  Value(YAML::Node node, std::string key, std::string file)
      : node_(node), key_(std::move(key)), file_(std::move(file)) {}

  FileLoc loc() const {
    const YAML::Mark mark = node_.Mark();
    return {file_, mark.line >= 0 ? mark.line + 1 : 0, mark.column >= 0 ? mark.column + 1 : 0};
  }
  const std::string& key() const { return key_; }
  const YAML::Node& node() const { return node_; }

  [[noreturn]] void fail(const std::string& rule) const {
    std::string shown = node_.IsScalar()     ? shortened(printable(node_.Scalar()))
                        : node_.IsSequence() ? "[...]"
                        : node_.IsMap()      ? "{...}"
                                             : "";
    throw ConfigError(located(loc(), key_ + (shown.empty() ? "" : " = " + shown) + ": " + rule));
  }

  double number() const {
    if (!node_.IsScalar()) fail("must be a number");
    const std::string& text = node_.Scalar();
    const std::string lowered = lower(text);
    if (lowered == ".nan" || lowered == ".inf" || lowered == "-.inf" || lowered == "+.inf") fail("must be a finite number");
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size()) fail("must be a number");
    if (!std::isfinite(value)) fail("must be a finite number");
    return value;
  }
  double number_in(double low, double high, bool high_open, const std::string& range) const {
    const double v = number();
    if (v < low || v > high || (high_open && v == high)) fail("must be in " + range);
    return v;
  }
  double positive() const {
    const double v = number();
    if (!(v > 0.0)) fail("must be > 0");
    return v;
  }
  // A number in [low, high] (docs/reliability.md: what ilp can hold), else an error
  // naming the range and its unit.
  double bounded(double low, double high, const std::string& unit) const {
    const double v = number();
    if (low > 0.0 && !(v > 0.0)) fail("must be > 0");
    if (low == 0.0 && v < 0.0) fail("must be >= 0");
    if (v < low) fail("must be at least " + shown(low) + unit);
    if (v > high) fail("must be at most " + shown(high) + unit);
    return v;
  }
  static std::string shown(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
  }
  long long integer(long long low, long long high) const {
    const double v = number();
    if (v != std::floor(v)) fail("must be a whole number");
    if (v < static_cast<double>(low) || v > static_cast<double>(high))
      fail("must be between " + std::to_string(low) + " and " + std::to_string(high));
    return static_cast<long long>(v);
  }
  // A name or keyword: at most kMaxNameChars, no control characters.
  std::string text() const {
    if (!node_.IsScalar()) fail("must be a string");
    const std::string& s = node_.Scalar();
    if (s.size() > kMaxNameChars)
      fail("is " + std::to_string(s.size()) + " characters long, more than " + std::to_string(kMaxNameChars));
    if (printable(s) != s) fail("must not hold control characters");
    return s;
  }
  // A file or folder path: at most kMaxPathChars.
  std::string path() const {
    if (!node_.IsScalar()) fail("must be a string");
    const std::string& s = node_.Scalar();
    if (s.size() > kMaxPathChars)
      fail("is " + std::to_string(s.size()) + " characters long, more than " + std::to_string(kMaxPathChars));
    return s;
  }
  Eigen::Vector3d vector3() const {
    if (!node_.IsSequence() || node_.size() != 3) fail("must be a list of 3 numbers [x, y, z]");
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = element(k).number();
    return v;
  }
  // A reflectance: one number (gray) or [r, g, b], each in [0, 1).
  Eigen::Vector3d reflectance() const {
    if (node_.IsScalar()) return Eigen::Vector3d::Constant(number_in(0.0, 1.0, true, "[0, 1)"));
    if (!node_.IsSequence() || node_.size() != 3) fail("must be a number in [0, 1) or a list [r, g, b]");
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = element(k).number_in(0.0, 1.0, true, "[0, 1)");
    return v;
  }
  Value element(std::size_t k) const { return {node_[k], key_ + "[" + std::to_string(k) + "]", file_}; }
  std::vector<Value> list() const {
    if (!node_.IsSequence()) fail("must be a list");
    std::vector<Value> out;
    for (std::size_t k = 0; k < node_.size(); ++k) out.push_back(element(k));
    return out;
  }

  static std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  }

 private:
  YAML::Node node_;
  std::string key_;
  std::string file_;
};

// Counts the documents of a YAML stream (the parser's events; nothing is built).
class DocumentCounter : public YAML::EventHandler {
 public:
  int documents = 0;
  YAML::Mark second;
  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents == 2) second = mark;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

// YAML::Load reads the first document and ignores the rest: a second one is refused.
inline void reject_second_document(const std::string& text, const std::string& path) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DocumentCounter counter;
  if (!parser.HandleNextDocument(counter) || !parser.HandleNextDocument(counter) || counter.documents < 2) return;
  const YAML::Mark& mark = counter.second;
  throw ConfigError(located({path, mark.line >= 0 ? mark.line + 1 : 0, mark.column >= 0 ? mark.column + 1 : 0},
                            "a second YAML document (after '---'): a config file holds one job"));
}

// Flow collections nested deeper than kMaxNestingLevels ('[[[[...', '{{{...') or
// block sequences ('- - - ...') are refused before yaml-cpp recurses into them.
inline void reject_deep_nesting(const std::string& text, const std::string& path) {
  int depth = 0, line = 1;
  char quote = 0;
  bool comment = false, line_start = true;
  int dashes = 0;  // "- " items opened on this line before its first other character
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      comment = false;
      line_start = true;
      dashes = 0;
      if (quote == '\'') quote = 0;  // (a plain scalar cannot span; keep the count honest)
      continue;
    }
    if (comment) continue;
    if (quote) {
      if (c == '\\' && quote == '"') ++i;
      else if (c == quote) quote = 0;
      continue;
    }
    if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' || line_start)) comment = true;
    else if (c == '"' || c == '\'') quote = c;
    else if (c == '[' || c == '{') ++depth;
    else if ((c == ']' || c == '}') && depth > 0) --depth;
    if (line_start && c == '-' && i + 1 < text.size() && (text[i + 1] == ' ' || text[i + 1] == '\t')) ++dashes;
    else if (c != ' ' && c != '\t') line_start = false;
    if (depth > kMaxNestingLevels || dashes > kMaxNestingLevels)
      throw ConfigError(located({path, line, 0}, "YAML nesting deeper than " + std::to_string(kMaxNestingLevels) +
                                                   " levels: not a job file"));
  }
}

// yaml-cpp keeps repeated keys and lets lookups see the first: refuse them instead.
inline void reject_duplicate_keys(const Value& map) {
  std::set<std::string> seen;
  for (const auto& item : map.node()) {
    const std::string name = item.first.Scalar();
    if (!seen.insert(name).second) {
      const YAML::Mark mark = item.first.Mark();
      const std::string key = map.key().empty() ? name : map.key() + "." + name;
      throw ConfigError(located({map.loc().file, mark.line + 1, mark.column + 1}, "duplicate key '" + key + "'"));
    }
  }
}

// A YAML map whose keys must all be known.
class Map {
 public:
  Map(const Value& value, const std::vector<std::string>& allowed) : value_(value) {
    if (!value.node().IsMap()) value.fail("must be a map of keys");
    std::set<std::string> known(allowed.begin(), allowed.end());
    reject_duplicate_keys(value);
    for (const auto& item : value.node()) {
      const std::string name = item.first.Scalar();
      if (!known.count(name)) {
        std::string expected;
        for (const std::string& k : allowed) expected += (expected.empty() ? "" : ", ") + k;
        const YAML::Mark mark = item.first.Mark();
        throw ConfigError(located({file(), mark.line + 1, mark.column + 1},
                                  "unknown key '" + prefix() + name + "' (expected one of: " + expected + ")"));
      }
    }
  }
  const Value& value() const { return value_; }
  // Where the key `name` itself is written (a map or list value starts elsewhere).
  FileLoc key_loc(const std::string& name) const {
    for (const auto& item : value_.node())
      if (item.first.Scalar() == name) {
        const YAML::Mark mark = item.first.Mark();
        return {file(), mark.line + 1, mark.column + 1};
      }
    return value_.loc();
  }
  std::optional<Value> get(const std::string& name) const {
    YAML::Node child = value_.node()[name];
    if (!child.IsDefined() || child.IsNull()) return std::nullopt;
    return Value(child, prefix() + name, file());
  }
  Value require(const std::string& name) const {
    auto v = get(name);
    if (!v) throw ConfigError(located(value_.loc(), prefix() + name + ": required key is missing"));
    return *v;
  }

 private:
  std::string prefix() const { return value_.key().empty() ? "" : value_.key() + "."; }
  std::string file() const { return value_.loc().file; }
  Value value_;
};


// A list of 2 numbers [x, y], each read and checked by `check`.
inline Eigen::Vector2d pair_of(const Value& v, double (*check)(const Value&)) {
  if (!v.node().IsSequence() || v.node().size() != 2) v.fail("must be a list of 2 numbers [x, y]");
  return {check(v.element(0)), check(v.element(1))};
}

// luminaires: (job/config_luminaires.cpp) the search's keys, products, placed luminaires.
// products_named: luminaires.products is a list of names chosen from job.products (a
// room choosing from its building's catalogue), not the products' definitions.
void read_luminaires(const Map& luminaires, JobConfig& job, bool products_named = false);
// config_goals.cpp: the grids section, then the goals section (its entries name grids
// and products; presets, observers, the immediate surrounding area).
void read_grids(const Value& section, JobConfig& job);
void read_goals(const Value& section, JobConfig& job);
// config_scenarios.cpp: the scenarios section (after goals, whose areas it names).
void read_scenarios(const Value& section, JobConfig& job);
std::vector<std::string> luminaire_keys();  // every key of the luminaires section

// (job/config.cpp) The keys a single-room job and each room of a building job have:
// luminaires, grids, maintenance_factor, goals, constraints, objective, energy.
void read_room_keys(const Map& map, JobConfig& job, bool products_named);
// A building job's top level: luminaires (products, size_m only), maintenance_factor and
// energy as the rooms' defaults; a single room's keys there are errors naming them.
void read_building_keys(const Map& top, JobConfig& job);
// (job/config_rooms.cpp) rooms: each entry read over a copy of the building's keys.
void read_rooms(const Value& rooms, JobConfig& building);

}  // namespace ilp::config_yaml
