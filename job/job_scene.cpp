#include "job/job_scene.h"

#include <xxhash.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <set>
#include <memory>
#include <new>
#include <sstream>
#include <string_view>

#include "core/base/key_hash.h"
#include "core/cost/cost_model.h"
#include "core/scene/mesh_import.h"

namespace ilp {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string fmt_rgb(const Eigen::Vector3d& v) {
  std::ostringstream os;
  if (v[0] == v[1] && v[0] == v[2]) os << v[0];
  else os << "[" << v[0] << ", " << v[1] << ", " << v[2] << "]";
  return os.str();
}

// The run log's line for a placed product: what it is, how turned and at what output.
std::string placed_product_line(const LuminaireSetting& l) {
  std::ostringstream os;
  os << "luminaires.placed '" << l.name << "': product '" << l.product << "', "
     << (l.type.shape == OutlineShape::disc ? "round " : "rectangular ") << l.type.length_m << " x " << l.type.width_m
     << " m, rotated " << l.rotation_deg << " deg, " << l.flux_lm << " lm";
  return os.str();
}

// The frame the mesh is read in: the job's up_axis and scale_to_m where it sets them,
// else what an imported file states, else the defaults (metres, z up). For imported
// formats the log says which and why, and a unit neither the file nor the job states is
// an error (issue 22: a 3DS file in millimetres would otherwise be read as metres,
// a thousand times too large, without a word but the log's). OBJ, PLY and OFF never
// state one and keep the default; every shipped job sets scale_to_m.
SceneOptions scene_frame(const SceneSpec& spec, const TriangleMesh& mesh, std::vector<std::string>& log) {
  SceneOptions o = spec.scene;
  if (!is_imported_format(lower_extension(spec.mesh_path))) return o;
  const MeshFrame& stated = mesh.frame;
  std::ostringstream unit, up;
  if (!spec.scale_to_m_loc.file.empty()) {
    unit << "unit: scene.scale_to_m = " << o.scale_to_m << " m per unit, as the job sets it";
    if (stated.scale_to_m) unit << " (the file states " << stated.unit_note << ")";
  } else if (stated.scale_to_m) {
    o.scale_to_m = *stated.scale_to_m;
    unit << "unit: " << stated.unit_note;
  } else {
    throw ConfigError(located(spec.mesh_loc, "scene.mesh: " + spec.mesh_path +
                                                ": the file does not state its unit (" +
                                                (lower_extension(spec.mesh_path) == ".3ds" ? "3DS files carry none"
                                                                                          : "no unit in the file") +
                                                "): set scene.scale_to_m, the metres per file unit (1 for metres, "
                                                "0.001 for millimetres; `ilp inspect --scale`)"));
  }
  if (!spec.up_axis_loc.file.empty()) {
    up << "up axis: scene.up_axis = " << (o.up_axis == UpAxis::y ? "y" : "z") << ", as the job sets it";
    if (stated.up_axis) up << " (the file states " << stated.up_note << ")";
  } else if (stated.up_axis) {
    o.up_axis = *stated.up_axis;
    up << "up axis: " << stated.up_note;
  } else {
    up << "up axis: the file does not state its up axis: taken as " << (o.up_axis == UpAxis::y ? "y" : "z")
       << " (set scene.up_axis if it is not)";
  }
  log.push_back(unit.str());
  log.push_back(up.str());
  return o;
}

bool matches(const std::string& name, const std::string& pattern) {
  if (!pattern.empty() && pattern.back() == '*') return name.rfind(pattern.substr(0, pattern.size() - 1), 0) == 0;
  return name == pattern;
}

// A room's part of the model (SceneSpec::keep_surfaces): every surface no pattern
// matches is excluded. A pattern that matches no surface is an error at its line.
void keep_only(const std::vector<std::string>& names, const std::vector<SurfacePattern>& keep,
               std::vector<bool>& excluded) {
  if (keep.empty()) return;
  std::vector<bool> kept(names.size(), false);
  for (const SurfacePattern& p : keep) {
    bool any = false;
    for (std::size_t s = 0; s < names.size(); ++s)
      if (matches(names[s], p.pattern)) kept[s] = any = true;
    if (!any) throw ConfigError(located(p.loc, p.key + " = " + p.pattern + ": no surface of the mesh matches it"));
  }
  for (std::size_t s = 0; s < names.size(); ++s)
    if (!kept[s]) excluded[s] = true;
}

// "KEY: unknown surface 'NAME' in MESH (surfaces: a, b, ...)": the first 12 of `names`
// (in order), located at `loc`.
ConfigError unknown_surface(const FileLoc& loc, const std::string& key, const std::string& name,
                            const std::string& mesh_path, const std::vector<std::string>& names) {
  std::string known;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (k == 12) {
      known += ", ...";
      break;
    }
    known += (known.empty() ? "" : ", ") + names[k];
  }
  return ConfigError(located(loc, key + ": unknown surface '" + name + "' in " + mesh_path + " (surfaces: " + known + ")"));
}

}  // namespace

