// The grids and goals sections of a job file: calculation grids, goal entries with their
// metrics, EN 12464-1's presets (Em, U0, UGR_L, Ez, the walls' and ceiling's values, the
// immediate surrounding area), observers (job/config.h documents the settings).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "job/config.h"
#include "job/config_yaml.h"
#include "job/goal_rules.h"
#include "job/products.h"

namespace ilp {
namespace {

using namespace config_yaml;
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


}  // namespace

namespace config_yaml {

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

}  // namespace config_yaml

std::span<const GoalPreset> goal_presets() { return kPresets; }

double surrounding_average_lux(double task_average_lux) {
  // EN 12464-1:2021 (task Em -> immediate surrounding Em); below 200 lx the task's own.
  constexpr std::pair<double, double> kSteps[] = {{750, 500}, {500, 300}, {300, 200}, {200, 150}};
  for (const auto& [task, surrounding] : kSteps)
    if (task_average_lux >= task) return surrounding;
  return task_average_lux;
}


}  // namespace ilp
