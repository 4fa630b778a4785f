// The DXF plan: ASCII DXF R12 written directly (group code, value lines), read by
// every CAD program: the scene cut at a height, furniture tops, luminaires, labels.
#include <array>
#include <cmath>
#include <iomanip>
#include <locale>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include "output/layout_export.h"

namespace ilp {
namespace {

constexpr const char* kWalls = "ILP_WALLS";
constexpr const char* kFurniture = "ILP_FURNITURE";
constexpr const char* kLuminaires = "ILP_LUMINAIRES";
constexpr const char* kLabels = "ILP_LABELS";

// Writes group codes and values, numbers in the C locale.
class Dxf {
 public:
  explicit Dxf(std::ostream& out) : out_(out) {}
  Dxf& code(int c, const std::string& value) {
    out_ << c << '\n' << value << '\n';
    return *this;
  }
  Dxf& code(int c, double value) {
    std::ostringstream os;
    os.imbue(std::locale::classic());
    os << std::setprecision(10) << (value == 0.0 ? 0.0 : value);
    return code(c, os.str());
  }
  Dxf& integer(int c, int value) { return code(c, std::to_string(value)); }
  void line(const char* layer, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double z) {
    code(0, "LINE").code(8, layer).code(10, a.x()).code(20, a.y()).code(30, z).code(11, b.x()).code(21, b.y()).code(31, z);
  }

 private:
  std::ostream& out_;
};

// The segment where a triangle meets the plane z = h, if it does (not lying in it).
bool cut(const std::array<Eigen::Vector3d, 3>& t, double h, Eigen::Vector2d& a, Eigen::Vector2d& b) {
  std::vector<Eigen::Vector2d> hits;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& p = t[k];
    const Eigen::Vector3d& q = t[(k + 1) % 3];
    const double dp = p.z() - h, dq = q.z() - h;
    if ((dp < 0.0 && dq >= 0.0) || (dp >= 0.0 && dq < 0.0)) {
      const double s = dp / (dp - dq);
      hits.push_back((p + s * (q - p)).head<2>());
    }
  }
  if (hits.size() != 2 || (hits[0] - hits[1]).norm() < 1e-9) return false;
  a = hits[0];
  b = hits[1];
  return true;
}

// A position key for welding patch corners (0.1 mm).
std::pair<long long, long long> key2(const Eigen::Vector2d& p) {
  return {std::llround(p.x() * 1e4), std::llround(p.y() * 1e4)};
}

// Segments that join end to end along one line, merged (a wall cut through many patches
// gives one line): at each point where exactly two segments meet and run on in one
// direction, the two become one.
using Segment = std::pair<Eigen::Vector2d, Eigen::Vector2d>;
std::vector<Segment> merge_collinear(std::vector<Segment> s) {
  using Key = std::pair<long long, long long>;
  std::map<Key, std::vector<std::size_t>> at;
  std::vector<bool> alive(s.size(), true);
  for (std::size_t i = 0; i < s.size(); ++i) {
    at[key2(s[i].first)].push_back(i);
    at[key2(s[i].second)].push_back(i);
  }
  for (bool changed = true; changed;) {  // again until nothing joins: a merge can enable one at a key passed
  changed = false;
  for (auto& [key, list] : at) {
    std::erase_if(list, [&](std::size_t i) { return !alive[i]; });
    if (list.size() != 2 || list[0] == list[1]) continue;
    Segment& a = s[list[0]];
    const Segment& b = s[list[1]];
    // a runs (far_a -> joint), b runs (joint -> far_b).
    const Eigen::Vector2d far_a = key2(a.first) == key ? a.second : a.first;
    const Eigen::Vector2d far_b = key2(b.first) == key ? b.second : b.first;
    const Eigen::Vector2d joint = key2(a.first) == key ? a.first : a.second;
    const Eigen::Vector2d u = joint - far_a, v = far_b - joint;
    if (std::abs(u.x() * v.y() - u.y() * v.x()) > 1e-6 * u.norm() * v.norm() || u.dot(v) <= 0.0) continue;
    const std::size_t gone = list[1];
    a = {far_a, far_b};
    alive[gone] = false;
    std::vector<std::size_t>& far = at[key2(far_b)];
    for (std::size_t& i : far)
      if (i == gone) i = list[0];
    list.clear();
    changed = true;
  }
  }
  std::vector<Segment> out;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (alive[i]) out.push_back(s[i]);
  return out;
}

}  // namespace

