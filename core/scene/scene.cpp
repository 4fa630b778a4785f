#include "core/scene/scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <ostream>
#include <set>
#include <sstream>

#include "core/base/key_hash.h"
#include "core/scene/contact_cuts.h"

namespace ilp {
namespace {

// kDegenerateRelArea (scene.h): below it a triangle cannot be told from a line in
// float ray casting.
constexpr double kMaxCoordinate_m = 1e6;  // |x|, |y|, |z| of any vertex after scale_to_m (1000 km)

Patch make_patch(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                 int surface, const Eigen::Vector3d& reflectance) {
  Patch p;
  p.vertices_m = {a, b, c};
  const Eigen::Vector3d cross = (b - a).cross(c - a);
  p.area_m2 = 0.5 * cross.norm();
  p.normal = cross.normalized();
  p.centroid_m = (a + b + c) / 3.0;
  p.surface = surface;
  p.reflectance = reflectance;
  return p;
}

}  // namespace

Eigen::Vector3d to_scene_frame(const Eigen::Vector3d& p, const SceneOptions& options) {
  Eigen::Vector3d q = p * options.scale_to_m;
  if (options.up_axis == UpAxis::y) return {q.x(), -q.z(), q.y()};  // rotate +90 deg about x
  return q;
}

int Scene::find_surface(const std::string& name) const {
  for (std::size_t s = 0; s < surfaces.size(); ++s)
    if (surfaces[s].name == name) return static_cast<int>(s);
  return -1;
}

std::vector<int> Scene::patches_of(const std::vector<std::string>& names) const {
  std::vector<bool> wanted(surfaces.size(), names.empty());
  for (const std::string& name : names) {
    const int s = find_surface(name);
    if (s < 0) throw std::invalid_argument("surface '" + name + "' is not in the scene");
    wanted[static_cast<std::size_t>(s)] = true;
  }
  std::vector<int> out;
  for (std::size_t i = 0; i < patches.size(); ++i)
    if (wanted[static_cast<std::size_t>(patches[i].surface)]) out.push_back(static_cast<int>(i));
  return out;
}

std::vector<int> Scene::all_patches() const {
  std::vector<int> out(patches.size());
  std::iota(out.begin(), out.end(), 0);
  return out;
}

double Scene::total_area_m2() const {
  double area = 0.0;
  for (const Patch& p : patches) area += p.area_m2;
  return area;
}

Scene make_scene(const TriangleMesh& mesh, const TriangleReflectance& reflectance,
                 const SceneOptions& options) {
  Scene scene;
  for (const std::string& name : mesh.surface_names) scene.surfaces.push_back({name});
  scene.stats.faces_read = mesh.faces_read;
  scene.stats.triangles_read = mesh.triangles.size();

  std::vector<Eigen::Vector3d> positions;
  positions.reserve(mesh.positions.size());
  Eigen::AlignedBox3d bounds;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    positions.push_back(to_scene_frame(mesh.positions[v], options));
    // Beyond this, float ray origins lose the millimetres and counts overflow.
    if (!(positions.back().cwiseAbs().maxCoeff() <= kMaxCoordinate_m)) {
      std::ostringstream os;
      os << mesh.path << ": vertex " << v + 1 << " lies at [" << positions.back().transpose()
         << "] m (after scale_to_m), beyond the " << kMaxCoordinate_m << " m from the origin a scene may span";
      throw SceneError(os.str());
    }
  }
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) bounds.extend(positions[t[k]]);
  const double diagonal2 = bounds.isEmpty() ? 0.0 : bounds.diagonal().squaredNorm();

  // Keep the non-degenerate triangles, each once, and count the patches they will make.
  // A duplicate (the same three points in the same turning order, whatever the vertex
  // records, in the same surface) would be a second patch in the same place, both lit,
  // twice the area. A reversed copy is a back-to-back twin (two-sided) and stays, and
  // so does a coincident triangle of another surface (a sheet of paper on a desk).
  std::vector<std::size_t> kept;
  std::vector<int> divisions;
  std::size_t patch_count = 0;
  std::set<std::pair<int, std::array<double, 9>>> seen;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d &a = positions[tri[0]], &b = positions[tri[1]], &c = positions[tri[2]];
    const double doubled_area = (b - a).cross(c - a).norm();
    if (!(doubled_area > kDegenerateRelArea * diagonal2)) {
      ++scene.stats.degenerate_dropped;
      continue;
    }
    {
      // The rotation that puts the lexicographically smallest point first keeps the
      // turning order, so equal keys mean the same triangle facing the same way.
      std::array<const Eigen::Vector3d*, 3> v{&a, &b, &c};
      auto less = [](const Eigen::Vector3d* p, const Eigen::Vector3d* q) {
        return std::lexicographical_compare(p->data(), p->data() + 3, q->data(), q->data() + 3);
      };
      const std::size_t first = static_cast<std::size_t>(std::min_element(v.begin(), v.end(), less) - v.begin());
      std::array<double, 9> key{};
      for (std::size_t k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d) key[3 * k + static_cast<std::size_t>(d)] = (*v[(first + k) % 3])[d];
      if (!seen.insert({mesh.triangle_surface[t], key}).second) {
        ++scene.stats.duplicate_dropped;
        continue;
      }
    }
    int m = 1;
    if (options.max_patch_edge_m > 0.0) {
      const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
      // In double first: a tiny edge would overflow the int (and the patch count).
      const double cuts = std::max(1.0, std::ceil(longest / options.max_patch_edge_m - 1e-9));
      if (!(cuts * cuts <= static_cast<double>(options.max_patches)))
        throw PatchLimitError(mesh.path + ": meshing with max_patch_edge_m = " + std::to_string(options.max_patch_edge_m) +
                              " would make more than " + std::to_string(options.max_patches) + " patches");
      m = static_cast<int>(cuts);
    }
    patch_count += static_cast<std::size_t>(m) * static_cast<std::size_t>(m);
    if (patch_count > options.max_patches)
      throw PatchLimitError(mesh.path + ": meshing with max_patch_edge_m = " + std::to_string(options.max_patch_edge_m) +
                       " would make more than " + std::to_string(options.max_patches) + " patches");
    kept.push_back(t);
    divisions.push_back(m);
  }
  if (kept.empty())
    throw SceneError(mesh.path + ": no usable faces (" + std::to_string(scene.stats.degenerate_dropped) +
                     " degenerate faces dropped)");

  // Where other faces touch or cross each kept triangle (contact_cuts.h).
  std::vector<std::vector<ContactSegment>> contacts;
  if (options.cut_at_contacts) {
    std::vector<Triangle3> triangles;
    std::vector<int> surfaces;
    triangles.reserve(kept.size());
    for (const std::size_t t : kept) {
      const auto& tri = mesh.triangles[t];
      triangles.push_back({positions[tri[0]], positions[tri[1]], positions[tri[2]]});
      surfaces.push_back(mesh.triangle_surface[t]);
    }
    contacts = contact_segments(triangles, surfaces);
    for (const auto& c : contacts) scene.stats.contact_segments += c.size();
  }

  // Uniform subdivision: every edge of triangle t is cut into m equal pieces, so each
  // sub-triangle's edges are parallel to the parent's and 1/m as long; areas are equal.
  // A sub-triangle a contact line passes through is cut along it.
  scene.patches.reserve(patch_count);
  std::vector<Triangle3> pieces;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const std::size_t t = kept[k];
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d &a = positions[tri[0]], &b = positions[tri[1]], &c = positions[tri[2]];
    const int m = divisions[k];
    const int surface = mesh.triangle_surface[t];
    const Eigen::Vector3d& rho = reflectance[t];
    auto grid = [&](int i, int j) -> Eigen::Vector3d {
      return a + (b - a) * (static_cast<double>(i) / m) + (c - a) * (static_cast<double>(j) / m);
    };
    const std::vector<ContactSegment>* cuts = contacts.empty() || contacts[k].empty() ? nullptr : &contacts[k];
    auto add = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
      if (!cuts) {
        scene.patches.push_back(make_patch(p, q, r, surface, rho));
        return;
      }
      pieces.clear();
      scene.stats.patches_cut += cut_along_segments({p, q, r}, *cuts, pieces);
      for (const Triangle3& piece : pieces) scene.patches.push_back(make_patch(piece[0], piece[1], piece[2], surface, rho));
    };
    for (int j = 0; j < m; ++j)
      for (int i = 0; i + j < m; ++i) {
        add(grid(i, j), grid(i + 1, j), grid(i, j + 1));
        if (i + j + 2 <= m) add(grid(i + 1, j), grid(i + 1, j + 1), grid(i, j + 1));
      }
  }
  if (scene.patches.size() > options.max_patches)
    throw PatchLimitError(mesh.path + ": meshing with max_patch_edge_m = " + std::to_string(options.max_patch_edge_m) +
                          " and cuts along contact lines would make more than " + std::to_string(options.max_patches) +
                          " patches");

  scene.channels = 1;
  for (const Patch& p : scene.patches)
    if (p.reflectance[0] != p.reflectance[1] || p.reflectance[0] != p.reflectance[2]) scene.channels = 3;
  scene.bounds_m = bounds;
  scene.stats.mesh_patches = scene.patches.size();
  return scene;
}

