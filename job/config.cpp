#include "job/config.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <utility>

#include "job/products.h"

namespace ilp {
namespace {

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
void reject_second_document(const std::string& text, const std::string& path) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DocumentCounter counter;
  if (!parser.HandleNextDocument(counter) || !parser.HandleNextDocument(counter) || counter.documents < 2) return;
  const YAML::Mark& mark = counter.second;
  throw ConfigError(located({path, mark.line >= 0 ? mark.line + 1 : 0, mark.column >= 0 ? mark.column + 1 : 0},
                            "a second YAML document (after '---'): a config file holds one job"));
}

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

// scene.regions: [{name, facing, height_m: [low, high], min_area_m2}, ...]
void read_regions(const Value& list, JobConfig& job) {
  std::set<std::string> names;
  for (const Value& item : list.list()) {
    const Map rule(item, {"name", "facing", "height_m", "min_area_m2"});
    RegionRule r;
    const Value name = rule.require("name");
    r.name = name.text();
    if (r.name.empty()) name.fail("must not be empty");
    if (!names.insert(r.name).second) name.fail("is used by another region");
    if (auto v = rule.get("facing")) {
      const std::string f = v->text();
      if (f == "up") r.facing = Facing::up;
      else if (f == "down") r.facing = Facing::down;
      else if (f == "vertical") r.facing = Facing::vertical;
      else if (f != "any") v->fail("must be up, down, vertical or any");
    }
    if (auto v = rule.get("height_m")) {
      if (!v->node().IsSequence() || v->node().size() != 2) v->fail("must be a list [low, high] in metres");
      r.height_m = {v->element(0).number(), v->element(1).number()};
      if (!(r.height_m->second >= r.height_m->first)) v->element(1).fail("must be >= height_m[0]");
    }
    if (auto v = rule.get("min_area_m2")) {
      r.min_area_m2 = v->number();
      if (r.min_area_m2 < 0.0) v->fail("must be >= 0");
    }
    r.loc = item.loc();
    job.surface_split.regions.push_back(r);
  }
  if (job.surface_split.regions.empty()) list.fail("must list at least one region");
}

Eigen::Vector2d pair_of(const Value& v, double (*check)(const Value&));

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
  if (auto v = scene.get("scale_to_m")) job.scene.scale_to_m = v->bounded(kMinScale, kMaxScale, " (metres per file unit)");
  if (auto v = scene.get("max_patch_edge_m")) {
    job.scene.max_patch_edge_m = v->bounded(kMinPatchEdge_m, kMaxLength_m, " m");
    job.max_patch_edge_loc = v->loc();
  }
  if (auto v = scene.get("surfaces_from")) {
    const std::string from = Value::lower(v->text());
    if (from == "group") job.mesh_read.surface_naming = SurfaceNaming::group;
    else if (from == "object") job.mesh_read.surface_naming = SurfaceNaming::object;
    else if (from == "material") job.mesh_read.surface_naming = SurfaceNaming::material;
    else if (from == "connected") job.surface_split.connected = true;  // groups, split into connected pieces
    else v->fail("must be group, object, material or connected");
  }
  if (auto v = scene.get("weld_tolerance_m")) job.surface_split.weld_tolerance_m = v->positive();
  if (auto v = scene.get("regions")) read_regions(*v, job);
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
  if (auto v = scene.get("add_floor"))
    for (const Value& item : v->list()) {
      const Map floor(item, {"name", "rectangle_m", "z_m", "reflectance"});
      FloorSetting f;
      f.loc = item.loc();
      const Value name = floor.require("name");
      f.name = name.text();
      if (f.name.empty()) name.fail("must not be empty");
      for (const FloorSetting& other : job.add_floors)
        if (other.name == f.name) name.fail("a floor of this name is already added");
      const Value rect = floor.require("rectangle_m");
      if (!rect.node().IsSequence() || rect.node().size() != 2) rect.fail("must be two corners [[x0, y0], [x1, y1]]");
      const Eigen::Vector2d a = pair_of(rect.element(0), [](const Value& x) { return x.number(); });
      const Eigen::Vector2d b = pair_of(rect.element(1), [](const Value& x) { return x.number(); });
      f.lo = a.cwiseMin(b);
      f.hi = a.cwiseMax(b);
      if (!((f.hi - f.lo).minCoeff() > 0.0)) rect.fail("the corners must differ in x and in y");
      if (auto z = floor.get("z_m")) f.z_m = z->number();
      f.rgb = floor.require("reflectance").reflectance();
      job.add_floors.push_back(f);
    }
  if (auto v = scene.get("exclude_surfaces"))
    for (const Value& item : v->list()) {
      job.exclude_surfaces.push_back(item.text());
      job.exclude_surface_locs.push_back(item.loc());
    }
  if (auto v = scene.get("two_sided")) {
    if (v->node().IsScalar()) {
      if (v->text() != "all") v->fail("must be all or a list of surface names");
      job.two_sided_all = true;
    } else {
      for (const Value& item : v->list()) {
        job.two_sided_surfaces.push_back(item.text());
        job.two_sided_locs.push_back(item.loc());
      }
    }
  }
  if (auto v = scene.get("emitting_surfaces")) {
    for (const Value& item : v->list()) {
      const Map emitter(item, {"surface", "exitance_lm_per_m2"});
      const Value surface = emitter.require("surface");
      const Value exitance = emitter.require("exitance_lm_per_m2");
      const double e = exitance.bounded(0.0, kMaxExitance_lm_per_m2, " lm/m²");
      job.emitting_surfaces.push_back({surface.text(), e, surface.loc()});
    }
  }
}

