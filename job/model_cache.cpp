// The cache file, little-endian throughout (u32/u64/i32 integers, f64 IEEE doubles,
// str = u32 length + bytes, vec = u64 n + n f64, mat = u64 rows + u64 cols + f64
// column-major):
//
//   "ILPMODEL"  u32 format version  u64 file size in bytes (checksum included)
//   str key  u64 goal patches  u64 candidates  f64 fixed_flux_lm  i32 sample_size
//   vec fixed_lux  vec fixed_direct_lux  mat candidate_lux_per_lm  mat candidate_direct_lux_per_lm
//   SampleOperatorStats, every field in declaration order (size_t as u64, bool as u8, int as i32)
//   f64 build_seconds  u64 log lines  str each line (the model's whole log: geometry lines first)
//   16 bytes: XXH3-128 of every byte before it, in xxHash's canonical (big-endian) form
#include "job/model_cache.h"

#include <signal.h>
#include <unistd.h>
#include <xxhash.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "core/base/error.h"

namespace ilp {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'I', 'L', 'P', 'M', 'O', 'D', 'E', 'L'};
constexpr std::size_t kChecksumBytes = sizeof(XXH128_canonical_t);
static_assert(kChecksumBytes == 16);

struct StateDeleter {
  void operator()(XXH3_state_t* s) const { XXH3_freeState(s); }
};
using HashState = std::unique_ptr<XXH3_state_t, StateDeleter>;

HashState new_hash_state() {
  HashState state(XXH3_createState());
  if (!state || XXH3_128bits_reset(state.get()) != XXH_OK) throw std::bad_alloc();
  return state;
}

std::array<unsigned char, kChecksumBytes> canonical(XXH128_hash_t hash) {
  XXH128_canonical_t c;
  XXH128_canonicalFromHash(&c, hash);
  std::array<unsigned char, kChecksumBytes> out{};
  std::memcpy(out.data(), c.digest, kChecksumBytes);
  return out;
}

std::string hex(const std::array<unsigned char, kChecksumBytes>& bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  for (unsigned char b : bytes) {
    out += kDigits[b >> 4];
    out += kDigits[b & 15];
  }
  return out;
}

// ---- The key.

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

// "<hex digest> <bytes>" of the file's bytes, or "missing" / "unreadable". With
// `mtllibs`, also collects the names of the OBJ's mtllib statements in file order.
std::string file_digest(const fs::path& path, std::vector<std::string>* mtllibs) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "missing";
  HashState state = new_hash_state();
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
  return hex(canonical(XXH3_128bits_digest(state.get()))) + " " + std::to_string(bytes);
}

// Strings length-prefixed, so no name can imitate a separator.
void put(std::ostream& t, const std::string& s) { t << s.size() << ':' << s; }
void put(std::ostream& t, const Eigen::Vector3d& v) { t << v.x() << ' ' << v.y() << ' ' << v.z(); }

