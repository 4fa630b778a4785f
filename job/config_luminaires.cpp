// The luminaires section of a job file: the search (mounting surface, flux range or
// products, layout), the products and the luminaires placed by hand.
#include <algorithm>
#include <filesystem>
#include <map>

#include "job/config_yaml.h"
#include "job/products.h"

namespace ilp::config_yaml {
namespace {

// The keys of luminaires that describe the search; each needs mounting_surface.
// (products is not one: placed luminaires may name them without a search.)
constexpr const char* kSearchKeys[] = {"model",          "flux_lm",             "efficacy_lm_per_w",
                                       "mount_offset_m", "candidate_spacing_m", "count",
                                       "layout",         "array",               "wall_distance_m",
                                       "ceiling_module_m"};


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

}  // namespace

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


}  // namespace ilp::config_yaml