// The keys of luminaires that describe the search; each needs mounting_surface.
// (products is not one: placed luminaires may name them without a search.)
constexpr const char* kSearchKeys[] = {"model",          "flux_lm",             "efficacy_lm_per_w",
                                       "mount_offset_m", "candidate_spacing_m", "count",
                                       "layout",         "array",               "wall_distance_m",
                                       "ceiling_module_m"};

// A list of 2 numbers [x, y], each read and checked by `check`.
Eigen::Vector2d pair_of(const Value& v, double (*check)(const Value&)) {
  if (!v.node().IsSequence() || v.node().size() != 2) v.fail("must be a list of 2 numbers [x, y]");
  return {check(v.element(0)), check(v.element(1))};
}

// The square panel's flux: a fixed package (one number) or a range [min, max].
void read_panel_flux(const Map& luminaires, const Value& mounting, LuminaireSearch& search) {
  const auto flux = luminaires.get("flux_lm");
  if (!flux) mounting.fail("needs luminaires.flux_lm: [min, max] or one number (or luminaires.products)");
  search.flux_loc = flux->loc();
  if (flux->node().IsScalar()) {
    search.flux_min_lm = search.flux_max_lm = flux->bounded(1e-6, kMaxFlux_lm, " lm");
  } else {
    if (!flux->node().IsSequence() || flux->node().size() != 2) flux->fail("must be a list [min, max] or one number");
    search.flux_min_lm = flux->element(0).bounded(0.0, kMaxFlux_lm, " lm");
    search.flux_max_lm = flux->element(1).bounded(1e-6, kMaxFlux_lm, " lm");
    if (search.flux_max_lm < search.flux_min_lm) flux->element(1).fail("must be at least the minimum flux_lm[0]");
  }
  if (auto v = luminaires.get("efficacy_lm_per_w")) {
    search.efficacy_lm_per_w = v->positive();
    if (search.efficacy_lm_per_w > kMaxEfficacy_lm_per_w) v->fail("must be at most 1000 lm/W");
  }
}

void read_products(const Value& section, JobConfig& job) {
  const std::filesystem::path base = std::filesystem::path(job.path).parent_path();
  std::set<std::string> names;
  for (const Value& item : section.list()) {
    const Map m(item, {"name", "photometry", "model", "size_m", "flux_lm", "power_w", "dimming", "maintenance_factor",
                       "rotations_deg", "mount_offset_m"});
    ProductSetting p;
    p.loc = item.loc();
    p.name = m.require("name").text();
    if (p.name.empty()) m.require("name").fail("must not be empty");
    if (!names.insert(p.name).second) m.require("name").fail("product name used twice");
    const auto photometry = m.get("photometry"), model = m.get("model");
    if (photometry && model) model->fail("not with photometry (a product is one or the other)");
    if (photometry) {
      p.photometry_path = (base / photometry->text()).lexically_normal().string();
      p.photometry_loc = photometry->loc();
      if (auto v = m.get("size_m")) v->fail("only for model: square_lambertian (a photometric file gives its size)");
    } else {
      if (!model) item.fail("needs photometry: FILE (.ies or .ldt) or model: square_lambertian");
      if (model->text() != "square_lambertian") model->fail("must be square_lambertian");
      if (auto v = m.get("size_m")) p.size_m = v->number_in(0.01, 10.0, false, "[0.01, 10] m");
      if (!m.get("flux_lm") || !m.get("power_w")) item.fail("model: square_lambertian needs flux_lm and power_w");
    }
    if (auto v = m.get("flux_lm")) p.flux_lm = v->number_in(1e-3, 1e7, false, "[0.001, 1e7] lm");
    if (auto v = m.get("power_w")) {
      p.power_w = v->number_in(1e-3, 1e6, false, "[0.001, 1e6] W");
      p.power_loc = v->loc();
    } else {
      p.power_loc = p.photometry_loc;
    }
    if (auto v = m.get("dimming")) {
      if (!v->node().IsSequence() || v->node().size() != 2) v->fail("must be a list [min, max] of fractions of the rated output");
      p.dim_min = v->element(0).number_in(0.0, 1.0, false, "[0, 1]");
      p.dim_max = v->element(1).number_in(0.0, 1.0, false, "[0, 1]");
      if (!(p.dim_max > 0.0) || p.dim_max < p.dim_min) v->element(1).fail("must be > 0 and at least dimming[0]");
    }
    if (auto v = m.get("maintenance_factor")) p.maintenance_factor = v->number_in(0.1, 1.0, false, "[0.1, 1]");
    if (auto v = m.get("rotations_deg")) {
      for (const Value& r : v->list()) p.rotations_deg.push_back(r.number_in(-360.0, 360.0, false, "[-360, 360] degrees"));
      if (p.rotations_deg.empty()) v->fail("must list at least one rotation");
    }
    if (auto v = m.get("mount_offset_m")) {
      p.mount_offset_m = v->number_in(0.0, 10.0, true, "(0, 10) m");
      if (*p.mount_offset_m <= 0.0) v->fail("must be in (0, 10) m");
      p.mount_offset_loc = v->loc();
    }
    job.products.push_back(p);
  }
  if (job.products.empty()) section.fail("must list at least one product");
}