// Everything the operator depends on, one item a line, doubles exact.
std::string key_text(const JobConfig& job, const ModelSpec& model) {
  std::ostringstream t;
  t << std::setprecision(17);
  t << "ilp lighting model cache, format " << kLightingModelCacheVersion << "\n";

  // The input files. The mesh's path does not matter, only its bytes and how it is
  // read: the extension picks the reader, and PLY/OFF name their surface after the stem.
  const fs::path mesh(job.mesh_path);
  std::string ext = mesh.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  t << "mesh format ";
  put(t, ext);
  t << "\n";
  if (ext != ".obj") {
    t << "mesh stem ";
    put(t, mesh.stem().string());
    t << "\n";
  }
  std::vector<std::string> mtllibs;
  t << "mesh bytes " << file_digest(mesh, ext == ".obj" ? &mtllibs : nullptr) << "\n";
  for (const std::string& name : mtllibs) {
    t << "mtllib ";
    put(t, name);
    t << " bytes " << file_digest(mesh.parent_path() / name, nullptr) << "\n";
  }

  // The scene.
  t << "surface naming " << static_cast<int>(job.mesh_read.surface_naming) << "\n";
  if (job.surface_split.active()) {  // (absent otherwise, so older keys stay valid)
    t << "split connected " << job.surface_split.connected << " weld " << job.surface_split.weld_tolerance_m << "\n";
    for (const RegionRule& r : job.surface_split.regions) {
      t << "region ";
      put(t, r.name);
      t << " facing " << (r.facing ? static_cast<int>(*r.facing) : -1);
      if (r.height_m) t << " height " << r.height_m->first << ' ' << r.height_m->second;
      t << " min area " << r.min_area_m2 << "\n";
    }
  }
  t << "up axis " << static_cast<int>(job.scene.up_axis) << "\nscale_to_m " << job.scene.scale_to_m
    << "\nmax_patch_edge_m " << job.scene.max_patch_edge_m << "\nmax_patches " << job.scene.max_patches << "\n";
  for (const ReflectanceSetting& r : job.reflectance) {  // in file order: a later one wins
    t << "reflectance ";
    put(t, r.surface);
    t << ' ';
    put(t, r.rgb);
    t << "\n";
  }
  t << "default reflectance ";
  if (job.default_reflectance) put(t, *job.default_reflectance);
  else t << "none";
  t << "\n";
  for (const EmitterSetting& e : job.emitting_surfaces) {
    t << "emitting ";
    put(t, e.surface);
    t << ' ' << e.exitance_lm_per_m2 << "\n";
  }
  for (const std::string& name : job.exclude_surfaces) {
    t << "excluded ";
    put(t, name);
    t << "\n";
  }
  for (const FloorSetting& f : job.add_floors) {  // scene.add_floor: geometry the mesh file lacks
    t << "added floor ";
    put(t, f.name);
    t << ' ' << f.lo.x() << ' ' << f.lo.y() << ' ' << f.hi.x() << ' ' << f.hi.y() << ' ' << f.z_m << ' ';
    put(t, f.rgb);
    t << "\n";
  }
  t << "two-sided " << (job.two_sided_all ? "all" : "listed") << "\n";
  for (const std::string& name : job.two_sided_surfaces) {
    t << "two-sided ";
    put(t, name);
    t << "\n";
  }

  // Luminaires: the placed ones and the candidates' grid.
  t << "luminaire size " << job.luminaire_size_m << "\n";
  if (job.search)
    t << model.candidates.type.key() << " rotation " << model.candidates.rotation_deg << " wall " << job.search->wall_distance_m
      << " module " << job.search->ceiling_module_m << "\n";
  // Each placed luminaire's type (its product's distribution, shape and size), turn,
  // position and flux: the light it gives and the opening that shades.
  for (const LuminaireSetting& l : job.luminaires) {
    t << "placed ";
    put(t, l.name);
    t << ' ';
    put(t, l.position_m);
    t << ' ' << l.flux_lm << ' ' << l.type.key() << " rotation " << l.rotation_deg << "\n";
  }
  if (job.search) {
    const LuminaireSearch& s = *job.search;
    t << "search model ";
    put(t, s.model);
    t << " mounting ";
    put(t, s.mounting_surface);
    t << " offset " << model.candidates.mount_offset_m << " spacing " << s.candidate_spacing_m << "\n";
    // A sample size chosen for a target error is judged with every candidate at the
    // top of the flux range (compute_lighting_operator): only then does it matter.
    if (job.sample.target_error) t << "probe flux " << model.probe_flux_lm << "\n";
  } else {
    t << "no search\n";
  }

  // The goal patches: each goal name's surfaces (the first entry of a name counts, as
  // in lighting_model_geometry), not its targets or metrics.
  std::set<std::string> seen;
  for (const GoalSetting& g : job.goals) {
    if (!seen.insert(g.name).second) continue;
    t << "goal ";
    put(t, g.name);
    for (const std::string& s : g.surfaces) {
      t << ' ';
      put(t, s);
    }
    t << " facing " << static_cast<int>(g.facing) << "\n";
    if (!g.grid.empty()) {
      t << "on grid ";
      put(t, g.grid);
      t << "\n";
    }
  }
  // Every grid of the job (lighting_model_geometry lays them all): each value that places its points.
  for (const CalcGridSetting& c : job.grids) {
    t << "grid ";
    put(t, c.name);
    t << " kind " << static_cast<int>(c.kind) << " over ";
    put(t, c.over_surface);
    t << " polygon";
    for (const Eigen::Vector2d& p : c.polygon_m) t << ' ' << p.x() << ' ' << p.y();
    t << " height " << c.height_m << " vertical " << c.from_m.x() << ' ' << c.from_m.y() << ' ' << c.to_m.x() << ' '
      << c.to_m.y() << ' ' << c.bottom_m << ' ' << c.top_m << ' ' << c.facing_left << " border " << c.border_m
      << " spacing " << (c.spacing_m ? *c.spacing_m : -1.0) << " max " << c.max_points << "\n";
  }

  // The solver (threads left out: the operator is the same for any thread count).
  t << "form factors rays " << job.form_factors.rays_per_patch << " seed " << job.form_factors.seed << "\n";
  t << "direct light points " << job.direct_light.receiver_points << " rays " << job.direct_light.shadow_rays
    << " seed " << job.direct_light.seed << "\n";
  const SampleSettings& s = job.sample;
  t << "sample size ";
  if (s.size) t << *s.size;
  else t << "none";
  t << " fraction " << s.fraction << " strategy " << static_cast<int>(s.strategy) << " seed " << s.seed
    << " indirect " << static_cast<int>(s.indirect) << " target error ";
  if (s.target_error) t << *s.target_error;
  else t << "none";
  t << " error samples " << s.error_samples << " pilot fraction " << s.pilot_fraction << "\n";
  t << "max sample size " << s.max_size_for_target << "\n";  // caps the k sample_fraction or target_error gives
  if (job.ignore_material_kd) t << "material Kd ignored\n";
  return t.str();
}