void require_search_surfaces(const SearchSurfaces& search, const std::string& mesh_path, const Scene& scene) {
  std::set<std::string> mesh_surfaces;  // sorted, as load_job_scene names them
  for (const Surface& surface : scene.surfaces)
    if (!surface.is_luminaire()) mesh_surfaces.insert(surface.name);
  auto require = [&](const std::string& name, const FileLoc& loc, const std::string& key) {
    if (!mesh_surfaces.contains(name))
      throw unknown_surface(loc, key, name, mesh_path, {mesh_surfaces.begin(), mesh_surfaces.end()});
  };
  if (!search.suspended) require(search.mounting_surface, search.mounting_loc, "luminaires.mounting_surface");
  if (!search.floor_surface.empty()) require(search.floor_surface, search.floor_loc, "luminaires.floor_surface");
}

namespace {

// The mesh's surfaces by name, for the keys that name them (an unknown name: the error
// lists the surfaces there are).
struct MeshSurfaces {
  std::map<std::string, int> index;
  std::string mesh_path;
  int require(const std::string& name, const FileLoc& loc, const std::string& key) const {
    auto it = index.find(name);
    if (it == index.end()) {
      std::vector<std::string> names;
      for (const auto& [n, _] : index) names.push_back(n);
      throw unknown_surface(loc, key, name, mesh_path, names);
    }
    return it->second;
  }
};

// scene.mesh read (within the machine's memory), its notes logged.
TriangleMesh read_job_mesh(const SceneSpec& spec, std::vector<std::string>& log) {
  // A model read through assimp never takes more than the machine (or its cgroup) has
  // available: a malformed file can make assimp allocate without bound. A caller with a
  // smaller budget (--max-memory) sets the limit itself.
  MeshReadOptions read = spec.mesh_read;
  if (!read.import_limits.max_memory_bytes) read.import_limits.max_memory_bytes = memory_budget_bytes(std::nullopt);
  TriangleMesh mesh;
  try {
    mesh = load_mesh(spec.mesh_path, read);
  } catch (const SceneError& e) {
    throw SceneError(located(spec.mesh_loc, std::string("scene.mesh: ") + e.what()));
  }
  log.insert(log.end(), mesh.notes.begin(), mesh.notes.end());
  return mesh;
}

struct TriangleEdits {
  std::size_t excluded = 0, doubled = 0;
};

// Excluded surfaces lose their triangles (the surface stays, empty); two-sided ones get a
// reversed copy of each triangle, back to back with it.
TriangleEdits exclude_and_double(const SceneSpec& spec, const MeshSurfaces& surfaces, TriangleMesh& mesh) {
  std::vector<bool> excluded(mesh.surface_names.size(), false), two_sided(mesh.surface_names.size(), spec.two_sided_all);
  for (std::size_t k = 0; k < spec.exclude_surfaces.size(); ++k)
    excluded[surfaces.require(spec.exclude_surfaces[k], spec.exclude_surface_locs[k], "scene.exclude_surfaces")] = true;
  keep_only(mesh.surface_names, spec.keep_surfaces, excluded);
  for (std::size_t k = 0; k < spec.two_sided_surfaces.size(); ++k)
    two_sided[surfaces.require(spec.two_sided_surfaces[k], spec.two_sided_locs[k], "scene.two_sided")] = true;
  TriangleEdits edits;
  const std::size_t n = mesh.triangles.size();
  std::size_t kept = 0;
  for (std::size_t t = 0; t < n; ++t) {
    const int s = mesh.triangle_surface[t];
    if (excluded[s]) {
      ++edits.excluded;
      continue;
    }
    mesh.triangles[kept] = mesh.triangles[t];
    mesh.triangle_surface[kept] = s;
    mesh.triangle_material[kept] = mesh.triangle_material[t];
    ++kept;
  }
  mesh.triangles.resize(kept);
  mesh.triangle_surface.resize(kept);
  mesh.triangle_material.resize(kept);
  for (std::size_t t = 0; t < kept; ++t) {
    const int s = mesh.triangle_surface[t];
    if (!two_sided[s]) continue;
    const Eigen::Vector3i tri = mesh.triangles[t];
    mesh.triangles.push_back(Eigen::Vector3i(tri[0], tri[2], tri[1]));
    mesh.triangle_surface.push_back(s);
    mesh.triangle_material.push_back(mesh.triangle_material[t]);
    ++edits.doubled;
  }
  return edits;
}

// Added floors: a rectangle each, in the file's frame and units (make_scene turns it
// back); returns each one's surface and reflectance.
std::vector<std::pair<int, Eigen::Vector3d>> add_floors(const SceneSpec& spec, const SceneOptions& frame,
                                                        MeshSurfaces& surfaces, TriangleMesh& mesh,
                                                        std::vector<std::string>& log) {
  std::vector<std::pair<int, Eigen::Vector3d>> added_rho;
  for (const FloorSetting& f : spec.add_floors) {
    if (surfaces.index.count(f.name))
      throw ConfigError(located(f.loc, "scene.add_floor: name '" + f.name + "' is already a surface of the mesh"));
    const int s = static_cast<int>(mesh.surface_names.size());
    mesh.surface_names.push_back(f.name);
    surfaces.index[f.name] = s;
    added_rho.emplace_back(s, f.rgb);
    auto to_file = [&](double x, double y) {
      const Eigen::Vector3d p = Eigen::Vector3d(x, y, f.z_m) / frame.scale_to_m;
      return frame.up_axis == UpAxis::y ? Eigen::Vector3d(p.x(), p.z(), -p.y()) : p;
    };
    const int base = static_cast<int>(mesh.positions.size());
    for (const Eigen::Vector3d& p : {to_file(f.lo.x(), f.lo.y()), to_file(f.hi.x(), f.lo.y()), to_file(f.hi.x(), f.hi.y()),
                                     to_file(f.lo.x(), f.hi.y())})
      mesh.positions.push_back(p);
    for (const Eigen::Vector3i& t : {Eigen::Vector3i(base, base + 1, base + 2), Eigen::Vector3i(base, base + 2, base + 3)}) {
      mesh.triangles.push_back(t);
      mesh.triangle_surface.push_back(s);
      mesh.triangle_material.push_back(-1);
    }
    log.push_back("scene.add_floor: '" + f.name + "' added, a rectangle facing up");
  }
  return added_rho;
}

// Reflectance per surface from the config, then per triangle (config > MTL Kd > default).
TriangleReflectance triangle_reflectance(const SceneSpec& spec, const MeshSurfaces& surfaces, const TriangleMesh& mesh,
                                         const std::vector<std::pair<int, Eigen::Vector3d>>& added_rho) {
  std::vector<std::optional<Eigen::Vector3d>> surface_rho(mesh.surface_names.size());
  for (const auto& [s, rgb] : added_rho) surface_rho[static_cast<std::size_t>(s)] = rgb;
  for (const ReflectanceSetting& r : spec.reflectance)
    surface_rho[surfaces.require(r.surface, r.loc, "scene.reflectance." + r.surface)] = r.rgb;
  TriangleReflectance rho(mesh.triangles.size());
  std::vector<int> bad_kd_surface(mesh.materials.size(), -1);  // per material: a surface that uses it
  std::vector<int> bad_kd_order;                               // materials in the order found
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int s = mesh.triangle_surface[t];
    const int m = mesh.triangle_material[t];
    if (surface_rho[s]) {
      rho[t] = *surface_rho[s];
    } else if (m >= 0 && mesh.materials[m].kd && !spec.ignore_material_kd) {
      rho[t] = *mesh.materials[m].kd;
      if (((rho[t].array() < 0.0) || (rho[t].array() >= 1.0)).any() && bad_kd_surface[m] < 0) {
        bad_kd_surface[m] = s;
        bad_kd_order.push_back(m);
      }
    } else if (spec.default_reflectance) {
      rho[t] = *spec.default_reflectance;
    } else {
      throw ConfigError(located(spec.mesh_loc, "surface '" + mesh.surface_names[s] +
                                                  "' has no reflectance: give it in scene.reflectance "
                                                  "(or scene.default_reflectance), or a Kd in the MTL"));
    }
  }
  // Every material with an unusable Kd at once (real models often carry Kd 1), each
  // with its line; the error points at the first.
  if (!bad_kd_order.empty()) {
    std::string list;
    for (int m : bad_kd_order) {
      const MeshMaterial& material = mesh.materials[m];
      list += std::string(list.empty() ? "" : "; ") + "'" + material.name + "' = " + fmt_rgb(*material.kd) +
              " (line " + std::to_string(material.kd_loc.line) + ", surface '" + mesh.surface_names[bad_kd_surface[m]] +
              "')";
    }
    throw SceneError(located(mesh.materials[bad_kd_order.front()].kd_loc,
                             "Kd outside [0, 1) for " + std::to_string(bad_kd_order.size()) + " material(s): " + list +
                                 ": set their surfaces' reflectance in scene.reflectance of " + spec.path));
  }
  return rho;
}

