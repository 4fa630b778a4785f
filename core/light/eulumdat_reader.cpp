// The EULUMDAT (.ldt) reader, every Isym: the header fields 1-27 line by line, the
// stored C planes the symmetry implies, the angles and the intensities (cd/klm, scaled
// to cd), and the header's LORL, DFF and tilt checked against the data.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/light/photometry.h"
#include "core/light/photometry_reading.h"

namespace ilp {

using namespace photometry_detail;

namespace {

class FieldReader : public BoundedNumbers<FieldReader> {
 public:
  FieldReader(std::vector<std::string_view> lines, std::string path) : lines_(std::move(lines)), path_(std::move(path)) {}

  std::size_t remaining() const { return lines_.size() - pos_; }
  int line() const { return static_cast<int>(pos_) + 1; }
  const std::string& path() const { return path_; }

  template <class Name>
  std::string_view raw(const Name& field) {
    if (pos_ >= lines_.size()) {
      fail(path_, static_cast<int>(lines_.size()), name_of(field), "the file ends before this field: truncated");
    }
    return trim(lines_[pos_++]);
  }
  std::string text(const std::string& field) {
    const int at = line();
    return bounded_text(raw(field), path_, at, field);
  }
  template <class Name>
  double number(const Name& field) {
    const int at = line();
    const std::string_view t = raw(field);
    double v = 0;
    if (!parse_number(t, v, true)) {
      fail(path_, at, name_of(field), std::string("'").append(t.substr(0, 40)).append("' is not a finite number"));
    }
    return v;
  }
  // The first non-blank line left, or -1.
  int next_non_blank() const {
    for (std::size_t i = pos_; i < lines_.size(); ++i) {
      if (!trim(lines_[i]).empty()) return static_cast<int>(i) + 1;
    }
    return -1;
  }

