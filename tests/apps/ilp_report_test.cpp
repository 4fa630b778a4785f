// The shipped office_products job's report.pdf through the real program (issue 22):
// pdftotext reads the summary table, every goal line, LENI, the data sheet with its
// polar curve, the plan, the isolux plan and the grid's value table, each with the
// numbers of result.json and grid.csv; pdftoppm renders every page; LENI in result.json
// is the hand formula of its own power and area; no folder of the machine is printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "output/grid_csv.h"
#include "output/report_pdf.h"
#include "output/result_record.h"
#include "tests/apps/cli_runner.h"
#include "tests/output/pdf_text.h"
#include "tests/test_support.h"

namespace fs = std::filesystem;

namespace {

using ilp::test::OutputContains;
using ilp::test::read_file;
using ilp::test::run_ilp;
using ilp::test::RunResult;
using ilp::test::TempDir;

std::string fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

std::string squeezed(const std::string& text) { return std::regex_replace(text, std::regex("[ \t]+"), " "); }

// The rows of the report's value table as pdftotext -layout lines them up: "y v1 v2 ...",
// maintained lux rounded to whole lux, x ascending (the first 12 columns), y from the top.
std::vector<std::string> value_rows(const ilp::GridCsvGrid& grid) {
  std::map<long, std::map<long, double>> by_y;  // y in mm -> x in mm -> lux
  std::set<long> xs;
  for (const ilp::GridCsvPoint& p : grid.points) {
    const long x = std::lround(p.position_m.x() * 1000.0), y = std::lround(p.position_m.y() * 1000.0);
    by_y[y][x] = p.total_initial_lux * grid.maintenance_factor;
    xs.insert(x);
  }
  std::vector<std::string> rows;
  for (auto it = by_y.rbegin(); it != by_y.rend(); ++it) {
    std::string row = fixed(static_cast<double>(it->first) / 1000.0, 2);
    int column = 0;
    for (long x : xs) {
      if (column++ == 12) break;
      const auto v = it->second.find(x);
      row += ' ';  // (appending, not " " + string: GCC 12's false -Wrestrict)
      row += v == it->second.end() ? std::string("–") : fixed(v->second, 0);
    }
    rows.push_back(row);
  }
  return rows;
}

TEST(IlpReport, OfficeProductsPdfHoldsTheVerifiedNumbers) {
  TempDir dir;
  const RunResult r = run_ilp(dir, {"run", ILP_SOURCE_DIR "/configs/office_products.yaml", "--out", dir.file("out"),
                                    "--cache", dir.file("cache"), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir.file("out/report.pdf"))) << r.out;
  const ilp::ResultRecord rec = ilp::read_result_json(dir.file("out/result.json"));
  ASSERT_TRUE(rec.energy.has_value());
  ASSERT_FALSE(rec.bill_of_materials.empty());
  ASSERT_FALSE(rec.grids.empty());

  // LENI by hand from result.json's own power and floor area: an office (2250 h + 250 h)
  // with constant-illuminance control at MF 0.8 (F_C 0.9), 6 kWh/(m²·a) parasitic.
  const double hand = (rec.power_w * 0.9 * (2250.0 + 250.0) / 1000.0 + 6.0 * rec.floor_area_m2) / rec.floor_area_m2;
  EXPECT_NEAR(rec.energy->leni_kwh_per_m2, hand, 1e-9);
  EXPECT_TRUE(OutputContains(r.out, "LENI " + fixed(hand, 2) + " kWh/(m²·a)"));

  const std::string text = squeezed(ilp::test::pdf_text(dir.file("out/report.pdf"), dir.file("")));
  // Summary: the answer and every goal line as result.json has it.
  EXPECT_TRUE(OutputContains(text, "Lighting report: office_products.yaml"));
  const ilp::BillLine& bill = rec.bill_of_materials.front();
  EXPECT_TRUE(OutputContains(text, std::to_string(bill.count) + " × " + bill.product));
  EXPECT_TRUE(OutputContains(text, "Installed power " + fixed(rec.power_w, 1) + " W"));
  EXPECT_TRUE(OutputContains(text, fixed(rec.power_density_w_per_m2, 2) + " W/m² over " + fixed(rec.floor_area_m2, 2) + " m²"));
  EXPECT_TRUE(OutputContains(text, fixed(rec.power_density_w_per_m2_per_100_lx, 2) + " W/m²/100 lx"));
  EXPECT_TRUE(OutputContains(text, "LENI (EN 15193-1) " + fixed(hand, 2) + " kWh/(m²·a)"));
  for (const std::vector<std::string>& row : ilp::report_goal_rows(rec)) {
    std::string line;
    for (const std::string& cell : row) line += (line.empty() ? "" : " ") + cell;
    EXPECT_TRUE(OutputContains(text, line));
  }
  for (const ilp::GoalRecord& g : rec.goals) EXPECT_TRUE(g.verified.has_value()) << g.name;
  // Room data.
  EXPECT_TRUE(OutputContains(text, "Model office.obj"));
  EXPECT_TRUE(OutputContains(text, "walls"));
  // The plan (its own title, as text) and each grid's isolux plan, statistics and values.
  EXPECT_TRUE(OutputContains(text, std::to_string(rec.luminaires.size()) + " luminaires, " + fixed(rec.power_w, 1) + " W, verified maintained illuminance"));
  const std::vector<ilp::GridCsvGrid> csv =
      ilp::parse_grid_csv(read_file(dir.file("out/grid.csv")), dir.file("out/grid.csv"));
  ASSERT_EQ(csv.size(), rec.grids.size());
  for (std::size_t g = 0; g < rec.grids.size(); ++g) {
    const ilp::GridRecord& grid = rec.grids[g];
    EXPECT_TRUE(grid.verified);
    EXPECT_TRUE(OutputContains(text, "Calculation grid: " + grid.name));
    EXPECT_TRUE(OutputContains(text, "maintained illuminance (lx)"));  // the isolux plan's legend
    EXPECT_TRUE(OutputContains(text, std::to_string(grid.points) + " " + fixed(grid.spacing_m, 2) + " m " + fixed(grid.area_m2, 2) +
                                         " m² " + fixed(grid.maintained.average_lux, 1) + " lx " +
                                         fixed(grid.maintained.min_lux, 1) + " lx " + fixed(grid.maintained.max_lux, 1) +
                                         " lx " + fixed(grid.maintained.uniformity, 3)));
    for (const std::string& row : value_rows(csv[g])) EXPECT_TRUE(OutputContains(text, row));
  }
  // The product's data sheet with its polar curve (drawn: its legend is text too).
  EXPECT_TRUE(OutputContains(text, "Data sheet: " + bill.product));
  EXPECT_TRUE(OutputContains(text, "Photometric file " + bill.source));
  EXPECT_TRUE(OutputContains(text, "C0–C180 (C0 right)"));
  EXPECT_TRUE(OutputContains(text, "cd/klm (per 1000 lm"));
  // Bill of materials and verification.
  EXPECT_TRUE(OutputContains(text, "Bill of materials"));
  EXPECT_TRUE(OutputContains(text, "exact radiosity solve"));
  EXPECT_TRUE(OutputContains(text, "Rays per patch " + std::to_string(rec.verification_rays_per_patch)));
  // No folder of this machine anywhere in the report, the printout or the bill of
  // materials of result.json (it used to hold the photometric file's absolute path).
  EXPECT_EQ(bill.source, fs::path(bill.source).filename().string());
  EXPECT_EQ(r.out.find(ILP_SOURCE_DIR "/data"), std::string::npos) << r.out;
  EXPECT_EQ(text.find(ILP_SOURCE_DIR), std::string::npos);
  EXPECT_EQ(read_file(dir.file("out/report.pdf")).find(ILP_SOURCE_DIR), std::string::npos);

  // Every page renders.
  const std::string info = dir.file("pdfinfo.txt");
  ASSERT_EQ(ilp::test::run_capture("pdfinfo '" + dir.file("out/report.pdf") + "'", info), 0);
  std::smatch pages;
  const std::string info_text = read_file(info);
  ASSERT_TRUE(std::regex_search(info_text, pages, std::regex("Pages:\\s+(\\d+)")));
  const int page_count = std::stoi(pages[1].str());
  EXPECT_GE(page_count, 6);
  ASSERT_EQ(ilp::test::run_capture("pdftoppm -png -r 30 '" + dir.file("out/report.pdf") + "' '" + dir.file("page") + "'",
                                   dir.file("pdftoppm.txt")),
            0);
  int rendered = 0;
  for (const auto& e : fs::directory_iterator(dir.file("")))
    if (e.path().filename().string().rfind("page-", 0) == 0 && fs::file_size(e.path()) > 1000) ++rendered;
  EXPECT_EQ(rendered, page_count);
}

}  // namespace
