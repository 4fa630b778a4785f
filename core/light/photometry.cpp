// IES LM-63 and EULUMDAT readers, the symmetry expansion of the candela web, its PCHIP
// interpolation and the trapezoid flux integral.
//
// Reading is defensive: every count is checked against what is left of the file before
// anything is allocated, every number must be finite and within a plausible range, and
// every failure names the file, the line of the offending token and the field.
#include "core/light/photometry.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <type_traits>
#include <utility>

namespace ilp {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kFeetToMetres = 0.3048;
// Angles closer than this (degrees) are the same angle (files print 2-6 decimals).
constexpr double kAngleTolDeg = 1e-6;
// Plausibility limits: beyond them a value is a corrupt file, not a luminaire.
constexpr double kMaxCandela = 1e9;       // the brightest searchlights are ~1e9 cd
constexpr double kMaxFluxLm = 1e8;        // a 1 MW sodium lamp makes ~1.5e8 lm
constexpr double kMaxPowerW = 1e7;
constexpr double kMaxDimensionM = 1000.0;
constexpr double kMaxDimensionMm = 1e6;
constexpr double kMaxFactor = 1e6;        // candela multiplier, EULUMDAT conversion factor
constexpr long kMaxCount = 10000000;     // angle counts; checked against the file's size anyway
constexpr std::size_t kMaxFileBytes = std::size_t{64} << 20;
// Header-vs-data checks warn beyond this many percentage points.
constexpr double kHeaderCheckPoints = 2.0;

[[noreturn]] void fail(const std::string& path, int line, const std::string& field, const std::string& what) {
  throw PhotometryError(located(FileLoc{path, line, 0}, "field " + field + ": " + what));
}

std::string fmt(double x) {
  std::ostringstream os;
  os.precision(6);
  os << x;
  return os.str();
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return out;
}

std::string_view trim(std::string_view s) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

bool valid_utf8(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    int extra = 0;
    if (c < 0x80) extra = 0;
    else if ((c & 0xE0) == 0xC0 && c >= 0xC2) extra = 1;
    else if ((c & 0xF0) == 0xE0) extra = 2;
    else if ((c & 0xF8) == 0xF0 && c <= 0xF4) extra = 3;
    else return false;
    if (extra > 0 && i + static_cast<std::size_t>(extra) >= s.size()) return false;
    for (int k = 1; k <= extra; ++k) {
      if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return false;
    }
    i += static_cast<std::size_t>(extra) + 1;
  }
  return true;
}

// Text fields as UTF-8: kept if they already are, else read as ISO-8859-1 (EULUMDAT's charset).
std::string to_utf8(std::string_view s) {
  if (valid_utf8(s)) return std::string(s);
  std::string out;
  out.reserve(s.size() * 2);
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x80) {
      out.push_back(ch);
    } else {
      out.push_back(static_cast<char>(0xC0 | (c >> 6)));
      out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
    }
  }
  return out;
}

// The text without a UTF-8 BOM and without anything from a DOS end-of-file byte (^Z) on.
std::string_view strip_bom_and_eof(std::string_view text) {
  if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  const std::size_t eof = text.find('\x1A');
  if (eof != std::string_view::npos) text = text.substr(0, eof);
  return text;
}

// Lines split at LF, CRLF or a lone CR; line i of the result is file line i + 1.
std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n' || text[i] == '\r') {
      lines.push_back(text.substr(start, i - start));
      if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      start = i + 1;
    }
  }
  if (start < text.size()) lines.push_back(text.substr(start));
  return lines;
}

// A finite number written in full (leading '+' allowed; `decimal_comma`: "0,5" = 0.5).
bool parse_number(std::string_view token, double& out, bool decimal_comma = false) {
  token = trim(token);
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  std::string buffer;
  if (decimal_comma && token.find(',') != std::string_view::npos && token.find('.') == std::string_view::npos) {
    buffer.assign(token);
    std::replace(buffer.begin(), buffer.end(), ',', '.');
    token = buffer;
  }
  double value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value)) return false;
  out = value;
  return true;
}

// A field name, built only when a message needs it (a string, or a callable returning one).
template <class Name>
std::string name_of(const Name& name) {
  if constexpr (std::is_invocable_v<const Name&>) {
    return name();
  } else {
    return std::string(name);
  }
}

