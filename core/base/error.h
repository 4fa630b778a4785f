// Error types and source locations for everything the user hands us.
// Libraries throw; programs catch once in main and exit non-zero. Every message
// that concerns user input names the file, line and key it came from.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace ilp {

// Where a value came from: file, 1-based line and column (0 = unknown).
struct FileLoc {
  std::string file;
  int line = 0;
  int column = 0;
};

// "file:line:col" (line/column left out when unknown).
std::string to_string(const FileLoc& loc);

class IlpError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A job configuration (YAML) that is malformed or breaks a rule.
class ConfigError : public IlpError {
 public:
  using IlpError::IlpError;
};

// A mesh or material file that cannot be read or makes no usable scene.
class SceneError : public IlpError {
 public:
  using IlpError::IlpError;
};

// A numerical failure: non-convergence, NaN/Inf, a singular system.
class NumericalError : public IlpError {
 public:
  using IlpError::IlpError;
};

// "file:line:col: message".
std::string located(const FileLoc& loc, const std::string& message);

// Why `path` cannot be read as a `what` file ("config", "mesh", ...): "PATH: is a
// folder, not a config file", "PATH: is a FIFO (named pipe), not a ...", a device or
// a socket; empty for a regular file (symbolic links followed) and for a path that
// does not exist (the caller's open then fails with its own message). Checked before
// opening: open() of a FIFO blocks until a writer comes, for ever in practice.
std::string not_a_regular_file(const std::string& path, const std::string& what);

// Text from a file made safe for a terminal, SVG, JSON or a log: control characters
// (below 0x20 but tab, and 0x7f) as \xNN, so that an escape sequence in a vendor's
// file is shown, not obeyed; newlines kept when `keep_newlines`.
std::string printable(std::string_view text, bool keep_newlines = false);

// `text` shortened to at most `max_chars` bytes (on a UTF-8 boundary) with "..." and
// the full length appended when cut: for echoing a value in a message.
std::string shortened(std::string_view text, std::size_t max_chars = 80);

}  // namespace ilp
