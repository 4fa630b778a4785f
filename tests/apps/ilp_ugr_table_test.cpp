// `ilp ugr-table`: the CIE 190 table of a photometric file, as text and as CSV, and the error
// contract for a file that cannot be read.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "tests/apps/cli_runner.h"
#include "tests/test_support.h"

namespace {

using ilp::test::lines_of;
using ilp::test::OutputContains;
using ilp::test::run_ilp;
using ilp::test::RunResult;
using ilp::test::TempDir;

const std::string kExample = std::string(ILP_SOURCE_DIR) + "/tests/data/glare/cie190_example.ldt";

TEST(IlpUgrTable, CsvIsTheCie190TableOfTheExampleLuminaire) {
  TempDir dir;
  const RunResult r = run_ilp(dir, {"ugr-table", "--csv", kExample});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> rows = lines_of(r.out);
  ASSERT_EQ(rows.size(), 19u);
  std::vector<double> row_4x8;  // the 11th room, 4H x 8H
  std::istringstream in(rows[10]);
  for (std::string cell; std::getline(in, cell, ',');) row_4x8.push_back(std::stod(cell));
  ASSERT_EQ(row_4x8.size(), 10u);
  // CIE 190:2010's printed table for its example luminaire, 4H x 8H: crosswise 13.0 (70/50/20)
  // and 14.7 (30/30/20); endwise 14.7 and 16.4 (tests/data/glare/cie190_example_ugr_cie190.csv).
  EXPECT_NEAR(row_4x8[0], 13.0, 0.5);
  EXPECT_NEAR(row_4x8[4], 14.7, 0.5);
  EXPECT_NEAR(row_4x8[5], 14.7, 0.5);
  EXPECT_NEAR(row_4x8[9], 16.4, 0.5);
}

TEST(IlpUgrTable, TextNamesTheFileAndTheConventions) {
  TempDir dir;
  const RunResult r = run_ilp(dir, {"ugr-table", kExample});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(OutputContains(r.out, "cie190_example.ldt"));
  EXPECT_TRUE(OutputContains(r.out, "crosswise = line of sight in the C0-C180 plane"));
  EXPECT_TRUE(OutputContains(r.out, "4H x  8H"));
  EXPECT_TRUE(OutputContains(r.out, "70/50/20"));
}

TEST(IlpUgrTable, UnreadableFileIsOneErrorLine) {
  TempDir dir;
  const RunResult r = run_ilp(dir, {"ugr-table", dir.file("missing.ldt")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(lines_of(r.err).size(), 1u);
  EXPECT_TRUE(OutputContains(r.err, "error: "));
}

}  // namespace