void read_search(const Map& luminaires, const Value& mounting, JobConfig& job) {
  LuminaireSearch& search = job.search.emplace();
  search.mounting_surface = mounting.text();
  if (search.mounting_surface.empty()) mounting.fail("must name a surface");
  search.mounting_loc = mounting.loc();
  search.layout_loc = mounting.loc();  // where the layout is decided when layout is not given
  if (auto v = luminaires.get("model")) {
    search.model = v->text();
    if (search.model != "square_lambertian") v->fail("must be square_lambertian");
  }
  if (!job.products.empty()) {
    for (const char* key : {"model", "flux_lm", "efficacy_lm_per_w"})
      if (auto v = luminaires.get(key)) v->fail("not with luminaires.products (each product gives its own)");
  } else {
    read_panel_flux(luminaires, mounting, search);
  }
  if (auto v = luminaires.get("wall_distance_m")) search.wall_distance_m = v->number_in(0.0, 100.0, false, "[0, 100]");
  if (auto v = luminaires.get("ceiling_module_m")) search.ceiling_module_m = v->number_in(0.05, 10.0, false, "[0.05, 10]");
  if (auto v = luminaires.get("mount_offset_m")) {
    search.mount_offset_m = v->number_in(0.0, 10.0, true, "(0, 10)");
    if (search.mount_offset_m <= 0.0) v->fail("must be in (0, 10)");
    search.offset_loc = v->loc();
  }
  if (auto v = luminaires.get("candidate_spacing_m")) {
    search.candidate_spacing_m = v->bounded(kMinSpacing_m, kMaxLength_m, " m");
    search.spacing_loc = v->loc();
  }
  const auto layout = luminaires.get("layout"), array = luminaires.get("array"), count = luminaires.get("count");
  if (layout) {
    const std::string family = layout->text();
    if (family == "free") search.layout = LayoutFamily::free;
    else if (family == "array") search.layout = LayoutFamily::array;
    else layout->fail("must be free or array");
    search.layout_loc = layout->loc();
  }
  if (search.layout == LayoutFamily::array) {
    if (!array) layout->fail("needs luminaires.array: {rows, columns}");
    if (count) count->fail("not with layout: array (the array fixes the count)");
    const Map block(*array, {"rows", "columns", "spacing_m", "offset_m"});
    search.array_rows = static_cast<int>(block.require("rows").integer(1, 32));
    search.array_columns = static_cast<int>(block.require("columns").integer(1, 32));
    if (auto v = block.get("spacing_m"))
      search.array_spacing_m = pair_of(*v, [](const Value& e) {
        const double x = e.positive();
        if (x > kMaxLength_m) e.fail("must be at most 1e+05 m");
        return x;
      });
    if (auto v = block.get("offset_m"))
      search.array_offset_m = pair_of(*v, [](const Value& e) {
        return e.bounded(0.0, kMaxLength_m, " m");
      });
  } else {
    if (array) array->fail("needs luminaires.layout: array");
    if (count) {
      if (count->node().IsScalar()) {
        search.count_min = search.count_max = static_cast<int>(count->integer(1, 64));
      } else if (count->node().IsSequence() && count->node().size() == 2) {
        search.count_min = static_cast<int>(count->element(0).integer(1, 64));
        search.count_max = static_cast<int>(count->element(1).integer(1, 64));
        if (search.count_max < search.count_min) count->element(1).fail("must be >= the minimum count[0]");
      } else {
        count->fail("must be a whole number N or a list [min, max]");
      }
      search.count_loc = count->loc();
    }
  }
}

// The products placed luminaires name, each resolved once (its file read once).
using ResolvedProducts = std::map<std::string, ProductVariant>;