// The patches, meshed from the edited mesh (errors located at the keys that cause them).
Scene mesh_scene(const SceneSpec& spec, const TriangleMesh& mesh, const TriangleReflectance& rho,
                 const SceneOptions& frame) {
  try {
    return make_scene(mesh, rho, frame);
  } catch (const PatchLimitError& e) {
    const FileLoc& loc = spec.max_patch_edge_loc.file.empty() ? spec.mesh_loc : spec.max_patch_edge_loc;
    throw ConfigError(located(loc, std::string("scene.max_patch_edge_m: ") + e.what()));
  } catch (const SceneError& e) {
    throw SceneError(located(spec.mesh_loc, std::string("scene.mesh: ") + e.what()));
  }
}

// The job's own sources: emitting surfaces and placed luminaires (inside the model).
void place_job_sources(const SceneSpec& spec, const MeshSurfaces& surfaces, JobScene& out) {
  Scene& scene = out.scene;
  for (std::size_t k = 0; k < spec.emitting_surfaces.size(); ++k) {
    const EmitterSetting& e = spec.emitting_surfaces[k];
    const std::string key = "scene.emitting_surfaces[" + std::to_string(k) + "].surface";
    set_surface_exitance(scene, surfaces.require(e.surface, e.loc, key), e.exitance_lm_per_m2);
  }
  const Eigen::AlignedBox3d mesh_bounds = scene.bounds_m;
  for (const LuminaireSetting& l : spec.luminaires) {
    // Outside the model is almost always a unit or axis mix-up (mm, y up).
    if (!mesh_bounds.contains(l.position_m)) {
      std::ostringstream os;
      os << "luminaires.placed: '" << l.name << "' at [" << l.position_m.transpose() << "] m lies outside the scene, ["
         << mesh_bounds.min().transpose() << "] .. [" << mesh_bounds.max().transpose()
         << "] m (positions are in metres, z up, after scale_to_m and up_axis)";
      throw ConfigError(located(l.loc, os.str()));
    }
    if (scene.find_surface(l.name) >= 0)
      throw ConfigError(located(l.loc, "luminaires.placed: name '" + l.name + "' is already a surface of the mesh"));
    add_luminaire(scene, l.name, l.type, {l.position_m, l.rotation_deg}, l.flux_lm);
    if (!l.product.empty()) out.log.push_back(placed_product_line(l));
  }
}