// ---- Writing.

// Appends little-endian values to a stream, counting and hashing them. Without a
// stream it only counts (the first pass, for the file size in the header).
class Writer {
 public:
  Writer(std::ostream* out, XXH3_state_t* hash) : out_(out), hash_(hash) {}
  std::uint64_t bytes() const { return bytes_; }

  void raw(const void* data, std::size_t n) {
    bytes_ += n;
    if (hash_) XXH3_128bits_update(hash_, data, n);
    if (out_) out_->write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
  }
  void u8(std::uint8_t v) { raw(&v, 1); }
  void u32(std::uint32_t v) {
    unsigned char b[4];
    for (int i = 0; i < 4; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
    raw(b, 4);
  }
  void u64(std::uint64_t v) {
    unsigned char b[8];
    for (int i = 0; i < 8; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
    raw(b, 8);
  }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void str(const std::string& s) {
    if (s.size() > std::numeric_limits<std::uint32_t>::max()) throw std::length_error("model cache: string too long");
    u32(static_cast<std::uint32_t>(s.size()));
    raw(s.data(), s.size());
  }
  void doubles(const double* data, std::size_t n) {
    if constexpr (std::endian::native == std::endian::little) {
      raw(data, n * sizeof(double));
    } else {
      for (std::size_t i = 0; i < n; ++i) f64(data[i]);
    }
  }
  void vec(const Eigen::VectorXd& v) {
    u64(static_cast<std::uint64_t>(v.size()));
    doubles(v.data(), static_cast<std::size_t>(v.size()));
  }
  void mat(const Eigen::MatrixXd& m) {
    u64(static_cast<std::uint64_t>(m.rows()));
    u64(static_cast<std::uint64_t>(m.cols()));
    doubles(m.data(), static_cast<std::size_t>(m.size()));
  }

 private:
  std::ostream* out_;
  XXH3_state_t* hash_;
  std::uint64_t bytes_ = 0;
};

void write_stats(Writer& w, const SampleOperatorStats& s) {
  w.u64(s.patches);
  w.u64(s.population);
  w.u64(s.sample_patches);
  w.u8(s.census ? 1 : 0);
  w.u8(s.direct_only ? 1 : 0);
  w.i32(s.channels);
  w.u64(s.goal_patches);
  w.u64(s.goal_points);
  w.u64(s.point_fallback_rows);
  w.u64(s.direct_rows);
  w.u64(s.cheap_direct_rows);
  w.u64(s.goal_fallback_rows);
  w.f64(s.goal_fallback_area_fraction);
  w.u64(s.sample_fallback_rows);
  w.f64(s.condition_estimate);
  w.f64(s.max_row_sum);
  w.f64(s.condition_bound_inf);
  w.u64(s.rays_cast);
  w.f64(s.goal_seconds);
  w.f64(s.sample_row_seconds);
  w.f64(s.direct_seconds);
  w.f64(s.solve_seconds);
  w.f64(s.response_seconds);
}

// Everything before the checksum.
void write_body(Writer& w, const LightingModel& model, const std::string& key, std::uint64_t file_size) {
  w.raw(kMagic, sizeof kMagic);
  w.u32(kLightingModelCacheVersion);
  w.u64(file_size);
  w.str(key);
  w.u64(static_cast<std::uint64_t>(model.goal_rows()));
  w.u64(model.grid.size());
  w.f64(model.fixed_flux_lm);
  w.i32(model.sample_size);
  w.vec(model.fixed_lux);
  w.vec(model.fixed_direct_lux);
  w.mat(model.candidate_lux_per_lm);
  w.mat(model.candidate_direct_lux_per_lm);
  write_stats(w, model.stats);
  w.f64(model.build_seconds);
  w.u64(model.log.size());
  for (const std::string& line : model.log) w.str(line);
}

// ---- Reading.

// Reads little-endian values from the file's body (before the checksum); any read
// past its end sets `failed` and reads zeros, so parsing never throws.
class Reader {
 public:
  Reader(std::istream& in, std::uint64_t limit) : in_(in), left_(limit) {}
  bool failed() const { return failed_; }
  std::uint64_t left() const { return left_; }

  bool raw(void* data, std::uint64_t n) {
    if (failed_ || n > left_) {
      failed_ = true;
      return false;
    }
    in_.read(static_cast<char*>(data), static_cast<std::streamsize>(n));
    if (static_cast<std::uint64_t>(in_.gcount()) != n) {
      failed_ = true;
      return false;
    }
    left_ -= n;
    return true;
  }
  std::uint8_t u8() {
    std::uint8_t v = 0;
    raw(&v, 1);
    return v;
  }
  std::uint32_t u32() {
    unsigned char b[4] = {};
    if (!raw(b, 4)) return 0;
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(b[i]) << (8 * i);
    return v;
  }
  std::uint64_t u64() {
    unsigned char b[8] = {};
    if (!raw(b, 8)) return 0;
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(b[i]) << (8 * i);
    return v;
  }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  double f64() { return std::bit_cast<double>(u64()); }
  std::string str() {
    const std::uint32_t n = u32();
    if (failed_ || n > left_) {
      failed_ = true;
      return {};
    }
    std::string s(n, '\0');
    raw(s.data(), n);
    return s;
  }
  bool doubles(double* data, std::uint64_t n) {
    if (failed_ || n > left_ / sizeof(double)) {
      failed_ = true;
      return false;
    }
    if constexpr (std::endian::native == std::endian::little) {
      return raw(data, n * sizeof(double));
    } else {
      for (std::uint64_t i = 0; i < n; ++i) data[i] = f64();
      return !failed_;
    }
  }

 private:
  std::istream& in_;
  std::uint64_t left_;
  bool failed_ = false;
};

void read_stats(Reader& r, SampleOperatorStats& s) {
  s.patches = r.u64();
  s.population = r.u64();
  s.sample_patches = r.u64();
  s.census = r.u8() != 0;
  s.direct_only = r.u8() != 0;
  s.channels = r.i32();
  s.goal_patches = r.u64();
  s.goal_points = r.u64();
  s.point_fallback_rows = r.u64();
  s.direct_rows = r.u64();
  s.cheap_direct_rows = r.u64();
  s.goal_fallback_rows = r.u64();
  s.goal_fallback_area_fraction = r.f64();
  s.sample_fallback_rows = r.u64();
  s.condition_estimate = r.f64();
  s.max_row_sum = r.f64();
  s.condition_bound_inf = r.f64();
  s.rays_cast = r.u64();
  s.goal_seconds = r.f64();
  s.sample_row_seconds = r.f64();
  s.direct_seconds = r.f64();
  s.solve_seconds = r.f64();
  s.response_seconds = r.f64();
}

// The operator part, read into its own variables first: the model is touched only
// once all of it is read and checked.
struct OperatorPart {
  double fixed_flux_lm = 0.0;
  int sample_size = 0;
  Eigen::VectorXd fixed_lux, fixed_direct_lux;
  Eigen::MatrixXd candidate_lux_per_lm, candidate_direct_lux_per_lm;
  SampleOperatorStats stats;
  double build_seconds = 0.0;
  std::vector<std::string> log;
};

const std::string kSizesDiffer = "sizes do not match the scene's goal patches/candidates";

}  // namespace

std::string lighting_model_key(const JobConfig& job, const ModelSpec& model) {
  const std::string text = key_text(job, model);
  return hex(canonical(XXH3_128bits(text.data(), text.size())));
}

namespace {

// Temporaries "KEY.ilpmodel.tmp.PID.N" of processes that no longer run (killed while
// writing) are removed; a running process's are left alone.
void remove_stale_temporaries(const fs::path& folder) {
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::size_t at = name.find(".ilpmodel.tmp.");
    if (at == std::string::npos) continue;
    const std::string rest = name.substr(at + 14);
    char* stop = nullptr;
    const long pid = std::strtol(rest.c_str(), &stop, 10);
    if (stop == rest.c_str() || *stop != '.' || pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    fs::remove(it->path(), ignored);
  }
}

}  // namespace

void save_lighting_model(const std::string& path, const LightingModel& model, const std::string& key) {
  remove_stale_temporaries(fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path());
  const Eigen::Index G = model.goal_rows(), C = static_cast<Eigen::Index>(model.grid.size());
  if (model.fixed_lux.size() != G || model.fixed_direct_lux.size() != G || model.candidate_lux_per_lm.rows() != G ||
      model.candidate_lux_per_lm.cols() != C || model.candidate_direct_lux_per_lm.rows() != G ||
      model.candidate_direct_lux_per_lm.cols() != C)
    throw std::invalid_argument("save_lighting_model: the model's operator is not built (sizes do not match)");

  Writer counter(nullptr, nullptr);
  write_body(counter, model, key, 0);
  const std::uint64_t file_size = counter.bytes() + kChecksumBytes;

  // A name of this process's own, so that two runs writing the same model (a sweep
  // in parallel) never write into one temporary file.
  static std::atomic<unsigned> serial{0};
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(serial++);
  auto fail = [&](const std::string& why) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw IlpError(path + ": cannot write the model cache (" + why + ")");
  };
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail("cannot create " + tmp);
    HashState hash = new_hash_state();
    Writer w(&out, hash.get());
    write_body(w, model, key, file_size);
    const auto checksum = canonical(XXH3_128bits_digest(hash.get()));
    out.write(reinterpret_cast<const char*>(checksum.data()), static_cast<std::streamsize>(checksum.size()));
    out.close();
    if (!out || w.bytes() + kChecksumBytes != file_size) fail("write failed");
  } catch (const IlpError&) {
    throw;
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) fail("rename failed: " + ec.message());
}

