// The IES LM-63 reader (type C photometry, every version photometry.h lists): the
// identifier and keyword lines, TILT, the parameter lines, the angles and the candela
// values, each checked against what is left of the file and a plausible range.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/light/photometry.h"
#include "core/light/photometry_reading.h"

namespace ilp {

using namespace photometry_detail;

namespace {

struct Token {
  std::string_view text;
  int line = 0;
};

class TokenReader : public BoundedNumbers<TokenReader> {
 public:
  TokenReader(std::vector<Token> tokens, std::string path, int last_line)
      : tokens_(std::move(tokens)), path_(std::move(path)), last_line_(last_line) {}

  std::size_t remaining() const { return tokens_.size() - pos_; }
  int line() const { return pos_ < tokens_.size() ? tokens_[pos_].line : last_line_; }
  const std::string& path() const { return path_; }

  template <class Name>
  double number(const Name& field) {
    if (pos_ >= tokens_.size()) fail(path_, last_line_, name_of(field), "the file ends here: truncated (a value is missing)");
    const Token& t = tokens_[pos_];
    double v = 0;
    if (!parse_number(t.text, v)) {
      fail(path_, t.line, name_of(field), std::string("'").append(t.text.substr(0, 40)).append("' is not a finite number"));
    }
    ++pos_;
    return v;
  }

