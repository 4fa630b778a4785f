// The job's report as a client gets it (report.pdf, A4): a summary page (the answer in
// one table: products and counts, power, W/m², W/m² per 100 lx, LENI; every goal line
// with target, value and verdict), the room (dimensions, surfaces with reflectances and
// heights above the floor, maintenance factor, luminaire schedule), the plan, per
// calculation grid its isolux plan with its statistics and point values, a data sheet
// per product (its photometric file's figures and polar curve), the bill of materials
// and the verification. Drawn with cairo's PDF surface; the SVGs the output set renders
// go onto the pages through librsvg, so their text stays text. Built from the
// ResultRecord (what result.json holds) and those SVGs alone: whatever goal lines the
// record carries and whatever the plan draws appear without changes here. Files are
// named by their file names, never a folder of the machine.
#pragma once

#include <string>
#include <vector>

#include "core/light/photometry.h"
#include "output/isolux_plan.h"
#include "output/result_record.h"

namespace ilp {

// A product of the bill of materials with what its data sheet shows.
struct ReportProduct {
  std::string name;                      // as the bill of materials names it
  std::string file;                      // its photometric file's name (no folder); "" for the plain panel
  const Photometry* photometry = nullptr;  // the file as read; null: the square Lambertian test panel
  double rated_flux_lm = 0.0;            // at full output, as the job uses it
  double power_w = 0.0;                  // at full output
  double dim_min = 1.0, dim_max = 1.0;   // output range, fractions of the rated
  double length_m = 0.0, width_m = 0.0;  // the luminous opening as placed (length along the luminaire's x)
};

struct ReportInput {
  std::string job;                       // the job file's name (no folder): the title
  const ResultRecord* record = nullptr;  // required
  std::string plan_svg;                  // plan.svg's text; empty: no plan page
  std::vector<IsoluxGridView> grids;     // one per calculation grid, in record.grids' order (by name)
  std::vector<ReportProduct> products;   // one data sheet each
};

// The text lines of the summary's verdict table, each goal then each constraint: name,
// metric (unit) or "constraint", target (">= 500.0 lx"), predicted, verified, verdict
// ("met", "NOT MET by 3.2 %", "(fails on verification only)").
std::vector<std::vector<std::string>> report_goal_rows(const ResultRecord& record);

// Writes the report to `path` atomically (output/atomic_file.h). Throws IlpError naming
// the file when the record is missing, an SVG cannot be read or rendered, a grid view
// is invalid (isolux_plan_layout's rules) or the file cannot be written.
void write_report_pdf(const std::string& path, const ReportInput& input);

}  // namespace ilp
