// OBJ/MTL are parsed here because OpenMesh's OBJ reader drops the group, object and
// material tags that name our surfaces; PLY and OFF go through OpenMesh.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/scene/mesh.h"
#include "core/scene/mesh_import.h"
#include "core/base/key_hash.h"

namespace ilp {
namespace {

namespace fs = std::filesystem;

// Splits at white space only. PLY and OFF have no comments: OpenMesh reads a '#' as part
// of a word ("end_header#" made its header parser loop for ever; found by ply_off_fuzz).
std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

// Splits at white space, ignoring everything from a '#' on (a comment): OBJ and MTL.
std::vector<std::string_view> split_ws(std::string_view line) { return split_words(line.substr(0, line.find('#'))); }

// The text after `keyword` up to a comment, trimmed: names may contain spaces.
std::string rest_of_line(std::string_view line, std::string_view keyword) {
  line = line.substr(0, line.find('#'));
  std::string_view s = line.substr(line.find(keyword) + keyword.size());
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

double parse_finite(std::string_view token, const FileLoc& loc, const char* what) {
  double value = 0.0;
  const char* first = token.data();
  if (!token.empty() && token.front() == '+') ++first;
  auto [end, ec] = std::from_chars(first, token.data() + token.size(), value);
  if (ec == std::errc::result_out_of_range)
    throw SceneError(located(loc, std::string(what) + " '" + std::string(token) + "' is out of range"));
  if (ec != std::errc() || end != token.data() + token.size())
    throw SceneError(located(loc, std::string(what) + " '" + std::string(token) + "' is not a number"));
  if (!std::isfinite(value))
    throw SceneError(located(loc, std::string(what) + " '" + std::string(token) + "' is not a finite number"));
  return value;
}

// A UTF-8 byte order mark (some Windows exporters write one) is not part of the first line.
void strip_bom(std::string& line, int line_no) {
  if (line_no == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
}

std::vector<MeshMaterial> load_mtl(const fs::path& path, const FileLoc& referenced_from) {
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw SceneError(located(referenced_from, "mtllib: '" + path.string() + "' is a folder, not a material file"));
  if (const std::string why = not_a_regular_file(path.string(), "material"); !why.empty())
    throw SceneError(located(referenced_from, "mtllib: " + why));
  std::ifstream in(path);
  if (!in) throw SceneError(located(referenced_from, "mtllib: cannot open material file '" + path.string() + "'"));
  std::vector<MeshMaterial> materials;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    strip_bom(line, line_no);
    auto tokens = split_ws(line);
    if (tokens.empty()) continue;
    const FileLoc loc{path.string(), line_no};
    if (tokens[0] == "newmtl") {
      if (tokens.size() < 2) throw SceneError(located(loc, "newmtl without a name"));
      materials.push_back({rest_of_line(line, "newmtl"), std::nullopt, {}});
    } else if (tokens[0] == "Kd") {
      if (materials.empty()) throw SceneError(located(loc, "Kd before any newmtl"));
      if (tokens.size() >= 2 && (tokens[1] == "spectral" || tokens[1] == "xyz")) continue;  // config must give it
      if (tokens.size() != 2 && tokens.size() != 4)
        throw SceneError(located(loc, "Kd needs 1 or 3 values, found " + std::to_string(tokens.size() - 1)));
      Eigen::Vector3d kd;
      kd.setConstant(parse_finite(tokens[1], loc, "Kd value"));
      if (tokens.size() >= 4)
        for (int c = 1; c < 3; ++c) kd[c] = parse_finite(tokens[1 + c], loc, "Kd value");
      materials.back().kd = kd;
      materials.back().kd_loc = loc;
    }
  }
  return materials;
}

// Resolves an OBJ vertex reference ("7", "7/2", "-1//3") to a 0-based index.
int parse_vertex_ref(std::string_view token, std::size_t vertex_count, const FileLoc& loc) {
  std::string_view head = token.substr(0, token.find('/'));
  long index = 0;
  auto [end, ec] = std::from_chars(head.data(), head.data() + head.size(), index);
  if (ec != std::errc() || end != head.data() + head.size() || index == 0)
    throw SceneError(located(loc, "face vertex '" + std::string(token) + "' is not a valid index"));
  long resolved = index > 0 ? index - 1 : static_cast<long>(vertex_count) + index;
  if (resolved < 0 || resolved >= static_cast<long>(vertex_count))
    throw SceneError(located(loc, "face vertex '" + std::string(token) + "' refers to vertex " +
                                      std::to_string(index) + " but only " + std::to_string(vertex_count) +
                                      " are defined above this line"));
  return static_cast<int>(resolved);
}

TriangleMesh load_obj(const fs::path& path, const MeshReadOptions& options) {
  std::ifstream in(path);
  if (!in) throw SceneError(path.string() + ": cannot open mesh file");
  TriangleMesh mesh;
  mesh.path = path.string();
  std::map<std::string, int> surface_index, material_index;
  std::string group, object, material;
  int current_material = -1;
  std::string line;
  int line_no = 0;

  auto surface_for_face = [&]() {
    const std::string* tags[3] = {&group, &object, &material};
    int first = static_cast<int>(options.surface_naming);
    std::string name = "default";
    for (int k = first; k < 3; ++k)
      if (!tags[k]->empty()) { name = *tags[k]; break; }
    auto [it, inserted] = surface_index.emplace(name, static_cast<int>(mesh.surface_names.size()));
    if (inserted) mesh.surface_names.push_back(name);
    return it->second;
  };

  while (std::getline(in, line)) {
    ++line_no;
    strip_bom(line, line_no);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    auto tokens = split_ws(line);
    if (tokens.empty()) continue;
    const FileLoc loc{mesh.path, line_no};
    const std::string_view key = tokens[0];
    if (key == "v") {
      if (tokens.size() < 4) throw SceneError(located(loc, "vertex needs 3 coordinates"));
      mesh.positions.emplace_back(parse_finite(tokens[1], loc, "vertex coordinate"),
                                  parse_finite(tokens[2], loc, "vertex coordinate"),
                                  parse_finite(tokens[3], loc, "vertex coordinate"));
    } else if (key == "f") {
      if (tokens.size() < 4) throw SceneError(located(loc, "face needs at least 3 vertices"));
      std::vector<int> ids;
      for (std::size_t k = 1; k < tokens.size(); ++k)
        ids.push_back(parse_vertex_ref(tokens[k], mesh.positions.size(), loc));
      const int surface = surface_for_face();
      ++mesh.faces_read;
      if (ids.size() > 3) ++mesh.polygons_split;
      for (std::size_t k = 1; k + 1 < ids.size(); ++k) {  // fan triangulation
        mesh.triangles.emplace_back(ids[0], ids[k], ids[k + 1]);
        mesh.triangle_surface.push_back(surface);
        mesh.triangle_material.push_back(current_material);
      }
    } else if (key == "g") {
      group = rest_of_line(line, "g");
    } else if (key == "o") {
      object = rest_of_line(line, "o");
    } else if (key == "usemtl") {
      material = rest_of_line(line, "usemtl");
      auto [it, inserted] = material_index.emplace(material, static_cast<int>(mesh.materials.size()));
      if (inserted) mesh.materials.push_back({material, std::nullopt, {}});
      current_material = it->second;
    } else if (key == "mtllib") {
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        for (MeshMaterial& m : load_mtl(path.parent_path() / std::string(tokens[k]), loc)) {
          auto [it, inserted] = material_index.emplace(m.name, static_cast<int>(mesh.materials.size()));
          if (inserted) mesh.materials.push_back(m);
          else if (!mesh.materials[it->second].kd) mesh.materials[it->second] = m;
        }
      }
    }
    // vn, vt, s, l, p and other statements carry nothing radiosity uses.
  }
  return mesh;
}

struct DeclaredCounts {
  long long vertices = -1, faces = -1;  // -1: not known (unusual header)
};

// A count from a header: a whole number >= 0 and at most the file's size in bytes
// (every element takes at least a byte), checked before anything is allocated.
long long header_count(std::string_view token, const std::string& what, const fs::path& path, int line,
                       std::uintmax_t file_bytes) {
  long long count = -1;
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), count);
  if (ec != std::errc() || end != token.data() + token.size() || count < 0)
    throw SceneError(located({path.string(), line}, "the header's " + what + " count '" + std::string(token) +
                                                        "' is not a whole number >= 0"));
  if (static_cast<std::uintmax_t>(count) > file_bytes)
    throw SceneError(located({path.string(), line}, "the header declares " + std::string(token) + " " + what +
                                                        "s but the file holds only " + std::to_string(file_bytes) +
                                                        " bytes (a damaged or truncated file)"));
  return count;
}

