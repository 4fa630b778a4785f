#include "core/study/scene_inspect.h"

#include "core/base/setting.h"
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <unordered_map>

#include "core/scene/surface_split.h"

namespace ilp {
namespace {

constexpr int kProbeRays = 5;  // along the normal and 60 degrees off it towards +-t1, +-t2

struct ProbeHit {
  int patch = -1;
  bool front = true;
};

// Probe directions around a unit normal.
std::array<Eigen::Vector3d, kProbeRays> probe_directions(const Eigen::Vector3d& n) {
  const Eigen::Vector3d axis = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d t1 = n.cross(axis).normalized(), t2 = n.cross(t1);
  const double c = 0.5, s = std::sqrt(3.0) / 2.0;
  return {n, c * n + s * t1, c * n - s * t1, c * n + s * t2, c * n - s * t2};
}

std::string percent(double share) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(share < 0.1 ? 1 : 0) << 100.0 * share << " %";
  return os.str();
}

// Edges of the mesh's non-degenerate triangles after welding: open, non-manifold and
// inconsistently wound, counted per surface (an edge counts for each surface of its triangles).
void count_edges(const TriangleMesh& mesh, const SceneOptions& frame, double tolerance, SceneInspection& out,
                 std::vector<SurfaceInspection>& per_surface) {
  const FramedVertices framed = framed_vertices(mesh, frame);
  const std::vector<Eigen::Vector3d>& p = framed.positions;
  const std::vector<bool>& used = framed.used;
  const double diagonal2 = framed.diagonal2;
  const std::vector<int> rep = weld_positions(p, used, tolerance, out.welded_vertices);
  struct EdgeUse {
    int count = 0, forward = 0;  // triangles using it; of those, traversing it from the lower vertex
    int first_surface = -1, second_surface = -1;
  };
  std::unordered_map<std::uint64_t, EdgeUse> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    const int s = mesh.triangle_surface[t];
    SurfaceInspection& surface = per_surface[static_cast<std::size_t>(s)];
    ++surface.triangles;
    const Eigen::Vector3d& a = p[static_cast<std::size_t>(tri[0])];
    if (!((p[static_cast<std::size_t>(tri[1])] - a).cross(p[static_cast<std::size_t>(tri[2])] - a).norm() >
          kDegenerateRelArea * diagonal2)) {
      ++surface.degenerate;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const auto u = static_cast<std::uint64_t>(rep[static_cast<std::size_t>(tri[k])]);
      const auto v = static_cast<std::uint64_t>(rep[static_cast<std::size_t>(tri[(k + 1) % 3])]);
      if (u == v) continue;
      EdgeUse& e = edges[std::min(u, v) << 32 | std::max(u, v)];
      ++e.count;
      if (u < v) ++e.forward;
      if (e.first_surface < 0) e.first_surface = s;
      else if (e.second_surface < 0) e.second_surface = s;
    }
  }
  for (const auto& [key, e] : edges) {
    std::size_t SurfaceInspection::*field = nullptr;
    if (e.count == 1) {
      field = &SurfaceInspection::open_edges;
      ++out.open_edges;
    } else if (e.count > 2) {
      field = &SurfaceInspection::nonmanifold_edges;
      ++out.nonmanifold_edges;
    } else if (e.forward != 1) {
      field = &SurfaceInspection::flipped_edges;
      ++out.flipped_edges;
    }
    if (!field) continue;
    ++(per_surface[static_cast<std::size_t>(e.first_surface)].*field);
    if (e.second_surface >= 0 && e.second_surface != e.first_surface)
      ++(per_surface[static_cast<std::size_t>(e.second_surface)].*field);
  }
}


// Per surface of the scene, its name and kind (counts filled in by the steps below).
std::vector<SurfaceInspection> blank_surfaces(const Scene& scene, const InspectOptions& options) {
  std::vector<SurfaceInspection> all(scene.surfaces.size());
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) {
    all[s].name = scene.surfaces[s].name;
    all[s].is_luminaire = scene.surfaces[s].is_luminaire();
    all[s].two_sided = s < options.two_sided.size() && options.two_sided[s];
  }
  return all;
}

