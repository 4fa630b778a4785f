// The PDF report (output/report_pdf.h) read back as a client's tools read it: its text
// (pdftotext) holds the summary, the room, the grid's value table, the data sheet and
// the verification with the record's numbers; fonts are embedded (pdffonts); no folder
// of the machine appears; a bad SVG is an error naming the file and nothing is written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <regex>
#include <sstream>
#include <vector>

#include "core/base/error.h"
#include "core/glare/ugr_table.h"
#include "output/report_pdf.h"
#include "tests/output/pdf_text.h"
#include "tests/test_support.h"

namespace {

using ilp::test::Contains;
using ilp::test::TempDir;

ilp::Photometry cosine_file() {
  std::ostringstream os;
  os << "IESNA:LM-63-2002\n[LUMINAIRE] Test panel 600\n[MANUFAC] Testwerk\nTILT=NONE\n";
  os << "1 3000 1 19 1 1 2 0.6 0.6 0\n1.0 1.0 30\n";
  for (int g = 0; g <= 90; g += 5) os << g << ' ';
  os << "\n0\n";
  for (int g = 0; g <= 90; g += 5) os << 950.0 * std::cos(g * std::numbers::pi / 180.0) << ' ';
  os << '\n';
  return ilp::parse_ies(os.str(), "/home/designer/secret-project/photometry/panel.ies");
}

ilp::ResultRecord record() {
  ilp::ResultRecord r;
  r.program_version = "ilp 0.1.0";
  r.config = "/home/designer/secret-project/job.yaml";
  r.objective = "min_power";
  r.layout_family = "field";
  r.arrangement = "2 x 2 field";
  r.spacing_x_m = 2.0;
  r.spacing_y_m = 1.5;
  for (int k = 0; k < 4; ++k)
    r.luminaires.push_back({"L" + std::to_string(k + 1), 1.0 + 2.0 * (k % 2), 1.0 + 1.5 * (k / 2), 2.75, 2400.0, 24.5,
                            "panel 3000 lm", 0.0, 2.75});
  r.bill_of_materials.push_back({"panel 3000 lm", "panel.ies", 4, 3000.0, 30.625, 0.8, 98.0});
  r.goals.push_back({"work_plane", {}, "average", "lx", 500.0, 503.21, 500.04, true, false, 0.0, "work_plane"});
  r.goals.push_back({"work_plane", {}, "uniformity", "", 0.6, 0.712, 0.6843, true, false, 0.0, "work_plane"});
  r.goals.push_back({"floor", {"floor"}, "minimum", "lx", 100.0, 104.0, 96.5, false, true, 0.0, ""});
  ilp::VerdictLine distance{"min_distance_m", {}, "distance between neighbours", "m", 1.0, 1.5, std::nullopt, true, false, 0.0, ""};
  distance.kind = "constraint";
  distance.rule = ">=";
  r.constraints.push_back(distance);
  r.power_w = 98.0;
  r.floor_area_m2 = 12.0;
  r.floor_area_source = "floor";
  r.power_density_w_per_m2 = 98.0 / 12.0;
  r.power_density_w_per_m2_per_100_lx = 98.0 / 12.0 / 5.0;
  r.maintenance_factor = 0.8;
  r.grids.push_back({"work_plane", 6, 6.0, 1.0, 0, true, {625.0, 400.0, 800.0, 0.64}, {500.04, 320.0, 640.0, 0.64}});
  r.verification = "exact";
  r.verification_rays_per_patch = 1024;
  r.patches = 812;
  r.population = 800;
  r.sample_size = 40;
  r.candidates = 96;
  r.all_met = false;
  r.feasible = true;
  r.room = ilp::RoomRecord{"room.obj", 4.0, 3.0, 3.0, 0.0,
                           {{"floor", 12.0, 0.2, 0.0, 0.0}, {"ceiling", 12.0, 0.7, 3.0, 3.0}, {"walls", 42.0, 0.5, 0.0, 3.0}}};
  r.energy = ilp::EnergyRecord{"office", false, 2250.0, 250.0, 1.0, 1.0, 0.9, 6.0, 98.0, 12.0, 220.5, 72.0, 292.5, 24.375};
  return r;
}

// A 3 x 2 grid at 0.5 .. 2.5 m x 0.75 .. 2.25 m with distinct values.
ilp::IsoluxGridView grid_view() {
  ilp::IsoluxGridView v;
  v.name = "work_plane";
  v.nx = 3;
  v.ny = 2;
  v.origin_m = {0.5, 0.75};
  v.spacing_m = {1.0, 1.5};
  v.maintained_lux = {321.0, 456.0, 398.0, 512.0, 640.0, 587.0};
  v.target_lux = 500.0;
  v.maintenance_factor = 0.8;
  v.room_outline_m = {{{0, 0}, {4, 0}, {4, 3}, {0, 3}}};
  return v;
}

std::string plan_svg() {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"400\" height=\"300\"><rect x=\"10\" y=\"10\" "
         "width=\"380\" height=\"280\" fill=\"#eee\"/><text x=\"20\" y=\"40\" font-size=\"14\">PLANMARK L1</text></svg>";
}

// Collapses runs of spaces so that table cells read as "a b c".
std::string squeezed(const std::string& text) { return std::regex_replace(text, std::regex(" +"), " "); }

TEST(ReportPdf, TextHoldsTheRecordsNumbersWithUnits) {
  TempDir dir;
  const ilp::ResultRecord r = record();
  const ilp::Photometry photometry = cosine_file();
  ilp::ReportInput in;
  in.job = "job.yaml";
  in.record = &r;
  in.plan_svg = plan_svg();
  in.grids.push_back(grid_view());
  in.products.push_back({"panel 3000 lm", "panel.ies", &photometry, 3000.0, 30.625, 0.3, 1.0, 0.6, 0.6});
  const std::string pdf = dir.file("report.pdf");
  ilp::write_report_pdf(pdf, in);
  ASSERT_TRUE(std::filesystem::exists(pdf));
  const std::string text = squeezed(ilp::test::pdf_text(pdf, dir.file("")));
  // Summary: the answer and every goal line with its verdict.
  EXPECT_TRUE(Contains(text, "Lighting report: job.yaml"));
  EXPECT_TRUE(Contains(text, "4 × panel 3000 lm (set to 80.0 %)"));
  EXPECT_TRUE(Contains(text, "Installed power 98.0 W"));
  EXPECT_TRUE(Contains(text, "8.17 W/m² over 12.00 m² (floor)"));
  EXPECT_TRUE(Contains(text, "1.63 W/m²/100 lx"));
  EXPECT_TRUE(Contains(text, "24.38 kWh/(m²·a)"));
  EXPECT_TRUE(Contains(text, "work_plane average (lx) >= 500.0 lx 503.2 lx 500.0 lx met"));
  EXPECT_TRUE(Contains(text, "work_plane uniformity >= 0.600 0.712 0.684 met"));
  EXPECT_TRUE(Contains(text, "floor minimum (lx) >= 100.0 lx 104.0 lx 96.5 lx NOT MET by 3.5 %"));
  EXPECT_TRUE(Contains(text, "min_distance_m constraint >= 1.000 m 1.500 m – met")) << "constraints too";
  EXPECT_TRUE(Contains(text, "NOT MET: floor minimum 96.5 lx < 100.0 lx (by 3.5 lx, 3.5 %)")) << "the failing line named";
  // Room: dimensions, reflectances, heights, schedule.
  EXPECT_TRUE(Contains(text, "4.00 m × 3.00 m × 3.00 m"));
  EXPECT_TRUE(Contains(text, "walls 42.00 m² 0.50 0.00 m 3.00 m"));
  EXPECT_TRUE(Contains(text, "L4 panel 3000 lm 3.00 m 2.50 m 2.75 m 0° 2400 lm 24.5 W"));
  // The plan's own text survives as text.
  EXPECT_TRUE(Contains(text, "PLANMARK L1"));
  // The grid: statistics and the value table, highest y first as on the plan.
  EXPECT_TRUE(Contains(text, "6 1.00 m 6.00 m² 500.0 lx 320.0 lx 640.0 lx 0.640 0.500"));
  EXPECT_TRUE(Contains(text, "2.25 512 640 587"));
  EXPECT_TRUE(Contains(text, "0.75 321 456 398"));
  // The data sheet: the file's figures and the curve's values (950 cd at nadir / flux).
  EXPECT_TRUE(Contains(text, "Data sheet: panel 3000 lm"));
  EXPECT_TRUE(Contains(text, "Testwerk"));
  EXPECT_TRUE(Contains(text, "Efficacy 98.0 lm/W"));
  EXPECT_TRUE(Contains(text, "600 mm along C0–C180 × 600 mm along C90–C270"));
  EXPECT_TRUE(Contains(text, "C0–C180"));
  std::ostringstream nadir;
  nadir << "C0 " << std::fixed;  // the C0 row starts at gamma 0
  nadir.precision(1);
  nadir << 950.0 * 1000.0 / photometry.luminaire_flux_lm;
  EXPECT_TRUE(Contains(text, nadir.str())) << nadir.str();
  // Bill of materials and verification.
  EXPECT_TRUE(Contains(text, "panel 3000 lm panel.ies 4 3000 lm 30.6 W 80.0 % 98.0 W"));
  EXPECT_TRUE(Contains(text, "exact radiosity solve"));
  EXPECT_TRUE(Contains(text, "work_plane average 503.2 lx 500.0 lx -0.63 %"));
  // File names only: the folders of the machine appear nowhere.
  EXPECT_EQ(text.find("/home/designer"), std::string::npos);
  EXPECT_EQ(ilp::test::read_file(pdf).find("/home/designer"), std::string::npos);
}

// A word's box in the PDF (pdftotext -bbox), points from the page's top left.
struct WordBox {
  std::string text;
  double x_min, y_min, x_max, y_max;
};

std::vector<WordBox> word_boxes(const std::string& pdf, const std::string& scratch) {
  const std::string out = scratch + "/bbox.html";
  EXPECT_EQ(ilp::test::run_capture("pdftotext -bbox '" + pdf + "' '" + out + "'", scratch + "/bbox.log"), 0);
  const std::string html = ilp::test::read_file(out);
  const std::regex word(R"re(<word xMin="([0-9.]+)" yMin="([0-9.]+)" xMax="([0-9.]+)" yMax="([0-9.]+)">([^<]*)</word>)re");
  std::vector<WordBox> boxes;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), word); it != std::sregex_iterator(); ++it)
    boxes.push_back({(*it)[5], std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]), std::stod((*it)[4])});
  return boxes;
}

