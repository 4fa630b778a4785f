#include "output/atomic_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <mutex>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <system_error>
#include <thread>

#include "core/base/error.h"

namespace ilp {
namespace {

namespace fs = std::filesystem;

// A suffix no other process or call uses: PID and a per-process counter (files), or
// PID and 32 random bits (folders, which a crashed earlier process of the same PID
// may have left).
std::string unique_suffix(bool random) {
  static std::atomic<unsigned> serial{0};
  std::string out = std::to_string(::getpid()) + "-";
  if (!random) return out + std::to_string(serial++);
  std::random_device rd;
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(rd()));
  return out + hex;
}

// Whether the process that left a temporary named "...PREFIX<pid>-..." still runs.
bool owner_runs(const std::string& name, const std::string& prefix) {
  const std::string rest = name.substr(prefix.size());
  char* end = nullptr;
  const long pid = std::strtol(rest.c_str(), &end, 10);
  if (end == rest.c_str() || *end != '-' || pid <= 0) return true;  // not ours: leave it
  if (pid == ::getpid()) return true;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH;
}

// Removes the entries of `dir` named PREFIX<pid>-... whose process has gone.
void remove_leftovers(const fs::path& dir, const std::string& prefix) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0 || owner_runs(name, prefix)) continue;
    std::error_code ignored;
    fs::remove_all(it->path(), ignored);
  }
}

// The test hooks: pause (to be killed) or fail at a named point.
void test_hook(const std::string& point) {
  if (const char* fail = std::getenv("ILP_TEST_OUTPUT_FAIL"); fail && point == fail)
    throw IlpError("output: failing at '" + point + "' (ILP_TEST_OUTPUT_FAIL)");
  if (const char* pause = std::getenv("ILP_TEST_OUTPUT_PAUSE"); pause && point == pause) {
    std::cerr << "ilp-test: paused at " << point << std::endl;
    std::this_thread::sleep_for(std::chrono::seconds(60));
  }
}

// flock(2) on a folder for the length of a scope (advisory: ilp processes only).
class FolderLock {
 public:
  explicit FolderLock(const fs::path& dir) : fd_(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ >= 0)
      while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
      }
  }
  ~FolderLock() {
    if (fd_ >= 0) ::close(fd_);  // closing releases the lock
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_;
};

// Hard links (a copy where linking fails) of what `from` holds besides `owned` and
// ilp's temporaries, into `to`.
void carry_over(const fs::path& from, const fs::path& to, const std::vector<std::string>& owned) {
  std::error_code ec;
  for (fs::directory_iterator it(from, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (std::find(owned.begin(), owned.end(), name) != owned.end()) continue;
    const fs::path target = to / name;
    std::error_code link_ec;
    fs::copy(it->path(), target, fs::copy_options::recursive | fs::copy_options::copy_symlinks |
                                     fs::copy_options::create_hard_links, link_ec);
    if (!link_ec) continue;
    std::error_code ignored;
    fs::remove_all(target, ignored);
    std::error_code copy_ec;
    fs::copy(it->path(), target, fs::copy_options::recursive | fs::copy_options::copy_symlinks, copy_ec);
    if (copy_ec)
      throw IlpError(from.string() + ": cannot keep '" + name + "' in the new output set (" + copy_ec.message() + ")");
  }
  if (ec) throw IlpError(from.string() + ": cannot read the output folder (" + ec.message() + ")");
}

// renameat2(RENAME_EXCHANGE): both paths exist before and after, swapped atomically.
// Returns 0 or errno.
int exchange(const fs::path& a, const fs::path& b) {
#ifdef RENAME_EXCHANGE
  if (::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0) return 0;
  return errno;
#else
  (void)a;
  (void)b;
  return EINVAL;
#endif
}

}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const fs::path target(path);
  const std::string prefix = target.filename().string() + ".tmp-";
  const std::string tmp = path + ".tmp-" + unique_suffix(false);
  {
    std::error_code ec;
    if (fs::is_directory(target, ec)) throw IlpError(path + ": write failed (a folder is in the way)");
  }
  try {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw IlpError(path + ": cannot write");
    write(out);
    if (!out.flush()) throw IlpError(path + ": write failed");
    out.close();  // can still fail: some file systems report write errors only on close
    if (!out) throw IlpError(path + ": write failed");
    std::error_code ec;
    fs::rename(tmp, path, ec);  // atomic on POSIX when both are on one file system
    if (ec) throw IlpError(path + ": write failed (" + ec.message() + ")");
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
  remove_leftovers(target.has_parent_path() ? target.parent_path() : fs::path("."), prefix);
}

