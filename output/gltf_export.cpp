// The scene coloured by illuminance as binary glTF 2.0 (.glb), written with
// nlohmann-json: a node per surface, a node per luminaire, one binary buffer.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/atomic_file.h"
#include "output/layout_export.h"

namespace ilp {
namespace {

using json = nlohmann::ordered_json;

constexpr std::uint32_t kFloat = 5126;       // glTF componentType FLOAT
constexpr std::uint32_t kArrayBuffer = 34962;

// glTF is y up: the scene's (x, y, z) is glTF's (x, z, -y).
Eigen::Vector3f to_gltf(const Eigen::Vector3d& p) {
  return Eigen::Vector3f(static_cast<float>(p.x()), static_cast<float>(p.z()), static_cast<float>(-p.y()));
}

// sRGB (the colour map's) to the linear values glTF's COLOR_0 holds.
float linear_from_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

// The binary buffer and the JSON that describes it, built up mesh by mesh.
class GltfBuilder {
 public:
  // Adds float VEC3 data as an accessor (its own buffer view); returns its index.
  int add_vec3(const std::vector<Eigen::Vector3f>& values, bool with_bounds) {
    const std::size_t offset = bin_.size();
    bin_.resize(offset + values.size() * 12);
    for (std::size_t k = 0; k < values.size(); ++k) std::memcpy(bin_.data() + offset + 12 * k, values[k].data(), 12);
    views_.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * 12}, {"target", kArrayBuffer}});
    json accessor = {{"bufferView", views_.size() - 1}, {"componentType", kFloat}, {"count", values.size()}, {"type", "VEC3"}};
    if (with_bounds) {  // POSITION must carry min and max
      Eigen::Vector3f lo = values.front(), hi = values.front();
      for (const Eigen::Vector3f& v : values) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      accessor["min"] = {lo.x(), lo.y(), lo.z()};
      accessor["max"] = {hi.x(), hi.y(), hi.z()};
    }
    accessors_.push_back(std::move(accessor));
    return static_cast<int>(accessors_.size()) - 1;
  }

  // A node named `name` with one mesh of triangles (3 positions each), optional colours.
  void add_node(const std::string& name, const std::vector<Eigen::Vector3f>& positions,
                const std::vector<Eigen::Vector3f>* colours, int material) {
    json attributes = {{"POSITION", add_vec3(positions, true)}};
    if (colours) attributes["COLOR_0"] = add_vec3(*colours, false);
    meshes_.push_back({{"name", name}, {"primitives", json::array({{{"attributes", attributes}, {"material", material}}})}});
    nodes_.push_back({{"name", name}, {"mesh", meshes_.size() - 1}});
  }

  std::string glb(const json& materials, bool unlit_used) const {
    json j;
    j["asset"] = {{"version", "2.0"}, {"generator", "ilp"}};
    if (unlit_used) j["extensionsUsed"] = {"KHR_materials_unlit"};
    j["scene"] = 0;
    json roots = json::array();
    for (std::size_t k = 0; k < nodes_.size(); ++k) roots.push_back(k);
    j["scenes"] = json::array({{{"name", "ilp"}, {"nodes", roots}}});
    j["nodes"] = nodes_;
    j["meshes"] = meshes_;
    j["materials"] = materials;
    j["accessors"] = accessors_;
    j["bufferViews"] = views_;
    j["buffers"] = json::array({{{"byteLength", bin_.size()}}});
    std::string text = j.dump();
    while (text.size() % 4) text += ' ';
    std::string bin(bin_.begin(), bin_.end());
    while (bin.size() % 4) bin += '\0';
    std::string out;
    auto u32 = [&](std::uint32_t v) {
      for (int b = 0; b < 4; ++b) out += static_cast<char>((v >> (8 * b)) & 0xff);
    };
    u32(0x46546C67);  // "glTF"
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    u32(static_cast<std::uint32_t>(text.size()));
    u32(0x4E4F534A);  // "JSON"
    out += text;
    u32(static_cast<std::uint32_t>(bin.size()));
    u32(0x004E4942);  // "BIN\0"
    out += bin;
    return out;
  }

 private:
  std::vector<unsigned char> bin_;
  json views_ = json::array(), accessors_ = json::array(), meshes_ = json::array(), nodes_ = json::array();
};

}  // namespace

void write_illuminance_gltf(const std::string& path, const Scene& scene, const Eigen::VectorXd& lux_per_patch,
                            const ColourScale& scale, const std::vector<ExportLuminaire>& luminaires) {
  if (lux_per_patch.size() != static_cast<Eigen::Index>(scene.patches.size()))
    throw std::invalid_argument("write_illuminance_gltf: " + std::to_string(lux_per_patch.size()) + " lux values for " +
                                std::to_string(scene.patches.size()) + " patches");
  GltfBuilder b;
  // Material 0: the surfaces, coloured per vertex and unlit (the colour is the value);
  // material 1: the luminaires' openings, emissive white.
  const json materials = json::array(
      {{{"name", "illuminance"},
        {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
        {"extensions", {{"KHR_materials_unlit", json::object()}}}},
       {{"name", "luminaire"},
        {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
        {"emissiveFactor", {1.0, 1.0, 1.0}},
        {"doubleSided", true}}});
  std::vector<std::vector<std::size_t>> patches_of(scene.surfaces.size());
  for (std::size_t i = 0; i < scene.patches.size(); ++i) patches_of[static_cast<std::size_t>(scene.patches[i].surface)].push_back(i);
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) {
    if (patches_of[s].empty() || scene.surfaces[s].is_luminaire() || scene.surfaces[s].is_virtual) continue;
    std::vector<Eigen::Vector3f> positions, colours;
    for (std::size_t i : patches_of[s]) {
      const Eigen::Vector3d srgb = colour_map(scale.fraction(lux_per_patch[static_cast<Eigen::Index>(i)]));
      const Eigen::Vector3f linear(linear_from_srgb(srgb[0]), linear_from_srgb(srgb[1]), linear_from_srgb(srgb[2]));
      for (const Eigen::Vector3d& v : scene.patches[i].vertices_m) {
        positions.push_back(to_gltf(v));
        colours.push_back(linear);
      }
    }
    b.add_node(scene.surfaces[s].name, positions, &colours, 0);
  }
  for (const ExportLuminaire& l : luminaires) {
    const std::vector<Eigen::Vector3d> outline = luminaire_outline_m(l.type, l.placement);
    std::vector<Eigen::Vector3f> positions;
    for (std::size_t k = 1; k + 1 < outline.size(); ++k)  // a fan facing the aim (the outline reversed)
      for (const Eigen::Vector3d& v : {outline[0], outline[k + 1], outline[k]}) positions.push_back(to_gltf(v));
    b.add_node(l.id, positions, nullptr, 1);
  }
  const std::string glb = b.glb(materials, true);
  write_file_atomically(path, [&](std::ostream& out) { out.write(glb.data(), static_cast<std::streamsize>(glb.size())); });
}

}  // namespace ilp
