#include "core/scene/surface_split.h"

#include "core/base/setting.h"
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "core/base/key_hash.h"

namespace ilp {
namespace {

struct Cell {
  std::int64_t x, y, z;
  bool operator==(const Cell&) const = default;
};
struct CellHash {
  std::size_t operator()(const Cell& c) const {
    std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(c.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(c.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

}  // namespace

// Searches the 27 cells of size tolerance around each position.
std::vector<int> weld_positions(const std::vector<Eigen::Vector3d>& p, const std::vector<bool>& used, double tolerance,
                      std::size_t& representatives) {
  std::vector<int> rep(p.size(), -1);
  std::unordered_map<Cell, std::vector<int>, CellHash> cells;
  cells.reserve(p.size());
  const double tol2 = tolerance * tolerance;
  auto cell_of = [&](const Eigen::Vector3d& v) {
    return Cell{static_cast<std::int64_t>(std::floor(v.x() / tolerance)),
                static_cast<std::int64_t>(std::floor(v.y() / tolerance)),
                static_cast<std::int64_t>(std::floor(v.z() / tolerance))};
  };
  std::vector<int> reps;  // representative -> vertex
  for (std::size_t v = 0; v < p.size(); ++v) {
    if (!used[v]) continue;
    const Cell c = cell_of(p[v]);
    int found = -1;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = cells.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == cells.end()) continue;
          for (int r : it->second)
            if ((p[static_cast<std::size_t>(reps[static_cast<std::size_t>(r)])] - p[v]).squaredNorm() <= tol2 &&
                (found < 0 || r < found))
              found = r;
        }
    if (found < 0) {
      found = static_cast<int>(reps.size());
      reps.push_back(static_cast<int>(v));
      cells[c].push_back(found);
    }
    rep[v] = found;
  }
  representatives = reps.size();
  return rep;
}

namespace {

int find_root(std::vector<int>& parent, int a) {
  while (parent[static_cast<std::size_t>(a)] != a) {
    parent[static_cast<std::size_t>(a)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
    a = parent[static_cast<std::size_t>(a)];
  }
  return a;
}

void unite(std::vector<int>& parent, int a, int b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a == b) return;
  if (b < a) std::swap(a, b);
  parent[static_cast<std::size_t>(b)] = a;  // the lower index roots: deterministic
}

struct Piece {
  int surface = -1;
  Facing facing = Facing::vertical;
  double area_m2 = 0.0;
  double z_min = std::numeric_limits<double>::infinity(), z_max = -std::numeric_limits<double>::infinity();
  std::size_t first_triangle = 0;
  std::size_t triangles = 0;
  int rule = -1;
  std::string name;
};

std::string describe(const RegionRule& r) {
  std::ostringstream os;
  os << "facing " << (r.facing ? to_string(*r.facing) : "any");
  if (r.height_m) os << ", height " << r.height_m->first << " .. " << r.height_m->second << " m";
  if (r.min_area_m2 > 0.0) os << ", at least " << r.min_area_m2 << " m2";
  return os.str();
}

}  // namespace

std::string_view to_string(Facing facing) {
  switch (facing) {
    case Facing::up: return "up";
    case Facing::down: return "down";
    case Facing::vertical: return "vertical";
  }
  return "?";
}

Facing facing_of(const Eigen::Vector3d& n) {
  constexpr double kVerticalCos = 0.9;  // as goals' facing (optimizer/lighting_model.cpp)
  if (n.z() >= kVerticalCos) return Facing::up;
  if (n.z() <= -kVerticalCos) return Facing::down;
  return Facing::vertical;
}

FramedVertices framed_vertices(const TriangleMesh& mesh, const SceneOptions& frame) {
  FramedVertices out;
  out.positions.resize(mesh.positions.size());
  out.used.assign(mesh.positions.size(), false);
  Eigen::AlignedBox3d bounds;
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) out.used[static_cast<std::size_t>(t[k])] = true;
  for (std::size_t v = 0; v < out.positions.size(); ++v) {
    out.positions[v] = to_scene_frame(mesh.positions[v], frame);
    if (out.used[v]) bounds.extend(out.positions[v]);
  }
  out.diagonal2 = bounds.isEmpty() ? 0.0 : bounds.diagonal().squaredNorm();
  return out;
}

SurfaceSplitReport split_surfaces(TriangleMesh& mesh, const SceneOptions& frame, const SurfaceSplitOptions& options) {
  SurfaceSplitReport report;
  if (!options.active()) return report;
  if (!(options.weld_tolerance_m > 0.0)) throw std::invalid_argument("split_surfaces: weld tolerance must be > 0");
  const std::size_t T = mesh.triangles.size();
  const FramedVertices framed = framed_vertices(mesh, frame);
  const std::vector<Eigen::Vector3d>& p = framed.positions;
  const std::vector<bool>& used = framed.used;
  const double diagonal2 = framed.diagonal2;
  const std::vector<int> rep = weld_positions(p, used, options.weld_tolerance_m, report.welded_vertices);

  // Facing and area per triangle; degenerate ones (-1) have no facing.
  std::vector<int> facing(T, -1);
  std::vector<double> area(T, 0.0);
  for (std::size_t t = 0; t < T; ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    const Eigen::Vector3d cross = (p[static_cast<std::size_t>(tri[1])] - p[static_cast<std::size_t>(tri[0])])
                                      .cross(p[static_cast<std::size_t>(tri[2])] - p[static_cast<std::size_t>(tri[0])]);
    if (!(cross.norm() > kDegenerateRelArea * diagonal2)) continue;
    area[t] = 0.5 * cross.norm();
    facing[t] = static_cast<int>(facing_of(cross.normalized()));
  }

  // Triangles of one surface and one facing that share a welded vertex are one piece.
  std::vector<int> parent(T);
  std::iota(parent.begin(), parent.end(), 0);
  {
    const std::uint64_t surfaces = std::max<std::size_t>(1, mesh.surface_names.size());
    std::unordered_map<std::uint64_t, int> first;
    first.reserve(3 * T);
    for (std::size_t t = 0; t < T; ++t) {
      if (facing[t] < 0) continue;
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t key =
            ((static_cast<std::uint64_t>(rep[static_cast<std::size_t>(mesh.triangles[t][k])]) * 3 +
              static_cast<std::uint64_t>(facing[t])) * surfaces) + static_cast<std::uint64_t>(mesh.triangle_surface[t]);
        const auto [it, inserted] = first.emplace(key, static_cast<int>(t));
        if (!inserted) unite(parent, it->second, static_cast<int>(t));
      }
    }
  }
  std::vector<Piece> pieces;
  std::vector<int> piece_of(T, -1);
  {
    std::vector<int> root_piece(T, -1);
    for (std::size_t t = 0; t < T; ++t) {
      if (facing[t] < 0) continue;
      const int r = find_root(parent, static_cast<int>(t));
      int& slot = root_piece[static_cast<std::size_t>(r)];
      if (slot < 0) {
        slot = static_cast<int>(pieces.size());
        Piece piece;
        piece.surface = mesh.triangle_surface[t];
        piece.facing = static_cast<Facing>(facing[t]);
        piece.first_triangle = t;
        pieces.push_back(piece);
      }
      Piece& piece = pieces[static_cast<std::size_t>(slot)];
      piece.area_m2 += area[t];
      ++piece.triangles;
      for (int k = 0; k < 3; ++k) {
        const double z = p[static_cast<std::size_t>(mesh.triangles[t][k])].z();
        piece.z_min = std::min(piece.z_min, z);
        piece.z_max = std::max(piece.z_max, z);
      }
      piece_of[t] = slot;
    }
  }
  report.pieces = pieces.size();