 private:
  std::vector<std::string_view> lines_;
  std::size_t pos_ = 0;
  std::string path_;
};

LuminousOpening eulumdat_opening(const std::array<double, 9>& mm, Photometry& p) {
  // mm: fields 13-21 (luminaire length, width, height; luminous length, width; heights C0..C270).
  LuminousOpening o;
  double length = mm[3], width = mm[4];
  double height = std::max({mm[5], mm[6], mm[7], mm[8]});
  if (length == 0 && width == 0) {
    length = mm[0];
    width = mm[1];
    height = 0;
    if (length > 0) warn(p, "luminous area not given (fields 16-17 are 0): the luminaire dimensions are used");
  }
  if (length == 0 && width == 0) return o;
  if (width == 0) {  // EULUMDAT: width 0 = round
    o.shape = height > 0 ? OpeningShape::cylinder : OpeningShape::disc;
    width = length;
  } else if (length == 0) {  // only a width: a line across
    o.shape = OpeningShape::line;
  } else {
    o.shape = OpeningShape::rectangle;
  }
  o.length_m = length / 1000;
  o.width_m = width / 1000;
  o.height_m = height / 1000;
  return o;
}

// Fields 1-27 (text fields into p, with the lamp sets and the stated DFF and LORL); what
// the rest of the file needs.
struct EulumdatHeader {
  long isym = 0;                // 3: symmetry indicator, 0..4
  long mc = 0;                  // 4: C planes in the full web
  int mc_at = 0;                // its line
  long ng = 0;                  // 6: gamma angles
  std::array<double, 9> mm{};   // 13-21: dimensions, mm
  double conversion = 0;        // 24: intensity conversion factor
  double tilt = 0;              // 25: tilt during measurement, degrees
};

EulumdatHeader read_eulumdat_header(FieldReader& in, const std::string& path, Photometry& p) {
  p.manufacturer = in.text("1 company identification");
  const int ityp_at = in.line();
  const long ityp = in.integer_in("2 Ityp", -1000000, 1000000);
  if (ityp < 0 || ityp > 3) fail(path, ityp_at, "2 Ityp", "unknown type indicator " + std::to_string(ityp) + " (0..3)");
  const int isym_at = in.line();
  const long isym = in.integer_in("3 Isym", -1000000, 1000000);
  if (isym < 0 || isym > 4) fail(path, isym_at, "3 Isym", "unknown symmetry indicator " + std::to_string(isym) + " (0..4)");
  const int mc_at = in.line();
  const long mc = in.integer_in("4 Mc", 1, kMaxCount);
  in.number_in("5 Dc", 0, 360);
  const long ng = in.integer_in("6 Ng", 2, kMaxCount);
  in.number_in("7 Dg", 0, 180);
  in.text("8 measurement report number");
  p.luminaire = in.text("9 luminaire name");
  p.catalogue = in.text("10 luminaire number");
  in.text("11 file name");
  in.text("12 date/user");
  static const char* const kDimNames[9] = {"13 luminaire length/diameter", "14 luminaire width",  "15 luminaire height",
                                           "16 luminous area length/diameter", "17 luminous area width",
                                           "18 luminous height C0", "19 luminous height C90",
                                           "20 luminous height C180", "21 luminous height C270"};
  std::array<double, 9> mm{};
  for (int k = 0; k < 9; ++k) mm[static_cast<std::size_t>(k)] = in.number_in(kDimNames[k], 0, kMaxDimensionMm);
  p.stated_dff_percent = in.number_in("22 DFF", 0, 100.5);
  p.stated_lor_percent = in.number_in("23 LORL", 0, 200);
  const int conv_at = in.line();
  const double conversion = in.number_in("24 intensity conversion factor", 0, kMaxFactor);
  if (!(conversion > 0)) fail(path, conv_at, "24 intensity conversion factor", "must be > 0");
  const double tilt = in.number_in("25 tilt during measurement", -180, 180);
  const long n_sets = in.integer_in("26 number of lamp sets", 1, static_cast<long>(std::max<std::size_t>(in.remaining() / 6, 1)));
  for (long s = 0; s < n_sets; ++s) {
    const std::string prefix = " (lamp set " + std::to_string(s + 1) + ")";
    LampSet ls;
    const int count_at = in.line();
    ls.count = static_cast<int>(in.integer_in("26a number of lamps" + prefix, -100000, 100000));
    if (ls.count == 0) fail(path, count_at, "26a number of lamps" + prefix, "0 lamps (negative = absolute photometry)");
    ls.type = in.text("26b lamp type" + prefix);
    const int flux_at = in.line();
    ls.flux_lm = in.number_in("26c total luminous flux" + prefix, 0, kMaxFluxLm);
    if (!(ls.flux_lm > 0)) fail(path, flux_at, "26c total luminous flux" + prefix, "must be > 0 lm");
    ls.colour = in.text("26d colour temperature" + prefix);
    ls.colour_rendering = in.text("26e colour rendering" + prefix);
    ls.power_w = in.number_in("26f wattage including ballast" + prefix, 0, kMaxPowerW);
    p.lamp_sets.push_back(std::move(ls));
  }
  for (int k = 0; k < 10; ++k) in.number([k] { return "27 direct ratio[" + std::to_string(k) + "]"; });
  return {isym, mc, mc_at, ng, mm, conversion, tilt};
}

// The stored C planes (0-based indices into the Mc angles of field 28) for Isym, after
// checking Mc and the counts against what the file holds.
std::vector<long> stored_planes(const FieldReader& in, const std::string& path, const EulumdatHeader& h) {
  const long isym = h.isym, mc = h.mc, ng = h.ng;
  const int mc_at = h.mc_at;
  // Stored C planes (1-based Mc1..Mc2 of the layout) and the symmetry they imply.
  if ((isym == 2 && mc % 2 != 0) || ((isym == 3 || isym == 4) && mc % 4 != 0)) {
    fail(path, mc_at, "4 Mc",
         "Mc = " + std::to_string(mc) + " with Isym " + std::to_string(isym) + " must be a multiple of " +
             (isym == 2 ? "2" : "4"));
  }
  const long n_planes = isym == 0 ? mc : isym == 1 ? 1 : isym == 4 ? mc / 4 + 1 : mc / 2 + 1;
  const std::uint64_t needed = static_cast<std::uint64_t>(mc) + static_cast<std::uint64_t>(ng) +
                               static_cast<std::uint64_t>(n_planes) * static_cast<std::uint64_t>(ng);
  if (needed > in.remaining()) {
    fail(path, mc_at, "4 Mc",
         "Mc = " + std::to_string(mc) + ", Ng = " + std::to_string(ng) + " and Isym " + std::to_string(isym) +
             " need " + std::to_string(needed) + " more lines (angles and intensities) but the file has " +
             std::to_string(in.remaining()) + ": truncated or wrong counts");
  }
  std::vector<long> stored;
  switch (isym) {
    case 0: for (long k = 0; k < mc; ++k) stored.push_back(k); break;
    case 1: stored.push_back(0); break;
    case 2: for (long k = 0; k <= mc / 2; ++k) stored.push_back(k); break;
    case 3: for (long k = 0; k <= mc / 2; ++k) stored.push_back((3 * mc / 4 + k) % mc); break;
    default: for (long k = 0; k <= mc / 4; ++k) stored.push_back(k); break;
  }
  return stored;
}

// Field 28, the Mc C angles: rising, and at the angles Isym fixes.
std::vector<double> read_c_angles(FieldReader& in, const std::string& path, const EulumdatHeader& h) {
  const long isym = h.isym, mc = h.mc;
  std::vector<double> c_all;
  std::vector<int> c_lines;
  c_all.reserve(static_cast<std::size_t>(mc));
  for (long k = 0; k < mc; ++k) {
    const auto field = [k] { return "28 C angle[" + std::to_string(k) + "]"; };
    const int at = in.line();
    c_lines.push_back(at);
    c_all.push_back(in.number_in(field, 0, 360 - kAngleTolDeg));
    if (k > 0 && c_all[k] <= c_all[k - 1]) {
      fail(path, at, field(), fmt(c_all[k]) + " does not rise after " + fmt(c_all[k - 1]) + " (angles must increase strictly)");
    }
  }
  const auto require_c = [&](long index, double angle) {
    if (!near(c_all[static_cast<std::size_t>(index)], angle)) {
      fail(path, c_lines[static_cast<std::size_t>(index)],
           "28 C angle[" + std::to_string(index) + "]",
           fmt(c_all[static_cast<std::size_t>(index)]) + " should be " + fmt(angle) + " for Isym " + std::to_string(isym) +
               " with Mc = " + std::to_string(mc) + ": the angles are not a valid symmetry");
    }
  };
  if (isym != 1) require_c(0, 0);
  if (isym == 2) require_c(mc / 2, 180);
  if (isym == 3) { require_c(mc / 4, 90); require_c(3 * mc / 4, 270); }
  if (isym == 4) require_c(mc / 4, 90);
  return c_all;
}

// Field 29, the Ng gamma angles, into p.gamma_angles_deg: rising.
void read_gamma_angles(FieldReader& in, const std::string& path, long ng, Photometry& p) {
  for (long i = 0; i < ng; ++i) {
    const auto field = [i] { return "29 gamma angle[" + std::to_string(i) + "]"; };
    const int at = in.line();
    p.gamma_angles_deg.push_back(in.number_in(field, 0, 180));
    if (i > 0 && p.gamma_angles_deg[i] <= p.gamma_angles_deg[i - 1]) {
      fail(path, at, field(),
           fmt(p.gamma_angles_deg[i]) + " does not rise after " + fmt(p.gamma_angles_deg[i - 1]) +
               " (angles must increase strictly)");
    }
  }
}

// Field 30: the stored planes' intensities, scaled to cd; nothing may follow them.
// Sets p.absolute and p.symmetry; `data_line`: where the intensities start.
StoredWeb read_intensities(FieldReader& in, const std::string& path, const EulumdatHeader& h,
                           const std::vector<long>& stored, const std::vector<double>& c_all, Photometry& p,
                           int& data_line) {
  const long isym = h.isym, ng = h.ng;
  const double scale = h.conversion * p.lamp_sets.front().flux_lm / 1000.0;
  p.absolute = p.lamp_sets.front().count < 0;
  StoredWeb w;
  w.cd.resize(static_cast<Eigen::Index>(stored.size()), ng);
  data_line = in.line();
  for (std::size_t j = 0; j < stored.size(); ++j) {
    const double c = c_all[static_cast<std::size_t>(stored[j])];
    w.c_deg.push_back(c);
    for (long i = 0; i < ng; ++i) {
      const auto field = [&] {
        return std::string("30 intensity[C=").append(fmt(c)).append(", gamma=").append(fmt(p.gamma_angles_deg[i])).append("]");
      };
      const int at = in.line();
      const double v = in.number(field);
      if (v < 0) fail(path, at, field(), fmt(v) + " cd/klm is negative");
      const double cd = v * scale;
      if (cd > kMaxCandela) fail(path, at, field(), fmt(cd) + " cd is beyond any luminaire (limit 1e9 cd)");
      if (cd > 0 && cd < kMinNonZeroCandela) fail(path, at, field(), fmt(cd) + " cd is not zero yet below 1e-30 cd: no measurement");
      w.cd(static_cast<Eigen::Index>(j), i) = cd;
    }
  }
  if (const int extra = in.next_non_blank(); extra > 0) {
    fail(path, extra, "30 intensities",
         "more values after the " + std::to_string(stored.size() * static_cast<std::size_t>(ng)) +
             " the header announces (" + std::to_string(stored.size()) + " C planes x " + std::to_string(ng) +
             " gamma angles for Isym " + std::to_string(isym) + ")");
  }
  static const PhotometricSymmetry kSym[5] = {PhotometricSymmetry::none, PhotometricSymmetry::rotational,
                                              PhotometricSymmetry::bilateral_c0_c180,
                                              PhotometricSymmetry::bilateral_c90_c270, PhotometricSymmetry::quadrant};
  p.symmetry = kSym[isym];
  return w;
}

// Header against data: the stated LORL and DFF against the integrated web, and the tilt.
void check_header_against_data(Photometry& p, double tilt) {
  const double lor_percent = 100.0 * p.luminaire_flux_lm / p.lamp_sets.front().flux_lm;
  if (std::abs(lor_percent - p.stated_lor_percent) > kHeaderCheckPoints) {
    warn(p, "field 23 LORL states " + fmt(p.stated_lor_percent) + " % but the intensities integrate to " +
                fmt(lor_percent) + " %");
  }
  const double dff_percent = 100.0 * (1 - p.upward_fraction);
  if (std::abs(dff_percent - p.stated_dff_percent) > kHeaderCheckPoints) {
    warn(p, "field 22 DFF states " + fmt(p.stated_dff_percent) + " % downward but the intensities give " +
                fmt(dff_percent) + " % (" + fmt(100 * p.upward_fraction) + " % goes up)");
  }
  if (tilt != 0) warn(p, "field 25: measured at a tilt of " + fmt(tilt) + " degrees, not applied");
}

}  // namespace

Photometry parse_eulumdat(std::string_view raw, const std::string& path) {
  if (raw.size() > kMaxFileBytes) fail(path, 0, "file", "larger than 64 MiB: not a photometric file");
  FieldReader in(split_lines(strip_bom_and_eof(raw)), path);
  Photometry p;
  p.path = path;
  p.format = PhotometryFormat::eulumdat;

  const EulumdatHeader h = read_eulumdat_header(in, path, p);
  const std::vector<long> stored = stored_planes(in, path, h);
  const std::vector<double> c_all = read_c_angles(in, path, h);
  read_gamma_angles(in, path, h.ng, p);
  int data_line = 0;
  const StoredWeb w = read_intensities(in, path, h, stored, c_all, p, data_line);
  expand_web(p, w);

  p.lamp_flux_lm = p.lamp_sets.front().flux_lm;
  p.input_power_w = p.lamp_sets.front().power_w;
  p.opening = eulumdat_opening(h.mm, p);
  finish(p, data_line);
  check_header_against_data(p, h.tilt);
  return p;
}

}  // namespace ilp