// Geometry from the patches: area, bounds, the shares facing up, down and sideways and
// the mean heights of the up and down parts, per surface and in all.
void add_patch_geometry(const Scene& scene, std::vector<SurfaceInspection>& all, SceneInspection& out) {
  std::vector<double> up_area(all.size(), 0.0), down_area(all.size(), 0.0), up_z(all.size(), 0.0),
      down_z(all.size(), 0.0);
  for (const Patch& p : scene.patches) {
    const std::size_t s = static_cast<std::size_t>(p.surface);
    SurfaceInspection& surface = all[s];
    ++surface.patches;
    surface.area_m2 += p.area_m2;
    for (const Eigen::Vector3d& v : p.vertices_m) surface.bounds_m.extend(v);
    switch (facing_of(p.normal)) {
      case Facing::up: up_area[s] += p.area_m2; up_z[s] += p.area_m2 * p.centroid_m.z(); break;
      case Facing::down: down_area[s] += p.area_m2; down_z[s] += p.area_m2 * p.centroid_m.z(); break;
      case Facing::vertical: surface.vertical_share += p.area_m2; break;
    }
  }
  for (std::size_t s = 0; s < all.size(); ++s) {
    SurfaceInspection& surface = all[s];
    if (surface.area_m2 > 0.0) {
      surface.up_share = up_area[s] / surface.area_m2;
      surface.down_share = down_area[s] / surface.area_m2;
      surface.vertical_share /= surface.area_m2;
    }
    surface.up_mean_z_m = up_area[s] > 0.0 ? up_z[s] / up_area[s] : 0.0;
    surface.down_mean_z_m = down_area[s] > 0.0 ? down_z[s] / down_area[s] : 0.0;
    out.area_m2 += surface.area_m2;
  }
  out.patches = scene.patches.size();
  out.bounds_m = scene.bounds_m;
}

// Probe rays, every patch or an even stride; one slot per ray, so any thread count
// gives the same result. Fills the escape and back-hit shares, per surface and in all.
void cast_probe_rays(const Scene& scene, const RayCaster& caster, const InspectOptions& options,
                     std::vector<SurfaceInspection>& all, SceneInspection& out) {
  const std::size_t stride = std::max<std::size_t>(1, (scene.patches.size() + options.max_probe_patches - 1) /
                                                         std::max<std::size_t>(1, options.max_probe_patches));
  const std::size_t probes = (scene.patches.size() + stride - 1) / stride;
  std::vector<ProbeHit> hits(probes * kProbeRays);
  const double offset = caster.ray_offset_m();
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, probes, 256), [&](const tbb::blocked_range<std::size_t>& r) {
      const auto ray_modes = RayCaster::prepare_thread();
      for (std::size_t q = r.begin(); q != r.end(); ++q) {
        const Patch& p = scene.patches[q * stride];
        const Eigen::Vector3d origin = p.centroid_m + offset * p.normal;
        const auto dirs = probe_directions(p.normal);
        for (int k = 0; k < kProbeRays; ++k) {
          const RayHit h = caster.first_hit(origin, dirs[static_cast<std::size_t>(k)]);
          hits[q * kProbeRays + static_cast<std::size_t>(k)] = {h.patch, h.front};
        }
      }
    });
  });
  std::vector<double> sent(all.size(), 0.0), escaped(all.size(), 0.0);
  std::vector<std::size_t> back_received(all.size(), 0);
  double sent_all = 0.0, escaped_all = 0.0, back_all = 0.0;
  for (std::size_t q = 0; q < probes; ++q) {
    const Patch& p = scene.patches[q * stride];
    const std::size_t s = static_cast<std::size_t>(p.surface);
    for (int k = 0; k < kProbeRays; ++k) {
      const ProbeHit& h = hits[q * kProbeRays + static_cast<std::size_t>(k)];
      sent[s] += p.area_m2;
      sent_all += p.area_m2;
      if (h.patch < 0) {
        escaped[s] += p.area_m2;
        escaped_all += p.area_m2;
        continue;
      }
      const std::size_t hs = static_cast<std::size_t>(scene.patches[static_cast<std::size_t>(h.patch)].surface);
      ++all[hs].rays_received;
      if (!h.front) {
        ++back_received[hs];
        back_all += p.area_m2;
      }
    }
  }
  out.probe_rays = probes * kProbeRays;
  out.escape_share = sent_all > 0.0 ? escaped_all / sent_all : 0.0;
  out.back_hit_share = sent_all > 0.0 ? back_all / sent_all : 0.0;
  for (std::size_t s = 0; s < all.size(); ++s) {
    all[s].escape_share = sent[s] > 0.0 ? escaped[s] / sent[s] : 0.0;
    all[s].back_struck_share = all[s].rays_received ? static_cast<double>(back_received[s]) / all[s].rays_received : 0.0;
  }
}

// Suggestions: the largest downward area high in the model, the largest upward area low in it.
void suggest_mounting_and_floor(const Scene& scene, SceneInspection& out) {
  const double z0 = scene.bounds_m.min().z(), span = std::max(1e-12, scene.bounds_m.max().z() - z0);
  double best_mount = 0.0, best_floor = 0.0;
  for (std::size_t s = 0; s < out.surfaces.size(); ++s) {
    const SurfaceInspection& x = out.surfaces[s];
    if (x.is_luminaire) continue;
    const double down = x.down_share * x.area_m2, up = x.up_share * x.area_m2;
    const double h_down = (x.down_mean_z_m - z0) / span, h_up = (x.up_mean_z_m - z0) / span;
    if (down >= 1.0 && h_down >= 0.6 && down * h_down * h_down > best_mount) {
      best_mount = down * h_down * h_down;
      out.mounting = static_cast<int>(s);
    }
    if (up >= 1.0 && h_up <= 0.4 && up * (1.0 - h_up) * (1.0 - h_up) > best_floor) {
      best_floor = up * (1.0 - h_up) * (1.0 - h_up);
      out.floor = static_cast<int>(s);
    }
  }
}