void write_dxf_plan(std::ostream& out, const Scene& scene, const std::vector<ExportLuminaire>& luminaires,
                    double floor_z_m, double cut_height_m) {
  Dxf d(out);
  d.code(0, "SECTION").code(2, "HEADER").code(9, "$ACADVER").code(1, "AC1009");
  d.code(9, "$INSUNITS").integer(70, 6);  // metres
  d.code(0, "ENDSEC");
  d.code(0, "SECTION").code(2, "TABLES");
  d.code(0, "TABLE").code(2, "LTYPE").integer(70, 1);
  d.code(0, "LTYPE").code(2, "CONTINUOUS").integer(70, 0).code(3, "Solid line").integer(72, 65).integer(73, 0).code(40, 0.0);
  d.code(0, "ENDTAB");
  d.code(0, "TABLE").code(2, "LAYER").integer(70, 4);
  const std::pair<const char*, int> layers[] = {{kWalls, 7}, {kFurniture, 8}, {kLuminaires, 2}, {kLabels, 5}};
  for (const auto& [name, colour] : layers)
    d.code(0, "LAYER").code(2, name).integer(70, 0).integer(62, colour).code(6, "CONTINUOUS");
  d.code(0, "ENDTAB").code(0, "ENDSEC");
  d.code(0, "SECTION").code(2, "ENTITIES");

  // Walls: every mesh surface cut at the cut height, merged per surface.
  const double h = floor_z_m + cut_height_m;
  std::vector<std::vector<Segment>> per_surface(scene.surfaces.size());
  std::vector<std::map<std::pair<std::pair<long long, long long>, std::pair<long long, long long>>, int>> edges(scene.surfaces.size());
  std::vector<std::map<std::pair<long long, long long>, Eigen::Vector2d>> corners(scene.surfaces.size());
  for (const Patch& p : scene.patches) {
    const std::size_t s = static_cast<std::size_t>(p.surface);
    if (scene.surfaces[s].is_luminaire() || scene.surfaces[s].is_virtual) continue;
    Eigen::Vector2d a, b;
    if (cut(p.vertices_m, h, a, b)) per_surface[s].emplace_back(a, b);
    // Furniture tops: up-facing patches between the floor and the cut; their outline is
    // the edges only one of the surface's patches has.
    if (p.normal.z() > 0.9 && p.centroid_m.z() > floor_z_m + 0.05 && p.centroid_m.z() < h)
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector2d u = p.vertices_m[k].head<2>(), v = p.vertices_m[(k + 1) % 3].head<2>();
        auto ku = key2(u), kv = key2(v);
        corners[s][ku] = u;
        corners[s][kv] = v;
        ++edges[s][ku < kv ? std::make_pair(ku, kv) : std::make_pair(kv, ku)];
      }
  }
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) {
    for (const auto& [a, b] : merge_collinear(per_surface[s])) d.line(kWalls, a, b, 0.0);
    std::vector<Segment> outline;
    for (const auto& [e, count] : edges[s])
      if (count == 1) outline.emplace_back(corners[s][e.first], corners[s][e.second]);
    for (const auto& [a, b] : merge_collinear(outline)) d.line(kFurniture, a, b, 0.0);
  }

  // Luminaires: outline and label.
  for (const ExportLuminaire& l : luminaires) {
    const std::vector<Eigen::Vector3d> outline = luminaire_outline_m(l.type, l.placement);
    d.code(0, "POLYLINE").code(8, kLuminaires).integer(66, 1).code(10, 0.0).code(20, 0.0).code(30, 0.0).integer(70, 1);
    for (const Eigen::Vector3d& v : outline)
      d.code(0, "VERTEX").code(8, kLuminaires).code(10, v.x()).code(20, v.y()).code(30, 0.0);
    d.code(0, "SEQEND").code(8, kLuminaires);
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector3d& v : outline) box.extend(v.head<2>());
    std::string label = l.id + " " + (l.product.empty() ? l.type.name : l.product);
    if (l.above_floor_m) {
      std::ostringstream os;
      os.imbue(std::locale::classic());
      os << std::fixed << std::setprecision(2) << " h=" << *l.above_floor_m << " m";
      label += os.str();
    }
    d.code(0, "TEXT").code(8, kLabels).code(10, box.max().x() + 0.05).code(20, box.max().y() + 0.05).code(30, 0.0)
        .code(40, 0.15).code(1, label);
  }
  d.code(0, "ENDSEC").code(0, "EOF");
}

}  // namespace ilp