 private:
  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  std::string path_;
  int last_line_;
};

// Tokens of lines [first, end): separated by blanks, tabs and commas; "END" stops the data.
std::vector<Token> tokenize(const std::vector<std::string_view>& lines, std::size_t first) {
  std::vector<Token> tokens;
  for (std::size_t i = first; i < lines.size(); ++i) {
    const std::string_view l = lines[i];
    std::size_t k = 0;
    while (k < l.size()) {
      while (k < l.size() && (l[k] == ' ' || l[k] == '\t' || l[k] == ',' || l[k] == '\f' || l[k] == '\v')) ++k;
      const std::size_t start = k;
      while (k < l.size() && !(l[k] == ' ' || l[k] == '\t' || l[k] == ',' || l[k] == '\f' || l[k] == '\v')) ++k;
      if (k > start) {
        const std::string_view t = l.substr(start, k - start);
        if (upper(t) == "END") return tokens;
        tokens.push_back(Token{t, static_cast<int>(i) + 1});
      }
    }
  }
  return tokens;
}

// Angles that must rise strictly, each within [lo, hi].
std::vector<double> read_angles(TokenReader& in, const std::string& field, long count, double lo, double hi,
                                const std::string& path) {
  std::vector<double> a;
  a.reserve(static_cast<std::size_t>(count));
  for (long i = 0; i < count; ++i) {
    const auto name = [&] { return field + "[" + std::to_string(i) + "]"; };
    const int at = in.line();
    a.push_back(in.number_in(name, lo, hi));
    if (i > 0 && a[i] <= a[i - 1]) {
      fail(path, at, name(), fmt(a[i]) + " does not rise after " + fmt(a[i - 1]) + " (angles must increase strictly)");
    }
  }
  return a;
}

bool near(double a, double b) { return std::abs(a - b) <= kAngleTolDeg; }

PhotometricSymmetry ies_symmetry(const std::vector<double>& h, const std::string& path, int line) {
  if (h.size() == 1) return PhotometricSymmetry::rotational;
  const double first = h.front(), last = h.back();
  if (near(first, 0) && near(last, 90)) return PhotometricSymmetry::quadrant;
  if (near(first, 0) && near(last, 180)) return PhotometricSymmetry::bilateral_c0_c180;
  if (near(first, 90) && near(last, 270)) return PhotometricSymmetry::bilateral_c90_c270;
  if (near(first, 0) && last > 180) return PhotometricSymmetry::none;  // 0..360, or 0..<360 closed periodically
  fail(path, line, "horizontal angles",
       fmt(first) + ".." + fmt(last) +
           " is not a valid type C symmetry (one angle, 0..90, 0..180, 90..270 or 0..360)");
}

// LM-63-2002's signs (docs/photometry.md, "Luminous openings"): 0 is no extent, a
// negative value a round extent (disc, ellipse, cylinder, sphere), a positive one a
// straight one. The footprint seen from below decides the shape.
LuminousOpening ies_opening(double width, double length, double height, Photometry& p) {
  LuminousOpening o;
  o.width_m = std::abs(width);
  o.length_m = std::abs(length);
  o.height_m = std::abs(height);
  if (width == 0 && length == 0) {  // a point (a luminous height alone has no footprint)
    if (height != 0) warn(p, "a luminous height of " + fmt(o.height_m) + " m without width or length: taken as a point");
    o.height_m = 0;
    return o;
  }
  if (width == 0 || length == 0) {
    if (width < 0 || length < 0) {  // LM-63 vertical circle: its diameter as a disc
      o.shape = OpeningShape::disc;
      o.width_m = o.length_m = std::max(o.width_m, o.length_m);
      warn(p, "a round opening with one size 0: taken as a disc of " + fmt(o.width_m) + " m");
      return o;
    }
    o.shape = OpeningShape::line;  // a bare tube or a strip: one size 0
    return o;
  }
  if (width < 0 && length < 0) {  // disc, ellipse, vertical cylinder, sphere
    o.shape = height == 0 ? OpeningShape::disc : OpeningShape::cylinder;
    if (o.width_m != o.length_m) warn(p, "an elliptical opening: taken as round, " + fmt(std::max(o.width_m, o.length_m)) + " m across");
    if (height < 0) warn(p, "spherical opening (negative height) taken as a vertical cylinder");
    return o;
  }
  o.shape = OpeningShape::rectangle;  // or a horizontal cylinder (one negative size): its footprint
  if (width < 0 || length < 0)
    warn(p, "a horizontal cylinder (one negative size): its footprint taken as a rectangle of " + fmt(o.length_m) +
                " x " + fmt(o.width_m) + " m");
  if (height < 0) warn(p, "negative height: taken as " + fmt(o.height_m) + " m");
  return o;
}

// The lines before the numbers: the identifier (its version), the keywords (or a 1986
// file's free text) and the TILT line.
struct IesPreamble {
  bool lm63_2002_or_later = false;  // no ballast-lamp factor in the candela scale
  std::size_t tilt_line = 0;        // 0-based
  std::string tilt;                 // "NONE" or "INCLUDE"
};

IesPreamble read_ies_preamble(const std::vector<std::string_view>& lines, const std::string& path, Photometry& p) {
  // Identifier line, keywords (or 1986 free text), TILT.
  std::size_t first_text = 0;
  const std::string id = upper(trim(lines[0]));
  std::string id_compact;
  for (char c : id) {
    if (c != ' ' && c != '\t') id_compact.push_back(c);
  }
  if (id_compact.rfind("IESNA", 0) == 0 || id_compact.rfind("IES:", 0) == 0) {
    p.version = std::string(trim(lines[0]));
    first_text = 1;
  }
  const bool lm63_2002_or_later = id_compact.find("2002") != std::string::npos ||
                                  id_compact.find("2019") != std::string::npos;
  std::size_t tilt_line = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string compact;
    for (char c : upper(trim(lines[i]))) {
      if (c != ' ' && c != '\t') compact.push_back(c);
    }
    if (compact.rfind("TILT=", 0) == 0) {
      tilt_line = i;
      break;
    }
  }
  if (tilt_line == lines.size()) {
    fail(path, static_cast<int>(lines.size()), "TILT", "no TILT= line: not an IES LM-63 file, or truncated before TILT");
  }
  std::string* last_keyword = nullptr;
  std::string free_text;
  for (std::size_t i = first_text; i < tilt_line; ++i) {
    const std::string_view l = trim(lines[i]);
    if (l.size() >= 2 && l.front() == '[' && l.find(']') != std::string_view::npos) {
      const std::size_t close = l.find(']');
      const std::string key = upper(trim(l.substr(1, close - 1)));
      const int at = static_cast<int>(i) + 1;
      std::string field(1, '[');  // (not "[" + ...: GCC 12 warns falsely, -Wrestrict)
      field.append(printable(shortened(key, 40))).push_back(']');
      const std::string value = bounded_text(trim(l.substr(close + 1)), path, at, field);
      if (key == "MORE" && last_keyword) {
        *last_keyword += " " + value;
        if (last_keyword->size() > kMaxTextChars) bounded_text(*last_keyword, path, at, "[MORE]");
        continue;
      }
      last_keyword = nullptr;
      if (key == "LUMINAIRE") last_keyword = &p.luminaire;
      else if (key == "MANUFAC") last_keyword = &p.manufacturer;
      else if (key == "LUMCAT") last_keyword = &p.catalogue;
      if (last_keyword && last_keyword->empty()) *last_keyword = value;
      else last_keyword = nullptr;
    } else if (free_text.empty() && !l.empty()) {
      free_text = bounded_text(l, path, static_cast<int>(i) + 1, "text");
    }
  }
  if (p.luminaire.empty() && p.version.empty()) p.luminaire = free_text;  // 1986: first line of text

