// The luminaires section of a job file: the search (mounting surface, flux range or
// products, layout), the products and the luminaires placed by hand.
#include <algorithm>
#include <filesystem>
#include <map>

#include "job/config_yaml.h"
#include "job/products.h"
#include "optimizer/group_search.h"

namespace ilp::config_yaml {
namespace {

// The keys of luminaires that describe the search; each needs mounting_surface.
// (products is not one: placed luminaires may name them without a search.)
constexpr const char* kSearchKeys[] = {"model",          "flux_lm",             "efficacy_lm_per_w",
                                       "mount_offset_m", "candidate_spacing_m", "count",
                                       "layout",         "array",               "wall_distance_m",
                                       "ceiling_module_m", "field",             "rows",
                                       "bays",           "zone",                "output",
                                       "floor_surface"};

constexpr int kMaxFreeCount = 64;        // luminaires a free layout may search (NLopt: 2-3 variables each)
constexpr int kMaxRegularCount = 10000;  // luminaires of a field, rows or bays layout

// A whole number N (the range [N, N]) or a range [min, max], each in [low, high].
CountRange count_range(const Value& v, int low, int high) {
  if (v.node().IsScalar()) {
    const int n = static_cast<int>(v.integer(low, high));
    return {n, n};
  }
  if (!v.node().IsSequence() || v.node().size() != 2) v.fail("must be a whole number N or a list [min, max]");
  const CountRange r{static_cast<int>(v.element(0).integer(low, high)), static_cast<int>(v.element(1).integer(low, high))};
  if (r.max < r.min) v.element(1).fail("must be >= the minimum [0]");
  return r;
}

// edge_ratio: one number or a range [min, max], each in [0.05, 1].
void read_edge_ratio(const Map& block, RegularLayoutParams& p) {
  const auto v = block.get("edge_ratio");
  if (!v) return;
  const std::string rule = "[0.05, 1] (0.5: half a spacing to the zone's edge)";
  if (v->node().IsScalar()) {
    p.edge_ratio_min = p.edge_ratio_max = v->number_in(0.05, 1.0, false, rule);
    return;
  }
  if (!v->node().IsSequence() || v->node().size() != 2) v->fail("must be a number or a range [min, max]");
  p.edge_ratio_min = v->element(0).number_in(0.05, 1.0, false, rule);
  p.edge_ratio_max = v->element(1).number_in(0.05, 1.0, false, rule);
  if (p.edge_ratio_max < p.edge_ratio_min) v->element(1).fail("must be >= the minimum [0]");
}

double position_tolerance(const Map& block) {
  const auto v = block.get("position_tolerance_m");
  return v ? v->bounded(0.0, 10.0, " m") : 0.05;
}

void read_field(const Value& v, RegularLayoutParams& p) {
  const Map block(v, {"rows", "columns", "edge_ratio", "max_spacing_ratio", "position_tolerance_m"});
  if (auto r = block.get("rows")) p.rows = count_range(*r, 1, 100);
  if (auto c = block.get("columns")) p.columns = count_range(*c, 1, 100);
  read_edge_ratio(block, p);
  if (auto r = block.get("max_spacing_ratio")) p.max_spacing_ratio = r->number_in(1.0, 100.0, false, "[1, 100]");
  p.position_tolerance_m = position_tolerance(block);
}

void read_rows(const Value& v, RegularLayoutParams& p) {
  const Map block(v, {"rows", "per_row", "continuous", "edge_ratio", "position_tolerance_m"});
  p.rows = CountRange{1, 8};
  p.columns = CountRange{1, 20};
  if (auto r = block.get("rows")) p.rows = count_range(*r, 1, 100);
  if (auto c = block.get("per_row")) p.columns = count_range(*c, 1, 200);
  if (auto c = block.get("continuous")) {
    const std::string t = c->text();
    if (t != "true" && t != "false") c->fail("must be true or false");
    p.continuous = t == "true";
  }
  read_edge_ratio(block, p);
  p.position_tolerance_m = position_tolerance(block);
}

void read_bays(const Value& v, RegularLayoutParams& p) {
  const Map block(v, {"module_m", "origin_m", "per_bay", "position_tolerance_m"});
  p.bay_module_m = pair_of(block.require("module_m"), [](const Value& e) { return e.bounded(0.1, 1000.0, " m"); });
  if (auto o = block.get("origin_m"))
    p.bay_origin_m = pair_of(*o, [](const Value& e) { return e.bounded(-kMaxLength_m, kMaxLength_m, " m"); });
  if (auto n = block.get("per_bay")) p.per_bay = count_range(*n, 1, 16);
  p.position_tolerance_m = position_tolerance(block);
}

void read_zone(const Value& v, LuminaireSearch& search) {
  const Map block(v, {"rectangle_m", "margin_m"});
  search.zone_loc = v.loc();
  search.zone_set = true;
  const auto rect = block.get("rectangle_m"), margin = block.get("margin_m");
  if (rect && margin) margin->fail("not with rectangle_m (the margin widens the goals' outline)");
  if (margin) search.zone_margin_m = margin->bounded(0.0, 1000.0, " m");
  if (!rect) return;
  if (!rect->node().IsSequence() || rect->node().size() != 2) rect->fail("must be [[x0, y0], [x1, y1]] (m)");
  auto corner = [](const Value& c) {
    return pair_of(c, [](const Value& e) { return e.bounded(-kMaxLength_m, kMaxLength_m, " m"); });
  };
  const Eigen::Vector2d a = corner(rect->element(0)), b = corner(rect->element(1));
  if (!((b - a).minCoeff() > 0.0)) rect->fail("the second corner must lie above the first in x and y");
  search.zone_m = std::make_pair(a, b);
  search.zone_loc = rect->loc();
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
                       "rotations_deg", "mount_offset_m", "tilt_deg", "length_axis_c_deg", "ra"});
    ProductSetting p;
    p.loc = item.loc();
    p.name = m.require("name").text();
    if (p.name.empty()) m.require("name").fail("must not be empty");
    if (!names.insert(p.name).second) m.require("name").fail("product name used twice");
    const auto photometry = m.get("photometry"), model = m.get("model");
    if (photometry && model) model->fail("not with photometry (a product is one or the other)");
    if (photometry) {
      p.photometry_path = (base / photometry->path()).lexically_normal().string();
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
    if (auto v = m.get("tilt_deg")) p.tilt_deg = v->number_in(0.0, 90.0, false, "[0, 90] degrees");
    if (auto v = m.get("ra")) {
      p.ra = v->number_in(0.0, 100.0, false, "[0, 100]");
      p.ra_loc = v->loc();
    }
    if (auto v = m.get("length_axis_c_deg")) {
      if (!photometry) v->fail("only for photometry: FILE (the panel's sides are its own)");
      const double c = v->number();
      if (c != 0.0 && c != 90.0) v->fail("must be 0 or 90 (the C-plane along the opening's length)");
      p.length_axis_c_deg = c;
      p.length_axis_loc = v->loc();
    }
    job.products.push_back(p);
  }
  if (job.products.empty()) section.fail("must list at least one product");
}

