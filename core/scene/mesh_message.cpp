// The isolated import's message (mesh_message.h): a header, a kind, then the fields in
// a fixed order, each count before its items, and a trailer that proves the end came.
#include "core/scene/mesh_message.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace ilp {
namespace {

constexpr char kMagic[4] = {'I', 'L', 'P', 'M'};
constexpr char kTrailer[4] = {'M', 'E', 'N', 'D'};
constexpr std::uint32_t kVersion = 1;
constexpr std::uint8_t kKindMesh = 1, kKindError = 2;

class Writer {
 public:
  template <class T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void count(std::size_t n) { pod(static_cast<std::uint64_t>(n)); }
  void text(const std::string& s) {
    count(s.size());
    out_.append(s);
  }
  void raw(const char* p, std::size_t n) { out_.append(p, n); }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}

  template <class T>
  T pod(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  // A count of items of `item_bytes` each (at least 1), checked against what is left,
  // so that a damaged count never asks for more memory than the message holds.
  std::size_t count(const char* what, std::size_t item_bytes) {
    const std::uint64_t n = pod<std::uint64_t>(what);
    if (n > (bytes_.size() - at_) / item_bytes)
      fail(std::string("truncated or damaged: ") + what + " count " + std::to_string(n) + " is beyond the " +
           std::to_string(bytes_.size() - at_) + " bytes left");
    return static_cast<std::size_t>(n);
  }
  std::string text(const char* what) {
    const std::size_t n = count(what, 1);
    std::string s(bytes_.substr(at_, n));
    at_ += n;
    return s;
  }
  void expect(const char (&tag)[4], const char* what) {
    need(4, what);
    if (std::memcmp(bytes_.data() + at_, tag, 4) != 0) fail(std::string(what) + " is wrong");
    at_ += 4;
  }
  bool at_end() const { return at_ == bytes_.size(); }
  std::size_t offset() const { return at_; }
  [[noreturn]] void fail(const std::string& why) const {
    throw MeshMessageError(why + " (at byte " + std::to_string(at_) + " of " + std::to_string(bytes_.size()) + ")");
  }

 private:
  void need(std::size_t n, const char* what) const {
    if (bytes_.size() - at_ < n) fail(std::string("truncated in the ") + what);
  }

  std::string_view bytes_;
  std::size_t at_ = 0;
};

void write_header(Writer& w, std::uint8_t kind) {
  w.raw(kMagic, 4);
  w.pod(kVersion);
  w.pod(kind);
}

}  // namespace

std::string encode_mesh_message(const TriangleMesh& m) {
  Writer w;
  write_header(w, kKindMesh);
  w.count(m.positions.size());
  for (const Eigen::Vector3d& p : m.positions) w.pod(std::array<double, 3>{p.x(), p.y(), p.z()});
  w.count(m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Eigen::Vector3i& v = m.triangles[t];
    w.pod(std::array<std::int32_t, 5>{v[0], v[1], v[2], m.triangle_surface[t], m.triangle_material[t]});
  }
  w.count(m.surface_names.size());
  for (const std::string& s : m.surface_names) w.text(s);
  w.count(m.materials.size());
  for (const MeshMaterial& mat : m.materials) {
    w.text(mat.name);
    w.pod(static_cast<std::uint8_t>(mat.kd.has_value()));
    const Eigen::Vector3d kd = mat.kd.value_or(Eigen::Vector3d::Zero());
    w.pod(std::array<double, 3>{kd.x(), kd.y(), kd.z()});
    w.text(mat.kd_loc.file);
    w.pod(std::array<std::int32_t, 2>{mat.kd_loc.line, mat.kd_loc.column});
  }
  w.pod(std::array<std::uint64_t, 3>{m.faces_read, m.polygons_split, m.zero_area_dropped});
  w.pod(static_cast<std::uint8_t>(m.frame.scale_to_m.has_value()));
  w.pod(m.frame.scale_to_m.value_or(0.0));
  w.pod(static_cast<std::uint8_t>(!m.frame.up_axis ? 0 : *m.frame.up_axis == UpAxis::y ? 1 : 2));
  w.text(m.frame.unit_note);
  w.text(m.frame.up_note);
  w.count(m.notes.size());
  for (const std::string& n : m.notes) w.text(n);
  w.raw(kTrailer, 4);
  return w.take();
}

std::string encode_error_message(const std::string& error) {
  Writer w;
  write_header(w, kKindError);
  w.text(error);
  w.raw(kTrailer, 4);
  return w.take();
}