std::size_t ply_type_bytes(std::string_view type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

// A whole number >= 0 spelled by all of `token` (no sign, no fraction, no trailing text).
bool whole_number(std::string_view token, long long& out) {
  out = -1;
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && end == token.data() + token.size() && out >= 0;
}

bool ply_integer_type(std::string_view type) {
  return ply_type_bytes(type) > 0 && type != "float" && type != "float32" && type != "double" && type != "float64";
}

bool ply_signed_type(std::string_view type) {
  return type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" || type == "int32";
}

// PLY. OpenMesh parses the header word by word and the ASCII body number by number (a
// line ending means nothing to it), so any word it reads where this check expects
// another shifts the rest of the file and a value becomes a face's vertex count (up to
// 4e9: a loop that fills memory). The header is therefore held to a layout where the two
// readings agree: one statement a line, end_header alone, lists only where OpenMesh reads
// them (a face's vertex_indices first, then texcoord), one vertex and one face element.
// Then the body: ASCII, one line per element with the values its properties call for;
// binary, walked the way OpenMesh walks it, each list count within the bytes that follow.
struct PlyProperty {
  bool list = false;
  std::string type, count_type;  // count_type: lists only
};

struct PlyElement {
  std::string name;
  long long count = 0;
  int line = 0;
  std::vector<PlyProperty> properties;
};

// What the PLY header declares and where OpenMesh and this check stand after it.
struct PlyHeader {
  DeclaredCounts counts;
  std::string format;
  std::vector<PlyElement> elements;
  int first_face = -1;               // index of the face element, -1 if none
  int line_no = 0;                   // the end_header line
  std::uintmax_t openmesh_pos = 0;   // where OpenMesh's header parser stands before it reads end_header
  std::uintmax_t header_end = 0;     // the byte after the end_header line
};

// Reads the header up to end_header, held to the layout described above check_ply.
PlyHeader read_ply_header(std::ifstream& in, const fs::path& path, std::uintmax_t file_bytes) {
  PlyHeader h;
  std::string line;
  bool ended = false;
  std::uintmax_t offset = 0;  // where the next line starts
  while (std::getline(in, line)) {
    const std::uintmax_t line_start = offset;
    offset += line.size() + (in.eof() ? 0 : 1);
    ++h.line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto tokens = split_words(line);
    const FileLoc loc{path.string(), h.line_no};
    if (h.line_no == 1) {
      if (tokens.size() != 1 || tokens[0] != "ply")
        throw SceneError(path.string() + ": could not read the mesh: not a PLY file (no 'ply' on the first line)");
      continue;
    }
    if (tokens.empty()) continue;
    const std::string_view key = tokens[0];
    if (key == "comment") {  // OpenMesh reads the rest of the line
      h.openmesh_pos = offset;
      continue;
    }
    if (key == "end_header") {
      if (tokens.size() != 1) throw SceneError(located(loc, "end_header must stand alone on its line"));
      ended = true;
      h.header_end = offset;
      break;
    }
    if (key == "format") {
      if (!h.format.empty() || tokens.size() != 3 || tokens[2] != "1.0" ||
          (tokens[1] != "ascii" && tokens[1] != "binary_little_endian" && tokens[1] != "binary_big_endian"))
        throw SceneError(located(loc, "format must be ascii, binary_little_endian or binary_big_endian, then a version"));
      h.format = std::string(tokens[1]);
    } else if (h.format.empty()) {
      throw SceneError(located(loc, "the format line must follow the 'ply' line"));
    } else if (key == "element") {
      if (tokens.size() != 3) throw SceneError(located(loc, "element needs a name and a count"));
      PlyElement e{std::string(tokens[1]), header_count(tokens[2], std::string(tokens[1]), path, h.line_no, file_bytes),
                   h.line_no, {}};
      if ((e.name == "vertex" && h.counts.vertices >= 0) || (e.name == "face" && h.counts.faces >= 0))
        throw SceneError(located(loc, "a second '" + e.name + "' element (OpenMesh would read the first with the count of the second)"));
      if (e.name == "vertex") h.counts.vertices = e.count;
      if (e.name == "face") {
        h.counts.faces = e.count;
        h.first_face = static_cast<int>(h.elements.size());
      }
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      const bool list = tokens.size() >= 2 && tokens[1] == "list";
      if (h.elements.empty() || tokens.size() != (list ? 5u : 3u) || ply_type_bytes(tokens[list ? 2 : 1]) == 0 ||
          (list && ply_type_bytes(tokens[3]) == 0))
        throw SceneError(located(loc, "property must follow an element and be 'property TYPE NAME' or 'property list "
                                      "COUNT_TYPE TYPE NAME' with PLY types (char, uchar, short, ..., float, double)"));
      PlyElement& e = h.elements.back();
      // Elements after the first face element are not read by OpenMesh: any list will do there.
      const bool read_by_openmesh = h.first_face < 0 || static_cast<int>(h.elements.size()) - 1 <= h.first_face;
      if (list && read_by_openmesh) {
        const std::string_view name = tokens[4];
        const bool indices = name == "vertex_indices" || name == "vertex_index";
        if (e.name != "face" || (!indices && name != "texcoord"))
          throw SceneError(located(loc, "list property '" + std::string(name) + "' of element '" + e.name +
                                            "': only a face's vertex_indices and texcoord lists are read (OpenMesh "
                                            "would misread the rest of the file)"));
        if (indices && !e.properties.empty())
          throw SceneError(located(loc, "vertex_indices must be the face element's first property (OpenMesh drops "
                                        "the properties before it and misreads the faces)"));
      }
      if (list && !ply_integer_type(tokens[2]))
        throw SceneError(located(loc, "a list's count type must be an integer type, not '" + std::string(tokens[2]) + "'"));
      // A binary body's coordinates and normals are read as 4-byte floats whatever their
      // type says, so another type shifts every later value: a face's vertex count became
      // 2^31 - 1 and filled memory (found by ply_off_fuzz).
      const std::string_view name = tokens[list ? 4 : 2], type = tokens[1];
      const bool read_as_float = name == "x" || name == "y" || name == "z" || name == "nx" || name == "ny" || name == "nz";
      if (!list && e.name == "vertex" && read_as_float && h.format != "ascii" && type != "float" && type != "float32")
        throw SceneError(located(loc, "vertex property '" + std::string(name) + "' is '" + std::string(type) +
                                          "': a binary PLY's coordinates and normals are read as float (float32) only "
                                          "(convert the file, or write it as ASCII PLY)"));
      e.properties.push_back({list, std::string(tokens[list ? 3 : 1]), list ? std::string(tokens[2]) : std::string()});
    } else if (key == "obj_info") {
      // OpenMesh reads each word after obj_info as a header keyword.
      for (std::size_t k = 1; k < tokens.size(); ++k)
        if (tokens[k] == "element" || tokens[k] == "property" || tokens[k] == "end_header" || tokens[k] == "comment")
          throw SceneError(located(loc, "obj_info holds the header keyword '" + std::string(tokens[k]) +
                                            "' (OpenMesh would read it as one)"));
    } else {
      throw SceneError(located(loc, "unknown PLY header keyword '" + std::string(key) + "'"));
    }
    h.openmesh_pos = line_start + static_cast<std::uintmax_t>(tokens.back().data() + tokens.back().size() - line.data());
  }
  if (!ended) throw SceneError(path.string() + ": the PLY header has no end_header (a truncated or damaged file)");
  if (h.format.empty()) throw SceneError(path.string() + ": the PLY header has no format line");
  return h;
}

// A binary body, walked the way OpenMesh walks it, each list count within the bytes that follow.
void check_ply_binary_body(std::ifstream& in, const fs::path& path, std::uintmax_t file_bytes, const PlyHeader& h) {
  long double need = 0;
  for (const PlyElement& e : h.elements) {
    std::size_t bytes = 0;
    for (const PlyProperty& p : e.properties) bytes += ply_type_bytes(p.list ? p.count_type : p.type);
    need += static_cast<long double>(e.count) * static_cast<long double>(bytes);
  }
  const std::uintmax_t body = file_bytes > h.header_end ? file_bytes - h.header_end : 0;
  if (need > static_cast<long double>(body))
    throw SceneError(path.string() + ": the header declares elements needing at least " +
                     std::to_string(static_cast<unsigned long long>(need)) + " bytes but only " +
                     std::to_string(body) + " follow it (truncated?)");
  // OpenMesh finds the binary body 12 bytes ("\nend_header\n", 14 with "\r\n") past the
  // end of the last header statement: anything else there and it reads from the wrong byte.
  std::ifstream at(path, std::ios::binary);
  at.seekg(static_cast<std::streamoff>(h.openmesh_pos));
  char c1 = 0, c2 = 0;
  at.get(c1);
  at.get(c2);
  if (h.openmesh_pos + (c1 == '\r' && c2 == '\n' ? 14 : 12) != h.header_end)
    throw SceneError(path.string() + ": a binary PLY's end_header must directly follow the last element or "
                                     "property line (no comment, blank line or trailing space before or after it)");
  in.clear();
  in.seekg(static_cast<std::streamoff>(h.header_end));
  const bool little = h.format == "binary_little_endian";
  std::uintmax_t left = body;
  for (std::size_t ei = 0; ei < h.elements.size(); ++ei) {
    const PlyElement& e = h.elements[ei];
    if (h.first_face >= 0 && static_cast<int>(ei) > h.first_face) break;  // OpenMesh stops after the faces
    bool has_list = false;
    std::uintmax_t row = 0;
    for (const PlyProperty& p : e.properties) {
      has_list = has_list || p.list;
      row += ply_type_bytes(p.type);
    }
    if (!has_list) {
      const std::uintmax_t bytes = static_cast<std::uintmax_t>(e.count) * row;  // <= need <= body
      in.ignore(static_cast<std::streamsize>(bytes));
      left -= bytes;
      continue;
    }
    for (long long k = 0; k < e.count; ++k)
      for (const PlyProperty& p : e.properties) {
        const std::size_t count_bytes = p.list ? ply_type_bytes(p.count_type) : 0;
        const std::size_t value_bytes = ply_type_bytes(p.type);
        if (left < (p.list ? count_bytes : value_bytes))
          throw SceneError(path.string() + ": the file ends in " + e.name + " " + std::to_string(k) + " of the " +
                           std::to_string(e.count) + " its header declares (truncated?)");
        if (!p.list) {
          in.ignore(static_cast<std::streamsize>(value_bytes));
          left -= value_bytes;
          continue;
        }
        unsigned char b[8] = {};
        in.read(reinterpret_cast<char*>(b), static_cast<std::streamsize>(count_bytes));
        left -= count_bytes;
        unsigned long long u = 0;
        for (std::size_t i = 0; i < count_bytes; ++i)
          u |= static_cast<unsigned long long>(b[little ? i : count_bytes - 1 - i]) << (8 * i);
        long long n = static_cast<long long>(u);
        if (ply_signed_type(p.count_type) && (u >> (8 * count_bytes - 1)) != 0)
          n = static_cast<long long>(u) - (1LL << (8 * count_bytes));
        if (n < 0 || static_cast<unsigned long long>(n) * value_bytes > left)
          throw SceneError(path.string() + ": " + e.name + " " + std::to_string(k) + " has a list of " +
                           std::to_string(n) + " values, more than the " + std::to_string(left) +
                           " bytes left in the file (a damaged or truncated file)");
        in.ignore(static_cast<std::streamsize>(static_cast<unsigned long long>(n) * value_bytes));
        left -= static_cast<std::uintmax_t>(n) * value_bytes;
      }
  }
}

// An ASCII body: one line per element with the values its properties call for.
void check_ply_ascii_body(std::ifstream& in, const fs::path& path, const PlyHeader& h) {
  std::string line;
  int line_no = h.line_no;
  for (const PlyElement& e : h.elements)
    for (long long k = 0; k < e.count; ++k) {
      std::vector<std::string_view> tokens;
      while (tokens.empty()) {
        if (!std::getline(in, line))
          throw SceneError(located({path.string(), line_no}, "the file ends after " + std::to_string(k) + " of the " +
                                                                 std::to_string(e.count) + " " + e.name +
                                                                 " lines its header declares (truncated?)"));
        ++line_no;
        tokens = split_words(line);
      }
      std::size_t at = 0;
      for (const PlyProperty& p : e.properties) {
        if (!p.list) {
          ++at;
          continue;
        }
        long long n = -1;
        if (at >= tokens.size() || !whole_number(tokens[at], n) || n > static_cast<long long>(tokens.size()))
          throw SceneError(located({path.string(), line_no}, e.name + " " + std::to_string(k) +
                                                                 ": the list count is missing or not a whole number"));
        at += 1 + static_cast<std::size_t>(n);
      }
      if (tokens.size() != at)
        throw SceneError(located({path.string(), line_no}, e.name + " " + std::to_string(k) + " has " +
                                                               std::to_string(tokens.size()) + " values, its header's properties call for " +
                                                               std::to_string(at) + " (truncated or damaged line)"));
    }
}

DeclaredCounts check_ply(const fs::path& path, std::uintmax_t file_bytes) {
  std::ifstream in(path, std::ios::binary);
  const PlyHeader header = read_ply_header(in, path, file_bytes);
  if (header.format != "ascii") {
    check_ply_binary_body(in, path, file_bytes, header);
  } else {
    check_ply_ascii_body(in, path, header);
  }
  return header.counts;
}

// OFF. OpenMesh reads the keyword line, then the counts and every value number by number
// (line endings mean nothing to it), except that after a vertex's coordinates (and a
// face's indices with a C prefix) it drops the rest of the line. A vertex line short of
// values or a face line with values beyond its count shifts the rest of the file, and
// a coordinate becomes a face's vertex count (up to 4e9: a loop that fills memory). So:
// the keyword alone on line 1, the three counts alone on the next line, each vertex line
// with its coordinates (and normal, N prefix), each face line with exactly its count of
// indices (at least, with C), every index a vertex's.
DeclaredCounts check_off(const fs::path& path, std::uintmax_t file_bytes) {
  DeclaredCounts out;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  int line_no = 0;
  if (!std::getline(in, line)) return out;  // an empty file: OpenMesh says it cannot read it
  line_no = 1;
  int vertex_values = 3;      // coordinates, and a normal with the N prefix
  bool face_colours = false;  // C prefix: OpenMesh drops the rest of a face line
  {
    const auto keyword = split_words(line);
    if (keyword.size() >= 2 && keyword[1] == "BINARY")  // its counts cannot be checked as text
      throw SceneError(path.string() + ": binary OFF is not read (convert it to ASCII OFF, PLY or OBJ)");
    if (keyword.size() > 1)
      throw SceneError(located({path.string(), 1}, "the OFF keyword must be alone on its line (the counts follow on the next)"));
    // [ST][C][N][4][n]OFF, in this order, as OpenMesh reads it.
    std::string_view k = keyword.empty() ? std::string_view() : keyword[0];
    bool normals = false, colours = false, higher = false;
    if (k.substr(0, 2) == "ST") k.remove_prefix(2);
    if (k.substr(0, 1) == "C") k.remove_prefix(1), colours = true;
    if (k.substr(0, 1) == "N") k.remove_prefix(1), normals = true;
    if (k.substr(0, 1) == "4") k.remove_prefix(1), higher = true;
    if (k.substr(0, 1) == "n") k.remove_prefix(1), higher = true;
    if (k != "OFF" || keyword[0].data() != line.data())
      throw SceneError(path.string() + ": could not read the mesh: not an OFF file (the first word is not OFF)");
    if (higher)
      throw SceneError(path.string() + ": an OFF file with 4 or n (vertices of other than 3 dimensions) is not read");
    vertex_values = normals ? 6 : 3;
    face_colours = colours;
  }
  std::vector<std::string_view> tokens;
  while (tokens.empty()) {
    if (!std::getline(in, line))
      throw SceneError(path.string() + ": the OFF header needs vertex, face and edge counts (a truncated file?)");
    ++line_no;
    tokens = split_words(line);
  }
  const int counts_line = line_no;
  if (tokens.size() != 3)
    throw SceneError(located({path.string(), counts_line}, "the OFF counts line must hold the vertex, face and edge "
                                                           "counts alone (found " + std::to_string(tokens.size()) +
                                                           " values)"));
  out.vertices = header_count(tokens[0], "vertex", path, counts_line, file_bytes);
  out.faces = header_count(tokens[1], "face", path, counts_line, file_bytes);
  header_count(tokens[2], "edge", path, counts_line, file_bytes);
  if (out.vertices + out.faces > static_cast<long long>(file_bytes))
    throw SceneError(located({path.string(), counts_line}, "the header declares " + std::to_string(out.vertices) +
                                                               " vertices and " + std::to_string(out.faces) +
                                                               " faces but the file holds only " +
                                                               std::to_string(file_bytes) + " bytes"));
  long long data_lines = 0;
  while (data_lines < out.vertices + out.faces && std::getline(in, line)) {
    ++line_no;
    tokens = split_words(line);
    if (tokens.empty()) continue;
    ++data_lines;
    const FileLoc loc{path.string(), line_no};
    if (data_lines <= out.vertices) {
      if (tokens.size() < static_cast<std::size_t>(vertex_values))
        throw SceneError(located(loc, "vertex " + std::to_string(data_lines - 1) + " has " +
                                          std::to_string(tokens.size()) + " values, fewer than the " +
                                          std::to_string(vertex_values) + " its keyword calls for"));
      continue;
    }
    const std::string face = "face " + std::to_string(data_lines - out.vertices - 1);
    long long n = -1;
    if (!whole_number(tokens[0], n))
      throw SceneError(located(loc, face + ": the vertex count '" + std::string(tokens[0]) + "' is not a whole number"));
    if (static_cast<long long>(tokens.size()) < 1 + n)
      throw SceneError(located(loc, face + " lists fewer vertex indices than its count (truncated?)"));
    if (!face_colours && static_cast<long long>(tokens.size()) > 1 + n)
      throw SceneError(located(loc, face + " has values after its " + std::to_string(n) +
                                        " vertex indices (a face colour needs the COFF keyword)"));
    for (long long i = 1; i <= n; ++i) {
      long long index = -1;
      if (!whole_number(tokens[static_cast<std::size_t>(i)], index) || index >= out.vertices)
        throw SceneError(located(loc, face + ": vertex index '" + std::string(tokens[static_cast<std::size_t>(i)]) +
                                          "' is not one of the " + std::to_string(out.vertices) + " vertices"));
    }
  }
  if (data_lines < out.vertices + out.faces)
    throw SceneError(path.string() + ": the file ends after " + std::to_string(data_lines) +
                     " data lines, but its header declares " + std::to_string(out.vertices) + " vertices and " +
                     std::to_string(out.faces) + " faces (truncated?)");
  return out;
}

TriangleMesh load_with_openmesh(const fs::path& path, const std::string& ext) {
  std::error_code ec;
  const std::uintmax_t file_bytes = fs::file_size(path, ec);
  if (ec) throw SceneError(path.string() + ": cannot open mesh file");
  const DeclaredCounts declared = ext == ".ply" ? check_ply(path, file_bytes) : check_off(path, file_bytes);
  omerr().disable();  // OpenMesh prints to the console otherwise; we report ourselves
  omlog().disable();
  OpenMesh::PolyMesh_ArrayKernelT<> poly;
  try {
    if (!OpenMesh::IO::read_mesh(poly, path.string()))
      throw SceneError(path.string() + ": OpenMesh could not read the mesh");
  } catch (const std::bad_alloc&) {
    throw SceneError(path.string() + ": out of memory reading the mesh");
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(path.string() + ": OpenMesh could not read the mesh (" + e.what() + ")");
  }
  if (declared.faces >= 0 && static_cast<long long>(poly.n_faces()) != declared.faces)
    throw SceneError(path.string() + ": OpenMesh read " + std::to_string(poly.n_faces()) + " of the " +
                     std::to_string(declared.faces) +
                     " faces its header declares (a face with an invalid or repeated vertex index, or a "
                     "non-numeric or non-finite value, stops or skips faces)");
  TriangleMesh mesh;
  mesh.path = path.string();
  mesh.surface_names.push_back(path.stem().string());
  for (auto vh : poly.vertices()) {
    const auto& p = poly.point(vh);
    Eigen::Vector3d v(p[0], p[1], p[2]);
    if (!v.allFinite())
      throw SceneError(path.string() + ": vertex " + std::to_string(vh.idx()) + " has a non-finite coordinate");
    mesh.positions.push_back(v);
  }
  for (auto fh : poly.faces()) {
    std::vector<int> ids;
    for (auto vh : poly.fv_range(fh)) ids.push_back(vh.idx());
    ++mesh.faces_read;
    if (ids.size() > 3) ++mesh.polygons_split;
    for (std::size_t k = 1; k + 1 < ids.size(); ++k) {
      mesh.triangles.emplace_back(ids[0], ids[k], ids[k + 1]);
      mesh.triangle_surface.push_back(0);
      mesh.triangle_material.push_back(-1);
    }
  }
  return mesh;
}

}  // namespace

TriangleMesh load_mesh(const std::string& path_string, const MeshReadOptions& options) {
  const fs::path path(path_string);
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw SceneError(path_string + ": is a folder, not a mesh file");
  if (const std::string why = not_a_regular_file(path_string, "mesh"); !why.empty()) throw SceneError(why);
  TriangleMesh mesh;
  if (ext == ".obj") mesh = load_obj(path, options);
  else if (ext == ".ply" || ext == ".off") mesh = load_with_openmesh(path, ext);
  else if (is_imported_format(ext)) mesh = load_with_assimp_isolated(path_string, ext, options);
  else throw SceneError(path_string + ": unsupported mesh format '" + ext +
                        "' (use .obj, .ply, .off, .gltf, .glb, .3ds, .dae, .fbx or .ifc)");
  if (mesh.triangles.empty()) throw SceneError(path_string + ": the mesh has no faces");
  return mesh;
}

// import_limits is left out: a limit decides whether a file is read, not what it gives.
static_assert(field_count<MeshReadOptions>() == 2, "MeshReadOptions changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const MeshReadOptions& o) { k.field("surface_naming", o.surface_naming); }

}  // namespace ilp
