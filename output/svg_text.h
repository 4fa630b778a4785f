// Text helpers shared by the SVG writers of this module (svg_plot.cpp, plan_svg.cpp):
// string assembly, XML escaping and character counts for label widths.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>

namespace ilp::svg {

// Concatenation by appending (strings, string_views, literals, chars): clearer than
// long operator+ chains, and free of GCC 12's false -Wrestrict warning on
// `"literal" + std::string&&`.
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string s;
  ((s += parts), ...);
  return s;
}

// Escapes XML's special characters and drops the control characters XML 1.0 forbids.
inline std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') break;
        out += c;
    }
  }
  return out;
}

// Characters (UTF-8 code points) in `text`.
inline std::size_t char_count(std::string_view text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;  // not a continuation byte
  }));
}

}  // namespace ilp::svg
