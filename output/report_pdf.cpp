#include "output/report_pdf.h"

#include <cairo-pdf.h>
#include <cairo.h>
#include <librsvg/rsvg.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <memory>
#include <ostream>
#include <sstream>

#include "core/base/error.h"
#include "core/glare/ugr_table.h"
#include "output/atomic_file.h"
#include "output/polar_curve.h"

namespace ilp {
namespace {

// A4 in PDF points (1/72 in), margins and type sizes.
constexpr double kPageW = 595.276, kPageH = 841.890, kMargin = 48.0;
constexpr double kBodyPt = 8.5, kSmallPt = 7.5;
constexpr double kLineGap = 1.35;  // line height / type size
constexpr const char* kFont = "DejaVu Sans";

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "–";
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

cairo_status_t write_to_stream(void* closure, const unsigned char* data, unsigned int length) {
  auto* out = static_cast<std::ostream*>(closure);
  out->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
  return *out ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

// A table: a header row, column widths as fractions of the text width, right-aligned
// columns (numbers), rows of cells (wrapped within their column).
struct Table {
  Table() = default;
  Table(std::vector<std::string> h, std::vector<double> w, std::vector<bool> r)
      : header(std::move(h)), widths(std::move(w)), right(std::move(r)) {}
  std::vector<std::string> header;
  std::vector<double> widths;
  std::vector<bool> right;
  std::vector<std::vector<std::string>> rows;
  double size_pt = kBodyPt;
  bool bold_last_row = false;
};

// Pages drawn top-down with a cursor: headings, wrapped text, tables that continue on
// the next page with their header, SVG documents scaled into the text width.
class PdfPages {
 public:
  PdfPages(cairo_t* cr, std::string footer, std::string file) : cr_(cr), footer_(std::move(footer)), file_(std::move(file)) {
    start_page();
  }

  void finish() { end_page(); }

  void new_page() {
    end_page();
    cairo_show_page(cr_);
    start_page();
  }

  // A new page unless `height` fits below the cursor.
  void ensure(double height) {
    if (y_ + height > kPageH - kMargin - 16.0) new_page();
  }

  void heading(const std::string& text, int level = 1) {
    const double size = level == 1 ? 15.0 : level == 2 ? 11.5 : 9.5;
    ensure(size * 3.0);
    if (level > 1) y_ += size * 0.6;
    font(size, true);
    y_ += size;
    move_show(kMargin, y_, text);
    y_ += size * 0.6;
    if (level == 1) {
      cairo_set_line_width(cr_, 0.8);
      cairo_move_to(cr_, kMargin, y_);
      cairo_line_to(cr_, kPageW - kMargin, y_);
      cairo_stroke(cr_);
      y_ += 8.0;
    }
  }

  // Text wrapped to the text width.
  void paragraph(const std::string& text, double size = kBodyPt, bool bold = false) {
    font(size, bold);
    for (const std::string& line : wrap(text, text_width())) {
      ensure(size * kLineGap);
      y_ += size * kLineGap;
      move_show(kMargin, y_, line);
    }
    y_ += size * 0.5;
  }

  void table(const Table& t) {
    const double width = text_width();
    std::vector<double> col_w, col_x;
    double x = kMargin;
    for (double f : t.widths) {
      col_x.push_back(x);
      col_w.push_back(f * width);
      x += f * width;
    }
    const double line_h = t.size_pt * kLineGap, pad = 2.5;
    auto row_lines = [&](const std::vector<std::string>& row, bool bold) {
      font(t.size_pt, bold);
      std::vector<std::vector<std::string>> cells;
      for (std::size_t c = 0; c < t.widths.size(); ++c)
        cells.push_back(wrap(c < row.size() ? row[c] : std::string(), col_w[c] - 2.0 * pad));
      return cells;
    };
    auto height_of = [&](const std::vector<std::vector<std::string>>& cells) {
      std::size_t n = 1;
      for (const auto& c : cells) n = std::max(n, c.size());
      return static_cast<double>(n) * line_h + 2.0 * pad;
    };
    auto draw_row = [&](const std::vector<std::vector<std::string>>& cells, bool bold, bool shaded) {
      const double h = height_of(cells);
      if (shaded) {
        cairo_set_source_rgb(cr_, 0.92, 0.93, 0.95);
        cairo_rectangle(cr_, kMargin, y_, width, h);
        cairo_fill(cr_);
        cairo_set_source_rgb(cr_, 0, 0, 0);
      }
      font(t.size_pt, bold);
      for (std::size_t c = 0; c < cells.size(); ++c)
        for (std::size_t l = 0; l < cells[c].size(); ++l) {
          const double base = y_ + pad + (static_cast<double>(l) + 1.0) * line_h - t.size_pt * 0.3;
          const double tx = t.right.size() > c && t.right[c] ? col_x[c] + col_w[c] - pad - advance(cells[c][l]) : col_x[c] + pad;
          move_show(tx, base, cells[c][l]);
        }
      y_ += h;
      cairo_set_source_rgb(cr_, 0.75, 0.75, 0.75);
      cairo_set_line_width(cr_, 0.4);
      cairo_move_to(cr_, kMargin, y_);
      cairo_line_to(cr_, kMargin + width, y_);
      cairo_stroke(cr_);
      cairo_set_source_rgb(cr_, 0, 0, 0);
    };
    const auto header = row_lines(t.header, true);
    ensure(height_of(header) + line_h * 2.0 + 2.0 * pad);
    draw_row(header, true, true);
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      const bool bold = t.bold_last_row && r + 1 == t.rows.size();
      const auto cells = row_lines(t.rows[r], bold);
      if (y_ + height_of(cells) > kPageH - kMargin - 16.0) {
        new_page();
        draw_row(header, true, true);
      }
      draw_row(cells, bold, false);
    }
    y_ += 8.0;
  }

  // An SVG document scaled to fit the text width and `max_height` (aspect kept),
  // centred; a new page first when less than `min_height` remains.
  void svg(const std::string& text, double max_height, double min_height) {
    GError* error = nullptr;
    std::unique_ptr<RsvgHandle, void (*)(RsvgHandle*)> handle(
        rsvg_handle_new_from_data(reinterpret_cast<const guint8*>(text.data()), text.size(), &error),
        [](RsvgHandle* h) { g_object_unref(h); });
    if (!handle) throw IlpError(file_ + ": cannot read an SVG to place (" + take_message(error) + ")");
    gdouble w = 0.0, h = 0.0;
    if (!rsvg_handle_get_intrinsic_size_in_pixels(handle.get(), &w, &h) || !(w > 0.0) || !(h > 0.0))
      throw IlpError(file_ + ": an SVG to place has no width and height in px");
    ensure(min_height);
    const double room = std::min(max_height, kPageH - kMargin - 16.0 - y_);
    const double scale = std::min(text_width() / w, room / h);
    const RsvgRectangle viewport{kMargin + (text_width() - w * scale) / 2.0, y_, w * scale, h * scale};
    if (!rsvg_handle_render_document(handle.get(), cr_, &viewport, &error))
      throw IlpError(file_ + ": cannot render an SVG (" + take_message(error) + ")");
    y_ += h * scale + 8.0;
  }

  double y() const { return y_; }
  static double text_width() { return kPageW - 2.0 * kMargin; }

 private:
  static std::string take_message(GError* error) {
    std::string message = error != nullptr && error->message != nullptr ? error->message : "unknown error";
    if (error != nullptr) g_error_free(error);
    return message;
  }

  void start_page() {
    ++page_;
    y_ = kMargin;
    cairo_set_source_rgb(cr_, 0, 0, 0);
  }

  void end_page() {
    font(kSmallPt, false);
    cairo_set_source_rgb(cr_, 0.35, 0.35, 0.35);
    move_show(kMargin, kPageH - kMargin / 2.0, footer_);
    const std::string number = "page " + std::to_string(page_);
    move_show(kPageW - kMargin - advance(number), kPageH - kMargin / 2.0, number);
    cairo_set_source_rgb(cr_, 0, 0, 0);
  }

  void font(double size, bool bold) {
    cairo_select_font_face(cr_, kFont, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, size);
  }

  double advance(const std::string& text) {
    cairo_text_extents_t e;
    cairo_text_extents(cr_, text.c_str(), &e);
    return e.x_advance;
  }

  void move_show(double x, double y, const std::string& text) {
    cairo_move_to(cr_, x, y);
    cairo_show_text(cr_, text.c_str());
  }

  // Words to lines no wider than `width` (a word wider than the line stands alone).
  std::vector<std::string> wrap(const std::string& text, double width) {
    std::vector<std::string> lines;
    std::istringstream words(text);
    std::string line;
    for (std::string whole; words >> whole;) {
      for (const std::string& word : split_long_word(whole, width)) {
        const std::string longer = line.empty() ? word : line + " " + word;
        if (!line.empty() && advance(longer) > width) {
          lines.push_back(line);
          line = word;
        } else {
          line = longer;
        }
      }
    }
    if (!line.empty() || lines.empty()) lines.push_back(line);
    return lines;
  }

  // A word wider than `width` (a long grid or goal name) in pieces that fit: each piece
  // ends after its last '_' where there is one, else at the last character that fits;
  // never inside a UTF-8 sequence. A word that fits is one piece.
  std::vector<std::string> split_long_word(std::string word, double width) {
    std::vector<std::string> pieces;
    while (advance(word) > width) {
      std::size_t fits = 0, underscore = 0;
      for (std::size_t end = 1; end <= word.size(); ++end) {
        if (end < word.size() && (static_cast<unsigned char>(word[end]) & 0xC0) == 0x80) continue;
        if (advance(word.substr(0, end)) > width) break;
        fits = end;
        if (word[end - 1] == '_') underscore = end;
      }
      std::size_t cut = underscore > 0 && underscore < word.size() ? underscore : fits;
      if (cut == 0) cut = std::min<std::size_t>(word.size(), 1);  // not one character fits: one a line
      while (cut < word.size() && (static_cast<unsigned char>(word[cut]) & 0xC0) == 0x80) ++cut;
      pieces.push_back(word.substr(0, cut));
      word.erase(0, cut);
    }
    if (!word.empty()) pieces.push_back(word);
    return pieces;
  }

  cairo_t* cr_;
  std::string footer_, file_;
  double y_ = kMargin;
  int page_ = 0;
};

// ---- the sections

std::string value_text(const GoalRecord& g, double v) {
  return fixed(v, g.unit.empty() ? 3 : 1) + (g.unit.empty() ? "" : " " + g.unit);
}

// "9 × linear LED 2112 lm (set to 97.0 %)" per bill line.
std::string products_text(const ResultRecord& r) {
  std::string out;
  for (const BillLine& b : r.bill_of_materials) {
    if (!out.empty()) out += "; ";
    out += std::to_string(b.count) + " × " + b.product;
    if (b.output_fraction < 1.0 - 1e-9) out += " (set to " + fixed(100.0 * b.output_fraction, 1) + " %)";
  }
  if (out.empty()) out = std::to_string(r.luminaires.size()) + " luminaires";
  return out;
}

std::string verdict_text(const ResultRecord& r) {
  if (!r.no_layout.empty()) return "No layout: " + r.no_layout;
  if (r.all_met) return std::string("Every goal is met") + (r.verification != "none" ? " as verified." : " as predicted.");
  const std::string failing = failing_lines_text(r);
  return "NOT MET: " + (failing.empty() ? std::string("the lines marked NOT MET below fail") : failing) + ".";
}

void summary_page(PdfPages& pdf, const ReportInput& in) {
  const ResultRecord& r = *in.record;
  pdf.heading("Lighting report: " + in.job);
  pdf.paragraph(r.program_version + ", objective " + r.objective + ". " + verdict_text(r), kBodyPt, true);
  Table answer({"", ""}, {0.34, 0.66}, {false, false});
  answer.rows.push_back({"Luminaires", products_text(r)});
  if (!r.arrangement.empty())
    answer.rows.push_back({"Layout", r.arrangement + ", spacing " + fixed(r.spacing_x_m, 2) + " m × " + fixed(r.spacing_y_m, 2) + " m"});
  else
    answer.rows.push_back({"Layout", r.layout_family});
  answer.rows.push_back({"Installed power", fixed(r.power_w, 1) + " W"});
  answer.rows.push_back({"Power density", fixed(r.power_density_w_per_m2, 2) + " W/m² over " + fixed(r.floor_area_m2, 2) +
                                              " m² (" + r.floor_area_source + ")"});
  if (r.power_density_w_per_m2_per_100_lx > 0.0)
    answer.rows.push_back({"Power density per 100 lx", fixed(r.power_density_w_per_m2_per_100_lx, 2) + " W/m²/100 lx"});
  if (r.energy) {
    const EnergyRecord& e = *r.energy;
    answer.rows.push_back({"LENI (EN 15193-1)", fixed(e.leni_kwh_per_m2, 2) + " kWh/(m²·a)"});
    answer.rows.push_back({"Annual energy", fixed(e.lighting_kwh, 0) + " kWh/a lighting + " + fixed(e.parasitic_kwh, 0) +
                                                " kWh/a parasitic = " + fixed(e.total_kwh, 0) + " kWh/a"});
    answer.rows.push_back({"Operating profile", e.building_type + (e.assumed ? " (assumed: the job has no energy section)" : "") +
                                                    ": t_D " + fixed(e.hours_day_h, 0) + " h/a, t_N " + fixed(e.hours_night_h, 0) +
                                                    " h/a, F_O " + fixed(e.occupancy_factor, 2) + ", F_D " +
                                                    fixed(e.daylight_factor, 2) + ", F_C " +
                                                    fixed(e.constant_illuminance_factor, 3) + ", parasitic " +
                                                    fixed(e.parasitic_kwh_per_m2, 1) + " kWh/(m²·a)"});
  }
  answer.rows.push_back({"Maintenance factor", fixed(r.maintenance_factor, 2) + " (values below are maintained)"});
  answer.header = {"The answer", ""};
  pdf.table(answer);
  pdf.heading("Goals and constraints", 2);
  Table goals({"line", "metric", "target", "predicted", "verified", "verdict"}, {0.19, 0.15, 0.20, 0.12, 0.12, 0.22},
              {false, false, true, true, true, false});
  goals.rows = report_goal_rows(r);
  pdf.table(goals);
  if (!r.grids.empty()) {
    pdf.heading("Calculation grids (maintained)", 2);
    Table grids({"grid", "points", "Em", "Emin", "Emax", "U0", "basis"}, {0.24, 0.10, 0.13, 0.13, 0.13, 0.10, 0.17}, {false, true, true, true, true, true, false});
    for (const GridRecord& g : r.grids)
      grids.rows.push_back({g.name, std::to_string(g.points), fixed(g.maintained.average_lux, 1) + " lx",
                            fixed(g.maintained.min_lux, 1) + " lx", fixed(g.maintained.max_lux, 1) + " lx",
                            fixed(g.maintained.uniformity, 3), g.verified ? "verified" : "predicted"});
    pdf.table(grids);
  }
}

void room_page(PdfPages& pdf, const ResultRecord& r) {
  pdf.new_page();
  pdf.heading("Room");
  Table room({"", ""}, {0.34, 0.66}, {false, false});
  room.header = {"Room data", ""};
  if (r.room) {
    room.rows.push_back({"Model", r.room->mesh});
    room.rows.push_back({"Extent (x × y × z)", fixed(r.room->length_x_m, 2) + " m × " + fixed(r.room->width_y_m, 2) + " m × " +
                                                   fixed(r.room->height_z_m, 2) + " m"});
    room.rows.push_back({"Finished floor", r.room->floor_z_m ? "z = " + fixed(*r.room->floor_z_m, 3) + " m (heights below are above it)"
                                                             : std::string("not known (heights below are the model's z)")});
  }
  room.rows.push_back({"Floor area", fixed(r.floor_area_m2, 2) + " m² (" + r.floor_area_source + ")"});
  room.rows.push_back({"Maintenance factor", fixed(r.maintenance_factor, 2)});
  pdf.table(room);
  if (r.room && !r.room->surfaces.empty()) {
    pdf.heading("Surfaces", 2);
    const bool floor = r.room->floor_z_m.has_value();
    Table surfaces({"surface", "area", "reflectance", floor ? "bottom above floor" : "bottom (z)", floor ? "top above floor" : "top (z)"}, {0.32, 0.16, 0.16, 0.18, 0.18}, {false, true, true, true, true});
    // The largest first, at most kSurfaceRows of them; the rest summed in one line
    // (result.json keeps every surface).
    std::vector<SurfaceRecord> largest = r.room->surfaces;
    std::stable_sort(largest.begin(), largest.end(),
                     [](const SurfaceRecord& a, const SurfaceRecord& b) { return a.area_m2 > b.area_m2; });
    constexpr std::size_t kSurfaceRows = 20;
    for (std::size_t i = 0; i < std::min(largest.size(), kSurfaceRows); ++i) {
      const SurfaceRecord& s = largest[i];
      surfaces.rows.push_back({s.name, fixed(s.area_m2, 2) + " m²", fixed(s.reflectance, 2), fixed(s.bottom_m, 2) + " m",
                               fixed(s.top_m, 2) + " m"});
    }
    if (largest.size() > kSurfaceRows) {
      double rest_m2 = 0.0;
      for (std::size_t i = kSurfaceRows; i < largest.size(); ++i) rest_m2 += largest[i].area_m2;
      surfaces.rows.push_back({std::to_string(largest.size() - kSurfaceRows) + " smaller surfaces",
                               fixed(rest_m2, 2) + " m²", "", "", ""});
    }
    pdf.table(surfaces);
  }
  pdf.heading("Luminaire schedule", 2);
  Table schedule({"id", "product", "x", "y", "height above floor", "rotation", "flux", "power"}, {0.07, 0.27, 0.10, 0.10, 0.14, 0.10, 0.12, 0.10}, {false, false, true, true, true, true, true, true});
  for (const LuminaireRecord& l : r.luminaires)
    schedule.rows.push_back({l.id, l.product.empty() ? "square panel" : l.product, fixed(l.x_m, 2) + " m",
                             fixed(l.y_m, 2) + " m", l.above_floor_m ? fixed(*l.above_floor_m, 2) + " m" : "z " + fixed(l.z_m, 2) + " m",
                             fixed(l.rotation_deg, 0) + "°", fixed(l.flux_lm, 0) + " lm", fixed(l.power_w, 1) + " W"});
  pdf.table(schedule);
}

// The grid's values as a table: x across (columns), y down from the highest row, as
// the isolux plan shows them; at most kColumns columns per block.
void grid_value_tables(PdfPages& pdf, const IsoluxGridView& v) {
  constexpr int kColumns = 12;
  for (int first = 0; first < v.nx; first += kColumns) {
    const int last = std::min(v.nx, first + kColumns);
    Table t;
    t.size_pt = kSmallPt;
    t.header.push_back(v.y_label + " \\ " + v.x_label);
    t.widths.push_back(0.16);
    t.right.push_back(false);
    for (int i = first; i < last; ++i) {
      t.header.push_back(fixed(v.origin_m.x() + i * v.spacing_m.x(), 2));
      t.widths.push_back(0.84 / kColumns);
      t.right.push_back(true);
    }
    for (int j = v.ny - 1; j >= 0; --j) {
      std::vector<std::string> row{fixed(v.origin_m.y() + j * v.spacing_m.y(), 2)};
      for (int i = first; i < last; ++i) row.push_back(fixed(v.maintained_lux[static_cast<std::size_t>(j * v.nx + i)], 0));
      t.rows.push_back(std::move(row));
    }
    pdf.table(t);
  }
}

void grid_pages(PdfPages& pdf, const ReportInput& in) {
  for (const IsoluxGridView& v : in.grids) {
    pdf.new_page();
    pdf.heading("Calculation grid: " + v.name);
    pdf.svg(isolux_plan_svg(v), 430.0, 300.0);
    const auto rec = std::find_if(in.record->grids.begin(), in.record->grids.end(),
                                  [&](const GridRecord& g) { return g.name == v.name; });
    if (rec != in.record->grids.end()) {
      Table stats({"points", "spacing", "area", "Em", "Emin", "Emax", "U0", "Emin/Emax"}, {0.10, 0.12, 0.14, 0.13, 0.13, 0.13, 0.10, 0.15}, std::vector<bool>(8, true));
      const GridValues& m = rec->maintained;
      stats.rows.push_back({std::to_string(rec->points), fixed(rec->spacing_m, 2) + " m", fixed(rec->area_m2, 2) + " m²",
                            fixed(m.average_lux, 1) + " lx", fixed(m.min_lux, 1) + " lx", fixed(m.max_lux, 1) + " lx",
                            fixed(m.uniformity, 3), m.max_lux > 0.0 ? fixed(m.min_lux / m.max_lux, 3) : "–"});
      pdf.paragraph(std::string("Maintained values (initial × MF ") + fixed(v.maintenance_factor, 2) + "), " +
                    (rec->verified ? "verified." : "predicted."));
      pdf.table(stats);
    }
    pdf.heading("Point values (maintained illuminance, lx; coordinates in m)", 3);
    grid_value_tables(pdf, v);
  }
}

// A text field a file fills (EULUMDAT writes "0" where it has nothing to say).
bool stated(const std::string& field) { return !field.empty() && field != "0"; }

std::string percent_or_dash(double v) { return std::isfinite(v) ? fixed(v, 1) + " %" : "not stated in the file"; }

// The product's tabular UGR (CIE 190: rooms X x Y in H, reflectances ceiling/walls/floor,
// spacing 0.25H, core/glare/ugr_table.h) at the rated flux the job uses: the file's table
// shifted by 8 log10(rated / file flux), as every luminance and the background scale alike.
void ugr_table_section(PdfPages& pdf, const Photometry& f, double rated_flux_lm) {
  const UgrTable table = ugr_table(f);
  if (table.rooms.empty() || !(table.flux_lm > 0.0)) return;
  const double shift = rated_flux_lm > 0.0 ? 8.0 * std::log10(rated_flux_lm / table.flux_lm) : 0.0;
  Table t;
  t.size_pt = kSmallPt;
  t.header = {"room X × Y"};
  t.widths = {0.12};
  t.right = {false};
  for (const char* viewing : {"cross", "end"})
    for (const RoomReflectances& r : table.reflectances) {
      t.header.push_back(std::string(viewing) + " " + fixed(100.0 * r.ceiling, 0) + "/" + fixed(100.0 * r.walls, 0) + "/" +
                         fixed(100.0 * r.floor, 0));
      t.widths.push_back(0.088);
      t.right.push_back(true);
    }
  for (std::size_t i = 0; i < table.rooms.size(); ++i) {
    std::vector<std::string> row{fixed(table.rooms[i].x_h, 0) + "H × " + fixed(table.rooms[i].y_h, 0) + "H"};
    for (const Eigen::MatrixXd* m : {&table.crosswise, &table.endwise})
      for (Eigen::Index j = 0; j < m->cols(); ++j) row.push_back(fixed((*m)(static_cast<Eigen::Index>(i), j) + shift, 1));
    t.rows.push_back(std::move(row));
  }
  pdf.ensure(kSmallPt * kLineGap * (static_cast<double>(t.rows.size()) + 8.0));  // the heading stays with its table
  pdf.heading("UGR table (CIE 190)", 3);
  pdf.paragraph("At " + fixed(rated_flux_lm > 0.0 ? rated_flux_lm : table.flux_lm, 0) +
                    " lm, luminaires 0.25H apart, H their height above the eye; reflectances ceiling/walls/floor "
                    "in %; cross: the line of sight in the C0–C180 plane, end: in C90–C270.",
                kSmallPt);
  pdf.table(t);
}

void product_page(PdfPages& pdf, const ReportProduct& p) {
  pdf.new_page();
  pdf.heading("Data sheet: " + p.name);
  Table t({"", ""}, {0.34, 0.66}, {false, false});
  t.header = {"Product", ""};
  t.rows.push_back({"Photometric file", p.file.empty() ? "none (ideal Lambertian square panel)" : p.file});
  const Photometry* f = p.photometry;
  if (f) {
    if (!f->manufacturer.empty()) t.rows.push_back({"Manufacturer", f->manufacturer});
    if (!f->luminaire.empty()) t.rows.push_back({"Luminaire", f->luminaire});
    if (!f->catalogue.empty()) t.rows.push_back({"Catalogue number", f->catalogue});
    t.rows.push_back({"Luminaire flux (file)", fixed(f->luminaire_flux_lm, 0) + " lm"});
  }
  t.rows.push_back({"Rated flux (as used)", fixed(p.rated_flux_lm, 0) + " lm"});
  t.rows.push_back({"Power", fixed(p.power_w, 1) + " W"});
  t.rows.push_back({"Efficacy", p.power_w > 0.0 ? fixed(p.rated_flux_lm / p.power_w, 1) + " lm/W" : "–"});
  t.rows.push_back({"Output range", p.dim_min < p.dim_max ? fixed(100.0 * p.dim_min, 0) + " % to " + fixed(100.0 * p.dim_max, 0) + " % (dimmable)"
                                                          : fixed(100.0 * p.dim_max, 0) + " % (fixed output)"});
  t.rows.push_back({"Luminous opening", fixed(1000.0 * p.length_m, 0) + " mm along C0–C180 × " + fixed(1000.0 * p.width_m, 0) +
                                            " mm along C90–C270"});
  if (f) {
    t.rows.push_back({"Light output ratio (LOR)", percent_or_dash(f->stated_lor_percent)});
    t.rows.push_back({"Downward flux fraction", percent_or_dash(f->stated_dff_percent)});
    t.rows.push_back({"Upward share (from the curves)", fixed(100.0 * f->upward_fraction, 1) + " %"});
    for (const LampSet& l : f->lamp_sets) {
      std::string lamp = std::to_string(std::abs(l.count)) + " × " + (l.type.empty() ? "lamp" : l.type);
      if (stated(l.colour)) lamp += ", colour " + l.colour;
      if (stated(l.colour_rendering)) lamp += ", CRI " + l.colour_rendering;
      if (l.power_w > 0.0) lamp += ", " + fixed(l.power_w, 1) + " W";
      t.rows.push_back({"Lamps", lamp});
    }
  }
  pdf.table(t);
  if (!f) return;
  const PolarCurve curve = polar_curve(*f);
  pdf.heading("Polar curve (cd/klm)", 2);
  pdf.svg(polar_curve_svg(curve), 230.0, 200.0);
  // Planes down, gamma across every 15 degrees: the four planes in one block.
  std::vector<std::size_t> at;
  for (std::size_t k = 0; k < curve.c0_c180.gamma_deg.size(); ++k)
    if (std::abs(std::remainder(curve.c0_c180.gamma_deg[k], 15.0)) < 1e-6) at.push_back(k);
  Table values;
  values.size_pt = kSmallPt;
  values.header.push_back("plane \\ gamma");
  values.widths.push_back(0.1);
  values.right.push_back(false);
  for (std::size_t k : at) {
    values.header.push_back(fixed(curve.c0_c180.gamma_deg[k], 0) + "°");
    values.widths.push_back(0.9 / static_cast<double>(at.size()));
    values.right.push_back(true);
  }
  const std::pair<const char*, const std::vector<double>*> planes[] = {{"C0", &curve.c0_c180.cd_per_klm},
                                                                       {"C90", &curve.c90_c270.cd_per_klm},
                                                                       {"C180", &curve.c0_c180.cd_per_klm_opposite},
                                                                       {"C270", &curve.c90_c270.cd_per_klm_opposite}};
  for (const auto& [name, v] : planes) {
    std::vector<std::string> row{name};
    for (std::size_t k : at) row.push_back(fixed((*v)[k], 1));
    values.rows.push_back(std::move(row));
  }
  pdf.heading("Intensity (cd/klm)", 3);
  pdf.table(values);
  ugr_table_section(pdf, *f, p.rated_flux_lm);
}

void bill_page(PdfPages& pdf, const ResultRecord& r) {
  pdf.new_page();
  pdf.heading("Bill of materials");
  Table t({"product", "photometric file", "count", "rated flux", "power each", "set to", "power"}, {0.24, 0.24, 0.08, 0.12, 0.11, 0.10, 0.11}, {false, false, true, true, true, true, true});
  int count = 0;
  double power = 0.0;
  for (const BillLine& b : r.bill_of_materials) {
    t.rows.push_back({b.product, file_name(b.source), std::to_string(b.count), fixed(b.rated_flux_lm, 0) + " lm",
                      fixed(b.unit_power_w, 1) + " W", fixed(100.0 * b.output_fraction, 1) + " %", fixed(b.total_power_w, 1) + " W"});
    count += b.count;
    power += b.total_power_w;
  }
  t.rows.push_back({"total", "", std::to_string(count), "", "", "", fixed(power, 1) + " W"});
  t.bold_last_row = true;
  pdf.table(t);
  if (r.fixed_flux_lm > 0.0)
    pdf.paragraph("Plus luminaires placed in the job (" + fixed(r.fixed_flux_lm, 0) + " lm), not counted above.");
}

void verification_page(PdfPages& pdf, const ResultRecord& r) {
  pdf.heading("Verification", 1);
  std::string method = r.verification == "exact"    ? "exact radiosity solve (every form-factor row, Gauss–Seidel)"
                       : r.verification == "sample" ? "sample-based operator with its own rays"
                                                    : "none: the values are the search's predictions";
  Table t({"How the layout was checked", ""}, {0.34, 0.66}, {false, false});
  t.rows.push_back({"Method", method});
  if (r.verification != "none") t.rows.push_back({"Rays per patch", std::to_string(r.verification_rays_per_patch)});
  if (r.verification_decisive_points > 0)
    t.rows.push_back({"Decisive points", std::to_string(r.verification_decisive_points) +
                                             " grid points deciding a minimum or maximum: gathered with " +
                                             std::to_string(r.verification_decisive_rays) + " rays; the " +
                                             std::to_string(r.verification_dominant_patches) +
                                             " patches they gather most from solved with precise direct light and " +
                                             std::to_string(r.verification_dominant_rays) + "-ray rows"});
  t.rows.push_back({"Scene", std::to_string(r.patches) + " patches, " + std::to_string(r.population) + " reflecting"});
  t.rows.push_back({"Search operator", "k = " + std::to_string(r.sample_size) + " sampled patches, " +
                                           std::to_string(r.candidates) + " candidate positions, ray seed " + std::to_string(r.seed)});
  t.rows.push_back({"Search", std::to_string(r.evaluations) + " evaluations in " + std::to_string(r.searches) +
                                  (r.searches == 1 ? " round" : " rounds") + ", optimizer seed " + std::to_string(r.optimizer_seed)});
  if (r.flux_correction != 1.0)
    t.rows.push_back({"Flux correction", "every flux × " + fixed(r.flux_correction, 4) + " after verification" +
                                             (r.flux_correction_limited ? " (limited by the flux range)" : "")});
  pdf.table(t);
  Table goals({"goal", "metric", "predicted", "verified", "verified − predicted"}, {0.26, 0.18, 0.18, 0.18, 0.20}, {false, false, true, true, true});
  for (const GoalRecord& g : r.goals)
    goals.rows.push_back({g.name, g.metric, value_text(g, g.predicted), g.verified ? value_text(g, *g.verified) : "–",
                          g.verified && g.predicted != 0.0 ? fixed(100.0 * (*g.verified - g.predicted) / g.predicted, 2) + " %" : "–"});
  pdf.heading("Predicted against verified", 2);
  if (r.flux_correction != 1.0)
    pdf.paragraph("Predicted: the search's model at the fluxes it chose. Verified: the exact check after every flux was "
                  "scaled by " + fixed(r.flux_correction, 4) + " so that the binding goal is just met; the difference "
                  "includes that scaling.", kSmallPt);
  pdf.table(goals);
  for (const std::string& line : r.calibration) pdf.paragraph(line, kSmallPt);
  if (!r.variants.empty()) {
    pdf.heading("Variants tried", 2);
    for (const VariantRecord& v : r.variants) pdf.paragraph(v.summary, kSmallPt);
  }
}

}  // namespace

std::vector<std::vector<std::string>> report_goal_rows(const ResultRecord& r) {
  std::vector<std::vector<std::string>> rows;
  auto add = [&](const VerdictLine& g) {
    std::string verdict = g.met ? "met" : "NOT MET";
    const double value = g.value();
    if (!g.met && g.target > 0.0) verdict += " by " + fixed(100.0 * std::abs(value - g.target) / g.target, 1) + " %";
    if (g.fails_only_on_verification) verdict += " (fails on verification only)";
    const bool constraint = g.kind == "constraint";
    rows.push_back({g.name, constraint ? std::string("constraint") : g.metric + (g.unit.empty() ? "" : " (" + g.unit + ")"),
                    verdict_target_text(g), verdict_value_text(g, g.predicted),
                    g.verified ? verdict_value_text(g, *g.verified) : "–", verdict});
  };
  for (const VerdictLine& g : r.goals) add(g);
  for (const VerdictLine& c : r.constraints) add(c);
  return rows;
}

void write_report_pdf(const std::string& path, const ReportInput& in) {
  if (in.record == nullptr) throw IlpError(path + ": no result to report");
  write_file_atomically(path, [&](std::ostream& out) {
    std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> surface(
        cairo_pdf_surface_create_for_stream(write_to_stream, &out, kPageW, kPageH), cairo_surface_destroy);
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
      throw IlpError(path + ": cannot create the PDF (" + cairo_status_to_string(cairo_surface_status(surface.get())) + ")");
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, ("Lighting report: " + in.job).c_str());
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, in.record->program_version.c_str());
    std::unique_ptr<cairo_t, void (*)(cairo_t*)> cr(cairo_create(surface.get()), cairo_destroy);
    {
      PdfPages pdf(cr.get(), "ilp report: " + in.job, path);
      summary_page(pdf, in);
      room_page(pdf, *in.record);
      if (!in.plan_svg.empty()) {
        pdf.new_page();
        pdf.heading("Plan");
        pdf.svg(in.plan_svg, 680.0, 300.0);
      }
      grid_pages(pdf, in);
      for (const ReportProduct& p : in.products) product_page(pdf, p);
      bill_page(pdf, *in.record);
      verification_page(pdf, *in.record);
      pdf.finish();
    }
    cairo_destroy(cr.release());
    cairo_surface_finish(surface.get());
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
      throw IlpError(path + ": writing the PDF failed (" + cairo_status_to_string(cairo_surface_status(surface.get())) + ")");
  });
}

}  // namespace ilp