void read_array(const Value& array, LuminaireSearch& search) {
  const Map block(array, {"rows", "columns", "spacing_m", "offset_m"});
  search.array_rows = static_cast<int>(block.require("rows").integer(1, 32));
  search.array_columns = static_cast<int>(block.require("columns").integer(1, 32));
  if (auto v = block.get("spacing_m"))
    search.array_spacing_m = pair_of(*v, [](const Value& e) {
      const double x = e.positive();
      if (x > kMaxLength_m) e.fail("must be at most 1e+05 m");
      return x;
    });
  if (auto v = block.get("offset_m"))
    search.array_offset_m = pair_of(*v, [](const Value& e) { return e.bounded(0.0, kMaxLength_m, " m"); });
}

// layout: the family and its block (array:, field:, rows:, bays:), and count.
void read_layout(const Map& luminaires, LuminaireSearch& search) {
  const auto layout = luminaires.get("layout"), count = luminaires.get("count");
  constexpr LayoutFamily families[] = {LayoutFamily::free, LayoutFamily::array, LayoutFamily::field, LayoutFamily::rows,
                                       LayoutFamily::bays};
  if (layout) {
    const std::string family = layout->text();
    const auto known = std::ranges::find(families, family, layout_family_key);
    if (known == std::end(families)) layout->fail("must be free, array, field, rows or bays");
    search.layout = *known;
    search.layout_loc = layout->loc();
  }
  // Each block belongs to its family.
  for (const LayoutFamily f : families) {
    const std::string key(layout_family_key(f));
    if (auto block = luminaires.get(key); block && f != search.layout)
      block->fail("needs luminaires.layout: " + key);
  }
  const bool regular = search.layout != LayoutFamily::free && search.layout != LayoutFamily::array;
  if (search.layout == LayoutFamily::array) {
    if (!luminaires.get("array")) layout->fail("needs luminaires.array: {rows, columns}");
    if (count) count->fail("not with layout: array (the array fixes the count)");
    read_array(*luminaires.get("array"), search);
    return;
  }
  if (search.layout == LayoutFamily::field && luminaires.get("field")) read_field(*luminaires.get("field"), search.regular);
  if (search.layout == LayoutFamily::rows) {
    search.regular.rows = CountRange{1, 8};
    search.regular.columns = CountRange{1, 20};
    if (auto v = luminaires.get("rows")) read_rows(*v, search.regular);
  }
  if (search.layout == LayoutFamily::bays) {
    if (!luminaires.get("bays")) layout->fail("needs luminaires.bays: {module_m: [x, y], origin_m: [x, y]}");
    read_bays(*luminaires.get("bays"), search.regular);
  }
  if (regular) search.count_max = kMaxRegularCount;  // the arrangements bound the count; `count` narrows it
  if (count) {
    const CountRange r = count_range(*count, 1, regular ? kMaxRegularCount : kMaxFreeCount);
    search.count_min = r.min;
    search.count_max = r.max;
    search.count_loc = count->loc();
  }
}

