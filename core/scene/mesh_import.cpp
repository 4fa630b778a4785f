// assimp behind one file: the scene graph flattened to world triangles, names from
// nodes or materials, reflectances from colours where plausible, and what the file
// states of its units and up axis (mesh_import.h).
#include "core/scene/mesh_import.h"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string_view>
#include <map>
#include <sstream>
#include <utility>

#include "core/scene/scene.h"

namespace ilp {
namespace {

struct Placed {
  const aiNode* node = nullptr;
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();
};

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return out;
}

// Every node with meshes and its world transform, depth first in file order
// (an explicit stack: a damaged file's tree can be deep).
std::vector<Placed> nodes_with_meshes(const aiScene& scene) {
  std::vector<Placed> out, stack{{scene.mRootNode, to_eigen(scene.mRootNode->mTransformation)}};
  while (!stack.empty()) {
    const Placed p = stack.back();
    stack.pop_back();
    if (p.node->mNumMeshes > 0) out.push_back(p);
    for (unsigned c = p.node->mNumChildren; c-- > 0;) {
      const aiNode* child = p.node->mChildren[c];
      if (child) stack.push_back({child, p.world * to_eigen(child->mTransformation)});
    }
  }
  return out;
}

// A name assimp gives by type only, not the model's own.
bool generic_node_name(const std::string& name) {
  return name.empty() || name.front() == '$' || name == "IfcMappedItem" || name == "<3DSRoot>" || name == "ROOT";
}

// The node's surface name: its own, or its parent's for a generic name or for the only
// child of a node without meshes (a 3DS object under its hierarchy node).
std::string node_surface_name(const aiNode* node) {
  const aiNode* n = node;
  while (n->mParent && n->mParent->mParent &&
         (generic_node_name(n->mName.C_Str()) || (n->mParent->mNumChildren == 1 && n->mParent->mNumMeshes == 0)))
    n = n->mParent;
  const std::string name = n->mName.C_Str();
  return generic_node_name(name) ? std::string() : name;
}

std::string material_name(const aiMaterial& m) {
  aiString name;
  if (m.Get(AI_MATKEY_NAME, name) != AI_SUCCESS) return {};
  return name.C_Str();
}

std::string fmt_colour(const Eigen::Vector3d& c) {
  std::ostringstream os;
  os.precision(3);
  if (c[0] == c[1] && c[1] == c[2]) os << c[0];
  else os << "[" << c[0] << ", " << c[1] << ", " << c[2] << "]";
  return os.str();
}

// A material's reflectance where plausible, and what the log says of it.
struct MaterialReading {
  MeshMaterial material;
  std::string taken;      // "'wall' 0.42 (base colour)", or empty
  std::string not_taken;  // "'tiles' (textured)", or empty
  std::string translucent;
};

MaterialReading read_material(const aiMaterial& m, const std::string& path, unsigned index) {
  MaterialReading r;
  r.material.name = material_name(m);
  if (r.material.name.empty()) r.material.name = "material_" + std::to_string(index);
  r.material.kd_loc = FileLoc{path, 0, 0};
  const std::string quoted = "'" + r.material.name + "'";
  aiColor4D base;
  std::string source;
  Eigen::Vector3d colour;
  bool textured = false;
  if (m.Get(AI_MATKEY_BASE_COLOR, base) == AI_SUCCESS) {  // glTF's metallic-roughness
    float metallic = 0.0f;
    m.Get(AI_MATKEY_METALLIC_FACTOR, metallic);
    colour = Eigen::Vector3d(base.r, base.g, base.b) * (1.0 - std::clamp(static_cast<double>(metallic), 0.0, 1.0));
    source = metallic > 0.0f ? "base colour x (1 - metallic)" : "base colour";
    textured = m.GetTextureCount(aiTextureType_BASE_COLOR) > 0 || m.GetTextureCount(aiTextureType_DIFFUSE) > 0;
  } else {
    aiColor4D diffuse;
    if (m.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) != AI_SUCCESS) {
      r.not_taken = quoted + " (no colour)";
      return r;
    }
    colour = Eigen::Vector3d(diffuse.r, diffuse.g, diffuse.b);
    source = "diffuse colour";
    textured = m.GetTextureCount(aiTextureType_DIFFUSE) > 0;
  }
  float opacity = 1.0f;
  if (m.Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && opacity < 1.0f) {
    std::ostringstream os;
    os.precision(2);
    os << quoted << " (opacity " << opacity << ")";
    r.translucent = os.str();
  }
  if (r.material.name == AI_DEFAULT_MATERIAL_NAME) {  // assimp's own, for meshes without one
    r.not_taken = quoted + " (assimp's default, not the file's)";
  } else if (textured) {
    r.not_taken = quoted + " (textured: its " + source + " scales a texture)";
  } else if (!colour.allFinite() || (colour.array() < 0.0).any() || (colour.array() >= 1.0).any()) {
    r.not_taken = quoted + " (" + source + " " + fmt_colour(colour) + " is outside [0, 1))";
  } else {
    r.material.kd = colour;
    r.taken = quoted + " " + fmt_colour(colour);
  }
  return r;
}