  const std::string_view tilt_text = trim(lines[tilt_line]);
  const std::string tilt_value = std::string(trim(tilt_text.substr(tilt_text.find('=') + 1)));
  const int tilt_at = static_cast<int>(tilt_line) + 1;
  const std::string tilt_upper = upper(tilt_value);
  if (tilt_upper != "NONE" && tilt_upper != "INCLUDE") {
    fail(path, tilt_at, "TILT",
         "TILT=" + tilt_value.substr(0, 60) +
             " (tilt factors in a separate file) is not supported: use TILT=NONE or TILT=INCLUDE");
  }
  return {lm63_2002_or_later, tilt_line, tilt_upper};
}

// TILT=INCLUDE: the table, kept for the record.
void read_tilt_table(TokenReader& in, Photometry& p) {
  TiltTable t;
  t.geometry = static_cast<int>(in.integer_in("TILT lamp-to-luminaire geometry", 1, 3));
  const long n = in.integer_in("TILT number of angles", 1, static_cast<long>(in.remaining() / 2));
  for (long i = 0; i < n; ++i) t.angles_deg.push_back(in.number_in([i] { return "TILT angles[" + std::to_string(i) + "]"; }, -360, 360));
  for (long i = 0; i < n; ++i) t.factors.push_back(in.number_in([i] { return "TILT factors[" + std::to_string(i) + "]"; }, 0, 100));
  p.tilt = std::move(t);
  warn(p, "TILT=INCLUDE: the " + std::to_string(n) + " tilt factors are kept but not applied (the web is at the tested tilt)");
}

// The parameter lines between TILT and the angles.
struct IesParameters {
  long lamps = 0;
  double lumens_per_lamp = 0;  // -1: absolute photometry
  double multiplier = 0;       // candela multiplier
  long nv = 0, nh = 0;         // vertical and horizontal angles
  int counts_at = 0;           // the line of the counts
  double width_m = 0, length_m = 0, height_m = 0;
  double ballast = 0;          // ballast factor
  double second = 0;           // ballast-lamp photometric factor (before LM-63-2002)
};

// Sets p.absolute and p.input_power_w.
IesParameters read_ies_parameters(TokenReader& in, const std::string& path, bool lm63_2002_or_later, Photometry& p) {
  const long lamps = in.integer_in("number of lamps", 0, 100000);
  const int lumens_at = in.line();
  const double lumens_per_lamp = in.number_in("lumens per lamp", -1, kMaxFluxLm);
  if (!(lumens_per_lamp > 0 || lumens_per_lamp == -1)) {
    fail(path, lumens_at, "lumens per lamp", fmt(lumens_per_lamp) + ": must be > 0, or -1 for absolute photometry");
  }
  p.absolute = lumens_per_lamp == -1;
  const int mult_at = in.line();
  const double multiplier = in.number_in("candela multiplier", 0, kMaxFactor);
  if (!(multiplier > 0)) fail(path, mult_at, "candela multiplier", "must be > 0");
  const int counts_at = in.line();
  const long nv = in.integer_in("number of vertical angles", 2, kMaxCount);
  const long nh = in.integer_in("number of horizontal angles", 1, kMaxCount);
  const int type_at = in.line();
  const long type = in.integer_in("photometric type", -1000000, 1000000);
  if (type == 2 || type == 3) {
    fail(path, type_at, "photometric type",
         std::string(type == 2 ? "type B (2)" : "type A (3)") + " is not supported: only type C (1) is read");
  }
  if (type != 1) fail(path, type_at, "photometric type", "unknown type " + std::to_string(type) + " (1 = C, 2 = B, 3 = A)");
  const long units = in.integer_in("units type", 1, 2);
  const double to_m = units == 1 ? kFeetToMetres : 1.0;
  const double width = in.number_in("width", -kMaxDimensionM, kMaxDimensionM) * to_m;
  const double length = in.number_in("length", -kMaxDimensionM, kMaxDimensionM) * to_m;
  const double height = in.number_in("height", -kMaxDimensionM, kMaxDimensionM) * to_m;
  const int bf_at = in.line();
  const double ballast = in.number_in("ballast factor", 0, 10);
  if (!(ballast > 0)) fail(path, bf_at, "ballast factor", "must be > 0");
  const int blf_at = in.line();
  const double second = in.number("ballast-lamp photometric factor");
  if (!lm63_2002_or_later && !(second > 0 && second <= 10)) {
    fail(path, blf_at, "ballast-lamp photometric factor", fmt(second) + " is outside (0, 10]");
  }
  p.input_power_w = in.number_in("input watts", 0, kMaxPowerW);
  return {lamps, lumens_per_lamp, multiplier, nv, nh, counts_at, width, length, height, ballast, second};
}

// The angles and the candela values (scaled to cd), after checking the counts against
// what the file holds. Sets p.gamma_angles_deg and p.symmetry; `data_line`: where the
// candela values start.
StoredWeb read_ies_web(TokenReader& in, const std::string& path, const IesParameters& par, double scale,
                       Photometry& p, int& data_line) {
  const long nv = par.nv, nh = par.nh;
  // Counts against what the file holds, before anything is allocated.
  const std::uint64_t needed = static_cast<std::uint64_t>(nv) + static_cast<std::uint64_t>(nh) +
                               static_cast<std::uint64_t>(nv) * static_cast<std::uint64_t>(nh);
  if (needed > in.remaining()) {
    fail(path, par.counts_at, "candela",
         "the header announces " + std::to_string(nv) + " x " + std::to_string(nh) + " candela values and their angles (" +
             std::to_string(needed) + " numbers) but only " + std::to_string(in.remaining()) +
             " follow: truncated or wrong counts");
  }
  p.gamma_angles_deg = read_angles(in, "vertical angles", nv, 0, 180, path);
  const int h_line = in.line();
  const std::vector<double> h = read_angles(in, "horizontal angles", nh, 0, 360, path);
  p.symmetry = ies_symmetry(h, path, h_line);
  const double g0 = p.gamma_angles_deg.front(), g1 = p.gamma_angles_deg.back();
  if (!(near(g0, 0) || near(g0, 90)) || !(near(g1, 90) || near(g1, 180))) {
    warn(p, "vertical angles " + fmt(g0) + ".." + fmt(g1) + " are not 0..90, 90..180 or 0..180: intensity is 0 outside");
  }

  StoredWeb w;
  w.c_deg = h;
  w.cd.resize(nh, nv);
  data_line = in.line();
  for (long j = 0; j < nh; ++j) {
    for (long i = 0; i < nv; ++i) {
      const auto field = [&] { return "candela[C=" + fmt(h[j]) + ", gamma=" + fmt(p.gamma_angles_deg[i]) + "]"; };
      const int at = in.line();
      const double v = in.number(field);
      if (v < 0) fail(path, at, field(), fmt(v) + " cd is negative");
      const double cd = v * scale;
      if (cd > kMaxCandela) fail(path, at, field(), fmt(cd) + " cd is beyond any luminaire (limit 1e9 cd)");
      if (cd > 0 && cd < kMinNonZeroCandela) fail(path, at, field(), fmt(cd) + " cd is not zero yet below 1e-30 cd: no measurement");
      w.cd(j, i) = cd;
    }
  }
  if (in.remaining() > 0) {
    fail(path, in.line(), "candela",
         std::to_string(in.remaining()) + " more values after the " + std::to_string(nv * nh) +
             " the header announces (" + std::to_string(nv) + " vertical x " + std::to_string(nh) + " horizontal)");
  }
  if (p.symmetry == PhotometricSymmetry::none && near(h.back(), 360)) w.plane_360 = static_cast<int>(nh - 1);
  return w;
}

}  // namespace

