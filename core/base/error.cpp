#include "core/base/error.h"

#include <sys/stat.h>

#include <cstdio>
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

std::string not_a_regular_file(const std::string& path, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return {};
  const char* kind = S_ISDIR(st.st_mode)    ? "a folder"
                     : S_ISFIFO(st.st_mode) ? "a FIFO (named pipe)"
                     : S_ISSOCK(st.st_mode) ? "a socket"
                     : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                                                                  : "a special file";
  return path + ": is " + kind + ", not a " + what + " file";
}

std::string printable(std::string_view text, bool keep_newlines) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if ((u >= 0x20 && u != 0x7f) || c == '\t' || (keep_newlines && c == '\n')) {
      out += c;
      continue;
    }
    char hex[8];
    std::snprintf(hex, sizeof hex, "\\x%02x", u);
    out += hex;
  }
  return out;
}

std::string shortened(std::string_view text, std::size_t max_chars) {
  if (text.size() <= max_chars) return std::string(text);
  std::size_t cut = max_chars;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 sequence
  return std::string(text.substr(0, cut)) + "... (" + std::to_string(text.size()) + " characters)";
}

}  // namespace ilp