// Every surface the job reports or lights keeps a patch (not all excluded or degenerate),
// and the search's surfaces are the mesh's.
void check_job_surfaces(const SceneSpec& spec, const MeshSurfaces& surfaces, const Scene& scene) {
  std::vector<std::size_t> patches_of(scene.surfaces.size(), 0);
  for (const Patch& p : scene.patches) ++patches_of[static_cast<std::size_t>(p.surface)];
  auto require_patches = [&](int surface, const FileLoc& loc, const std::string& key) {
    if (patches_of[static_cast<std::size_t>(surface)] == 0)
      throw ConfigError(located(loc, key + ": surface '" + scene.surfaces[static_cast<std::size_t>(surface)].name +
                                         "' has no patch left (left out by scene.exclude_surfaces or the room's surfaces, or every face "
                                         "degenerate)"));
  };
  for (std::size_t k = 0; k < spec.report_surfaces.size(); ++k) {
    const int s = scene.find_surface(spec.report_surfaces[k]);
    if (s < 0)
      throw ConfigError(located(spec.report_surface_locs[k], "report.surfaces: unknown surface '" +
                                                               spec.report_surfaces[k] + "'"));
    require_patches(s, spec.report_surface_locs[k], "report.surfaces");
  }
  // The inverse problem's surfaces: those of the mesh (a placed luminaire is no goal).
  for (const GoalSurfaces& g : spec.goals)
    for (const std::string& s : g.surfaces)
      require_patches(surfaces.require(s, g.loc, "goals." + g.name + ".surface"), g.loc, "goals." + g.name + ".surface");
  if (spec.search && !spec.search->suspended)
    surfaces.require(spec.search->mounting_surface, spec.search->mounting_loc, "luminaires.mounting_surface");
  if (spec.search && !spec.search->floor_surface.empty())
    surfaces.require(spec.search->floor_surface, spec.search->floor_loc, "luminaires.floor_surface");
}