Photometry parse_ies(std::string_view raw, const std::string& path) {
  if (raw.size() > kMaxFileBytes) fail(path, 0, "file", "larger than 64 MiB: not a photometric file");
  const std::vector<std::string_view> lines = split_lines(strip_bom_and_eof(raw));
  Photometry p;
  p.path = path;
  p.format = PhotometryFormat::ies;
  if (lines.empty()) fail(path, 1, "identifier", "the file is empty");
  const IesPreamble preamble = read_ies_preamble(lines, path, p);
  TokenReader in(tokenize(lines, preamble.tilt_line + 1), path, static_cast<int>(lines.size()));
  if (preamble.tilt == "INCLUDE") read_tilt_table(in, p);
  const IesParameters par = read_ies_parameters(in, path, preamble.lm63_2002_or_later, p);
  const double scale = par.multiplier * par.ballast * (preamble.lm63_2002_or_later ? 1.0 : par.second);
  int data_line = 0;
  const StoredWeb w = read_ies_web(in, path, par, scale, p, data_line);
  expand_web(p, w);

  p.lamp_flux_lm = p.absolute ? 0 : static_cast<double>(par.lamps) * par.lumens_per_lamp;
  p.opening = ies_opening(par.width_m, par.length_m, par.height_m, p);
  finish(p, data_line);
  p.lamp_sets.push_back(LampSet{static_cast<int>(par.lamps), "", p.lamp_flux_lm, "", "", p.input_power_w});
  if (!p.absolute && p.lamp_flux_lm > 0 && p.luminaire_flux_lm > 1.02 * p.lamp_flux_lm) {
    warn(p, "the web integrates to " + fmt(p.luminaire_flux_lm) + " lm, more than the stated lamp flux " +
                fmt(p.lamp_flux_lm) + " lm (light output ratio " + fmt(p.luminaire_flux_lm / p.lamp_flux_lm) + " > 1)");
  }
  return p;
}

}  // namespace ilp
