// The isolated import (mesh_import.h, load_with_assimp_isolated): fork, the child runs
// load_with_assimp and writes its answer to a pipe (mesh_message.h), the parent reads it
// until the child closes the pipe or the time is up, then judges how the child ended.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "core/scene/mesh_import.h"
#include "core/scene/mesh_message.h"

namespace ilp {
namespace {

using Clock = std::chrono::steady_clock;

// The assimp the messages name: Debian 12's libassimp-dev 5.2.5, the version the project
// pins (scripts/setup.sh). Not aiGetVersion*(): that release's library calls itself 5.2.4.
constexpr const char* kAssimp = "assimp 5.2.5";

constexpr const char* kLimitReached = " (the import's memory limit was reached)";

constexpr double kMaxTime_s = 1e7;  // about 4 months: a deadline the steady clock can hold

// Exit statuses of the child other than 0 (the message was written).
constexpr int kChildWriteFailed = 70;

std::string errno_text(int error) { return std::strerror(error); }

// "signal 11, SIGSEGV".
std::string signal_text(int sig) {
  std::string out = "signal " + std::to_string(sig);
  if (const char* abbrev = ::sigabbrev_np(sig)) out += std::string(", SIG") + abbrev;
  return out;
}

// The address space this process has mapped now (VmSize), in bytes; 0 if unknown.
double mapped_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages = 0.0;
  if (!(statm >> pages)) return 0.0;
  return pages * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

// The child's RLIMIT_AS: what the parent has mapped (the child inherits every mapping,
// TBB's stacks and malloc's arenas among them) plus the import's own allowance.
std::optional<rlim_t> address_space_cap(const ImportLimits& limits) {
  if (!limits.max_memory_bytes) return std::nullopt;
  const double cap = mapped_bytes() + *limits.max_memory_bytes;
  if (!(cap < static_cast<double>(RLIM_INFINITY) / 2)) return std::nullopt;
  return static_cast<rlim_t>(cap);
}

bool write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// The child: read the model, write the answer, leave through _exit (no atexit handlers,
// no destructors of statics, no flush of stdio buffers copied from the parent).
[[noreturn]] void run_child(int read_fd, int write_fd, const std::string& path, const std::string& ext,
                            const MeshReadOptions& options, std::optional<rlim_t> cap) {
  ::close(read_fd);
  // Only our end of the pipe stays open beside stdin, stdout and stderr: a copy of
  // another pipe's write end held here would keep that pipe's reader waiting.
  if (write_fd > 3) ::close_range(3, static_cast<unsigned>(write_fd) - 1, 0);
  ::close_range(static_cast<unsigned>(write_fd) + 1, ~0U, 0);
  // A crash ends the child with its signal, whatever handler the parent installed (a
  // sanitizer's or a debugger's would report or loop instead).
  for (int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) ::signal(sig, SIG_DFL);
  if (cap) {
    const rlimit limit{*cap, *cap};
    ::setrlimit(RLIMIT_AS, &limit);
  }
  std::string message;
  try {
    message = encode_mesh_message(load_with_assimp(path, ext, options));
  } catch (const SceneError& e) {
    std::string text = e.what();
    if (cap && text == path + ": out of memory reading the model") text += kLimitReached;
    message = encode_error_message(text);
  } catch (const std::bad_alloc&) {
    message = encode_error_message(path + ": out of memory reading the model" + (cap ? kLimitReached : ""));
  } catch (const std::exception& e) {
    message = encode_error_message(path + ": assimp cannot read it: " + e.what());
  } catch (...) {
    message = encode_error_message(path + ": assimp cannot read it (an unknown exception)");
  }
  const bool written = write_all(write_fd, message);
  ::close(write_fd);
  ::_exit(written ? 0 : kChildWriteFailed);
}

// Owns the read end of the pipe and the child until it is reaped: an exception on the
// way kills and reaps it, so no child outlives the call and no descriptor leaks.
class ChildProcess {
 public:
  ChildProcess(pid_t pid, int fd) : pid_(pid), fd_(fd) {}
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess() {
    close_pipe();
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      wait_blocking();
    }
  }
  int fd() const { return fd_; }
  void close_pipe() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  // The child's wait status once it has ended; nullopt while it runs.
  std::optional<int> try_wait() {
    int status = 0;
    pid_t r;
    do r = ::waitpid(pid_, &status, WNOHANG);
    while (r < 0 && errno == EINTR);
    if (r == 0) return std::nullopt;
    pid_ = -1;
    return status;
  }
  int kill_and_wait() {
    ::kill(pid_, SIGKILL);
    return wait_blocking();
  }