// The scene's lines after it is meshed: the mesh, the split, what was left out or doubled.
void log_meshed(const SceneSpec& spec, const TriangleMesh& mesh, const SurfaceSplitReport& split,
                const TriangleEdits& edits, JobScene& out) {
  std::ostringstream os;
  os << "mesh " << spec.mesh_path << ": " << out.scene.stats << " (" << mesh.polygons_split
     << " polygons fan-triangulated), " << mesh.surface_names.size() << " surfaces";
  out.log.push_back(os.str());
  out.log.insert(out.log.end(), split.log.begin(), split.log.end());
  if (edits.excluded > 0 || !spec.exclude_surfaces.empty())
    out.log.push_back(std::string(spec.keep_surfaces.empty() ? "" : "the room's surfaces and ") + "scene.exclude_surfaces: " + std::to_string(edits.excluded) + " triangles of " +
                      std::to_string(spec.exclude_surfaces.size()) + " surfaces left out");
  if (edits.doubled > 0)
    out.log.push_back("scene.two_sided: " + std::to_string(edits.doubled) +
                      " triangles doubled back to back (both sides reflect; counted in the triangles above)");
}

// The scene's last line: patches, area, bounds, channels and what emits.
void log_sources(const SceneSpec& spec, JobScene& out) {
  const Scene& scene = out.scene;
  double luminaire_flux_lm = 0.0, surface_flux_lm = 0.0;
  for (const Patch& p : scene.patches)
    (scene.surfaces[p.surface].is_luminaire() ? luminaire_flux_lm : surface_flux_lm) += p.area_m2 * p.exitance_lm_per_m2;
  if (luminaire_flux_lm + surface_flux_lm == 0.0 && !spec.search)  // an inverse job places its own
    out.log.push_back("warning: nothing emits light, so every illuminance will be 0 lx "
                      "(add luminaires.placed or scene.emitting_surfaces)");
  std::ostringstream os;
  os.precision(3);
  os << std::fixed << "scene: " << scene.patches.size() << " patches, " << scene.total_area_m2() << " m2, bounds ["
     << scene.bounds_m.min().transpose() << "] .. [" << scene.bounds_m.max().transpose() << "] m, "
     << (scene.channels == 1 ? "gray (1 channel)" : "coloured (3 channels)") << ", " << spec.luminaires.size()
     << (spec.luminaires.size() == 1 ? " luminaire" : " luminaires") << "; emitted flux " << std::setprecision(0)
     << luminaire_flux_lm << " lm from luminaires, "
     << surface_flux_lm << " lm from emitting surfaces";
  out.log.push_back(os.str());
}

}  // namespace