const ProductVariant& placed_product(const Value& name, const JobConfig& job, ResolvedProducts& resolved) {
  const std::string wanted = name.text();
  if (auto it = resolved.find(wanted); it != resolved.end()) return it->second;
  std::string known;
  for (const ProductSetting& p : job.products) {
    if (p.name == wanted) return resolved.emplace(wanted, product_base(p)).first->second;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  name.fail(known.empty() ? "unknown product: luminaires.products lists none"
                          : "unknown product (luminaires.products has " + known + ")");
}

std::string dimming_range(const ProductVariant& product) {
  return "[" + Value::shown(product.dim_min) + ", " + Value::shown(product.dim_max) + "]";
}

// flux_lm given for a product: within its dimming range x its rated flux.
double product_flux_lm(const Value& flux, const ProductVariant& product) {
  const double lm = flux.bounded(0.0, kMaxFlux_lm, " lm");
  // A relative slack, so that a rated flux written out in full is taken as it.
  constexpr double kSlack = 1e-9;
  const double rated = product.rated_flux_lm, low = product.dim_min * rated, high = product.dim_max * rated;
  if (lm >= low * (1.0 - kSlack) && lm <= high * (1.0 + kSlack)) return lm;
  if (low == high)
    flux.fail("must be product '" + product.product + "''s fixed output, " + Value::shown(low) +
              " lm (no dimming range; leave flux_lm out for it)");
  flux.fail("must be within product '" + product.product + "''s output, " + Value::shown(low) + " to " +
            Value::shown(high) + " lm (dimming " + dimming_range(product) + " x rated " + Value::shown(rated) + " lm)");
}

// A product's output in lm: flux_lm, or output (a fraction of the rated flux within
// the dimming range, default 1 = full output). `name` is the entry's product key.
double product_output_lm(const Map& lum, const Value& name, const ProductVariant& product) {
  const auto flux = lum.get("flux_lm"), output = lum.get("output");
  if (flux && output) output->fail("not with flux_lm (give the output one way)");
  if (flux) return product_flux_lm(*flux, product);
  const double fraction = output ? output->number() : 1.0;
  if (fraction >= product.dim_min && fraction <= product.dim_max) return fraction * product.rated_flux_lm;
  if (!output)
    name.fail("full output (1, the default) is outside the product's dimming range " + dimming_range(product) +
              ": give output");
  output->fail("must be within product '" + product.product + "''s dimming range " + dimming_range(product) +
               " (fractions of its rated output)");
}

LuminaireSetting read_placed(const Value& item, const JobConfig& job, ResolvedProducts& resolved) {
  const Map lum(item, {"name", "position_m", "flux_lm", "product", "rotation_deg", "output"});
  LuminaireSetting setting;
  if (auto name = lum.get("name")) {
    setting.name = name->text();
  } else {
    setting.name = "L";  // (not "L" + ...: GCC 12 warns falsely on operator+(const char*, string&&))
    setting.name += std::to_string(job.luminaires.size() + 1);
  }
  setting.position_m = lum.require("position_m").vector3();
  if (auto v = lum.get("rotation_deg")) setting.rotation_deg = v->number_in(-360.0, 360.0, false, "[-360, 360] degrees");
  setting.loc = item.loc();
  if (auto product = lum.get("product")) {
    const ProductVariant& p = placed_product(*product, job, resolved);
    setting.product = p.product;
    setting.type = p.type;
    setting.flux_lm = product_output_lm(lum, *product, p);
    return setting;
  }
  if (auto v = lum.get("output")) v->fail("needs product: (a fraction of a product's rated flux; the plain panel gives flux_lm)");
  setting.type = LuminaireType::square_lambertian(job.luminaire_size_m);
  setting.flux_lm = lum.require("flux_lm").bounded(0.0, kMaxFlux_lm, " lm");
  return setting;
}

void read_luminaires(const Map& luminaires, JobConfig& job) {
  if (auto v = luminaires.get("size_m")) job.luminaire_size_m = v->bounded(kMinLuminaireSize_m, kMaxLuminaireSize_m, " m");
  if (auto v = luminaires.get("products")) read_products(*v, job);
  if (auto v = luminaires.get("placed")) {
    std::set<std::string> names;
    ResolvedProducts resolved;
    for (const Value& item : v->list()) {
      LuminaireSetting setting = read_placed(item, job, resolved);
      if (!names.insert(setting.name).second) item.fail("luminaire name '" + setting.name + "' is used twice");
      job.luminaires.push_back(std::move(setting));
    }
  }
  if (auto mounting = luminaires.get("mounting_surface")) {
    read_search(luminaires, *mounting, job);
  } else {
    // The first search key in the file, so the error points where the reader looks.
    for (const auto& item : luminaires.value().node())
      for (const char* key : kSearchKeys)
        if (item.first.Scalar() == key)
          if (auto v = luminaires.get(key)) v->fail("needs luminaires.mounting_surface");
  }
}

// ---- goals

std::string format_number(double v) {
  std::ostringstream os;
  os << std::setprecision(12) << v;
  return os.str();
}

// The rule `metric` = v breaks against the other targets of goal `name` in `others`
// ("" when none): min_lux and average_lux may not exceed max_lux. `skip` is left out
// (the setting being replaced).
std::string goal_bound_rule(const std::vector<GoalSetting>& others, const std::string& name, GoalMetric metric,
                            double v, const GoalSetting* skip = nullptr) {
  for (const GoalSetting& g : others) {
    if (&g == skip || g.name != name) continue;
    const bool lower = metric == GoalMetric::minimum || metric == GoalMetric::average;
    const bool other_lower = g.metric == GoalMetric::minimum || g.metric == GoalMetric::average;
    if (lower && g.metric == GoalMetric::maximum && v > g.target)
      return "must be <= max_lux (" + format_number(g.target) + ") of goal '" + name + "'";
    if (metric == GoalMetric::maximum && other_lower && v < g.target)
      return std::string("must be >= ") + std::string(goal_key(g.metric)) + " (" + format_number(g.target) + ") of goal '" + name +
             "'";
  }
  return "";
}

constexpr GoalPreset kPresets[] = {
    {"office_writing", "Writing, typing, reading, data processing", 500.0, 0.60},
    {"office_filing", "Filing, copying", 300.0, 0.40},
    {"classroom", "Classrooms", 300.0, 0.60},
    {"board", "Black/green board", 500.0, 0.70},
    {"corridor", "Corridors, circulation", 100.0, 0.40},
    {"stairs_education", "Stairs (education)", 150.0, 0.40},
    {"entrance_hall_education", "Entrance halls (education)", 200.0, 0.40},
    {"toilets", "Toilets, cloakrooms", 200.0, 0.40},
};

std::vector<Eigen::Vector2d> point_list(const Value& v) {
  std::vector<Eigen::Vector2d> out;
  for (const Value& item : v.list()) out.push_back(pair_of(item, [](const Value& x) { return x.number(); }));
  return out;
}

void read_grids(const Value& section, JobConfig& job) {
  const std::vector<Value> entries = section.list();
  if (entries.empty()) section.fail("must list at least one grid");
  for (const Value& item : entries) {
    const Map entry(item, {"name", "over_surface", "rectangle_m", "polygon_m", "vertical", "height_m", "border_m",
                           "spacing_m", "max_points"});
    CalcGridSetting g;
    g.loc = item.loc();
    const Value name = entry.require("name");
    g.name = name.text();
    if (g.name.empty()) name.fail("must not be empty");
    if (find_grid(job, g.name) >= 0) name.fail("a grid of this name is already defined");
    const char* shapes[] = {"over_surface", "rectangle_m", "polygon_m", "vertical"};
    int given = 0;
    for (const char* k : shapes) given += entry.get(k) ? 1 : 0;
    if (given != 1) item.fail("needs exactly one of over_surface, rectangle_m, polygon_m, vertical");
    g.shape_loc = g.loc;
    if (auto v = entry.get("over_surface")) {
      g.over_surface = v->text();
      g.shape_loc = v->loc();
    }
    if (auto v = entry.get("rectangle_m")) {
      g.shape_loc = v->loc();
      const std::vector<Eigen::Vector2d> corners = point_list(*v);
      if (corners.size() != 2) v->fail("must be two corners [[x0, y0], [x1, y1]]");
      const Eigen::Vector2d lo = corners[0].cwiseMin(corners[1]), hi = corners[0].cwiseMax(corners[1]);
      if (!((hi - lo).minCoeff() > 0.0)) v->fail("the corners must differ in x and in y");
      g.polygon_m = {lo, Eigen::Vector2d(hi.x(), lo.y()), hi, Eigen::Vector2d(lo.x(), hi.y())};
    }
    if (auto v = entry.get("polygon_m")) {
      g.shape_loc = v->loc();
      g.polygon_m = point_list(*v);
      if (g.polygon_m.size() < 3) v->fail("must list at least 3 points [[x, y], ...]");
      if (!polygon_is_simple(g.polygon_m)) v->fail("the polygon is not simple (its edges cross or overlap)");
    }
    if (auto v = entry.get("vertical")) {
      const Map vertical(*v, {"from_m", "to_m", "bottom_m", "top_m", "facing"});
      g.kind = GridKind::vertical;
      g.shape_loc = v->loc();
      g.border_m = 0.0;
      g.from_m = pair_of(vertical.require("from_m"), [](const Value& x) { return x.number(); });
      g.to_m = pair_of(vertical.require("to_m"), [](const Value& x) { return x.number(); });
      if ((g.from_m - g.to_m).norm() == 0.0) v->fail("from_m and to_m must differ");
      g.bottom_m = vertical.require("bottom_m").number();
      const Value top = vertical.require("top_m");
      g.top_m = top.number();
      if (!(g.top_m > g.bottom_m)) top.fail("must be above bottom_m");
      g.height_loc = v->loc();
      if (auto f = vertical.get("facing")) {
        const std::string side = f->text();
        if (side == "left") g.facing_left = true;
        else if (side == "right") g.facing_left = false;
        else f->fail("must be left or right (of the direction from from_m to to_m)");
      }
    }
    if (auto v = entry.get("height_m")) {
      if (g.kind == GridKind::vertical) v->fail("a vertical grid takes vertical.bottom_m and top_m instead");
      g.height_m = v->number();
      g.height_loc = v->loc();
    } else if (g.kind == GridKind::horizontal) {
      g.height_loc = g.loc;
    }
    g.border_loc = g.loc;
    if (auto v = entry.get("border_m")) {
      g.border_m = v->number();
      if (!(g.border_m >= 0.0)) v->fail("must be >= 0");
      g.border_loc = v->loc();
    }
    if (auto v = entry.get("spacing_m")) {
      g.spacing_m = v->positive();
      g.spacing_loc = v->loc();
    }
    if (auto v = entry.get("max_points")) {
      g.max_points = static_cast<int>(v->integer(1, 10'000'000));
      g.max_points_loc = v->loc();
    }
    job.grids.push_back(g);
  }
}

// A goals entry's keys: where it is measured, then one per metric (optimizer/goal_spec.h).
std::vector<std::string> goal_entry_keys() {
  std::vector<std::string> keys{"name", "surface", "grid", "facing", "preset"};
  for (const MetricRule& rule : metric_rules()) keys.emplace_back(rule.key);
  return keys;
}

void read_goals(const Value& section, JobConfig& job) {
  const std::vector<Value> entries = section.list();
  if (entries.empty()) section.fail("must list at least one goal");
  for (const Value& item : entries) {
    const Map entry(item, goal_entry_keys());
    GoalSetting base;
    if (auto v = entry.get("facing")) {
      const std::string facing = v->text();
      if (facing == "any") base.facing = GoalFacing::any;
      else if (facing == "up") base.facing = GoalFacing::up;
      else if (facing == "down") base.facing = GoalFacing::down;
      else v->fail("must be any, up or down");
    }
    const auto grid = entry.get("grid");
    if (grid && entry.get("surface")) grid->fail("a goal is on a grid or on surfaces, not both");
    if (grid) {
      base.grid = grid->text();
      base.surfaces_loc = grid->loc();
      if (find_grid(job, base.grid) < 0)
        grid->fail(job.grids.empty() ? "no grids are defined (add a grids section before goals)"
                                     : "no grid of this name in grids");
      if (auto f = entry.get("facing")) f->fail("facing applies to surfaces; a grid's points face as the grid does");
    } else {
      const Value surface = entry.require("surface");
      if (surface.node().IsSequence()) {
        for (const Value& s : surface.list()) base.surfaces.push_back(s.text());
        if (base.surfaces.empty()) surface.fail("must be a surface name or a non-empty list of names");
      } else {
        base.surfaces.push_back(surface.text());
      }
      base.surfaces_loc = surface.loc();
    }
    if (auto v = entry.get("name")) {
      base.name = v->text();
      if (base.name.empty()) v->fail("must not be empty");
    } else if (grid) {
      base.name = base.grid;
    } else {
      for (const std::string& s : base.surfaces) base.name += (base.name.empty() ? "" : "+") + s;
    }
    for (const GoalSetting& g : job.goals)
      if (g.name == base.name && g.grid != base.grid)
        item.fail("goal '" + base.name + "' is already defined on " +
                  (g.grid.empty() ? std::string("surfaces") : "grid '" + g.grid + "'"));
    const GoalPreset* preset = nullptr;
    std::optional<Value> preset_value = entry.get("preset");
    if (preset_value) {
      const std::string key = preset_value->text();
      std::string known;
      for (const GoalPreset& p : kPresets) {
        if (key == p.key) preset = &p;
        known += (known.empty() ? "" : ", ") + std::string(p.key);
      }
      if (!preset) preset_value->fail("unknown preset (EN 12464-1 rows: " + known + ")");
    }
    // This entry's metrics, each checked alone and against the same goal's earlier
    // entries; a bound conflict inside the entry is reported at max_lux.
    std::vector<std::pair<GoalSetting, Value>> metrics;
    for (const MetricRule& rule_of_metric : metric_rules()) {
      const GoalMetric metric = rule_of_metric.metric;
      const std::string key(rule_of_metric.key);
      auto v = entry.get(key);
      const bool from_preset = !v && preset && (metric == GoalMetric::average || metric == GoalMetric::uniformity);
      if (from_preset) v = preset_value;  // an explicit key overrides the preset's value
      if (!v) continue;
      GoalSetting goal = base;
      goal.metric = metric;
      goal.target = from_preset ? (metric == GoalMetric::average ? preset->average_lux : preset->uniformity) : v->number();
      if (const std::string rule = target_rule(metric, goal.target); !rule.empty()) v->fail(rule);
      goal.loc = v->loc();
      for (const GoalSetting& g : job.goals)
        if (g.name == goal.name && g.metric == metric) v->fail("goal '" + goal.name + "' already has " + key);
      metrics.emplace_back(goal, *v);
    }
    if (metrics.empty()) item.fail("needs at least one of average_lux, min_lux, max_lux, uniformity (or a preset)");
    std::vector<GoalSetting> here;
    for (const auto& [goal, v] : metrics) here.push_back(goal);
    for (const auto& [goal, v] : metrics) {
      std::string rule;
      if (goal.metric == GoalMetric::maximum) rule = goal_bound_rule(here, goal.name, goal.metric, goal.target);
      if (rule.empty()) rule = goal_bound_rule(job.goals, goal.name, goal.metric, goal.target);
      if (!rule.empty()) v.fail(rule);
    }
    job.goals.insert(job.goals.end(), here.begin(), here.end());
  }
}

// Every goal parameter of the job, "goals.desks.average_lux, goals.floor.min_lux".
std::string goal_parameters(const JobConfig& job) {
  std::string out;
  for (const GoalSetting& g : job.goals)
    out += (out.empty() ? "goals." : ", goals.") + g.name + "." + std::string(goal_key(g.metric));
  return out;
}

// set_goal_parameter with the error reporting left to the caller: bad_key(rule) or
// bad_value(rule) is called (and must throw) when the key or the value is wrong.
template <class BadKey, class BadValue>
void apply_goal_parameter(JobConfig& job, const std::string& key, double value, BadKey bad_key, BadValue bad_value) {
  GoalSetting* found = nullptr;
  const std::size_t dot = key.rfind('.');
  if (key.rfind("goals.", 0) == 0 && dot != std::string::npos && dot > 6) {
    const std::string name = key.substr(6, dot - 6), metric = key.substr(dot + 1);
    for (GoalSetting& g : job.goals)
      if (g.name == name && metric == std::string(goal_key(g.metric))) found = &g;
  }
  if (!found) {
    bad_key("no goal parameter " + key + "; " +
            (job.goals.empty() ? std::string("the job has no goals") : "the job has " + goal_parameters(job)));
    return;
  }
  std::string rule = std::isfinite(value) ? target_rule(found->metric, value) : "must be a finite number";
  if (rule.empty()) rule = goal_bound_rule(job.goals, found->name, found->metric, value, found);
  if (!rule.empty()) {
    bad_value(rule);
    return;
  }
  found->target = value;
}

void read_constraints(const Map& constraints, JobConfig& job) {
  if (auto v = constraints.get("max_luminaires")) {
    const int cap = static_cast<int>(v->integer(1, 100'000'000));
    if (job.search && job.search->layout == LayoutFamily::free && cap < job.search->count_min)
      v->fail("is below the least luminaires.count (" + std::to_string(job.search->count_min) + ")");
    if (job.search && job.search->layout == LayoutFamily::array &&
        cap < job.search->array_rows * job.search->array_columns)
      v->fail("is below the array's rows x columns (" +
              std::to_string(job.search->array_rows * job.search->array_columns) + ")");
    job.constraints.max_luminaires = cap;
    job.constraints.max_luminaires_loc = v->loc();
  }
  if (auto v = constraints.get("min_distance_m")) {
    job.constraints.min_distance_m = v->bounded(0.0, kMaxLength_m, " m");
  }
}

void read_objective(const Value& v, JobConfig& job) {
  const ObjectiveRule* rule = objective_rule_for_key(v.text());
  if (!rule) v.fail("must be min_power or closest_to_target");
  job.objective = rule->objective;
  if (rule->averages_are_targets &&
      std::none_of(job.goals.begin(), job.goals.end(),
                   [](const GoalSetting& g) { return g.metric == GoalMetric::average; }))
    v.fail("needs at least one goal with average_lux");
}

// The text of `v`, which must be one of `names` (else the error lists them).
std::string one_of(const Value& v, std::initializer_list<const char*> names) {
  const std::string text = v.text();
  std::string list;
  for (const char* n : names) {
    if (text == n) return text;
    list += std::string(list.empty() ? "" : ", ") + n;
  }
  v.fail("must be one of " + list);
}

void read_optimizer(const Map& optimizer, JobConfig& job) {
  SearchOptions& o = job.optimizer;
  if (auto v = optimizer.get("global_algorithm"))
    o.global_algorithm = one_of(*v, {"GN_CRS2_LM", "GN_ISRES", "GN_ESCH", "GN_DIRECT_L", "GN_DIRECT_L_RAND", "none"});
  if (auto v = optimizer.get("local_algorithm")) {
    o.local_algorithm = one_of(*v, {"LN_SBPLX", "LN_COBYLA", "LN_BOBYQA", "LN_NELDERMEAD", "LN_PRAXIS", "none"});
    if (o.local_algorithm == "none" && o.global_algorithm == "none")
      v->fail("global_algorithm and local_algorithm cannot both be none");
  }
  if (auto v = optimizer.get("max_evaluations")) o.max_evaluations = static_cast<int>(v->integer(1, 100'000'000));
  if (auto v = optimizer.get("local_max_evaluations"))
    o.local_max_evaluations = static_cast<int>(v->integer(1, 100'000'000));
  if (auto v = optimizer.get("max_seconds")) {
    o.max_seconds = v->positive();
    if (o.max_seconds > kMaxSeconds) v->fail("must be at most 1e+07 s");
  }
  if (auto v = optimizer.get("seed")) o.seed = static_cast<std::uint64_t>(v->integer(0, (1ll << 53)));
}

void read_verification(const Map& verification, JobConfig& job) {
  VerificationSettings& s = job.verification;
  if (auto v = verification.get("method")) {
    const std::string m = v->text();
    if (m == "auto") s.method = VerificationMethod::automatic;
    else if (m == "exact") s.method = VerificationMethod::exact;
    else if (m == "sample") s.method = VerificationMethod::sample;
    else if (m == "none") s.method = VerificationMethod::none;
    else v->fail("must be auto, exact, sample or none");
  }
  if (auto v = verification.get("rays_per_patch")) s.rays_per_patch = static_cast<int>(v->integer(1, 1 << 24));
  if (auto v = verification.get("rounds")) s.rounds = static_cast<int>(v->integer(1, 10));
  if (auto v = verification.get("max_exact_patches"))
    s.max_exact_patches = static_cast<std::size_t>(v->integer(1, 100'000'000));
  if (auto v = verification.get("sample_fraction")) {
    s.sample_fraction = v->number_in(0.0, 1.0, false, "(0, 1]");
    if (s.sample_fraction <= 0.0) v->fail("must be in (0, 1]");
  }
}

void read_output(const Map& output, JobConfig& job) {
  OutputSettings& o = job.output;
  if (auto v = output.get("directory")) {
    o.directory = v->text();
    if (o.directory.empty()) v->fail("must not be empty");
  }
  if (auto v = output.get("formats")) {
    // One row per format: its name in the file and its flag.
    struct Format {
      const char* name;
      bool OutputSettings::*flag;
      bool needs_grids;
    };
    static constexpr Format kFormats[] = {
        {"json", &OutputSettings::json, false},          {"csv", &OutputSettings::csv, false},
        {"svg", &OutputSettings::svg, false},            {"ply", &OutputSettings::ply, false},
        {"grid_csv", &OutputSettings::grid_csv, true},   {"isolux_svg", &OutputSettings::isolux_svg, true},
        {"isolux_png", &OutputSettings::isolux_png, true}};
    std::string names;
    for (const Format& f : kFormats) names += (names.empty() ? "" : ", ") + std::string(f.name);
    const std::vector<Value> formats = v->list();
    if (formats.empty()) v->fail("must list at least one of " + names);
    for (const Format& f : kFormats) o.*f.flag = false;
    for (const Value& item : formats) {
      const std::string name = item.text();
      const Format* f = std::find_if(std::begin(kFormats), std::end(kFormats),
                                     [&](const Format& x) { return name == x.name; });
      if (f == std::end(kFormats)) item.fail("must be one of " + names);
      if (f->needs_grids && job.grids.empty()) item.fail("needs calculation grids (the job has no grids section)");
      if (o.*f->flag) item.fail("is listed twice");
      o.*f->flag = true;
    }
  }
}

// `at`: where the sweep key itself is (the section's value starts a line later).
void read_sweep(const Value& section, const FileLoc& at, JobConfig& job) {
  const Map sweep(section, {"key", "values"});
  if (job.goals.empty()) throw ConfigError(located(at, "sweep: needs goals (it varies one goal parameter)"));
  const Value key = sweep.require("key");
  const Value values = sweep.require("values");
  SweepSetting setting;
  setting.key = key.text();
  setting.loc = key.loc();
  const std::vector<Value> list = values.list();
  if (list.empty()) values.fail("must list at least one number");
  JobConfig trial = job;  // each value is tried as `ilp sweep` will set it
  for (const Value& item : list) {
    const double v = item.number();
    apply_goal_parameter(trial, setting.key, v, [&](const std::string& rule) { key.fail(rule); },
                         [&](const std::string& rule) { item.fail(rule); });
    setting.values.push_back(v);
  }
  job.sweep = setting;
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
  if (auto v = solver.get("max_sample_size")) {
    sample.max_size_for_target = static_cast<int>(v->integer(1, 100'000'000));
    sample.max_size_loc = v->loc();
  }
  if (auto v = solver.get("error_samples")) sample.error_samples = static_cast<int>(v->integer(2, 64));
  if (auto v = solver.get("pilot_fraction")) {
    sample.pilot_fraction = v->number_in(0.0, 1.0, false, "(0, 1]");
    if (sample.pilot_fraction <= 0.0) v->fail("must be in (0, 1]");
  }
}

}  // namespace