  // Order: by surface, then area (largest first), then first triangle.
  std::vector<int> order(pieces.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Piece &x = pieces[static_cast<std::size_t>(a)], &y = pieces[static_cast<std::size_t>(b)];
    if (x.surface != y.surface) return x.surface < y.surface;
    if (x.area_m2 != y.area_m2) return x.area_m2 > y.area_m2;
    return x.first_triangle < y.first_triangle;
  });
  report.rule_pieces.assign(options.regions.size(), 0);
  report.rule_area_m2.assign(options.regions.size(), 0.0);
  std::vector<int> rank(mesh.surface_names.size(), 0);
  std::vector<int> largest(mesh.surface_names.size(), -1);
  for (int index : order) {
    Piece& piece = pieces[static_cast<std::size_t>(index)];
    const std::size_t s = static_cast<std::size_t>(piece.surface);
    if (largest[s] < 0) largest[s] = index;
    for (std::size_t r = 0; r < options.regions.size() && piece.rule < 0; ++r) {
      const RegionRule& rule = options.regions[r];
      if (rule.facing && *rule.facing != piece.facing) continue;
      if (rule.height_m && !(piece.z_min >= rule.height_m->first && piece.z_max <= rule.height_m->second)) continue;
      if (piece.area_m2 < rule.min_area_m2) continue;
      piece.rule = static_cast<int>(r);
      piece.name = rule.name;
      ++report.rule_pieces[r];
      report.rule_area_m2[r] += piece.area_m2;
    }
    if (piece.rule >= 0) continue;
    piece.name = mesh.surface_names[s];
    if (options.connected) piece.name.append(".").append(std::to_string(++rank[s]));  // (GCC 12 warns on "." + string)
  }
  for (std::size_t r = 0; r < options.regions.size(); ++r)
    if (report.rule_pieces[r] == 0)
      throw ConfigError(located(options.regions[r].loc, setting_name(Setting::regions) + "[" + std::to_string(r) + "] '" +
                                                            options.regions[r].name + "': no piece of " + mesh.path +
                                                            " matches (" + describe(options.regions[r]) +
                                                            "); `ilp inspect` lists the surfaces and their heights"));

