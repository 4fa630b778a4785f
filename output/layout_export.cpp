// The luminaire schedule and the names of the Radiance export's files.
#include <cctype>
#include <iomanip>
#include <locale>
#include <map>
#include <sstream>

#include "output/layout_export.h"

namespace ilp {
namespace {

std::string quoted_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string number(double v, int decimals) {
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os << std::fixed << std::setprecision(decimals) << v;
  std::string s = os.str();
  if (s == "-0" || s.rfind("-0.", 0) == 0) {  // never "-0.000"
    bool zero = true;
    for (char c : s.substr(1)) zero = zero && (c == '0' || c == '.');
    if (zero) s.erase(0, 1);
  }
  return s;
}

}  // namespace

void write_schedule_csv(std::ostream& out, const std::vector<ExportLuminaire>& luminaires) {
  out << "id,product,x_m,y_m,z_m,height_above_floor_m,rotation_deg,tilt_deg,flux_lm,output_percent,power_w,source\n";
  for (const ExportLuminaire& l : luminaires) {
    const Eigen::Vector3d& p = l.placement.position_m;
    out << quoted_field(l.id) << ',' << quoted_field(l.product.empty() ? l.type.name : l.product) << ','
        << number(p.x(), 3) << ',' << number(p.y(), 3) << ',' << number(p.z(), 3) << ','
        << (l.above_floor_m ? number(*l.above_floor_m, 3) : std::string()) << ','
        << number(l.placement.rotation_deg, 1) << ',' << number(l.placement.tilt_deg, 1) << ','
        << number(l.flux_lm, 0) << ','
        << (l.rated_flux_lm > 0.0 ? number(100.0 * l.flux_lm / l.rated_flux_lm, 1) : std::string()) << ','
        << (l.placed_by_job && l.power_w <= 0.0 ? std::string() : number(l.power_w, 1)) << ',' << (l.placed_by_job ? "placed" : "layout") << '\n';
  }
}

std::string file_safe_name(const std::string& name) {
  std::string out;
  for (unsigned char c : name) out += (std::isalnum(c) || c == '-' || c == '_') ? static_cast<char>(c) : '_';
  return out.empty() ? std::string("_") : out;
}

std::vector<std::string> RadianceNames::all() const {
  std::vector<std::string> out{scene};
  for (const auto& [_, file] : product_dat) out.push_back(file);
  for (const auto& [_, file] : grid_pts) out.push_back(file);
  return out;
}

RadianceNames radiance_names(const std::vector<std::string>& products, const std::vector<std::string>& grids) {
  RadianceNames names;
  std::map<std::string, int> used{{names.scene, 1}};
  auto unique = [&](const std::string& stem, const std::string& ext) {
    const std::string base = "radiance_" + file_safe_name(stem);
    std::string name = base + ext;
    for (int k = 2; used.count(name); ++k) name = base + "_" + std::to_string(k) + ext;
    used[name] = 1;
    return name;
  };
  for (const std::string& p : products) names.product_dat.emplace_back(p, unique(p, ".dat"));
  for (const std::string& g : grids) names.grid_pts.emplace_back(g, unique(g, ".pts"));
  return names;
}

}  // namespace ilp