bool is_integer(double x) { return std::abs(x - std::round(x)) < 1e-9; }

// ------------------------------------------------------------------ interpolation (PCHIP)

// Fritsch-Carlson slope at an interior node from the neighbouring secants (non-uniform
// steps h0 before, h1 after): weighted harmonic mean, 0 at a local extremum.
double interior_slope(double h0, double h1, double d0, double d1) {
  if (d0 * d1 <= 0) return 0;
  const double w1 = 2 * h1 + h0, w2 = h1 + 2 * h0;
  return (w1 + w2) / (w1 / d0 + w2 / d1);
}

// Shape-preserving three-point slope at an end node (h0, d0 the end interval).
double end_slope(double h0, double h1, double d0, double d1) {
  double d = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
  if (d * d0 <= 0) return 0;
  if (d0 * d1 <= 0 && std::abs(d) > std::abs(3 * d0)) d = 3 * d0;
  return d;
}

// Slope at a node of the parabola through it and its two neighbours: linear in the data,
// so a tensor product built on it stays C1 in the other variable too.
double parabola_slope(double h0, double h1, double d0, double d1) { return (h1 * d0 + h0 * d1) / (h0 + h1); }

double hermite(double x0, double x1, double y0, double y1, double m0, double m1, double x) {
  const double h = x1 - x0;
  const double t = (x - x0) / h;
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * h * m0 + (-2 * t3 + 3 * t2) * y1 + (t3 - t2) * h * m1;
}

// PCHIP through (x[i], y(i)), i in [0, n), evaluated at xq inside interval k.
template <class Y>
double pchip_open(const std::vector<double>& x, Y y, int k, double xq) {
  const int n = static_cast<int>(x.size());
  const double h = x[k + 1] - x[k];
  const double d = (y(k + 1) - y(k)) / h;
  if (n == 2) return y(k) + d * (xq - x[k]);
  double m0, m1;
  if (k == 0) {
    const double h1 = x[2] - x[1];
    m0 = end_slope(h, h1, d, (y(2) - y(1)) / h1);
  } else {
    const double hp = x[k] - x[k - 1];
    m0 = interior_slope(hp, h, (y(k) - y(k - 1)) / hp, d);
  }
  if (k + 1 == n - 1) {
    const double hp = x[k] - x[k - 1];
    m1 = end_slope(h, hp, d, (y(k) - y(k - 1)) / hp);
  } else {
    const double hn = x[k + 2] - x[k + 1];
    m1 = interior_slope(h, hn, d, (y(k + 2) - y(k + 1)) / hn);
  }
  return hermite(x[k], x[k + 1], y(k), y(k + 1), m0, m1, xq);
}

// ------------------------------------------------------------------ symmetry expansion

// The angles C maps to under the symmetry group (C itself first), modulo 360.
std::vector<double> images(PhotometricSymmetry s, double c) {
  const auto wrap = [](double a) {
    a = std::fmod(a, 360.0);
    if (a < 0) a += 360.0;
    if (a >= 360.0 - kAngleTolDeg) a = 0;
    return a;
  };
  switch (s) {
    case PhotometricSymmetry::quadrant: return {wrap(c), wrap(180 - c), wrap(180 + c), wrap(360 - c)};
    case PhotometricSymmetry::bilateral_c0_c180: return {wrap(c), wrap(360 - c)};
    case PhotometricSymmetry::bilateral_c90_c270: return {wrap(c), wrap(180 - c)};
    default: return {wrap(c)};
  }
}

struct StoredWeb {
  std::vector<double> c_deg;  // the file's planes, in file order (any of them may be >= 360 before wrap)
  Eigen::MatrixXd cd;         // #planes by #gamma
  int plane_360 = -1;         // index of a stored C = 360 plane (IES 0..360), else -1
};

