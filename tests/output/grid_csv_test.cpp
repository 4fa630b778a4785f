// grid.csv: the header names every column with its unit, values round trip through
// the reader to the file's rounding, maintained = initial x factor, names are quoted,
// and bad files fail with file:line.
#include "output/grid_csv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/base/error.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::Contains;
using test::error_of;

std::vector<GridCsvGrid> sample_grids() {
  GridCsvGrid work{"work plane 0.80 m", 0.8, {}};
  for (int k = 0; k < 5; ++k)
    work.points.push_back({Eigen::Vector3d(0.5 + 0.2 * k, 0.7, 0.8), 300.123 + 17.3 * k, 450.456 + 21.7 * k});
  GridCsvGrid wall{"board, \"front\"", 0.67, {{Eigen::Vector3d(0.0, 1.25, 1.6), 0.004, 212.5}}};
  return {work, wall};
}

TEST(GridCsv, HeaderNamesEveryColumnWithItsUnit) {
  const std::string csv = grid_csv(sample_grids());
  EXPECT_TRUE(test::StartsWith(csv,
                               "grid,point,x_m,y_m,z_m,direct_initial_lux,total_initial_lux,maintenance_factor,"
                               "direct_maintained_lux,total_maintained_lux\n"));
  // Row: fixed decimals, maintained = initial x 0.8 (300.123 x 0.8 = 240.0984).
  EXPECT_TRUE(Contains(csv, "\nwork plane 0.80 m,0,0.5,0.7,0.8,300.12,450.46,0.8,240.1,360.36\n"));
  // A name with a comma and quotes is quoted, the quotes doubled.
  EXPECT_TRUE(Contains(csv, "\n\"board, \"\"front\"\"\",0,0,1.25,1.6,0,212.5,0.67,0,142.38\n"));
}

TEST(GridCsv, RoundTripsToTheFilesRounding) {
  const std::vector<GridCsvGrid> grids = sample_grids();
  const std::vector<GridCsvGrid> back = parse_grid_csv(grid_csv(grids), "grid.csv");
  ASSERT_EQ(back.size(), grids.size());
  for (std::size_t g = 0; g < grids.size(); ++g) {
    EXPECT_EQ(back[g].name, grids[g].name);
    EXPECT_DOUBLE_EQ(back[g].maintenance_factor, grids[g].maintenance_factor);
    ASSERT_EQ(back[g].points.size(), grids[g].points.size());
    for (std::size_t k = 0; k < grids[g].points.size(); ++k) {
      const GridCsvPoint &a = grids[g].points[k], &b = back[g].points[k];
      EXPECT_LE((a.position_m - b.position_m).cwiseAbs().maxCoeff(), 0.5e-4 + 1e-12) << g << "/" << k;
      EXPECT_NEAR(a.direct_initial_lux, b.direct_initial_lux, 0.5e-2 + 1e-9) << g << "/" << k;
      EXPECT_NEAR(a.total_initial_lux, b.total_initial_lux, 0.5e-2 + 1e-9) << g << "/" << k;
    }
  }
  // The initial columns, written again from what was read, are the same text.
  const auto initial_columns = [](const std::string& csv) {
    std::string out;
    std::istringstream in(csv);
    for (std::string line; std::getline(in, line);) out += line.substr(0, line.rfind(',', line.rfind(',') - 1)) + "\n";
    return out;
  };
  EXPECT_EQ(initial_columns(grid_csv(back)), initial_columns(grid_csv(grids)));
}

TEST(GridCsv, WritesAtomicallyAndRefusesBadValuesBeforeWriting) {
  test::TempDir dir;
  const std::string path = dir.file("grid.csv");
  write_grid_csv(path, sample_grids());
  EXPECT_EQ(test::read_file(path), grid_csv(sample_grids()));
  std::vector<GridCsvGrid> bad = sample_grids();
  bad[0].points[2].total_initial_lux = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_grid_csv(path, bad), std::invalid_argument);
  EXPECT_EQ(test::read_file(path), grid_csv(sample_grids())) << "the previous file stays";
  bad = sample_grids();
  bad[1].maintenance_factor = 0.0;
  EXPECT_THROW(grid_csv(bad), std::invalid_argument);
}

TEST(GridCsv, BadFilesFailWithFileAndLine) {
  const std::string header =
      "grid,point,x_m,y_m,z_m,direct_initial_lux,total_initial_lux,maintenance_factor,direct_maintained_lux,"
      "total_maintained_lux\n";
  const auto error = [](const std::string& text) {
    return error_of<IlpError>([&] { parse_grid_csv(text, "out/grid.csv"); });
  };
  EXPECT_TRUE(test::StartsWith(error("x,y,z\n"), "out/grid.csv:1: the header must be grid,point,"));
  EXPECT_TRUE(test::StartsWith(error(header + "a,0,1,2,3,4,5,0.5,2,2.5\na,0,1,2\n"), "out/grid.csv:3: 4 fields"));
  EXPECT_TRUE(test::StartsWith(error(header + "a,0,1,2,abc,4,5,0.5,2,2.5\n"), "out/grid.csv:2: z_m = 'abc'"));
  EXPECT_TRUE(test::StartsWith(error(header + "a,1,1,2,3,4,5,0.5,2,2.5\n"), "out/grid.csv:2: point = 1, expected 0"));
  EXPECT_TRUE(test::StartsWith(error(header + "a,0,1,2,3,4,5,0.5,2,3\n"), "out/grid.csv:2: the maintained values"));
  EXPECT_TRUE(test::StartsWith(error(header + "a,0,1,2,3,4,5,1.5,6,7.5\n"), "out/grid.csv:2: maintenance_factor"));
  EXPECT_TRUE(test::StartsWith(error(header + "\"a,0,1\n"), "out/grid.csv:2: unterminated"));
  // A blank last line and CRLF line ends are fine.
  EXPECT_EQ(parse_grid_csv(header + "a,0,1,2,3,4,5,0.5,2,2.5\r\n\n", "g").at(0).points.size(), 1u);
}

}  // namespace
}  // namespace ilp