std::span<const GoalPreset> goal_presets() { return kPresets; }

double initial_target(const JobConfig& job, const GoalSetting& goal) {
  return goal.metric == GoalMetric::uniformity ? goal.target : goal.target / job.maintenance_factor;
}

int find_grid(const JobConfig& job, const std::string& name) {
  for (std::size_t g = 0; g < job.grids.size(); ++g)
    if (job.grids[g].name == name) return static_cast<int>(g);
  return -1;
}

void set_goal_parameter(JobConfig& job, const std::string& key, double value) {
  apply_goal_parameter(
      job, key, value, [&](const std::string& rule) -> void { throw ConfigError("--set " + key + ": " + rule); },
      [&](const std::string& rule) -> void {
        throw ConfigError("--set " + key + " = " + format_number(value) + ": " + rule);
      });
}

SampleSizeRule SampleSettings::rule() const {
  return {size, fraction, max_size_for_target, target_error, error_samples, pilot_fraction};
}

int SampleSettings::size_for(std::size_t population) const { return rule().size_for(population); }

JobConfig load_job_config(const std::string& path) {
  JobConfig job;
  job.path = path;
  {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw ConfigError(path + ": is a folder, not a config file");
    std::ifstream probe(path);
    if (!probe) throw ConfigError(path + ": cannot open the config file");
  }
  YAML::Node root;
  try {
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // yaml-cpp stops reading at a NUL byte, and YAML::LoadAll then loops for ever (found by config_fuzz).
    if (const auto nul = text.find('\0'); nul != std::string::npos)
      throw ConfigError(located({path, 1 + static_cast<int>(std::count(text.begin(), text.begin() + nul, '\n'))},
                                "a NUL byte: the config must be a text file"));
    reject_second_document(text, path);
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(located({path, e.mark.line + 1, e.mark.column + 1}, "malformed YAML: " + e.msg));
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ": cannot read YAML: " + e.what());
  }
  if (!root.IsMap())
    throw ConfigError(path +
                      ": the config must be a YAML map of sections (scene, luminaires, goals, constraints, objective, "
                      "solver, optimizer, verification, output, sweep, report)");
  try {
    const Map top(Value(root, "", job.path), {"scene", "luminaires", "grids", "maintenance_factor", "goals",
                                              "constraints", "objective", "solver", "optimizer", "verification",
                                              "output", "sweep", "report"});
    read_scene(Map(top.require("scene"), {"mesh", "up_axis", "scale_to_m", "max_patch_edge_m", "surfaces_from",
                                          "reflectance", "default_reflectance", "emitting_surfaces",
                                          "exclude_surfaces", "two_sided", "weld_tolerance_m", "regions", "add_floor"}),
               job);
    if (auto v = top.get("luminaires"))
      read_luminaires(Map(*v, {"size_m", "placed", "model", "flux_lm", "efficacy_lm_per_w", "mounting_surface",
                               "mount_offset_m", "candidate_spacing_m", "count", "layout", "array", "products",
                               "wall_distance_m", "ceiling_module_m"}),
                      job);
    if (auto v = top.get("grids")) read_grids(*v, job);
    if (auto v = top.get("maintenance_factor")) {
      job.maintenance_factor = v->number();
      if (!(job.maintenance_factor > 0.0 && job.maintenance_factor <= 1.0)) v->fail("must be in (0, 1]");
      job.maintenance_loc = v->loc();
    }
    if (auto v = top.get("goals")) read_goals(*v, job);
    if (auto v = top.get("constraints")) read_constraints(Map(*v, {"max_luminaires", "min_distance_m"}), job);
    if (auto v = top.get("objective")) read_objective(*v, job);
    if (auto v = top.get("solver"))
      read_solver(Map(*v, {"method", "rays_per_patch", "seed", "threads", "relative_residual", "max_iterations",
                           "direct_receiver_points", "direct_shadow_rays", "sample_size", "sample_fraction",
                           "sampling", "sample_seed", "indirect", "target_error", "error_samples",
                           "pilot_fraction", "max_sample_size"}),
                  job);
    if (auto v = top.get("optimizer"))
      read_optimizer(Map(*v, {"global_algorithm", "local_algorithm", "max_evaluations", "local_max_evaluations",
                              "max_seconds", "seed"}),
                     job);
    if (auto v = top.get("verification"))
      read_verification(Map(*v, {"method", "rays_per_patch", "rounds", "max_exact_patches", "sample_fraction"}), job);
    if (auto v = top.get("output")) read_output(Map(*v, {"directory", "formats"}), job);
    if (auto v = top.get("sweep")) read_sweep(*v, top.key_loc("sweep"), job);
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
