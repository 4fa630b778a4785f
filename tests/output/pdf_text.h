// Reading a PDF back as a client's tools do (poppler-utils: pdftotext, pdffonts,
// pdftoppm), for the report tests. scripts/setup.sh installs poppler-utils.
#pragma once

#include <cstdlib>
#include <string>

#include "tests/test_support.h"

namespace ilp::test {

// `command` run by the shell with its stdout captured to `out_file`; its exit status.
inline int run_capture(const std::string& command, const std::string& out_file) {
  return std::system((command + " >'" + out_file + "' 2>&1").c_str());
}

// The PDF's text as pdftotext gives it (reading order, -layout keeps table rows on one
// line); "" (and a test failure) when pdftotext cannot run.
inline std::string pdf_text(const std::string& pdf, const std::string& scratch_dir, bool layout = true) {
  const std::string out = scratch_dir + "/pdftotext.txt";
  const int status = std::system(("pdftotext " + std::string(layout ? "-layout " : "") + "'" + pdf + "' '" + out + "'").c_str());
  EXPECT_EQ(status, 0) << "pdftotext failed on " << pdf << " (install poppler-utils: scripts/setup.sh)";
  return read_file(out);
}

}  // namespace ilp::test
