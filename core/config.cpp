#include "core/config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace ilp {
namespace {

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
    std::string shown = node_.IsScalar() ? node_.Scalar() : node_.IsSequence() ? "[...]" : node_.IsMap() ? "{...}" : "";
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
  long long integer(long long low, long long high) const {
    const double v = number();
    if (v != std::floor(v)) fail("must be a whole number");
    if (v < static_cast<double>(low) || v > static_cast<double>(high))
      fail("must be between " + std::to_string(low) + " and " + std::to_string(high));
    return static_cast<long long>(v);
  }
  std::string text() const {
    if (!node_.IsScalar()) fail("must be a string");
    return node_.Scalar();
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

// yaml-cpp keeps repeated keys and lets lookups see the first: refuse them instead.
void reject_duplicate_keys(const Value& map) {
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
  Map(const Value& value, std::initializer_list<const char*> allowed) : value_(value) {
    if (!value.node().IsMap()) value.fail("must be a map of keys");
    std::set<std::string> known(allowed.begin(), allowed.end());
    reject_duplicate_keys(value);
    for (const auto& item : value.node()) {
      const std::string name = item.first.Scalar();
      if (!known.count(name)) {
        std::string expected;
        for (const char* k : allowed) expected += std::string(expected.empty() ? "" : ", ") + k;
        const YAML::Mark mark = item.first.Mark();
        throw ConfigError(located({file(), mark.line + 1, mark.column + 1},
                                  "unknown key '" + prefix() + name + "' (expected one of: " + expected + ")"));
      }
    }
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

void read_scene(const Map& scene, JobConfig& job) {
  const Value mesh = scene.require("mesh");
  const std::filesystem::path base = std::filesystem::path(job.path).parent_path();
  job.mesh_path = (base / mesh.text()).lexically_normal().string();
  job.mesh_loc = mesh.loc();
  if (auto v = scene.get("up_axis")) {
    const std::string axis = Value::lower(v->text());
    if (axis == "y") job.scene.up_axis = UpAxis::y;
    else if (axis == "z") job.scene.up_axis = UpAxis::z;
    else v->fail("must be y or z");
  }
  if (auto v = scene.get("scale_to_m")) job.scene.scale_to_m = v->positive();
  if (auto v = scene.get("max_patch_edge_m")) {
    job.scene.max_patch_edge_m = v->positive();
    job.max_patch_edge_loc = v->loc();
  }
  if (auto v = scene.get("surfaces_from")) {
    const std::string from = Value::lower(v->text());
    if (from == "group") job.mesh_read.surface_naming = SurfaceNaming::group;
    else if (from == "object") job.mesh_read.surface_naming = SurfaceNaming::object;
    else if (from == "material") job.mesh_read.surface_naming = SurfaceNaming::material;
    else v->fail("must be group, object or material");
  }
  if (auto v = scene.get("reflectance")) {
    if (!v->node().IsMap()) v->fail("must map surface names to reflectances");
    reject_duplicate_keys(*v);
    for (const auto& item : v->node()) {
      const std::string surface = item.first.Scalar();
      const Value rho(item.second, v->key() + "." + surface, job.path);
      job.reflectance.push_back({surface, rho.reflectance(), rho.loc()});
    }
  }
  if (auto v = scene.get("default_reflectance")) job.default_reflectance = v->reflectance();
  if (auto v = scene.get("emitting_surfaces")) {
    for (const Value& item : v->list()) {
      const Map emitter(item, {"surface", "exitance_lm_per_m2"});
      const Value surface = emitter.require("surface");
      const Value exitance = emitter.require("exitance_lm_per_m2");
      const double e = exitance.number();
      if (e < 0.0) exitance.fail("must be >= 0");
      job.emitting_surfaces.push_back({surface.text(), e, surface.loc()});
    }
  }
}

void read_luminaires(const Map& luminaires, JobConfig& job) {
  if (auto v = luminaires.get("size_m")) job.luminaire_size_m = v->positive();
  if (auto v = luminaires.get("placed")) {
    std::set<std::string> names;
    for (const Value& item : v->list()) {
      const Map lum(item, {"name", "position_m", "flux_lm"});
      LuminaireSetting setting;
      if (auto name = lum.get("name")) {
        setting.name = name->text();
      } else {
        setting.name = "L";  // (not "L" + ...: GCC 12 warns falsely on operator+(const char*, string&&))
        setting.name += std::to_string(job.luminaires.size() + 1);
      }
      if (!names.insert(setting.name).second) item.fail("luminaire name '" + setting.name + "' is used twice");
      setting.position_m = lum.require("position_m").vector3();
      const Value flux = lum.require("flux_lm");
      setting.flux_lm = flux.number();
      if (setting.flux_lm < 0.0) flux.fail("must be >= 0");
      setting.loc = item.loc();
      job.luminaires.push_back(setting);
    }
  }
}

void read_solver(const Map& solver, JobConfig& job) {
  if (auto v = solver.get("rays_per_patch")) job.form_factors.rays_per_patch = static_cast<int>(v->integer(1, 1 << 24));
  if (auto v = solver.get("seed")) {
    job.form_factors.seed = static_cast<std::uint64_t>(v->integer(0, (1ll << 53)));
    job.direct_light.seed = job.form_factors.seed;
  }
  if (auto v = solver.get("threads")) {
    job.form_factors.threads = static_cast<int>(v->integer(0, 1024));
    job.direct_light.threads = job.form_factors.threads;
  }
  if (auto v = solver.get("relative_residual")) {
    job.radiosity.relative_residual = v->number_in(0.0, 1.0, true, "(0, 1)");
    if (job.radiosity.relative_residual <= 0.0) v->fail("must be in (0, 1)");
  }
  if (auto v = solver.get("max_iterations")) job.radiosity.max_iterations = static_cast<int>(v->integer(1, 100'000'000));
  if (auto v = solver.get("direct_receiver_points")) job.direct_light.receiver_points = static_cast<int>(v->integer(1, 4096));
  if (auto v = solver.get("direct_shadow_rays")) job.direct_light.shadow_rays = static_cast<int>(v->integer(1, 4096));
  if (auto v = solver.get("method")) {
    const std::string m = v->text();
    if (m == "sample") job.method = SolveMethod::sample;
    else if (m == "exact") job.method = SolveMethod::exact;
    else v->fail("must be sample or exact");
  }
  SampleSettings& sample = job.sample;
  const auto size = solver.get("sample_size"), fraction = solver.get("sample_fraction"),
             target = solver.get("target_error");
  if (size && fraction) fraction->fail("give sample_size or sample_fraction, not both");
  if (size) {
    sample.size = static_cast<int>(size->integer(1, 100'000'000));
    sample.size_loc = size->loc();
  }
  if (fraction) {
    sample.fraction = fraction->number_in(0.0, 1.0, false, "(0, 1]");
    if (sample.fraction <= 0.0) fraction->fail("must be in (0, 1]");
    sample.size_loc = fraction->loc();
  }
  if (target) {
    if (size || fraction) target->fail("give target_error or a sample size (sample_size, sample_fraction), not both");
    sample.target_error = target->number_in(0.0, 1.0, true, "(0, 1)");
    if (*sample.target_error <= 0.0) target->fail("must be in (0, 1)");
    sample.target_error_loc = target->loc();
  }
  if (auto v = solver.get("sampling")) {
    const auto strategy = parse_sample_strategy(v->text());
    if (!strategy) v->fail("must be uniform, area or stratified");
    sample.strategy = *strategy;
  }
  if (auto v = solver.get("sample_seed")) sample.seed = static_cast<std::uint64_t>(v->integer(0, (1ll << 53)));
  if (auto v = solver.get("indirect")) {
    const auto method = parse_indirect_method(v->text());
    if (!method) v->fail("must be sample_gather or exact_second_bounce");
    sample.indirect = *method;
  }
  if (auto v = solver.get("error_samples")) sample.error_samples = static_cast<int>(v->integer(2, 64));
  if (auto v = solver.get("pilot_fraction")) {
    sample.pilot_fraction = v->number_in(0.0, 1.0, false, "(0, 1]");
    if (sample.pilot_fraction <= 0.0) v->fail("must be in (0, 1]");
  }
}

}  // namespace

int SampleSettings::size_for(std::size_t population) const {
  if (size) return *size;
  return std::max(1, static_cast<int>(std::lround(fraction * static_cast<double>(population))));
}

JobConfig load_job_config(const std::string& path) {
  JobConfig job;
  job.path = path;
  {
    std::ifstream probe(path);
    if (!probe) throw ConfigError(path + ": cannot open the config file");
  }
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(located({path, e.mark.line + 1, e.mark.column + 1}, "malformed YAML: " + e.msg));
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ": cannot read YAML: " + e.what());
  }
  if (!root.IsMap()) throw ConfigError(path + ": the config must be a YAML map of sections (scene, luminaires, solver, report)");
  try {
    const Map top(Value(root, "", job.path), {"scene", "luminaires", "solver", "report"});
    read_scene(Map(top.require("scene"), {"mesh", "up_axis", "scale_to_m", "max_patch_edge_m", "surfaces_from",
                                          "reflectance", "default_reflectance", "emitting_surfaces"}),
               job);
    if (auto v = top.get("luminaires")) read_luminaires(Map(*v, {"size_m", "placed"}), job);
    if (auto v = top.get("solver"))
      read_solver(Map(*v, {"method", "rays_per_patch", "seed", "threads", "relative_residual", "max_iterations",
                           "direct_receiver_points", "direct_shadow_rays", "sample_size", "sample_fraction",
                           "sampling", "sample_seed", "indirect", "target_error", "error_samples",
                           "pilot_fraction"}),
                  job);
    if (auto v = top.get("report")) {
      const Map report(*v, {"surfaces"});
      if (auto s = report.get("surfaces"))
        for (const Value& item : s->list()) {
          job.report_surfaces.push_back(item.text());
          job.report_surface_locs.push_back(item.loc());
        }
    }
  } catch (const YAML::Exception& e) {
    throw ConfigError(located({path, e.mark.line + 1, e.mark.column + 1}, std::string("invalid YAML: ") + e.what()));
  }
  return job;
}

}  // namespace ilp