 private:
  int wait_blocking() {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    return status;
  }
  pid_t pid_;
  int fd_;
};

std::string seconds_text(double s) {
  std::ostringstream os;
  os << s;
  return os.str();
}

}  // namespace

TriangleMesh load_with_assimp_isolated(const std::string& path, const std::string& ext, const MeshReadOptions& options) {
  const ImportLimits& limits = options.import_limits;
  if (!(limits.max_time_s > 0.0 && limits.max_time_s <= kMaxTime_s))
    throw SceneError(path + ": the import's time limit " + seconds_text(limits.max_time_s) + " s must be in (0, " +
                     seconds_text(kMaxTime_s) + "]");
  const std::optional<rlim_t> cap = address_space_cap(limits);
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw SceneError(path + ": cannot start the process that reads it (pipe: " + errno_text(errno) + ")");
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw SceneError(path + ": cannot start the process that reads it (fork: " + errno_text(error) + ")");
  }
  if (pid == 0) run_child(fds[0], fds[1], path, ext, options, cap);
  ::close(fds[1]);  // the child's end: the read below sees the end of file when the child closes its copy
  ChildProcess child(pid, fds[0]);

  // Read until the child closes the pipe (it cannot block on a full pipe: we drain it).
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limits.max_time_s));
  const std::string took_too_long =
      path + ": assimp took longer than " + seconds_text(limits.max_time_s) + " s reading it (stopped)";
  std::string bytes;
  std::string buffer(1 << 16, '\0');
  for (bool open = true; open;) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) {
      child.kill_and_wait();
      throw SceneError(took_too_long);
    }
    pollfd p{child.fd(), POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, INT_MAX)));
    if (ready < 0 && errno != EINTR)
      throw SceneError(path + ": lost the process that reads it (poll: " + errno_text(errno) + ")");
    if (ready <= 0) continue;
    const ssize_t n = ::read(child.fd(), buffer.data(), buffer.size());
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n < 0) throw SceneError(path + ": lost the process that reads it (read: " + errno_text(errno) + ")");
    if (n == 0) open = false;
    else bytes.append(buffer.data(), static_cast<std::size_t>(n));
  }
  child.close_pipe();

  // The pipe is closed: the child is leaving (or closed it and went on, which ours never does).
  std::optional<int> status;
  while (!(status = child.try_wait())) {
    if (Clock::now() >= deadline) {
      child.kill_and_wait();
      throw SceneError(took_too_long);
    }
    ::usleep(1000);
  }
  if (WIFSIGNALED(*status)) {
    const int sig = WTERMSIG(*status);
    std::string why = "assimp crashed reading it (" + signal_text(sig) + ")";
    if (sig == SIGKILL) why = "the process reading it was killed (" + signal_text(sig) + ", from outside: the system "
                              "may have run out of memory)";
    throw SceneError(path + ": " + why + "; the file is malformed or uses a feature " + kAssimp + " cannot read");
  }
  if (!WIFEXITED(*status) || WEXITSTATUS(*status) != 0)
    throw SceneError(path + ": the process reading it with assimp ended with status " +
                     std::to_string(WIFEXITED(*status) ? WEXITSTATUS(*status) : *status) + " before it sent the model");
  MeshMessage message;
  try {
    message = decode_mesh_message(bytes);
  } catch (const MeshMessageError& e) {
    throw SceneError(path + ": the process reading it with assimp sent a truncated or malformed result: " + e.what());
  }
  if (message.is_error) throw SceneError(message.error);
  message.mesh.path = path;
  return std::move(message.mesh);
}

}  // namespace ilp