OutputSet::OutputSet(const std::string& folder, std::vector<std::string> owned)
    : given_(folder), owned_(std::move(owned)) {
  std::error_code ec;
  fs::path absolute = fs::absolute(folder, ec).lexically_normal();
  if (ec) throw IlpError(folder + ": cannot resolve the output folder (" + ec.message() + ")");
  if (!absolute.has_filename()) absolute = absolute.parent_path();  // "out/" -> "out"
  if (!absolute.has_filename() || absolute == absolute.root_path())
    throw IlpError(folder + ": cannot be the output folder (give a folder of its own, e.g. results/job)");
  // A symbolic link to a folder stays a link: the set goes into its target.
  if (fs::is_symlink(absolute, ec)) {
    absolute = fs::weakly_canonical(absolute, ec);
    if (ec) throw IlpError(folder + ": cannot resolve the link to the output folder (" + ec.message() + ")");
  }
  folder_ = absolute.string();
  const fs::path cwd = fs::current_path(ec).lexically_normal();
  if (!ec) {
    const auto [a, b] = std::mismatch(absolute.begin(), absolute.end(), cwd.begin(), cwd.end());
    if (a == absolute.end())
      throw IlpError(folder + ": the output folder holds the current folder, and ilp replaces the output folder as "
                              "a whole when a run completes: give a folder of its own (e.g. --out results/job)");
  }
  if (fs::exists(absolute, ec) && !fs::is_directory(absolute, ec))
    throw IlpError(folder + ": is not a folder (the output folder)");
  const fs::path parent = absolute.parent_path();
  fs::create_directories(parent, ec);
  if (ec) throw IlpError(parent.string() + ": cannot create the folder for outputs (" + ec.message() + ")");
  const std::string folder_name = absolute.filename().string();
  remove_leftovers(parent, "." + folder_name + ".ilp-tmp-");  // of killed runs: they would pile up
  staging_ = (parent / ("." + folder_name + ".ilp-tmp-" + unique_suffix(true))).string();
  if (!fs::create_directory(staging_, ec) || ec)
    throw IlpError(folder + ": cannot write outputs beside it (" + (ec ? ec.message() : "exists") + ")");
}

OutputSet::~OutputSet() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

std::string OutputSet::staging_path(const std::string& name) const {
  const std::string full = full_name(name);
  if (std::find(owned_.begin(), owned_.end(), full) == owned_.end())
    throw std::invalid_argument("OutputSet: '" + full + "' is not a file of this set");
  const fs::path path = fs::path(staging_) / full;
  if (!subfolder_.empty()) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw IlpError(explained(path.parent_path().string() + ": cannot create the folder (" + ec.message() + ")"));
  }
  return path.string();
}

void OutputSet::staged(const std::string& name) {
  // In a batch, in the owned order whatever order its writers finish in.
  const std::string full = full_name(name);
  const auto rank = [this](const std::string& n) { return std::find(owned_.begin(), owned_.end(), n) - owned_.begin(); };
  std::size_t count = 0;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto from = written_.begin() + static_cast<std::ptrdiff_t>(std::min(batch_from_, written_.size()));
    written_.insert(std::find_if(from, written_.end(), [&](const std::string& n) { return rank(n) > rank(full); }), full);
    count = written_.size();
  }
  test_hook(std::to_string(count));
}