// What looks wrong or is missing, in words for the user.
void add_warnings(const Scene& scene, const InspectOptions& options, SceneInspection& out) {
  auto& w = out.warnings;
  std::size_t mesh_surfaces = 0;
  const SurfaceInspection* largest = nullptr;
  for (const SurfaceInspection& s : out.surfaces)
    if (!s.is_luminaire) {
      ++mesh_surfaces;
      if (!largest || s.area_m2 > largest->area_m2) largest = &s;
    }
  if (largest && (mesh_surfaces == 1 || largest->area_m2 >= 0.9 * out.area_m2))
    w.push_back(mesh_surfaces == 1
                    ? "one surface ('" + largest->name + "') for the whole model: goals, reflectances and the mounting "
                      "surface need their own; split it with " + setting_name(Setting::surfaces_from) + ": connected or " +
                          setting_name(Setting::regions) + " (docs/config.md)"
                    : "'" + largest->name + "' holds " + percent(largest->area_m2 / out.area_m2) +
                          " of the area: consider splitting it (" + setting_name(Setting::surfaces_from) + ": connected or " +
                          setting_name(Setting::regions) + ")");
  if (scene.stats.degenerate_dropped > 0 || scene.stats.duplicate_dropped > 0)
    w.push_back(std::to_string(scene.stats.degenerate_dropped) + " degenerate triangles (zero or near-zero area) and " +
                std::to_string(scene.stats.duplicate_dropped) + " duplicates dropped by meshing");
  for (const SurfaceInspection& s : out.surfaces) {
    if (s.is_luminaire || s.two_sided || s.area_m2 < 0.005 * out.area_m2) continue;
    if (s.escape_share >= 0.5)
      w.push_back("'" + s.name + "': " + percent(s.escape_share) +
                  " of the probe rays from its front leave the model: it faces out of the room (wound inside out? "
                  "reverse it or use " + setting_name(Setting::two_sided) + ") or it is an outside surface (" +
                  setting_name(Setting::exclude_surfaces) + ")");
    if (s.rays_received >= 20 && s.back_struck_share >= 0.25)
      w.push_back("'" + s.name + "': " + percent(s.back_struck_share) +
                  " of the probe rays reaching it strike its back (light there is absorbed): wound the wrong way, "
                  "or one-sided where both sides are seen (" + setting_name(Setting::two_sided) + ")");
  }
  if (out.escape_share >= 0.01 || out.open_edges > 0) {
    std::ostringstream os;
    os << percent(out.escape_share) << " of all probe rays leave the model (openings: windows, holes, outward faces); "
       << out.open_edges << " open edges, " << out.nonmanifold_edges << " non-manifold edges (welded at "
       << options.weld_tolerance_m << " m)";
    w.push_back(os.str());
  }
  if (out.flipped_edges > 0) {
    std::vector<const SurfaceInspection*> worst;
    for (const SurfaceInspection& s : out.surfaces)
      if (s.flipped_edges > 0) worst.push_back(&s);
    std::sort(worst.begin(), worst.end(), [](auto* a, auto* b) {
      return a->flipped_edges != b->flipped_edges ? a->flipped_edges > b->flipped_edges : a->name < b->name;
    });
    std::string list;
    for (std::size_t k = 0; k < std::min<std::size_t>(3, worst.size()); ++k)
      list += (k ? ", '" : "'") + worst[k]->name + "' (" + std::to_string(worst[k]->flipped_edges) + ")";
    w.push_back(std::to_string(out.flipped_edges) +
                " edges where neighbouring triangles are wound inconsistently, most in " + list);
  }
  if (out.mounting < 0)
    w.push_back("no large surface faces down high in the model: nothing to suggest as a mounting surface");
  if (out.floor < 0) w.push_back("no large surface faces up low in the model: nothing to suggest as a floor");
}

}  // namespace

SceneInspection inspect_scene(const Scene& scene, const TriangleMesh& mesh, const SceneOptions& frame,
                              const RayCaster& caster, const InspectOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  SceneInspection out;
  std::vector<SurfaceInspection> all = blank_surfaces(scene, options);
  count_edges(mesh, frame, options.weld_tolerance_m, out, all);
  add_patch_geometry(scene, all, out);
  out.triangles = mesh.triangles.size();
  cast_probe_rays(scene, caster, options, all, out);
  // Surfaces with something in them, in scene order.
  for (SurfaceInspection& s : all)
    if (s.triangles > 0 || s.patches > 0) out.surfaces.push_back(std::move(s));
  suggest_mounting_and_floor(scene, out);
  add_warnings(scene, options, out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace ilp