  // New surfaces: the rules' names in rule order, then the rest in piece order.
  std::vector<std::string> names;
  std::map<std::string, int> index_of;
  auto surface_index = [&](const std::string& name) {
    const auto [it, inserted] = index_of.emplace(name, static_cast<int>(names.size()));
    if (inserted) names.push_back(name);
    return it->second;
  };
  for (const RegionRule& rule : options.regions) surface_index(rule.name);
  std::vector<int> piece_surface(pieces.size(), -1);
  for (int index : order) piece_surface[static_cast<std::size_t>(index)] = surface_index(pieces[static_cast<std::size_t>(index)].name);
  for (std::size_t t = 0; t < T; ++t) {
    const std::size_t s = static_cast<std::size_t>(mesh.triangle_surface[t]);
    int piece = piece_of[t] >= 0 ? piece_of[t] : largest[s];
    mesh.triangle_surface[t] = piece >= 0 ? piece_surface[static_cast<std::size_t>(piece)] : surface_index(mesh.surface_names[s]);
  }
  mesh.surface_names = std::move(names);

  std::ostringstream line;
  line << std::fixed << std::setprecision(2) << "surfaces split: " << report.pieces << " connected pieces of one facing ("
       << report.welded_vertices << " vertices after welding at " << std::defaultfloat << options.weld_tolerance_m
       << std::fixed << " m) -> " << mesh.surface_names.size() << " surfaces";
  report.log.push_back(line.str());
  for (std::size_t r = 0; r < options.regions.size(); ++r) {
    line.str("");
    line << setting_name(Setting::regions) << " '" << options.regions[r].name << "' (" << describe(options.regions[r])
         << "): " << report.rule_pieces[r] << " pieces, " << report.rule_area_m2[r] << " m2";
    report.log.push_back(line.str());
  }
  return report;
}

static_assert(field_count<RegionRule>() == 5, "RegionRule changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const RegionRule& r) {
  k.field("name", r.name).field("facing", r.facing).field("height_m", r.height_m).field("min_area_m2", r.min_area_m2);
  // Not loc: where the rule was written.
}

static_assert(field_count<SurfaceSplitOptions>() == 3,
              "SurfaceSplitOptions changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const SurfaceSplitOptions& o) {
  k.field("connected", o.connected).field("weld_tolerance_m", o.weld_tolerance_m).field("regions", o.regions);
}

}  // namespace ilp
