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
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/base/error.h"
#include "core/base/key_hash.h"
#include "job/job_scene.h"

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

static_assert(field_count<SampleOperatorStats>() == 23,
              "SampleOperatorStats changed: write and read the new field (write_stats, read_stats, the test's "
              "expect_same_operator) and bump kLightingModelCacheVersion");
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

std::string lighting_model_key_text(const SceneSpec& scene, const ModelSpec& model) {
  KeyWriter k;
  k.field("ilp_lighting_model_cache_format", kLightingModelCacheVersion);
  hash_scene_inputs(k, scene);
  k.field("model", model);
  return k.text();
}

std::string lighting_model_key(const SceneSpec& scene, const ModelSpec& model) {
  const std::string text = lighting_model_key_text(scene, model);
  return hex(canonical(XXH3_128bits(text.data(), text.size())));
}

namespace {

// This machine's name, in a temporary's name: a cache folder shared by the nodes of a
// cluster (docs/cluster.md) holds other machines' temporaries, whose process ids mean
// nothing here.
std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "host";
  std::string out(name);
  for (char& c : out)
    if (c == '/' || c == '.') c = '_';
  return out;
}

// Temporaries "KEY.ilpmodel.tmp.PID.N[.HOST]" of this machine's processes that no longer
// run (killed while writing) are removed; a running process's, and another machine's,
// are left alone.
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
    if (const char* host = std::strchr(stop + 1, '.'); host != nullptr && host_name() != host + 1) continue;
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
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(serial++) + "." + host_name();
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