// A list of up to `shown` items, then "and N more".
std::string listed(const std::vector<std::string>& items, std::size_t shown = 8) {
  std::string out;
  for (std::size_t k = 0; k < items.size() && k < shown; ++k) out += (k ? ", " : "") + items[k];
  if (items.size() > shown) out += " and " + std::to_string(items.size() - shown) + " more";
  return out;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// The start of a text file (at most `bytes`), to see what it declares.
std::string file_head(const std::string& path, std::size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string head(bytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(bytes));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return head;
}

// An IFC file's FILE_SCHEMA name ("IFC2X3", "IFC4"), or empty.
std::string ifc_schema(const std::string& path) {
  const std::string head = file_head(path, 1 << 14);
  const std::size_t at = head.find("FILE_SCHEMA");
  if (at == std::string::npos) return {};
  const std::size_t open = head.find('\'', at), close = open == std::string::npos ? open : head.find('\'', open + 1);
  if (close == std::string::npos || close - open > 40) return {};
  return head.substr(open + 1, close - open - 1);
}

// A rotation taking `up` (a unit axis vector) to +z, right-handed.
Eigen::Matrix3d rotation_to_z(const Eigen::Vector3d& up) {
  const Eigen::Vector3d e3 = up;
  const Eigen::Vector3d e1 = std::abs(up.x()) < 0.5 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e2 = e3.cross(e1);
  Eigen::Matrix3d r;
  r.row(0) = e1.transpose();
  r.row(1) = e2.transpose();
  r.row(2) = e3.transpose();
  return r;
}

// What the file states of its frame, and a correction of positions into it.
struct FrameReading {
  MeshFrame frame;
  Eigen::Matrix3d correction = Eigen::Matrix3d::Identity();  // applied after the node transforms
};

FrameReading read_frame(const aiScene& scene, const std::string& path, const std::string& ext) {
  FrameReading r;
  MeshFrame& f = r.frame;
  if (ext == ".gltf" || ext == ".glb") {
    f.scale_to_m = 1.0;
    f.up_axis = UpAxis::y;
    f.unit_note = "metres (glTF 2.0's specification)";
    f.up_note = "y up (glTF 2.0's specification)";
  } else if (ext == ".ifc") {
    f.scale_to_m = 1.0;
    f.up_axis = UpAxis::y;
    f.unit_note = "metres (the IFC file's length unit, applied by assimp)";
    f.up_note = "y up (IFC is z up; assimp turns it y up)";
  } else if (ext == ".dae") {
    // assimp applies <unit meter> and <up_axis>, COLLADA's defaults (1 m, Y_UP) where absent.
    const std::string head = file_head(path, 1 << 16);
    f.scale_to_m = 1.0;
    f.up_axis = UpAxis::y;
    f.unit_note = head.find("<unit") != std::string::npos ? "metres (the file's <unit>, applied by assimp)"
                                                          : "metres (no <unit>: COLLADA's default, 1 m)";
    f.up_note = head.find("<up_axis") != std::string::npos ? "y up (the file's <up_axis>, turned y up by assimp)"
                                                           : "y up (no <up_axis>: COLLADA's default, Y_UP)";
  } else if (ext == ".fbx") {
    const aiMetadata* meta = scene.mMetaData;
    double unit_cm = 0.0;
    float unit_cm_f = 0.0f;
    int up = -1, sign = 1;
    if (meta && meta->Get("UnitScaleFactor", unit_cm)) {
    } else if (meta && meta->Get("UnitScaleFactor", unit_cm_f)) {
      unit_cm = unit_cm_f;
    }
    if (std::isfinite(unit_cm) && unit_cm > 0.0) {
      f.scale_to_m = unit_cm / 100.0;
      std::ostringstream os;
      os << f.scale_to_m.value() << " m per unit (the file's UnitScaleFactor " << unit_cm << " cm)";
      f.unit_note = os.str();
    }
    if (meta && meta->Get("UpAxis", up) && up >= 0 && up <= 2) {
      meta->Get("UpAxisSign", sign);
      const char* axis_name[] = {"x", "y", "z"};
      const std::string stated = std::string(sign < 0 ? "-" : "+") + axis_name[up];
      if (up == 1 && sign > 0) {
        f.up_axis = UpAxis::y;
        f.up_note = "y up (the file's UpAxis)";
      } else if (up == 2 && sign > 0) {
        f.up_axis = UpAxis::z;
        f.up_note = "z up (the file's UpAxis)";
      } else {
        Eigen::Vector3d v = Eigen::Vector3d::Zero();
        v[up] = sign < 0 ? -1.0 : 1.0;
        r.correction = rotation_to_z(v);
        f.up_axis = UpAxis::z;
        f.up_note = "z up (the file's UpAxis is " + stated + "; turned to +z)";
      }
    }
  } else if (ext == ".3ds") {
    // assimp's 3DS loader turns the file's axes y up on its root node; undo it so the
    // positions are the file's, which states neither unit nor up axis.
    r.correction << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  }
  return r;
}

// assimp 5.2.5 dereferences a null pointer on a COLLADA array element without its
// count attribute (found by fuzz/import_fuzz.cpp): such a file is refused before it is
// handed over, naming the line.
void check_collada_arrays(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* tag : {"<float_array", "<int_array", "<Name_array", "<IDREF_array", "<bool_array", "<SIDREF_array",
                          "<token_array"}) {
    const std::string t(tag);
    for (std::size_t at = text.find(t); at != std::string::npos; at = text.find(t, at + t.size())) {
      const std::size_t end = text.find('>', at);
      const std::string_view element(text.data() + at, (end == std::string::npos ? text.size() : end) - at);
      const char next = at + t.size() < text.size() ? text[at + t.size()] : '>';
      if (!std::isspace(static_cast<unsigned char>(next)) && next != '>' && next != '/') continue;  // another tag
      if (element.find(" count=") != std::string_view::npos || element.find("\tcount=") != std::string_view::npos ||
          element.find("\ncount=") != std::string_view::npos)
        continue;
      const long line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n');
      throw SceneError(path + ":" + std::to_string(line) + ": " + t + "> without its count attribute (COLLADA requires "
                       "one; assimp 5.2.5 would crash reading the file)");
    }
  }
}

}  // namespace

