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
#include <tuple>
#include <utility>

#include "core/energy/leni.h"
#include "job/config_yaml.h"
#include "job/goal_rules.h"
#include "job/products.h"

namespace ilp {
namespace {

using namespace config_yaml;

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

// ---- scene

void read_scene(const Map& scene, JobConfig& job) {
  const Value mesh = scene.require("mesh");
  const std::filesystem::path base = std::filesystem::path(job.path).parent_path();
  job.mesh_path = (base / mesh.path()).lexically_normal().string();
  job.mesh_loc = mesh.loc();
  if (auto v = scene.get("up_axis")) {
    const std::string axis = Value::lower(v->text());
    if (axis == "y") job.scene.up_axis = UpAxis::y;
    else if (axis == "z") job.scene.up_axis = UpAxis::z;
    else v->fail("must be y or z");
    job.up_axis_loc = v->loc();
  }
  if (auto v = scene.get("scale_to_m")) {
    job.scene.scale_to_m = v->bounded(kMinScale, kMaxScale, " (metres per file unit)");
    job.scale_to_m_loc = v->loc();
  }
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

using goal_rules::format_number;

// EN 12464-1:2021 rows. Sources (docs/config.md, "Presets"): ../shared/LIGHTING.md (the
// offices' writing row with Ez, walls and ceiling; Em, modified Em, UGR_L, U0, Ra of the
// education and circulation rows it lists), the office table of
// performanceinlighting.com/ww/us/en-12464-1; the other rows as EN 12464-1 tabulates them
// (2011 numbering), not checked against the printed 2021 standard. Walls 50 lx and
// ceiling 30 lx (U0 >= 0.10) are the general requirement where a row gives none.
//  key, row, building type, Em, Em modified, U0, UGR_L, Ra, Ez,m, Em wall, Em ceiling, a task area with an
//  immediate surrounding area (rows of whole rooms and circulation areas have none)
constexpr GoalPreset kPresets[] = {
    {"office_filing", "Filing, copying, etc.", "offices", 300, 500, 0.40, 19, 80, 100, 100, 75, true},
    {"office_writing", "Writing, typing, reading, data processing", "offices", 500, 1000, 0.60, 19, 80, 150, 150, 100, true},
    {"office_technical_drawing", "Technical drawing", "offices", 750, 1500, 0.70, 16, 80, 150, 150, 100, true},
    {"office_cad", "CAD work stations", "offices", 500, 1000, 0.60, 19, 80, 150, 150, 100, true},
    {"office_conference", "Conference and meeting rooms", "offices", 500, 1000, 0.60, 19, 80, 150, 150, 100, true},
    {"office_reception", "Reception desk", "offices", 300, 500, 0.60, 22, 80, 100, 100, 75, true},
    {"office_archives", "Archives", "offices", 200, 300, 0.40, 25, 80, 75, 75, 50, false},
    {"classroom", "Classrooms, tutorial rooms", "education", 300, 500, 0.60, 19, 80, 0, 50, 30, true},
    {"classroom_adult", "Classrooms for evening classes and adult education", "education", 500, 750, 0.60, 19, 80, 0, 50, 30, true},
    {"lecture_hall", "Lecture hall", "education", 500, 750, 0.60, 19, 80, 0, 50, 30, true},
    {"board", "Black, green and white boards", "education", 500, 0, 0.70, 19, 80, 0, 50, 30, true},
    {"stairs_education", "Stairs (educational buildings)", "education", 150, 200, 0.40, 25, 80, 0, 50, 30, false},
    {"entrance_hall_education", "Entrance halls (educational buildings)", "education", 200, 300, 0.40, 22, 80, 0, 50, 30, false},
    {"toilets", "Toilets, cloakrooms", "education", 200, 0, 0.40, 25, 80, 0, 50, 30, false},
    {"health_waiting_room", "Waiting rooms", "health care", 200, 0, 0.40, 22, 80, 0, 50, 30, false},
    {"health_ward", "Wards: general lighting", "health care", 100, 0, 0.40, 19, 80, 0, 50, 30, false},
    {"health_examination", "Examination rooms: general lighting", "health care", 500, 0, 0.60, 19, 90, 0, 50, 30, false},
    {"health_treatment", "Examination and treatment", "health care", 1000, 0, 0.70, 19, 90, 0, 50, 30, true},
    {"retail_sales", "Sales area", "retail", 300, 0, 0.40, 22, 80, 0, 50, 30, false},
    {"retail_till", "Till area", "retail", 500, 0, 0.60, 19, 80, 0, 50, 30, true},
    {"industry_assembly_rough", "Assembly work: rough", "industry", 200, 0, 0.60, 25, 80, 0, 50, 30, true},
    {"industry_assembly_medium", "Assembly work: medium", "industry", 300, 0, 0.60, 25, 80, 0, 50, 30, true},
    {"industry_assembly_fine", "Assembly work: fine", "industry", 500, 0, 0.60, 22, 80, 0, 50, 30, true},
    {"industry_assembly_precision", "Assembly work: precision", "industry", 750, 0, 0.70, 19, 80, 0, 50, 30, true},
    {"industry_storage", "Store and stockrooms", "industry", 100, 0, 0.40, 25, 60, 0, 50, 30, false},
    {"corridor", "Corridors and circulation areas", "circulation", 100, 150, 0.40, 28, 40, 0, 50, 30, false},
    {"stairs", "Stairs, escalators, travolators", "circulation", 100, 150, 0.40, 25, 40, 0, 50, 30, false},
    {"worship_body", "Body of place of worship", "places of worship", 100, 0, 0.40, 25, 80, 0, 50, 30, false},
    {"worship_altar", "Chair, altar, pulpit", "places of worship", 300, 0, 0.60, 22, 80, 0, 50, 30, true},
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
    if (g.name.size() > kMaxGridNameChars)
      name.fail("more than " + std::to_string(kMaxGridNameChars) + " characters: the grid's file names (isolux_NAME.svg) would not fit");
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

// A goals entry's keys: where it is measured, the preset and its companions, the eyes,
// then one per metric (optimizer/goal_spec.h).
std::vector<std::string> goal_entry_keys() {
  std::vector<std::string> keys{"name", "surface", "grid", "facing", "preset", "em", "walls", "ceiling",
                                "surrounding", "eye_height_m", "observers"};
  for (const MetricRule& rule : metric_rules()) keys.emplace_back(rule.key);
  return keys;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The preset a goals entry names, or an error listing the rows closest to the name
// (by edit distance, or sharing a word with it), else every row.
const GoalPreset& find_preset(const Value& v) {
  const std::string key = v.text();
  for (const GoalPreset& p : kPresets)
    if (key == p.key) return p;
  std::vector<std::pair<std::size_t, std::string>> close;
  for (const GoalPreset& p : kPresets) {
    const std::string name = p.key;
    const std::size_t d = edit_distance(key, name);
    const bool shares_word = !key.empty() && (name.find(key.substr(0, key.find('_'))) != std::string::npos);
    if (d <= std::max<std::size_t>(3, name.size() / 3) || shares_word) close.emplace_back(d, name);
  }
  std::sort(close.begin(), close.end());
  std::string listed;
  for (std::size_t k = 0; k < close.size() && k < 6; ++k) listed += (k ? ", " : "") + close[k].second;
  if (listed.empty()) {
    for (const GoalPreset& p : kPresets) listed += (listed.empty() ? "" : ", ") + std::string(p.key);
    v.fail("unknown preset (EN 12464-1 rows: " + listed + ")");
  }
  v.fail("unknown preset; close EN 12464-1 rows: " + listed + " (docs/config.md lists all)");
}

// observers: [{position_m: [x, y], view_direction: [dx, dy], eye_height_m: h}, ...]
std::vector<ObserverSpec> read_observers(const Value& v, std::optional<double> eye_height_m) {
  std::vector<ObserverSpec> out;
  const std::vector<Value> items = v.list();
  if (items.empty()) v.fail("must list at least one observer (leave it out for the standard's four)");
  for (const Value& item : items) {
    const Map m(item, {"position_m", "view_direction", "eye_height_m"});
    ObserverSpec o;
    o.loc = item.loc();
    o.xy_m = pair_of(m.require("position_m"), [](const Value& e) { return e.bounded(-kMaxLength_m, kMaxLength_m, " m"); });
    const Value view = m.require("view_direction");
    o.view = pair_of(view, [](const Value& e) { return e.bounded(-1e6, 1e6, ""); });
    if (!(o.view.norm() > 0.0)) view.fail("must not be [0, 0]: the line of sight's horizontal direction");
    o.eye_height_m = eye_height_m.value_or(kSeatedEyeHeightM);
    if (auto h = m.get("eye_height_m")) o.eye_height_m = h->number_in(0.1, 100.0, false, "[0.1, 100] m");
    out.push_back(o);
  }
  return out;
}

// A product under a preset that asks for colour rendering must state its Ra, at least the row's.
void check_products_ra(const JobConfig& job, const GoalPreset& p, const Value& preset) {
  if (!(p.ra > 0.0)) return;
  const std::string why = "preset " + std::string(p.key) + " (" + preset.key() + " at line " +
                          std::to_string(preset.loc().line) + ") asks for Ra >= " + format_number(p.ra);
  for (std::size_t i = 0; i < job.products.size(); ++i) {
    const ProductSetting& product = job.products[i];
    const std::string key = "luminaires.products[" + std::to_string(i) + "].ra";
    if (!product.ra)
      throw ConfigError(located(product.loc, key + ": missing for product '" + product.name + "': " + why +
                                                 " (give the data sheet's Ra)"));
    if (*product.ra < p.ra)
      throw ConfigError(located(product.ra_loc, key + " = " + format_number(*product.ra) + ": below what the " + why));
  }
}

// The target a preset gives a metric (nothing when the row gives none).
std::optional<double> preset_target(const GoalPreset& p, GoalMetric metric, bool modified) {
  switch (metric) {
    case GoalMetric::average: return modified ? p.modified_lux : p.average_lux;
    case GoalMetric::uniformity: return p.uniformity;
    case GoalMetric::ugr: return p.ugr_max > 0.0 ? std::optional(p.ugr_max) : std::nullopt;
    case GoalMetric::cylindrical: return p.cylindrical_lux > 0.0 ? std::optional(p.cylindrical_lux) : std::nullopt;
    case GoalMetric::cylindrical_uniformity:
      return p.cylindrical_lux > 0.0 ? std::optional(kRoomSurfaceUniformity) : std::nullopt;
    case GoalMetric::minimum:  // EN 12464-1's rows give none of these
    case GoalMetric::maximum:
    case GoalMetric::modelling:
      return std::nullopt;
  }
  return std::nullopt;
}

// walls: / ceiling: of a preset entry: a goal on those surfaces with the row's Em and U0 >= 0.10.
void add_room_surface_goal(const Map& entry, const std::string& key, double average_lux, std::vector<GoalSetting>& goals) {
  const auto v = entry.get(key);
  if (!v) return;
  GoalSetting g;
  if (v->node().IsSequence()) {
    for (const Value& item : v->list()) g.surfaces.push_back(item.text());
    if (g.surfaces.empty()) v->fail("must be a surface name or a non-empty list of names");
  } else {
    g.surfaces.push_back(v->text());
  }
  for (const std::string& surface : g.surfaces) g.name += (g.name.empty() ? "" : "+") + surface;
  g.surfaces_loc = g.loc = v->loc();
  for (const GoalSetting& other : goals)
    if (other.name == g.name) v->fail("goal '" + g.name + "' is already defined: give its targets there, not here");
  g.metric = GoalMetric::average;
  g.target = average_lux;
  goals.push_back(g);
  g.metric = GoalMetric::uniformity;
  g.target = kRoomSurfaceUniformity;
  goals.push_back(g);
}

// surrounding: of a goals entry on a task area (a grid drawn as rectangle_m or polygon_m):
// EN 12464-1's immediate surrounding area, as a band grid "<grid>_surrounding" (the
// task's outline grown by width_m less the outline, at its height; core/grid/calc_grid.h)
// and a goal "<goal>_surrounding" on it with its Em (given, or the task's Em one step
// down the standard's scale) and U0 (given, or 0.40). `surrounding: false` leaves out
// what the entry's preset would add; a preset adds it for rows with a task area when the
// entry's grid is a rectangle or polygon (a grid over a floor is the whole room: the
// standard's "task area unknown" case, with no band inside the room).
void add_surrounding(const Map& entry, const GoalSetting& base, const GoalPreset* preset,
                     const std::optional<Value>& preset_value, const std::vector<GoalSetting>& task_goals, JobConfig& job) {
  const std::optional<Value> v = entry.get("surrounding");
  const int task_index = base.grid.empty() ? -1 : find_grid(job, base.grid);
  const bool drawn = task_index >= 0 && job.grids[static_cast<std::size_t>(task_index)].kind == GridKind::horizontal &&
                     !job.grids[static_cast<std::size_t>(task_index)].polygon_m.empty();
  double width_m = kSurroundingWidthM;
  std::optional<FileLoc> width_loc;
  std::optional<std::pair<double, FileLoc>> average, uniformity;
  if (v) {
    if (v->node().IsScalar()) {
      const std::string flag = v->text();
      if (flag == "false") return;
      if (flag != "true") v->fail("must be true, false or a map {width_m, average_lux, uniformity}");
    } else {
      const Map m(*v, {"width_m", "average_lux", "uniformity"});
      if (auto w = m.get("width_m")) {
        width_m = w->bounded(1e-6, kMaxLength_m, " m");
        width_loc = w->loc();
      }
      for (auto [key, metric, out] : {std::tuple{"average_lux", GoalMetric::average, &average},
                                      std::tuple{"uniformity", GoalMetric::uniformity, &uniformity}})
        if (auto t = m.get(key)) {
          const double target = t->number();
          if (const std::string rule = target_rule(metric, target); !rule.empty()) t->fail(rule);
          *out = std::pair(target, t->loc());
        }
    }
    if (base.grid.empty())
      v->fail("applies to a goal on a grid (the task area, drawn as rectangle_m or polygon_m)");
    if (!drawn)
      v->fail("needs the task area's grid '" + base.grid +
              "' drawn as rectangle_m or polygon_m (a grid over a floor covers the room: no band around it)");
  } else if (!(preset && preset->surrounding && drawn)) {
    return;
  }
  const Value& at = v ? *v : *preset_value;  // where the band comes from, for errors
  const FileLoc loc = at.loc();
  const CalcGridSetting& task = job.grids[static_cast<std::size_t>(task_index)];
  if (!average) {
    const auto em = std::find_if(task_goals.begin(), task_goals.end(),
                                 [](const GoalSetting& g) { return g.metric == GoalMetric::average; });
    if (em == task_goals.end())
      at.fail("needs average_lux, here or on the task (its Em gives the surrounding's by EN 12464-1's table)");
    average = std::pair(surrounding_average_lux(em->target), loc);
  }
  if (!uniformity) uniformity = std::pair(kSurroundingUniformity, loc);
  CalcGridSetting band = task;
  band.name = task.name + kSurroundingSuffix;
  band.loc = band.shape_loc = band.border_loc = loc;
  band.band_width_m = width_m;
  band.band_loc = width_loc.value_or(loc);
  band.border_m = 0.0;
  band.spacing_m.reset();  // the standard's, for the band's own outline
  if (band.name.size() > kMaxGridNameChars || find_grid(job, band.name) >= 0)
    at.fail("the band's grid '" + band.name + "' " +
            (band.name.size() > kMaxGridNameChars ? "has too long a name" : "is already defined"));
  GoalSetting goal;
  goal.name = base.name + kSurroundingSuffix;
  goal.grid = band.name;
  goal.surfaces_loc = loc;
  for (const GoalSetting& g : job.goals)
    if (g.name == goal.name) at.fail("the band's goal '" + goal.name + "' is already defined");
  job.grids.push_back(band);
  for (const auto& [metric, target] : {std::pair{GoalMetric::average, *average}, std::pair{GoalMetric::uniformity, *uniformity}}) {
    goal.metric = metric;
    goal.target = target.first;
    goal.loc = target.second;
    job.goals.push_back(goal);
  }
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
    if (auto v = entry.get("eye_height_m")) base.eye_height_m = v->number_in(0.1, 100.0, false, "[0.1, 100] m");
    if (auto v = entry.get("observers")) base.observers = read_observers(*v, base.eye_height_m);
    const GoalPreset* preset = nullptr;
    std::optional<Value> preset_value = entry.get("preset");
    if (preset_value) {
      preset = &find_preset(*preset_value);
      check_products_ra(job, *preset, *preset_value);
    }
    bool modified = false;
    if (auto v = entry.get("em")) {
      if (!preset) v->fail("needs a preset (em chooses its required or modified Em)");
      const std::string level = v->text();
      if (level != "required" && level != "modified") v->fail("must be required or modified");
      modified = level == "modified";
      if (modified && !(preset->modified_lux > 0.0))
        v->fail("preset " + std::string(preset->key) + " gives no modified Em (docs/config.md)");
    }
    // This entry's metrics, each checked alone and against the same goal's earlier
    // entries; a bound conflict inside the entry is reported at max_lux.
    std::vector<std::pair<GoalSetting, Value>> metrics;
    for (const MetricRule& rule_of_metric : metric_rules()) {
      const GoalMetric metric = rule_of_metric.metric;
      const std::string key(rule_of_metric.key);
      auto v = entry.get(key);
      const std::optional<double> from_preset = !v && preset ? preset_target(*preset, metric, modified) : std::nullopt;
      if (from_preset) v = preset_value;  // an explicit key overrides the preset's value
      if (!v) continue;
      if (rule_of_metric.area == AreaKind::cylindrical && !grid)
        v->fail(from_preset ? "the row gives Ez,m (cylindrical illuminance): put the goal on a grid (grid: NAME)"
                            : "is measured over a grid's points: put the goal on a grid (grid: NAME)");
      GoalSetting goal = base;
      goal.metric = metric;
      goal.target = from_preset ? *from_preset : v->number();
      if (const std::string rule = target_rule(metric, goal.target); !rule.empty()) v->fail(rule);
      goal.loc = v->loc();
      for (const GoalSetting& g : job.goals)
        if (g.name == goal.name && g.metric == metric) v->fail("goal '" + goal.name + "' already has " + key);
      metrics.emplace_back(goal, *v);
    }
    if (metrics.empty())
      item.fail("needs at least one of average_lux, min_lux, max_lux, uniformity, ugr_max, cylindrical_lux, "
                "cylindrical_uniformity, modelling (or a preset)");
    const bool eyes = std::any_of(metrics.begin(), metrics.end(), [](const auto& m) {
      return metric_rule(m.first.metric).area != AreaKind::illuminance;
    });
    const bool rates_glare = std::any_of(metrics.begin(), metrics.end(),
                                         [](const auto& m) { return m.first.metric == GoalMetric::ugr; });
    if (auto v = entry.get("eye_height_m"); v && !eyes) v->fail("applies to ugr_max and the cylindrical metrics only");
    if (auto v = entry.get("observers"); v && !rates_glare) v->fail("applies to ugr_max only");
    std::vector<GoalSetting> here;
    for (const auto& [goal, v] : metrics) here.push_back(goal);
    for (const auto& [goal, v] : metrics) {
      std::string rule;
      if (goal.metric == GoalMetric::maximum) rule = goal_rules::bound_rule(here, goal.name, goal.metric, goal.target);
      if (rule.empty()) rule = goal_rules::bound_rule(job.goals, goal.name, goal.metric, goal.target);
      if (!rule.empty()) v.fail(rule);
    }
    job.goals.insert(job.goals.end(), here.begin(), here.end());
    for (const char* key : {"walls", "ceiling"})
      if (auto v = entry.get(key); v && !preset) v->fail("needs a preset (its row's Em on these surfaces, U0 >= 0.10)");
    if (preset) {
      add_room_surface_goal(entry, "walls", preset->wall_lux, job.goals);
      add_room_surface_goal(entry, "ceiling", preset->ceiling_lux, job.goals);
    }
    add_surrounding(entry, base, preset, preset_value, here, job);
  }
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
  if (auto v = constraints.get("max_power_density_w_per_m2")) {
    job.constraints.max_power_density_w_per_m2 = v->bounded(1e-6, 1e6, " W/m²");
    job.constraints.max_power_density_loc = v->loc();
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
  if (auto v = verification.get("indirect_rays_per_patch"))
    s.indirect_rays_per_patch = static_cast<int>(v->integer(1, 1 << 24));
  if (auto v = verification.get("first_indirect_rays"))
    s.first_indirect_rays = static_cast<int>(v->integer(1, 1 << 24));
  if (auto v = verification.get("decisive_rays")) s.decisive_rays = static_cast<int>(v->integer(0, 1 << 24));
  if (auto v = verification.get("rounds")) s.rounds = static_cast<int>(v->integer(1, 10));
  if (auto v = verification.get("margin")) s.margin = v->number_in(0.0, 0.2, false, "[0, 0.2]");
  if (auto v = verification.get("max_exact_patches"))
    s.max_exact_patches = static_cast<std::size_t>(v->integer(1, 100'000'000));
  if (auto v = verification.get("sample_fraction")) {
    s.sample_fraction = v->number_in(0.0, 1.0, false, "(0, 1]");
    if (s.sample_fraction <= 0.0) v->fail("must be in (0, 1]");
  }
}

// building: a job of rooms, whose grids are each room's (a room without grids writes no grid files).
void read_output(const Map& output, JobConfig& job, bool building) {
  OutputSettings& o = job.output;
  if (auto v = output.get("directory")) {
    o.directory = v->path();
    if (o.directory.empty()) v->fail("must not be empty");
  }
  if (auto v = output.get("formats")) {
    const std::string names = output_format_keys();
    const std::vector<Value> formats = v->list();
    if (formats.empty()) v->fail("must list at least one of " + names);
    std::vector<std::string> listed;
    for (const Value& item : formats) {
      const std::string name = item.text();
      const OutputFormat* f = find_output_format(name);
      if (!f) item.fail("must be one of " + names);
      if (f->needs_grids && job.grids.empty() && !building) item.fail("needs calculation grids (the job has no grids section)");
      if (std::find(listed.begin(), listed.end(), name) != listed.end()) item.fail("is listed twice");
      listed.push_back(name);
    }
    o.formats.clear();  // in registry order, the order they are written
    for (const OutputFormat& f : output_formats())
      if (std::find(listed.begin(), listed.end(), f.key) != listed.end()) o.formats.emplace_back(f.key);
  }
  if (auto v = output.get("plan_cut_height_m")) o.plan_cut_height_m = v->bounded(0.001, 1000.0, " m");
}

// energy: {building_type, hours_day, hours_night, occupancy_factor, daylight_factor,
// constant_illuminance, parasitic_kwh_per_m2}.
void read_energy(const Value& section, JobConfig& job) {
  const Map energy(section, {"building_type", "hours_day", "hours_night", "occupancy_factor", "daylight_factor",
                             "constant_illuminance", "parasitic_kwh_per_m2"});
  EnergySettings& e = job.energy;
  e.given = true;
  e.loc = section.loc();
  if (auto v = energy.get("building_type")) {
    e.building_type = v->text();
    if (!find_building_type(e.building_type)) {
      std::string names;
      for (const BuildingHours& b : building_types()) names += (names.empty() ? "" : ", ") + std::string(b.key);
      v->fail("must be one of " + names);
    }
  }
  constexpr double kHoursPerYear = 8760.0;
  if (auto v = energy.get("hours_day")) e.hours_day = v->number_in(0.0, kHoursPerYear, false, "[0, 8760] h");
  if (auto v = energy.get("hours_night")) e.hours_night = v->number_in(0.0, kHoursPerYear, false, "[0, 8760] h");
  const BuildingHours row = *find_building_type(e.building_type);
  if (e.hours_day.value_or(row.day_h) + e.hours_night.value_or(row.night_h) > kHoursPerYear)
    (energy.get("hours_night") ? *energy.get("hours_night") : *energy.get("hours_day"))
        .fail("hours_day + hours_night must be at most 8760 h (a year)");
  if (auto v = energy.get("occupancy_factor")) {
    e.occupancy_factor = v->number_in(0.0, 1.0, false, "(0, 1]");
    if (e.occupancy_factor <= 0.0) v->fail("must be in (0, 1]");
  }
  if (auto v = energy.get("daylight_factor")) e.daylight_factor = v->number_in(0.0, 1.0, false, "[0, 1]");
  if (auto v = energy.get("constant_illuminance")) {
    const std::string flag = Value::lower(v->text());
    if (flag == "true") e.constant_illuminance = true;
    else if (flag == "false") e.constant_illuminance = false;
    else v->fail("must be true or false");
  }
  if (auto v = energy.get("parasitic_kwh_per_m2")) e.parasitic_kwh_per_m2 = v->number_in(0.0, 1000.0, false, "[0, 1000] kWh/(m²·a)");
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
  std::vector<GoalSetting> trial = job.goals;  // each value is tried as `ilp sweep` will set it
  for (const Value& item : list) {
    const double v = item.number();
    goal_rules::apply(trial, setting.key, v, [&](const std::string& rule) { key.fail(rule); },
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
  if (auto v = solver.get("reflected_stride")) sample.reflected_stride = static_cast<int>(v->integer(1, 64));
  if (auto v = solver.get("hit_block_patches"))
    sample.hit_block_patches = static_cast<int>(v->integer(1, 1'000'000'000));
  if (auto v = solver.get("error_samples")) sample.error_samples = static_cast<int>(v->integer(2, 64));
  if (auto v = solver.get("pilot_fraction")) {
    sample.pilot_fraction = v->number_in(0.0, 1.0, false, "(0, 1]");
    if (sample.pilot_fraction <= 0.0) v->fail("must be in (0, 1]");
  }
}

}  // namespace

namespace config_yaml {

std::vector<std::string> luminaire_keys() {
  return {"size_m", "placed", "model", "flux_lm", "efficacy_lm_per_w", "mounting_surface", "mount_offset_m",
          "candidate_spacing_m", "count", "layout", "array", "products", "wall_distance_m", "ceiling_module_m", "field",
          "rows", "bays", "zone", "output", "suspended", "on_wall", "floor_surface", "groups"};
}

void read_maintenance_factor(const Value& v, JobConfig& job) {
  job.maintenance_factor = v.number_in(0.1, 1.0, false, "[0.1, 1] (as a product's)");
  job.maintenance_loc = v.loc();
}

// In this order: goals name grids and products, the objective needs the goals.
void read_room_keys(const Map& map, JobConfig& job, bool products_named) {
  if (auto v = map.get("luminaires")) read_luminaires(Map(*v, luminaire_keys()), job, products_named);
  if (auto v = map.get("grids")) read_grids(*v, job);
  if (auto v = map.get("maintenance_factor")) read_maintenance_factor(*v, job);
  if (auto v = map.get("goals")) read_goals(*v, job);
  if (auto v = map.get("scenarios")) read_scenarios(*v, job);
  if (auto v = map.get("constraints")) read_constraints(Map(*v, {"max_luminaires", "min_distance_m", "max_power_density_w_per_m2"}), job);
  if (auto v = map.get("objective")) read_objective(*v, job);
  if (auto v = map.get("energy")) read_energy(*v, job);
}

// A building job's shared keys: the product catalogue, the maintenance factor and the
// energy profile every room starts from; what belongs to one room is refused here.
void read_building_keys(const Map& top, JobConfig& job) {
  for (const char* key : {"goals", "grids", "constraints", "objective", "sweep", "report", "scenarios"})
    if (top.get(key))
      throw ConfigError(located(top.key_loc(key), std::string(key) + ": with rooms, each room states its own (rooms[]." +
                                                      key + "; docs/building.md)"));
  if (auto v = top.get("luminaires")) read_luminaires(Map(*v, {"products", "size_m"}), job, false);
  if (auto v = top.get("maintenance_factor")) read_maintenance_factor(*v, job);
  if (auto v = top.get("energy")) read_energy(*v, job);
}

}  // namespace config_yaml

std::span<const GoalPreset> goal_presets() { return kPresets; }

double surrounding_average_lux(double task_average_lux) {
  // EN 12464-1:2021 (task Em -> immediate surrounding Em); below 200 lx the task's own.
  constexpr std::pair<double, double> kSteps[] = {{750, 500}, {500, 300}, {300, 200}, {200, 150}};
  for (const auto& [task, surrounding] : kSteps)
    if (task_average_lux >= task) return surrounding;
  return task_average_lux;
}


int find_grid(const JobConfig& job, const std::string& name) {
  for (std::size_t g = 0; g < job.grids.size(); ++g)
    if (job.grids[g].name == name) return static_cast<int>(g);
  return -1;
}

void set_goal_parameter(JobConfig& job, const std::string& key, double value) {
  goal_rules::apply(
      job.goals, key, value, [&](const std::string& rule) -> void { throw ConfigError("--set " + key + ": " + rule); },
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
    if (const std::string why = not_a_regular_file(path, "config"); !why.empty()) throw ConfigError(why);
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
    reject_deep_nesting(text, path);
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
                      "solver, optimizer, verification, output, energy, sweep, report)");
  try {
    const Map top(Value(root, "", job.path), {"scene", "luminaires", "grids", "maintenance_factor", "goals",
                                              "constraints", "objective", "solver", "optimizer", "verification",
                                              "output", "energy", "sweep", "report", "rooms", "scenarios"});
    read_scene(Map(top.require("scene"), {"mesh", "up_axis", "scale_to_m", "max_patch_edge_m", "surfaces_from",
                                          "reflectance", "default_reflectance", "emitting_surfaces",
                                          "exclude_surfaces", "two_sided", "weld_tolerance_m", "regions", "add_floor"}),
               job);
    if (top.get("rooms")) read_building_keys(top, job);
    else read_room_keys(top, job, false);
    if (auto v = top.get("solver"))
      read_solver(Map(*v, {"method", "rays_per_patch", "seed", "threads", "relative_residual", "max_iterations",
                           "direct_receiver_points", "direct_shadow_rays", "sample_size", "sample_fraction",
                           "sampling", "sample_seed", "indirect", "target_error", "error_samples",
                           "pilot_fraction", "max_sample_size", "reflected_stride",
                           "hit_block_patches"}),
                  job);
    if (auto v = top.get("optimizer"))
      read_optimizer(Map(*v, {"global_algorithm", "local_algorithm", "max_evaluations", "local_max_evaluations",
                              "max_seconds", "seed"}),
                     job);
    if (auto v = top.get("verification"))
      read_verification(Map(*v, {"method", "rays_per_patch", "indirect_rays_per_patch", "first_indirect_rays", "decisive_rays", "rounds", "max_exact_patches", "sample_fraction", "margin"}), job);
    if (auto v = top.get("output")) read_output(Map(*v, {"directory", "formats", "plan_cut_height_m"}), job, top.get("rooms").has_value());
    if (auto v = top.get("sweep")) read_sweep(*v, top.key_loc("sweep"), job);
    if (auto v = top.get("rooms")) read_rooms(*v, job);
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

JobConfig group_job(const JobConfig& job, std::size_t g) {
  const LuminaireGroup& group = job.groups.at(g);
  JobConfig out = job;
  out.groups.clear();
  out.search = group.search;
  out.products.clear();
  for (const std::string& name : group.products)
    for (const ProductSetting& p : job.products)
      if (p.name == name) out.products.push_back(p);
  return out;
}

}  // namespace ilp
