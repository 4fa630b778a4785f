#include "core/base/error.h"

#include <sstream>

namespace ilp {

std::string to_string(const FileLoc& loc) {
  std::ostringstream os;  // (string += on GCC 12 trips a false -Wrestrict)
  os << loc.file;
  if (loc.line > 0) {
    os << ':' << loc.line;
    if (loc.column > 0) os << ':' << loc.column;
  }
  return os.str();
}

std::string located(const FileLoc& loc, const std::string& message) {
  return to_string(loc) + ": " + message;
}

}  // namespace ilp