MeshMessage decode_mesh_message(std::string_view bytes) {
  Reader r(bytes);
  MeshMessage out;
  r.expect(kMagic, "header");
  if (const auto version = r.pod<std::uint32_t>("version"); version != kVersion)
    r.fail("version " + std::to_string(version) + " (expected " + std::to_string(kVersion) + ")");
  const auto kind = r.pod<std::uint8_t>("kind");
  if (kind == kKindError) {
    out.is_error = true;
    out.error = r.text("error text");
  } else if (kind == kKindMesh) {
    TriangleMesh& m = out.mesh;
    m.positions.resize(r.count("positions", 3 * sizeof(double)));
    for (Eigen::Vector3d& p : m.positions) {
      const auto xyz = r.pod<std::array<double, 3>>("positions");
      p = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
    }
    const std::size_t triangles = r.count("triangles", 5 * sizeof(std::int32_t));
    m.triangles.reserve(triangles);
    m.triangle_surface.reserve(triangles);
    m.triangle_material.reserve(triangles);
    for (std::size_t t = 0; t < triangles; ++t) {
      const auto v = r.pod<std::array<std::int32_t, 5>>("triangles");
      m.triangles.emplace_back(v[0], v[1], v[2]);
      m.triangle_surface.push_back(v[3]);
      m.triangle_material.push_back(v[4]);
    }
    m.surface_names.resize(r.count("surface names", sizeof(std::uint64_t)));
    for (std::string& s : m.surface_names) s = r.text("surface name");
    m.materials.resize(r.count("materials", 2 * sizeof(std::uint64_t)));
    for (MeshMaterial& mat : m.materials) {
      mat.name = r.text("material name");
      const bool has_kd = r.pod<std::uint8_t>("material kd") != 0;
      const auto kd = r.pod<std::array<double, 3>>("material kd");
      if (has_kd) mat.kd = Eigen::Vector3d(kd[0], kd[1], kd[2]);
      mat.kd_loc.file = r.text("material location");
      const auto lc = r.pod<std::array<std::int32_t, 2>>("material location");
      mat.kd_loc.line = lc[0];
      mat.kd_loc.column = lc[1];
    }
    const auto counts = r.pod<std::array<std::uint64_t, 3>>("counts");
    m.faces_read = counts[0];
    m.polygons_split = counts[1];
    m.zero_area_dropped = counts[2];
    const bool has_scale = r.pod<std::uint8_t>("frame") != 0;
    const double scale = r.pod<double>("frame");
    if (has_scale) m.frame.scale_to_m = scale;
    const auto up = r.pod<std::uint8_t>("frame");
    if (up > 2) r.fail("up axis code " + std::to_string(up));
    if (up) m.frame.up_axis = up == 1 ? UpAxis::y : UpAxis::z;
    m.frame.unit_note = r.text("unit note");
    m.frame.up_note = r.text("up note");
    m.notes.resize(r.count("notes", sizeof(std::uint64_t)));
    for (std::string& n : m.notes) n = r.text("note");
    // The indices, so that a damaged message cannot reach past a vector later.
    const auto vertices = static_cast<std::int64_t>(m.positions.size());
    for (std::size_t t = 0; t < triangles; ++t) {
      for (int k = 0; k < 3; ++k)
        if (m.triangles[t][k] < 0 || m.triangles[t][k] >= vertices)
          r.fail("triangle " + std::to_string(t) + " names vertex " + std::to_string(m.triangles[t][k]) + " of " +
                 std::to_string(vertices));
      if (m.triangle_surface[t] < 0 || static_cast<std::size_t>(m.triangle_surface[t]) >= m.surface_names.size())
        r.fail("triangle " + std::to_string(t) + " names surface " + std::to_string(m.triangle_surface[t]) + " of " +
               std::to_string(m.surface_names.size()));
      if (m.triangle_material[t] < -1 || m.triangle_material[t] >= static_cast<std::int64_t>(m.materials.size()))
        r.fail("triangle " + std::to_string(t) + " names material " + std::to_string(m.triangle_material[t]) + " of " +
               std::to_string(m.materials.size()));
    }
  } else {
    r.fail("kind " + std::to_string(kind));
  }
  r.expect(kTrailer, "trailer");
  if (!r.at_end()) r.fail("trailing bytes after the trailer");
  return out;
}

}  // namespace ilp