bool is_imported_format(const std::string& ext) {
  return ext == ".gltf" || ext == ".glb" || ext == ".3ds" || ext == ".dae" || ext == ".fbx" || ext == ".ifc";
}

TriangleMesh load_with_assimp(const std::string& path, const std::string& ext_in, const MeshReadOptions& options) {
  const std::string ext = lower(ext_in);
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_IFC_SKIP_SPACE_REPRESENTATIONS, true);  // room volumes are no surfaces
  // No FindDegenerates: it turns zero-area triangles into points and lines, whose count
  // would be lost; they are dropped and counted below instead.
  const unsigned flags = aiProcess_Triangulate | aiProcess_ValidateDataStructure;
  if (ext == ".dae") check_collada_arrays(path);
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(path, flags);
  } catch (const std::bad_alloc&) {
    throw SceneError(path + ": out of memory reading the model");
  } catch (const std::exception& e) {
    throw SceneError(path + ": assimp cannot read it: " + e.what());
  }
  if (!scene) {
    std::string why = importer.GetErrorString();
    // assimp catches an allocation failure itself and says only this.
    if (why == "std::bad_alloc") throw SceneError(path + ": out of memory reading the model");
    if (ext == ".ifc") {
      const std::string schema = ifc_schema(path);
      if (!schema.empty() && lower(schema) != "ifc2x3")
        why += " (the file's schema is " + schema +
               "; assimp reads IFC2x3 only: export the model as IFC2x3 or glTF from the authoring tool)";
    }
    throw SceneError(path + ": assimp cannot read it: " + (why.empty() ? std::string("no reason given") : why));
  }
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)
    throw SceneError(path + ": assimp read an incomplete scene (no meshes could be built from the file)");
  if (!scene->mRootNode) throw SceneError(path + ": the model has no node tree");

  TriangleMesh mesh;
  mesh.path = path;
  const FrameReading frame = read_frame(*scene, path, ext);
  mesh.frame = frame.frame;

  // Materials (what the log says of them comes after the triangles: used ones only).
  std::vector<MaterialReading> readings;
  for (unsigned m = 0; m < scene->mNumMaterials; ++m) {
    readings.push_back(read_material(*scene->mMaterials[m], path, m));
    mesh.materials.push_back(readings.back().material);
  }

  // World triangles, node by node.
  std::map<std::string, int> surface_index;
  auto surface_of = [&](const std::string& name) {
    auto [it, inserted] = surface_index.emplace(name, static_cast<int>(mesh.surface_names.size()));
    if (inserted) mesh.surface_names.push_back(name);
    return it->second;
  };
  std::size_t points_lines = 0;
  for (const Placed& p : nodes_with_meshes(*scene)) {
    const Eigen::Matrix3d linear = frame.correction * p.world.topLeftCorner<3, 3>();
    const Eigen::Vector3d shift = frame.correction * p.world.topRightCorner<3, 1>();
    const bool mirrored = linear.determinant() < 0.0;
    const std::string node_name = node_surface_name(p.node);
    for (unsigned k = 0; k < p.node->mNumMeshes; ++k) {
      const unsigned mesh_index = p.node->mMeshes[k];
      if (mesh_index >= scene->mNumMeshes) continue;
      const aiMesh& am = *scene->mMeshes[mesh_index];
      const int material = am.mMaterialIndex < scene->mNumMaterials ? static_cast<int>(am.mMaterialIndex) : -1;
      const std::string material_label = material >= 0 ? mesh.materials[static_cast<std::size_t>(material)].name : "";
      std::string name = options.surface_naming == SurfaceNaming::material ? material_label : node_name;
      if (name.empty()) name = options.surface_naming == SurfaceNaming::material ? node_name : material_label;
      if (name.empty()) name = "default";
      const int base = static_cast<int>(mesh.positions.size());
      for (unsigned v = 0; v < am.mNumVertices; ++v) {
        const aiVector3D& a = am.mVertices[v];
        const Eigen::Vector3d q = linear * Eigen::Vector3d(a.x, a.y, a.z) + shift;
        if (!q.allFinite())
          throw SceneError(path + ": mesh " + std::to_string(mesh_index) + " vertex " + std::to_string(v) +
                           " has a non-finite coordinate");
        mesh.positions.push_back(q);
      }
      int surface = -1;
      for (unsigned f = 0; f < am.mNumFaces; ++f) {
        const aiFace& face = am.mFaces[f];
        ++mesh.faces_read;
        if (face.mNumIndices != 3) {
          ++points_lines;
          continue;
        }
        if (surface < 0) surface = surface_of(name);
        Eigen::Vector3i t(base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                          base + static_cast<int>(face.mIndices[2]));
        if (mirrored) std::swap(t[1], t[2]);
        mesh.triangles.push_back(t);
        mesh.triangle_surface.push_back(surface);
        mesh.triangle_material.push_back(material);
      }
    }
  }
  if (mesh.triangles.empty())
    throw SceneError(path + ": the model has no triangles (" + std::to_string(scene->mNumMeshes) + " meshes" +
                     (points_lines ? ", " + std::to_string(points_lines) + " points and lines only" : std::string()) +
                     ")");

  // Zero-area triangles, by make_scene's rule (scene.h) over the model's bounds.
  Eigen::AlignedBox3d bounds;
  for (const Eigen::Vector3d& q : mesh.positions) bounds.extend(q);
  const double diagonal2 = bounds.diagonal().squaredNorm();
  std::size_t kept = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    const Eigen::Vector3d& a = mesh.positions[static_cast<std::size_t>(tri[0])];
    const double doubled_area =
        (mesh.positions[static_cast<std::size_t>(tri[1])] - a).cross(mesh.positions[static_cast<std::size_t>(tri[2])] - a).norm();
    if (!(doubled_area > kDegenerateRelArea * diagonal2)) continue;
    mesh.triangles[kept] = tri;
    mesh.triangle_surface[kept] = mesh.triangle_surface[t];
    mesh.triangle_material[kept] = mesh.triangle_material[t];
    ++kept;
  }
  mesh.zero_area_dropped = mesh.triangles.size() - kept;
  mesh.triangles.resize(kept);
  mesh.triangle_surface.resize(kept);
  mesh.triangle_material.resize(kept);
  if (mesh.triangles.empty())
    throw SceneError(path + ": the model has no triangles of non-zero area (all " +
                     std::to_string(mesh.zero_area_dropped) + " have zero area)");

  // Each used material's reading once (an IFC file repeats a style per element).
  std::vector<bool> used(mesh.materials.size(), false);
  for (int m : mesh.triangle_material)
    if (m >= 0) used[static_cast<std::size_t>(m)] = true;
  std::vector<std::string> taken, not_taken, translucent;
  auto add_once = [](std::vector<std::string>& list, const std::string& item) {
    if (!item.empty() && std::find(list.begin(), list.end(), item) == list.end()) list.push_back(item);
  };
  for (std::size_t m = 0; m < readings.size(); ++m) {
    if (!used[m]) continue;
    add_once(taken, readings[m].taken);
    add_once(not_taken, readings[m].not_taken);
    add_once(translucent, readings[m].translucent);
  }

  std::ostringstream os;
  os << "assimp read " << mesh.triangles.size() << " triangles in " << mesh.surface_names.size() << " surfaces ("
     << (options.surface_naming == SurfaceNaming::material ? "named by material" : "named by node") << ")";
  if (mesh.zero_area_dropped) os << "; " << mesh.zero_area_dropped << " zero-area triangles dropped";
  if (points_lines) os << "; " << points_lines << " point and line primitives ignored";
  mesh.notes.push_back(os.str());
  if (!taken.empty()) mesh.notes.push_back("reflectance from the materials' colour: " + listed(taken));
  if (!not_taken.empty()) mesh.notes.push_back("no reflectance taken from " + listed(not_taken));
  if (!translucent.empty())
    mesh.notes.push_back("translucent materials treated as opaque (ilp does not model transmission): " +
                         listed(translucent));
  return mesh;
}

}  // namespace ilp
