// Checks shared by the tests of the SVG writers: well-formedness as an XML parser
// would judge it, for the subset of SVG the writers emit.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

namespace ilp::test {

// Checks the document the way an XML parser would, for the subset the writer uses:
// one root <svg> element, every element closed in order, no '<' or stray '&' in text
// or attribute values (only the five predefined entities and numeric references).
inline ::testing::AssertionResult WellFormed(const std::string& svg) {
  std::vector<std::string> open;
  int roots = 0;
  for (std::size_t i = 0; i < svg.size();) {
    if (svg[i] == '&') {
      const std::size_t end = svg.find(';', i);
      const std::string entity = end == std::string::npos ? svg.substr(i) : svg.substr(i, end - i + 1);
      if (entity != "&amp;" && entity != "&lt;" && entity != "&gt;" && entity != "&quot;" && entity.rfind("&#", 0) != 0)
        return ::testing::AssertionFailure() << "stray '&' at " << i << ": " << entity;
      i = end + 1;
      continue;
    }
    if (svg[i] != '<') {
      if (open.empty() && !std::isspace(static_cast<unsigned char>(svg[i])))
        return ::testing::AssertionFailure() << "text outside the root element at " << i;
      ++i;
      continue;
    }
    const std::size_t end = svg.find('>', i);
    if (end == std::string::npos) return ::testing::AssertionFailure() << "unterminated tag at " << i;
    const std::string tag = svg.substr(i + 1, end - i - 1);
    if (tag.find('<') != std::string::npos) return ::testing::AssertionFailure() << "'<' inside tag at " << i;
    if (std::count(tag.begin(), tag.end(), '"') % 2 != 0)
      return ::testing::AssertionFailure() << "unbalanced quotes in <" << tag << ">";
    if (tag.front() == '/') {
      if (open.empty() || open.back() != tag.substr(1))
        return ::testing::AssertionFailure() << "</" << tag.substr(1) << "> closes "
                                             << (open.empty() ? std::string("nothing") : "<" + open.back() + ">");
      open.pop_back();
    } else {
      if (open.empty()) ++roots;
      if (tag.back() != '/') open.push_back(tag.substr(0, tag.find_first_of(" \n")));
    }
    i = end + 1;
  }
  if (!open.empty()) return ::testing::AssertionFailure() << "<" << open.back() << "> is never closed";
  if (roots != 1) return ::testing::AssertionFailure() << roots << " root elements";
  return ::testing::AssertionSuccess();
}

}  // namespace ilp::test