int add_luminaire(Scene& scene, const std::string& name, const LuminaireType& type, const LuminairePlacement& at,
                  double flux_lm) {
  const int surface = static_cast<int>(scene.surfaces.size());
  Surface s{name, flux_lm / type.opening_area_m2()};
  s.luminaire = static_cast<int>(scene.luminaires.size());
  scene.surfaces.push_back(s);
  scene.luminaires.push_back({type, at, surface, flux_lm});
  const std::vector<Eigen::Vector3d> outline = luminaire_outline_m(type, at);
  // The outline runs counter-clockwise seen from above; the fan is wound the other
  // way so that the front (emitting) side faces down.
  for (std::size_t k = 1; k + 1 < outline.size(); ++k) {
    Patch p = make_patch(outline[0], outline[k + 1], outline[k], surface, Eigen::Vector3d::Zero());
    p.exitance_lm_per_m2 = s.exitance_lm_per_m2;
    scene.patches.push_back(p);
    scene.bounds_m.extend(p.vertices_m[0]).extend(p.vertices_m[1]).extend(p.vertices_m[2]);
  }
  return surface;
}

int add_square_luminaire(Scene& scene, const std::string& name, const Eigen::Vector3d& position_m,
                         double size_m, double flux_lm) {
  return add_luminaire(scene, name, LuminaireType::square_lambertian(size_m), {position_m, 0.0}, flux_lm);
}