// A goal name longer than its column (work_plane_surrounding in the classroom's report
// ran into the metric column: "work_plane_surroundingaverage (lx)"). Regression: the name
// is now broken after an underscore within its column; no word crosses into the next.
// The room's surfaces: the 20 largest, then one line for the rest.
TEST(ReportPdf, LongNamesStayInTheirColumnAndSmallSurfacesAreSummed) {
  TempDir dir;
  ilp::ResultRecord r = record();
  const std::string long_name = "work_plane_surrounding_of_the_front_desks";
  r.goals.push_back({long_name, {}, "average", "lx", 300.0, 310.0, 305.0, true, false, 0.0, long_name});
  for (int k = 0; k < 25; ++k) r.room->surfaces.push_back({"chair_" + std::to_string(k), 0.01 * (k + 1), 0.5, 0.0, 0.9});
  ilp::ReportInput in;
  in.job = "job.yaml";
  in.record = &r;
  const std::string pdf = dir.file("report.pdf");
  ilp::write_report_pdf(pdf, in);
  const std::vector<WordBox> boxes = word_boxes(pdf, dir.file(""));
  ASSERT_FALSE(boxes.empty());
  // The metric of the long line: the "average" word right of a piece of the name, on its row.
  int pieces = 0;
  for (const WordBox& name : boxes) {
    if (name.text.rfind("work_plane_surr", 0) != 0 && name.text.find("front_desks") == std::string::npos) continue;
    ++pieces;
    for (const WordBox& other : boxes) {
      if (&other == &name || std::abs(other.y_min - name.y_min) > 1.0 || other.x_min <= name.x_min) continue;
      EXPECT_LT(name.x_max, other.x_min) << "'" << name.text << "' runs into '" << other.text << "'";
    }
  }
  EXPECT_GE(pieces, 2) << "the long name broken into pieces";
  const std::string text = squeezed(ilp::test::pdf_text(pdf, dir.file("")));
  EXPECT_TRUE(Contains(text, "walls 42.00 m²")) << "the largest surfaces listed";
  EXPECT_TRUE(Contains(text, "chair_24 0.25 m²"));
  EXPECT_FALSE(Contains(text, "chair_0 0.01 m²")) << "a small surface beyond the 20 largest";
  // 28 surfaces: 20 listed, 8 summed (chair_0 .. chair_7: 0.01 + ... + 0.08 = 0.36 m²).
  EXPECT_TRUE(Contains(text, "8 smaller surfaces 0.36 m²")) << text;
}