void OutputSet::begin_batch() {
  const std::lock_guard<std::mutex> lock(mutex_);
  batch_from_ = written_.size();
}

void OutputSet::end_batch() {
  const std::lock_guard<std::mutex> lock(mutex_);
  batch_from_ = kNoBatch;
}

void OutputSet::write(const std::string& name, const std::function<void(std::ostream&)>& writer) {
  try {
    write_file_atomically(staging_path(name), writer);
  } catch (const IlpError& e) {
    throw IlpError(explained(e.what()));
  }
  staged(name);
}

std::string OutputSet::explained(const std::string& message) const {
  std::string out = message;
  for (std::size_t at = out.find(staging_); at != std::string::npos; at = out.find(staging_, at + folder_.size()))
    out.replace(at, staging_.size(), folder_);
  struct statvfs fs_stat {};
  if (out.find("free on its file system)") == std::string::npos && ::statvfs(fs::path(staging_).parent_path().c_str(), &fs_stat) == 0) {
    const double free_mb = static_cast<double>(fs_stat.f_bavail) * static_cast<double>(fs_stat.f_frsize) / 1e6;
    char note[96];
    std::snprintf(note, sizeof note, " (%.0f MB free on its file system)", free_mb);
    out += note;
  }
  return out;
}

std::vector<std::string> OutputSet::commit() {
  if (committed_) throw std::logic_error("OutputSet: committed twice");
  const fs::path folder(folder_), staging(staging_), parent = folder.parent_path();
  const std::string folder_name = folder.filename().string();
  const std::string hidden = "." + folder_name;
  const FolderLock lock(parent);
  remove_leftovers(parent, hidden + ".ilp-tmp-");
  std::error_code ec;
  // A commit killed between its two renames (file systems without exchange) left the
  // old folder aside: it is the last complete set, so it goes back first.
  if (!fs::exists(folder, ec)) {
    for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      const std::string prefix = hidden + ".ilp-old-";
      if (name.rfind(prefix, 0) == 0 && !owner_runs(name, prefix)) {
        std::error_code ignored;
        fs::rename(it->path(), folder, ignored);
        break;
      }
    }
  }
  remove_leftovers(parent, hidden + ".ilp-old-");
  if (fs::exists(folder, ec)) {
    if (!fs::is_directory(folder, ec)) throw IlpError(folder_ + ": is not a folder (the output folder)");
    carry_over(folder, staging, owned_);
  }
  test_hook("carried");
  if (!fs::exists(folder, ec)) {
    fs::rename(staging, folder, ec);
    if (ec) throw IlpError(folder_ + ": cannot move the outputs into place (" + ec.message() + ")");
  } else if (const int err = exchange(staging, folder); err == 0) {
    committed_ = true;  // the staging path now holds the previous set
    test_hook("swapped");
    std::error_code ignored;
    fs::remove_all(staging, ignored);
  } else if (err == EINVAL || err == ENOSYS || err == EOPNOTSUPP) {
    const fs::path aside = parent / (hidden + ".ilp-old-" + unique_suffix(true));
    fs::rename(folder, aside, ec);
    if (ec) throw IlpError(folder_ + ": cannot move the previous outputs aside (" + ec.message() + ")");
    test_hook("aside");
    fs::rename(staging, folder, ec);
    if (ec) {
      std::error_code ignored;
      fs::rename(aside, folder, ignored);
      throw IlpError(folder_ + ": cannot move the outputs into place (" + ec.message() + ")");
    }
    committed_ = true;
    test_hook("swapped");
    std::error_code ignored;
    fs::remove_all(aside, ignored);
  } else {
    throw IlpError(folder_ + ": cannot move the outputs into place (" + std::strerror(err) + ")");
  }
  committed_ = true;
  std::vector<std::string> out;
  for (const std::string& name : written_) out.push_back((fs::path(given_) / name).string());
  return out;
}

}  // namespace ilp