// Fills p.c_angles_deg and p.candela_cd from the stored planes and p.symmetry.
void expand_web(Photometry& p, const StoredWeb& w) {
  const Eigen::Index ng = w.cd.cols();
  if (p.symmetry == PhotometricSymmetry::rotational) {
    p.c_angles_deg = {0.0};
    p.candela_cd = w.cd.topRows(1);
    return;
  }
  // (angle modulo 360, stored row), sorted, for lookups; the stored 360 plane is left out.
  std::vector<std::pair<double, int>> lookup;
  std::vector<double> nodes;
  for (int i = 0; i < static_cast<int>(w.c_deg.size()); ++i) {
    if (i == w.plane_360) continue;
    const std::vector<double> im = images(p.symmetry, w.c_deg[static_cast<std::size_t>(i)]);
    lookup.emplace_back(im.front(), i);
    nodes.insert(nodes.end(), im.begin(), im.end());
  }
  std::sort(lookup.begin(), lookup.end());
  std::sort(nodes.begin(), nodes.end());
  std::vector<double> unique;
  for (double a : nodes) {
    if (unique.empty() || a - unique.back() > kAngleTolDeg) unique.push_back(a);
  }
  const auto find_row = [&](double a) -> int {
    for (double b : images(p.symmetry, a)) {
      auto it = std::lower_bound(lookup.begin(), lookup.end(), std::make_pair(b - kAngleTolDeg, -1));
      if (it != lookup.end() && std::abs(it->first - b) <= kAngleTolDeg) return it->second;
    }
    return -1;
  };
  const Eigen::Index n = static_cast<Eigen::Index>(unique.size()) + 1;
  p.c_angles_deg = unique;
  p.c_angles_deg.push_back(360.0);
  p.candela_cd.resize(n, ng);
  for (Eigen::Index j = 0; j + 1 < n; ++j) {
    const int row = find_row(unique[static_cast<std::size_t>(j)]);
    // Every node is an image of a stored plane, so its preimage is found (an invariant).
    if (row < 0) throw PhotometryError(p.path + ": internal error: C = " + fmt(unique[static_cast<std::size_t>(j)]) + " has no stored plane");
    p.candela_cd.row(j) = w.cd.row(row);
  }
  p.candela_cd.row(n - 1) = w.plane_360 >= 0 ? Eigen::MatrixXd(w.cd.row(w.plane_360)) : Eigen::MatrixXd(p.candela_cd.row(0));
}

// Trapezoid rule of f(gamma) sin(gamma) d gamma over [lo, hi] of the gamma grid, f linear
// between nodes where [lo, hi] cuts an interval (exact split of the trapezoid).
double plane_integral(const std::vector<double>& gamma_deg, const Eigen::MatrixXd& cd, Eigen::Index row, double lo_deg,
                      double hi_deg) {
  double total = 0;
  for (std::size_t i = 0; i + 1 < gamma_deg.size(); ++i) {
    const double g0 = gamma_deg[i] * kDegToRad, g1 = gamma_deg[i + 1] * kDegToRad;
    const double f0 = cd(row, static_cast<Eigen::Index>(i)) * std::sin(g0);
    const double f1 = cd(row, static_cast<Eigen::Index>(i + 1)) * std::sin(g1);
    const double a = std::max(g0, lo_deg * kDegToRad), b = std::min(g1, hi_deg * kDegToRad);
    if (b <= a) continue;
    const auto f = [&](double g) { return f0 + (f1 - f0) * (g - g0) / (g1 - g0); };
    total += 0.5 * (f(a) + f(b)) * (b - a);
  }
  return total;
}

double web_integral(const Photometry& p, double lo_deg, double hi_deg) {
  if (p.candela_cd.rows() == 0 || p.gamma_angles_deg.size() < 2) return 0;
  if (p.c_angles_deg.size() == 1) return 2 * kPi * plane_integral(p.gamma_angles_deg, p.candela_cd, 0, lo_deg, hi_deg);
  double total = 0;
  double prev = plane_integral(p.gamma_angles_deg, p.candela_cd, 0, lo_deg, hi_deg);
  for (std::size_t j = 0; j + 1 < p.c_angles_deg.size(); ++j) {
    const double next =
        plane_integral(p.gamma_angles_deg, p.candela_cd, static_cast<Eigen::Index>(j + 1), lo_deg, hi_deg);
    total += 0.5 * (prev + next) * (p.c_angles_deg[j + 1] - p.c_angles_deg[j]) * kDegToRad;
    prev = next;
  }
  return total;
}