// The data sheet's UGR table is the product's CIE 190 table (core/glare) at the rated
// flux the job uses: the 4H x 8H room at 70/50/20, crosswise and endwise, shifted by
// 8 log10(rated / file flux) (here 3000 lm rated, the file's own).
TEST(ReportPdf, TheDataSheetCarriesTheProductsUgrTableAtItsRatedFlux) {
  TempDir dir;
  const ilp::ResultRecord r = record();
  const ilp::Photometry photometry = cosine_file();
  const ilp::UgrTable table = ilp::ugr_table(photometry);
  ilp::ReportInput in;
  in.job = "job.yaml";
  in.record = &r;
  const double rated_lm = 2.0 * table.flux_lm;  // a rated flux twice the file's: every value 8 log10 2 higher
  in.products.push_back({"panel 3000 lm", "panel.ies", &photometry, rated_lm, 30.625, 0.3, 1.0, 0.6, 0.6});
  const std::string pdf = dir.file("report.pdf");
  ilp::write_report_pdf(pdf, in);
  const std::string text = squeezed(ilp::test::pdf_text(pdf, dir.file("")));
  EXPECT_TRUE(Contains(text, "UGR table (CIE 190)"));
  std::size_t room = 0;
  for (; room < table.rooms.size(); ++room)
    if (table.rooms[room].x_h == 4 && table.rooms[room].y_h == 8) break;
  ASSERT_LT(room, table.rooms.size());
  const double shift = 8.0 * std::log10(2.0);
  std::ostringstream row;
  row << std::fixed;
  row.precision(1);
  row << "4H × 8H " << table.crosswise(static_cast<Eigen::Index>(room), 0) + shift;
  EXPECT_TRUE(Contains(text, row.str())) << row.str() << "\n" << text;
  std::ostringstream end;
  end << std::fixed;
  end.precision(1);
  end << " " << table.endwise(static_cast<Eigen::Index>(room), 4) + shift << "\n";
  const std::size_t at = text.find("4H × 8H ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NE(text.substr(at, text.find('\n', at) - at + 1).find(end.str()), std::string::npos)
      << "the row ends with the endwise 30/30/20 value" << end.str();
}

TEST(ReportPdf, FontsAreEmbedded) {
  TempDir dir;
  const ilp::ResultRecord r = record();
  ilp::ReportInput in;
  in.job = "job.yaml";
  in.record = &r;
  in.grids.push_back(grid_view());
  const std::string pdf = dir.file("report.pdf");
  ilp::write_report_pdf(pdf, in);
  const std::string out = dir.file("fonts.txt");
  ASSERT_EQ(ilp::test::run_capture("pdffonts '" + pdf + "'", out), 0);
  std::istringstream lines(ilp::test::read_file(out));
  int fonts = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.find("DejaVu") == std::string::npos) continue;
    ++fonts;
    // Columns: name type encoding emb sub uni object ID; "yes yes yes" = embedded, subset, ToUnicode.
    EXPECT_NE(line.find("yes yes yes"), std::string::npos) << line;
  }
  EXPECT_GT(fonts, 0) << ilp::test::read_file(out);
}

TEST(ReportPdf, ABadPlanIsAnErrorNamingTheFileAndWritesNothing) {
  TempDir dir;
  const ilp::ResultRecord r = record();
  ilp::ReportInput in;
  in.job = "job.yaml";
  in.record = &r;
  in.plan_svg = "<svg width=";
  const std::string pdf = dir.file("report.pdf");
  const std::string msg = ilp::test::error_of<ilp::IlpError>([&] { ilp::write_report_pdf(pdf, in); });
  EXPECT_TRUE(ilp::test::StartsWith(msg, pdf + ": cannot read an SVG"));
  EXPECT_FALSE(std::filesystem::exists(pdf));
  in.plan_svg.clear();
  in.record = nullptr;
  EXPECT_THROW(ilp::write_report_pdf(pdf, in), ilp::IlpError);
  EXPECT_FALSE(std::filesystem::exists(pdf));
}

}  // namespace