// By stage: the mesh read and its frame, surfaces split, left out and doubled, floors
// added, reflectances, meshing, the job's own sources, the surfaces checked, the log.
JobScene load_job_scene(const SceneSpec& spec, TriangleMesh* mesh_out) {
  JobScene out;
  TriangleMesh mesh = read_job_mesh(spec, out.log);
  const SceneOptions frame = scene_frame(spec, mesh, out.log);
  out.frame = frame;
  const SurfaceSplitReport split = split_surfaces(mesh, frame, spec.surface_split);
  MeshSurfaces surfaces{{}, spec.mesh_path};
  for (std::size_t s = 0; s < mesh.surface_names.size(); ++s) surfaces.index[mesh.surface_names[s]] = static_cast<int>(s);
  const TriangleEdits edits = exclude_and_double(spec, surfaces, mesh);
  const std::vector<std::pair<int, Eigen::Vector3d>> added_rho = add_floors(spec, frame, surfaces, mesh, out.log);
  const TriangleReflectance rho = triangle_reflectance(spec, surfaces, mesh, added_rho);
  out.scene = mesh_scene(spec, mesh, rho, frame);
  log_meshed(spec, mesh, split, edits, out);
  place_job_sources(spec, surfaces, out);
  check_job_surfaces(spec, surfaces, out.scene);
  log_sources(spec, out);
  if (mesh_out) *mesh_out = std::move(mesh);
  return out;
}

// ---- The scene's inputs in the operator cache's key.

namespace {

namespace fs = std::filesystem;

// The words of an OBJ line up to a comment, as mesh_io.cpp splits them.
std::vector<std::string> obj_words(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  line = line.substr(0, line.find('#'));
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) out.emplace_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

struct HashStateDeleter {
  void operator()(XXH3_state_t* s) const { XXH3_freeState(s); }
};

// "<32 hex digits of XXH3-128> <bytes>" of the file's bytes, or "missing" /
// "unreadable". With `mtllibs`, also collects the names of the OBJ's mtllib
// statements in file order.
std::string file_digest(const fs::path& path, std::vector<std::string>* mtllibs) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "missing";
  std::unique_ptr<XXH3_state_t, HashStateDeleter> state(XXH3_createState());
  if (!state || XXH3_128bits_reset(state.get()) != XXH_OK) throw std::bad_alloc();
  std::vector<char> buffer(1 << 16);
  std::string pending;  // an OBJ line not yet ended
  std::uint64_t bytes = 0;
  auto scan = [&](std::string_view line) {
    const std::vector<std::string> words = obj_words(line);
    if (!words.empty() && words[0] == "mtllib") mtllibs->insert(mtllibs->end(), words.begin() + 1, words.end());
  };
  while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0) {
    const auto n = static_cast<std::size_t>(in.gcount());
    XXH3_128bits_update(state.get(), buffer.data(), n);
    bytes += n;
    if (mtllibs) {
      pending.append(buffer.data(), n);
      std::size_t start = 0, end;
      while ((end = pending.find('\n', start)) != std::string::npos) {
        scan(std::string_view(pending).substr(start, end - start));
        start = end + 1;
      }
      pending.erase(0, start);
    }
  }
  if (in.bad()) return "unreadable";
  if (mtllibs && !pending.empty()) scan(pending);
  XXH128_canonical_t digest;
  XXH128_canonicalFromHash(&digest, XXH3_128bits_digest(state.get()));
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  for (unsigned char b : digest.digest) {
    out += kDigits[b >> 4];
    out += kDigits[b & 15];
  }
  return out + " " + std::to_string(bytes);
}

// The external files a .gltf names ("uri": "..." that is no data: URI), in file order.
std::vector<std::string> gltf_uris(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> out;
  const std::string key = "\"uri\"";
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + key.size())) {
    std::size_t open = text.find_first_not_of(" \t\r\n", at + key.size());
    if (open == std::string::npos || text[open] != ':') continue;
    open = text.find_first_not_of(" \t\r\n", open + 1);
    if (open == std::string::npos || text[open] != '"') continue;
    const std::size_t close = text.find('"', open + 1);
    if (close == std::string::npos) break;
    std::string uri = text.substr(open + 1, close - open - 1);
    if (uri.rfind("data:", 0) != 0) out.push_back(std::move(uri));
  }
  return out;
}

}  // namespace