void read_search(const Map& luminaires, const Value& mounting, JobConfig& job) {
  LuminaireSearch& search = job.search.emplace();
  if (mounting.key().ends_with(".suspended")) {  // a plane above the floor, no surface
    const Map block(mounting, {"height_m"});
    search.suspended_height_m = block.require("height_m").bounded(0.1, 1000.0, " m");
    search.suspended_loc = block.require("height_m").loc();
    if (auto v = luminaires.get("mount_offset_m")) v->fail("not with suspended (the height places the luminaires)");
  } else if (mounting.key().ends_with(".on_wall")) {  // a wall's faces facing one way, at a height
    const Map block(mounting, {"surface", "height_m", "facing"});
    WallMountSpec& wall = search.on_wall.emplace();
    const Value surface = block.require("surface");
    search.mounting_surface = surface.text();
    if (search.mounting_surface.empty()) surface.fail("must name a surface");
    wall.height_m = block.require("height_m").bounded(0.01, 1000.0, " m");
    wall.height_loc = block.require("height_m").loc();
    const Value facing = block.require("facing");
    const std::string f = facing.text();
    if (f == "+x" || f == "-x") wall.facing = Eigen::Vector2d(f[0] == '+' ? 1.0 : -1.0, 0.0);
    else if (f == "+y" || f == "-y") wall.facing = Eigen::Vector2d(0.0, f[0] == '+' ? 1.0 : -1.0);
    else facing.fail("must be +x, -x, +y or -y (the way the wall faces into the room)");
    wall.facing_loc = facing.loc();
    if (auto v = luminaires.get("ceiling_module_m")) v->fail("not with on_wall (a ceiling's module)");
    search.mounting_loc = surface.loc();
  } else {
    search.mounting_surface = mounting.text();
    if (search.mounting_surface.empty()) mounting.fail("must name a surface");
  }
  if (!search.on_wall) search.mounting_loc = mounting.loc();
  if (auto v = luminaires.get("floor_surface")) {
    search.floor_surface = v->text();
    if (search.floor_surface.empty()) v->fail("must name a surface");
    search.floor_loc = v->loc();
  }
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
  if (search.on_wall && !luminaires.get("layout")) search.layout = LayoutFamily::rows;  // a row along the wall
  read_layout(luminaires, search);
  if (search.on_wall && search.layout != LayoutFamily::rows && search.layout != LayoutFamily::field)
    luminaires.get("layout")->fail("must be rows or field with on_wall (a line along the wall)");
  if (auto v = luminaires.get("zone")) read_zone(*v, search);
  if (auto v = luminaires.get("output")) {
    const std::string t = v->text();
    if (t != "equal" && t != "individual") v->fail("must be equal or individual");
    search.individual_output = t == "individual";
    if (search.individual_output && (search.layout != LayoutFamily::free || !job.products.empty()))
      v->fail("individual output is for free layouts of the plain panel (products and regular layouts dim together)");
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

}  // namespace

// One entry of luminaires.groups: its name and products, then its search as the
// single group's keys give it (read_search on a copy of the job holding its products).
LuminaireGroup read_group(const Value& item, const JobConfig& job) {
  // (earlier groups are in job.groups: a name used twice is refused here)
  std::vector<std::string> allowed{"name", "products", "mounting_surface", "suspended", "on_wall"};
  for (const char* key : kSearchKeys) allowed.emplace_back(key);
  const Map block(item, allowed);
  LuminaireGroup group;
  group.loc = item.loc();
  group.name = block.require("name").text();
  if (group.name.empty()) block.require("name").fail("must name the group");
  for (const LuminaireGroup& other : job.groups)
    if (other.name == group.name) block.require("name").fail("group name '" + group.name + "' is used twice");
  JobConfig scratch = job;
  scratch.products.clear();
  const Value products = block.require("products");
  for (const Value& name : products.list()) {
    const std::string wanted = name.text();
    const auto it = std::find_if(job.products.begin(), job.products.end(), [&](const ProductSetting& p) { return p.name == wanted; });
    if (it == job.products.end()) name.fail("unknown product (a group names products of luminaires.products)");
    if (std::find(group.products.begin(), group.products.end(), wanted) != group.products.end()) name.fail("is listed twice");
    group.products.push_back(wanted);
    scratch.products.push_back(*it);
  }
  if (group.products.empty()) products.fail("must name at least one product of luminaires.products");
  const auto mounting = block.get("mounting_surface"), suspended = block.get("suspended"), on_wall = block.get("on_wall");
  if (mounting && suspended) suspended->fail("not with mounting_surface (one or the other)");
  if (on_wall && (mounting || suspended))
    on_wall->fail(std::string("not with ") + (mounting ? "mounting_surface" : "suspended") + " (one of them)");
  if (!mounting && !suspended && !on_wall) item.fail("a group needs mounting_surface, suspended or on_wall");
  read_search(block, mounting ? *mounting : suspended ? *suspended : *on_wall, scratch);
  group.search = *scratch.search;
  if (group.search.layout == LayoutFamily::free || group.search.layout == LayoutFamily::array) {
    const std::string rule = "field, rows or bays in a group (groups are searched together over regular arrangements)";
    if (auto v = block.get("layout")) v->fail("must be " + rule);
    item.fail("needs layout: " + rule);
  }
  return group;
}

void read_groups(const Map& luminaires, const Value& groups, JobConfig& job) {
  for (const char* key : {"mounting_surface", "suspended", "on_wall"})
    if (auto v = luminaires.get(key)) v->fail("not with luminaires.groups (each group gives its own)");
  for (const char* key : kSearchKeys)
    if (auto v = luminaires.get(key)) v->fail("not with luminaires.groups (each group gives its own)");
  const std::vector<Value> items = groups.list();
  if (items.empty()) groups.fail("must list at least one group");
  if (items.size() > static_cast<std::size_t>(kMaxSearchedGroups))
    items[static_cast<std::size_t>(kMaxSearchedGroups)].fail("at most " + std::to_string(kMaxSearchedGroups) + " groups are searched together");
  if (job.products.empty()) groups.fail("needs luminaires.products (each group names its products)");
  for (const Value& item : items) {
    LuminaireGroup group = read_group(item, job);
    job.groups.push_back(std::move(group));
  }
}

// A room's luminaires.products: names of its building's catalogue (job.products), which
// they replace, in the order given.
void select_products(const Value& section, JobConfig& job) {
  std::vector<ProductSetting> chosen;
  for (const Value& item : section.list()) {
    const std::string wanted = item.text();
    const auto it = std::find_if(job.products.begin(), job.products.end(), [&](const ProductSetting& p) { return p.name == wanted; });
    if (it == job.products.end())
      item.fail(job.products.empty() ? "unknown product: the building's luminaires.products lists none"
                                     : "unknown product (a room names products of the building's luminaires.products)");
    if (std::any_of(chosen.begin(), chosen.end(), [&](const ProductSetting& p) { return p.name == wanted; }))
      item.fail("is listed twice");
    chosen.push_back(*it);
  }
  if (chosen.empty()) section.fail("must name at least one product of the building's luminaires.products");
  job.products = std::move(chosen);
}

void read_luminaires(const Map& luminaires, JobConfig& job, bool products_named) {
  if (auto v = luminaires.get("size_m")) job.luminaire_size_m = v->bounded(kMinLuminaireSize_m, kMaxLuminaireSize_m, " m");
  if (auto v = luminaires.get("products")) {
    if (products_named) select_products(*v, job);
    else read_products(*v, job);
  }
  if (auto v = luminaires.get("placed")) {
    std::set<std::string> names;
    ResolvedProducts resolved;
    for (const Value& item : v->list()) {
      LuminaireSetting setting = read_placed(item, job, resolved);
      if (!names.insert(setting.name).second) item.fail("luminaire name '" + setting.name + "' is used twice");
      job.luminaires.push_back(std::move(setting));
    }
  }
  if (auto groups = luminaires.get("groups")) {
    read_groups(luminaires, *groups, job);
    return;
  }
  const auto mounting = luminaires.get("mounting_surface"), suspended = luminaires.get("suspended"),
             on_wall = luminaires.get("on_wall");
  if (mounting && suspended) suspended->fail("not with mounting_surface (one or the other)");
  if (on_wall && (mounting || suspended))
    on_wall->fail(std::string("not with ") + (mounting ? "mounting_surface" : "suspended") + " (one of them)");
  if (mounting || suspended || on_wall) {
    read_search(luminaires, mounting ? *mounting : suspended ? *suspended : *on_wall, job);
  } else {
    // The first search key in the file, so the error points where the reader looks.
    for (const auto& item : luminaires.value().node())
      for (const char* key : kSearchKeys)
        if (item.first.Scalar() == key)
          if (auto v = luminaires.get(key)) v->fail("needs luminaires.mounting_surface");
  }
}


}  // namespace ilp::config_yaml
