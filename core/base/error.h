// Error types and source locations for everything the user hands us.
// Libraries throw; programs catch once in main and exit non-zero. Every message
// that concerns user input names the file, line and key it came from.
#pragma once

#include <stdexcept>
#include <string>

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

}  // namespace ilp