std::optional<std::string> load_lighting_model(const std::string& path, const std::string& key, LightingModel& model) {
  remove_stale_temporaries(fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path());
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) return "no cache file";
  if (!fs::is_regular_file(status)) return "not a regular file";
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return "cannot read the cache file (" + ec.message() + ")";
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot read the cache file";

  // The header: what the file is, its version and how long it should be.
  constexpr std::uint64_t kHeaderBytes = sizeof kMagic + 4 + 8;
  char magic[sizeof kMagic] = {};
  in.read(magic, sizeof magic);
  const auto got = static_cast<std::size_t>(in.gcount());
  if (std::memcmp(magic, kMagic, got) != 0) return "corrupt: not an ilp model cache file";
  if (size < kHeaderBytes) return "truncated (" + std::to_string(size) + " bytes)";
  {
    Reader header(in, kHeaderBytes - sizeof kMagic);
    const std::uint32_t version = header.u32();
    if (version != kLightingModelCacheVersion)
      return "written by another format version (" + std::to_string(version) + "; this program reads " +
             std::to_string(kLightingModelCacheVersion) + ")";
    const std::uint64_t declared = header.u64();
    if (header.failed()) return "truncated";
    if (size < declared)
      return "truncated (" + std::to_string(size) + " of " + std::to_string(declared) + " bytes)";
    if (size > declared || declared < kHeaderBytes + kChecksumBytes)
      return "corrupt: " + std::to_string(size) + " bytes where the header says " + std::to_string(declared);
  }

  // The checksum over everything before it.
  const std::uint64_t body = size - kChecksumBytes;
  {
    in.seekg(0);
    HashState hash = new_hash_state();
    std::vector<char> buffer(1 << 20);
    std::uint64_t left = body;
    while (left > 0) {
      const auto n = static_cast<std::streamsize>(std::min<std::uint64_t>(left, buffer.size()));
      if (!in.read(buffer.data(), n)) return "truncated (the file changed while it was read)";
      XXH3_128bits_update(hash.get(), buffer.data(), static_cast<std::size_t>(n));
      left -= static_cast<std::uint64_t>(n);
    }
    std::array<unsigned char, kChecksumBytes> stored{};
    if (!in.read(reinterpret_cast<char*>(stored.data()), kChecksumBytes)) return "truncated";
    if (stored != canonical(XXH3_128bits_digest(hash.get()))) return "corrupt: checksum mismatch";
  }

  // The content: the key first, then the operator, checked against the model.
  in.clear();
  in.seekg(static_cast<std::streamoff>(kHeaderBytes));
  Reader r(in, body - kHeaderBytes);
  const std::string file_key = r.str();
  if (r.failed()) return "corrupt: malformed key";
  if (file_key != key) return "stale: the key differs (the scene or a parameter changed)";
  const std::uint64_t G = r.u64(), C = r.u64();
  if (r.failed()) return "corrupt: malformed sizes";
  if (G != static_cast<std::uint64_t>(model.goal_rows()) || C != model.grid.size())
    return kSizesDiffer + " (file " + std::to_string(G) + " x " + std::to_string(C) + ", scene " +
           std::to_string(model.goal_rows()) + " x " + std::to_string(model.grid.size()) + ")";
  OperatorPart part;
  part.fixed_flux_lm = r.f64();  // the geometry's: a check that the file is this scene's
  part.sample_size = r.i32();
  auto read_vec = [&](Eigen::VectorXd& v) {
    if (r.u64() != G || r.failed()) return false;
    v.resize(static_cast<Eigen::Index>(G));
    return r.doubles(v.data(), G);
  };
  auto read_mat = [&](Eigen::MatrixXd& m) {
    const std::uint64_t rows = r.u64(), cols = r.u64();
    if (rows != G || cols != C || r.failed()) return false;
    if (C != 0 && G > r.left() / sizeof(double) / C) return false;  // before allocating
    m.resize(static_cast<Eigen::Index>(G), static_cast<Eigen::Index>(C));
    return r.doubles(m.data(), G * C);
  };
  if (!read_vec(part.fixed_lux) || !read_vec(part.fixed_direct_lux) || !read_mat(part.candidate_lux_per_lm) ||
      !read_mat(part.candidate_direct_lux_per_lm))
    return r.failed() ? "corrupt: malformed operator" : kSizesDiffer + " (a matrix's dimensions)";
  read_stats(r, part.stats);
  part.build_seconds = r.f64();
  const std::uint64_t lines = r.u64();
  if (r.failed() || lines > r.left() / 4) return "corrupt: malformed statistics";
  for (std::uint64_t k = 0; k < lines && !r.failed(); ++k) part.log.push_back(r.str());
  if (r.failed() || r.left() != 0) return "corrupt: malformed log";
  if (part.fixed_flux_lm != model.fixed_flux_lm) return "stale: the placed luminaires' flux differs";
  // The file's log begins with the geometry's lines, which the model already has.
  if (part.log.size() < model.log.size() || !std::equal(model.log.begin(), model.log.end(), part.log.begin()))
    return "stale: the candidate grid's log differs from the cached one";

  model.sample_size = part.sample_size;
  model.fixed_lux = std::move(part.fixed_lux);
  model.fixed_direct_lux = std::move(part.fixed_direct_lux);
  model.candidate_lux_per_lm = std::move(part.candidate_lux_per_lm);
  model.candidate_direct_lux_per_lm = std::move(part.candidate_direct_lux_per_lm);
  model.stats = part.stats;
  model.build_seconds = part.build_seconds;
  model.log.insert(model.log.end(), part.log.begin() + static_cast<std::ptrdiff_t>(model.log.size()), part.log.end());
  return std::nullopt;
}

}  // namespace ilp