// Common checks once the web is in place: something is emitted, flux and upward share.
void finish(Photometry& p, int data_line) {
  if (p.candela_cd.size() == 0 || p.candela_cd.maxCoeff() <= 0) fail(p.path, data_line, "candela", "every value is 0");
  p.luminaire_flux_lm = integrate_flux_lm(p);
  if (!(p.luminaire_flux_lm > 0) || p.luminaire_flux_lm > kMaxFluxLm) {
    fail(p.path, data_line, "candela", "the web integrates to " + fmt(p.luminaire_flux_lm) + " lm, beyond any luminaire");
  }
  p.upward_fraction = std::clamp(integrate_upward_flux_lm(p) / p.luminaire_flux_lm, 0.0, 1.0);
  if (p.absolute) p.lamp_flux_lm = p.luminaire_flux_lm;
}

void warn(Photometry& p, const std::string& message) { p.warnings.push_back(p.path + ": " + message); }

// ------------------------------------------------------------------ IES LM-63

struct Token {
  std::string_view text;
  int line = 0;
};

// The range checks both readers share, on a Reader with line(), number(field) and
// path(): a number within [lo, hi], a whole number within [lo, hi].
template <class Reader>
class BoundedNumbers {
 public:
  template <class Name>
  double number_in(const Name& field, double lo, double hi) {
    Reader& r = static_cast<Reader&>(*this);
    const int at = r.line();
    const double v = r.number(field);
    if (v < lo || v > hi) fail(r.path(), at, name_of(field), fmt(v) + " is outside [" + fmt(lo) + ", " + fmt(hi) + "]");
    return v;
  }
  template <class Name>
  long integer_in(const Name& field, long lo, long hi) {
    Reader& r = static_cast<Reader&>(*this);
    const int at = r.line();
    const double v = r.number(field);
    if (!is_integer(v)) fail(r.path(), at, name_of(field), fmt(v) + " is not a whole number");
    if (v < static_cast<double>(lo) || v > static_cast<double>(hi)) {
      fail(r.path(), at, name_of(field),
           fmt(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
    return std::lround(v);
  }
};

class TokenReader : public BoundedNumbers<TokenReader> {
 public:
  TokenReader(std::vector<Token> tokens, std::string path, int last_line)
      : tokens_(std::move(tokens)), path_(std::move(path)), last_line_(last_line) {}

  std::size_t remaining() const { return tokens_.size() - pos_; }
  int line() const { return pos_ < tokens_.size() ? tokens_[pos_].line : last_line_; }
  int line_of_last() const { return pos_ > 0 ? tokens_[pos_ - 1].line : line(); }
  const std::string& path() const { return path_; }

  template <class Name>
  double number(const Name& field) {
    if (pos_ >= tokens_.size()) fail(path_, last_line_, name_of(field), "the file ends here: truncated (a value is missing)");
    const Token& t = tokens_[pos_];
    double v = 0;
    if (!parse_number(t.text, v)) {
      fail(path_, t.line, name_of(field), "'" + std::string(t.text.substr(0, 40)) + "' is not a finite number");
    }
    ++pos_;
    return v;
  }
  const Token* peek() const { return pos_ < tokens_.size() ? &tokens_[pos_] : nullptr; }

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

LuminousOpening ies_opening(double width, double length, double height, Photometry& p) {
  LuminousOpening o;
  if (width == 0 && length == 0 && height == 0) return o;
  if (width < 0 || length < 0) {  // round: disc, vertical cylinder, sphere
    const double w = width != 0 ? std::abs(width) : std::abs(length);
    const double l = length != 0 ? std::abs(length) : std::abs(width);
    o.width_m = w;
    o.length_m = l;
    if (height == 0) {
      o.shape = OpeningShape::disc;
    } else {
      o.shape = OpeningShape::cylinder;
      o.height_m = std::abs(height);
      if (height < 0) warn(p, "spherical or horizontal-cylinder opening (negative height) taken as a vertical cylinder");
    }
    return o;
  }
  o.shape = OpeningShape::rectangle;
  o.width_m = width;
  o.length_m = length;
  o.height_m = std::abs(height);
  if (height < 0) warn(p, "negative height with a rectangular opening: taken as " + fmt(o.height_m) + " m");
  return o;
}

}  // namespace

// ------------------------------------------------------------------ public: IES

Photometry parse_ies(std::string_view raw, const std::string& path) {
  if (raw.size() > kMaxFileBytes) fail(path, 0, "file", "larger than 64 MiB: not a photometric file");
  const std::vector<std::string_view> lines = split_lines(strip_bom_and_eof(raw));
  Photometry p;
  p.path = path;
  p.format = PhotometryFormat::ies;
  if (lines.empty()) fail(path, 1, "identifier", "the file is empty");

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
      const std::string value = to_utf8(trim(l.substr(close + 1)));
      if (key == "MORE" && last_keyword) {
        *last_keyword += " " + value;
        continue;
      }
      last_keyword = nullptr;
      if (key == "LUMINAIRE") last_keyword = &p.luminaire;
      else if (key == "MANUFAC") last_keyword = &p.manufacturer;
      else if (key == "LUMCAT") last_keyword = &p.catalogue;
      if (last_keyword && last_keyword->empty()) *last_keyword = value;
      else last_keyword = nullptr;
    } else if (free_text.empty() && !l.empty()) {
      free_text = to_utf8(l);
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

  TokenReader in(tokenize(lines, tilt_line + 1), path, static_cast<int>(lines.size()));
  if (tilt_upper == "INCLUDE") {
    TiltTable t;
    t.geometry = static_cast<int>(in.integer_in("TILT lamp-to-luminaire geometry", 1, 3));
    const long n = in.integer_in("TILT number of angles", 1, static_cast<long>(in.remaining() / 2));
    for (long i = 0; i < n; ++i) t.angles_deg.push_back(in.number_in([i] { return "TILT angles[" + std::to_string(i) + "]"; }, -360, 360));
    for (long i = 0; i < n; ++i) t.factors.push_back(in.number_in([i] { return "TILT factors[" + std::to_string(i) + "]"; }, 0, 100));
    p.tilt = std::move(t);
    warn(p, "TILT=INCLUDE: the " + std::to_string(n) + " tilt factors are kept but not applied (the web is at the tested tilt)");
  }

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

  // Counts against what the file holds, before anything is allocated.
  const std::uint64_t needed = static_cast<std::uint64_t>(nv) + static_cast<std::uint64_t>(nh) +
                               static_cast<std::uint64_t>(nv) * static_cast<std::uint64_t>(nh);
  if (needed > in.remaining()) {
    fail(path, counts_at, "candela",
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

  const double scale = multiplier * ballast * (lm63_2002_or_later ? 1.0 : second);
  StoredWeb w;
  w.c_deg = h;
  w.cd.resize(nh, nv);
  const int data_line = in.line();
  for (long j = 0; j < nh; ++j) {
    for (long i = 0; i < nv; ++i) {
      const auto field = [&] { return "candela[C=" + fmt(h[j]) + ", gamma=" + fmt(p.gamma_angles_deg[i]) + "]"; };
      const int at = in.line();
      const double v = in.number(field);
      if (v < 0) fail(path, at, field(), fmt(v) + " cd is negative");
      const double cd = v * scale;
      if (cd > kMaxCandela) fail(path, at, field(), fmt(cd) + " cd is beyond any luminaire (limit 1e9 cd)");
      w.cd(j, i) = cd;
    }
  }
  if (in.remaining() > 0) {
    fail(path, in.line(), "candela",
         std::to_string(in.remaining()) + " more values after the " + std::to_string(nv * nh) +
             " the header announces (" + std::to_string(nv) + " vertical x " + std::to_string(nh) + " horizontal)");
  }
  if (p.symmetry == PhotometricSymmetry::none && near(h.back(), 360)) w.plane_360 = static_cast<int>(nh - 1);
  expand_web(p, w);

  p.lamp_flux_lm = p.absolute ? 0 : static_cast<double>(lamps) * lumens_per_lamp;
  p.opening = ies_opening(width, length, height, p);
  finish(p, data_line);
  p.lamp_sets.push_back(LampSet{static_cast<int>(lamps), "", p.lamp_flux_lm, "", "", p.input_power_w});
  if (!p.absolute && p.lamp_flux_lm > 0 && p.luminaire_flux_lm > 1.02 * p.lamp_flux_lm) {
    warn(p, "the web integrates to " + fmt(p.luminaire_flux_lm) + " lm, more than the stated lamp flux " +
                fmt(p.lamp_flux_lm) + " lm (light output ratio " + fmt(p.luminaire_flux_lm / p.lamp_flux_lm) + " > 1)");
  }
  return p;
}

// ------------------------------------------------------------------ EULUMDAT

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
  std::string text(const std::string& field) { return to_utf8(raw(field)); }
  template <class Name>
  double number(const Name& field) {
    const int at = line();
    const std::string_view t = raw(field);
    double v = 0;
    if (!parse_number(t, v, true)) {
      fail(path_, at, name_of(field), "'" + std::string(t.substr(0, 40)) + "' is not a finite number");
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
  if (width == 0) {
    o.shape = height > 0 ? OpeningShape::cylinder : OpeningShape::disc;
    width = length;
  } else {
    o.shape = OpeningShape::rectangle;
  }
  o.length_m = length / 1000;
  o.width_m = width / 1000;
  o.height_m = height / 1000;
  return o;
}

}  // namespace

Photometry parse_eulumdat(std::string_view raw, const std::string& path) {
  if (raw.size() > kMaxFileBytes) fail(path, 0, "file", "larger than 64 MiB: not a photometric file");
  FieldReader in(split_lines(strip_bom_and_eof(raw)), path);
  Photometry p;
  p.path = path;
  p.format = PhotometryFormat::eulumdat;

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

  const double scale = conversion * p.lamp_sets.front().flux_lm / 1000.0;
  p.absolute = p.lamp_sets.front().count < 0;
  StoredWeb w;
  w.cd.resize(static_cast<Eigen::Index>(stored.size()), ng);
  const int data_line = in.line();
  for (std::size_t j = 0; j < stored.size(); ++j) {
    const double c = c_all[static_cast<std::size_t>(stored[j])];
    w.c_deg.push_back(c);
    for (long i = 0; i < ng; ++i) {
      const auto field = [&] { return "30 intensity[C=" + fmt(c) + ", gamma=" + fmt(p.gamma_angles_deg[i]) + "]"; };
      const int at = in.line();
      const double v = in.number(field);
      if (v < 0) fail(path, at, field(), fmt(v) + " cd/klm is negative");
      const double cd = v * scale;
      if (cd > kMaxCandela) fail(path, at, field(), fmt(cd) + " cd is beyond any luminaire (limit 1e9 cd)");
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
  expand_web(p, w);

  p.lamp_flux_lm = p.lamp_sets.front().flux_lm;
  p.input_power_w = p.lamp_sets.front().power_w;
  p.opening = eulumdat_opening(mm, p);
  finish(p, data_line);
  // Header against data.
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
  return p;
}

// ------------------------------------------------------------------ public: loading, flux, intensity

Photometry load_photometry(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw PhotometryError(path + (std::filesystem::exists(path, ec) ? ": not a regular file" : ": no such photometric file"));
  }
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw PhotometryError(path + ": cannot open the photometric file");
  const std::streamoff size = in.tellg();
  if (size < 0) throw PhotometryError(path + ": cannot read the photometric file");
  if (static_cast<std::uint64_t>(size) > kMaxFileBytes) {
    throw PhotometryError(path + ": the file is larger than 64 MiB: not a photometric file");
  }
  std::string text(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  in.read(text.data(), size);
  if (!in) throw PhotometryError(path + ": cannot read the photometric file");
  std::string ext;
  if (const std::size_t dot = path.find_last_of('.'); dot != std::string::npos && path.find('/', dot) == std::string::npos) {
    ext = upper(path.substr(dot));
  }
  if (ext == ".IES") return parse_ies(text, path);
  if (ext == ".LDT") return parse_eulumdat(text, path);
  // By content: an IES identifier or a TILT= line.
  const std::string_view body = strip_bom_and_eof(text);
  const std::string head = upper(trim(body.substr(0, std::min<std::size_t>(body.size(), 16))));
  bool ies = head.rfind("IESNA", 0) == 0 || head.rfind("IES:", 0) == 0;
  for (std::string_view l : split_lines(body)) {
    if (ies) break;
    ies = upper(trim(l)).rfind("TILT", 0) == 0 && l.find('=') != std::string_view::npos;
  }
  return ies ? parse_ies(text, path) : parse_eulumdat(text, path);
}

double integrate_flux_lm(const Photometry& p) { return web_integral(p, 0, 180); }

double integrate_upward_flux_lm(const Photometry& p) { return web_integral(p, 90, 180); }

Eigen::Vector2d direction_to_c_gamma_deg(const Eigen::Vector3d& d) {
  const double n = d.norm();
  if (!(n > 0)) return {0, 0};
  const double gamma = std::acos(std::clamp(-d.z() / n, -1.0, 1.0)) / kDegToRad;
  double c = std::atan2(d.y(), d.x()) / kDegToRad;
  if (c < 0) c += 360;
  if (c >= 360) c -= 360;
  return {c, gamma};
}

Eigen::Vector3d c_gamma_to_direction(double c_deg, double gamma_deg) {
  const double c = c_deg * kDegToRad, g = gamma_deg * kDegToRad;
  return {std::sin(g) * std::cos(c), std::sin(g) * std::sin(c), -std::cos(g)};
}

double Photometry::intensity_cd(double c_deg, double gamma_deg) const {
  const std::vector<double>& g = gamma_angles_deg;
  const int ng = static_cast<int>(g.size());
  if (ng < 2 || candela_cd.cols() != ng || candela_cd.rows() != static_cast<Eigen::Index>(c_angles_deg.size()) ||
      !std::isfinite(c_deg) || !std::isfinite(gamma_deg)) {
    return 0;
  }
  if (gamma_deg < g.front() - kAngleTolDeg || gamma_deg > g.back() + kAngleTolDeg) return 0;
  gamma_deg = std::clamp(gamma_deg, g.front(), g.back());
  const int k = std::clamp(static_cast<int>(std::upper_bound(g.begin(), g.end(), gamma_deg) - g.begin()) - 1, 0, ng - 2);
  const auto on_plane = [&](Eigen::Index row) {
    return pchip_open(g, [&](int i) { return candela_cd(row, i); }, k, gamma_deg);
  };
  const int nodes = static_cast<int>(c_angles_deg.size());
  if (nodes == 1) return std::max(0.0, on_plane(0));
  const int n = nodes - 1;  // distinct planes; node n is C = 360
  double c = std::fmod(c_deg, 360.0);
  if (c < 0) c += 360.0;
  const int j = std::clamp(
      static_cast<int>(std::upper_bound(c_angles_deg.begin(), c_angles_deg.end(), c) - c_angles_deg.begin()) - 1, 0, n - 1);
  // Periodic neighbours: node k < 0 is node k + n one turn earlier, node k > n is k - n one turn later.
  std::array<double, 4> a{}, v{};
  for (int t = 0; t < 4; ++t) {
    int idx = j - 1 + t;
    double shift = 0;
    if (idx < 0) { idx += n; shift = -360; }
    if (idx > n) { idx -= n; shift = 360; }
    a[static_cast<std::size_t>(t)] = c_angles_deg[static_cast<std::size_t>(idx)] + shift;
    v[static_cast<std::size_t>(t)] = on_plane(idx);
  }
  const double h0 = a[1] - a[0], h1 = a[2] - a[1], h2 = a[3] - a[2];
  const double d0 = (v[1] - v[0]) / h0, d1 = (v[2] - v[1]) / h1, d2 = (v[3] - v[2]) / h2;
  const double m1 = parabola_slope(h0, h1, d0, d1), m2 = parabola_slope(h1, h2, d1, d2);
  return std::max(0.0, hermite(a[1], a[2], v[1], v[2], m1, m2, c));
}

double Photometry::intensity_cd(const Eigen::Vector3d& direction_local) const {
  if (!(direction_local.norm() > 0)) return 0;
  const Eigen::Vector2d cg = direction_to_c_gamma_deg(direction_local);
  return intensity_cd(cg.x(), cg.y());
}

}  // namespace ilp