static_assert(field_count<ReflectanceSetting>() == 3, "ReflectanceSetting changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const ReflectanceSetting& r) {
  k.field("surface", r.surface).field("rgb", r.rgb);  // not loc
}

static_assert(field_count<FloorSetting>() == 6, "FloorSetting changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const FloorSetting& f) {
  k.field("name", f.name).field("lo", f.lo).field("hi", f.hi).field("z_m", f.z_m).field("rgb", f.rgb);  // not loc
}

static_assert(field_count<EmitterSetting>() == 3, "EmitterSetting changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const EmitterSetting& e) {
  k.field("surface", e.surface).field("exitance_lm_per_m2", e.exitance_lm_per_m2);  // not loc
}

static_assert(field_count<LuminaireSetting>() == 7, "LuminaireSetting changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const LuminaireSetting& l) {
  // Not loc, nor the product's name: its type (distribution, opening) is what lights the scene.
  k.field("name", l.name).field("position_m", l.position_m).field("flux_lm", l.flux_lm);
  k.field("rotation_deg", l.rotation_deg).field("type", l.type);
}

// Each SceneSpec field is a scene input below or named in the comment at the end (and
// each JobConfig field reaches the scene through SceneSpec or not at all: scene_spec).
static_assert(field_count<SceneSpec>() == 26,
              "SceneSpec changed: if load_job_scene reads the new field, hash it in hash_scene_inputs");
void hash_scene_inputs(KeyWriter& k, const SceneSpec& spec) {
  // The input files. The mesh's path does not matter, only its bytes and how it is
  // read: the extension picks the reader, and PLY/OFF name their surface after the stem.
  const fs::path mesh(spec.mesh_path);
  std::string ext = mesh.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  k.field("mesh_format", ext);
  if (ext != ".obj") k.field("mesh_stem", mesh.stem().string());
  std::vector<std::string> mtllibs;
  k.field("mesh_bytes", file_digest(mesh, ext == ".obj" ? &mtllibs : nullptr));
  k.field("mtllibs", mtllibs.size());
  for (const std::string& name : mtllibs)
    k.field("mtllib", name).field("mtllib_bytes", file_digest(mesh.parent_path() / name, nullptr));
  if (ext == ".gltf") {  // its buffers (and images) are files of their own
    const std::vector<std::string> uris = gltf_uris(mesh);
    k.field("gltf_uris", uris.size());
    for (const std::string& uri : uris)
      k.field("gltf_uri", uri).field("gltf_uri_bytes", file_digest(mesh.parent_path() / uri, nullptr));
  }
  // Set in the job, they override what an imported file states of its frame.
  k.field("up_axis_set", !spec.up_axis_loc.file.empty()).field("scale_to_m_set", !spec.scale_to_m_loc.file.empty());

  k.field("mesh_read", spec.mesh_read).field("scene", spec.scene).field("surface_split", spec.surface_split);
  k.field("reflectance", spec.reflectance);  // in file order: a later one wins
  k.field("default_reflectance", spec.default_reflectance);
  k.field("emitting_surfaces", spec.emitting_surfaces);
  k.field("add_floors", spec.add_floors);
  k.field("exclude_surfaces", spec.exclude_surfaces);
  std::vector<std::string> kept;
  for (const SurfacePattern& p : spec.keep_surfaces) kept.push_back(p.pattern);
  k.field("keep_surfaces", kept);
  k.field("two_sided_surfaces", spec.two_sided_surfaces).field("two_sided_all", spec.two_sided_all);
  k.field("luminaire_size_m", spec.luminaire_size_m).field("luminaires", spec.luminaires);
  k.field("ignore_material_kd", spec.ignore_material_kd);
  // Not scene inputs: path, mesh_loc, max_patch_edge_loc, (up_axis_loc and scale_to_m_loc
  // only as set or not, above), exclude_surface_locs, keep_surfaces' locs, two_sided_locs,
  // report_surfaces, report_surface_locs, goals and search (checked, never change the
  // scene).
}

}  // namespace ilp