const SceneLuminaire& luminaire_of(const Scene& scene, int surface) {
  return scene.luminaires.at(static_cast<std::size_t>(scene.surfaces.at(static_cast<std::size_t>(surface)).luminaire));
}

void set_surface_exitance(Scene& scene, int surface, double exitance_lm_per_m2) {
  scene.surfaces[surface].exitance_lm_per_m2 = exitance_lm_per_m2;
  for (Patch& p : scene.patches)
    if (p.surface == surface) p.exitance_lm_per_m2 = exitance_lm_per_m2;
}

std::ostream& operator<<(std::ostream& os, const SceneStats& s) {
  os << s.faces_read << " faces read, " << s.triangles_read << " triangles, " << s.degenerate_dropped
     << " degenerate dropped, " << s.duplicate_dropped << " duplicates dropped, " << s.mesh_patches << " patches";
  if (s.patches_cut > 0) os << " (" << s.patches_cut << " cut along " << s.contact_segments << " contact segments)";
  return os;
}

static_assert(field_count<SceneOptions>() == 5, "SceneOptions changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const SceneOptions& o) {
  k.field("up_axis", o.up_axis).field("scale_to_m", o.scale_to_m).field("max_patch_edge_m", o.max_patch_edge_m);
  k.field("cut_at_contacts", o.cut_at_contacts);
  // Not max_patches: it refuses a scene, never changes one.
}

}  // namespace ilp
