// Runs the real `ilp` program (ILP_BINARY) for the CLI tests: arguments quoted for
// the shell, stdout and stderr captured to files in the test's folder, the operator
// cache ($XDG_CACHE_HOME/ilp) kept there too.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.h"

namespace ilp::test {

inline std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// One folder of the machine's calibration (ILP_MACHINE_DIR) for every CLI test of this
// user: the first `ilp` to need it probes, the rest read it (core/cost/machine_speed.h).
inline std::string suite_machine_dir() {
  return (std::filesystem::temp_directory_path() / ("ilp_test_machine_" + std::to_string(::getuid()))).string();
}

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs `ilp <args>` with stdout and stderr captured to files in `dir`; `prefix` (e.g.
// {"nice", "-n", "19"}) runs it through another program.
inline RunResult run_ilp(const TempDir& dir, const std::vector<std::string>& args,
                         const std::vector<std::string>& prefix = {}) {
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  std::ostringstream command;  // (string + on GCC 12 trips a false -Wrestrict)
  // The operator cache goes to the test's folder, never to the user's; the machine's
  // calibration is probed once for the whole suite (tests of it give their own folder).
  command << "XDG_CACHE_HOME=" << quoted(dir.file("xdg-cache")) << " ILP_MACHINE_DIR=" << quoted(suite_machine_dir());
  for (const std::string& p : prefix) command << ' ' << quoted(p);
  command << ' ' << quoted(ILP_BINARY);
  for (const std::string& a : args) command << ' ' << quoted(a);
  command << " >" << quoted(out) << " 2>" << quoted(err) << " </dev/null";
  const int status = std::system(command.str().c_str());
  RunResult r;
  r.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

// For EXPECT_TRUE: what the program wrote contains `part`.
inline ::testing::AssertionResult OutputContains(const std::string& text, const std::string& part) {
  return Contains(text, part, "output");
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace ilp::test
