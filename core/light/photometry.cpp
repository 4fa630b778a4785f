// The candela web's shared machinery: the text helpers and range checks the IES and
// EULUMDAT readers (ies_reader.cpp, eulumdat_reader.cpp) share, the symmetry expansion of
// the stored planes, its PCHIP interpolation, the trapezoid flux integral, and loading a
// file by its extension or content.
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
#include <sstream>
#include <utility>

#include "core/light/photometry_reading.h"

namespace ilp {
namespace photometry_detail {

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

namespace {

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


}  // namespace

// Text fields as UTF-8: kept if they already are, else read as ISO-8859-1 (EULUMDAT's charset).
std::string bounded_text(std::string_view s, const std::string& path, int line, const std::string& field) {
  if (s.size() > kMaxTextChars)
    fail(path, line, field, std::to_string(s.size()) + " characters, more than " + std::to_string(kMaxTextChars));
  return printable(to_utf8(s));
}

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
bool parse_number(std::string_view token, double& out, bool decimal_comma) {
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


// ------------------------------------------------------------------ symmetry expansion

namespace {

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

}  // namespace

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

}  // namespace photometry_detail

using namespace photometry_detail;

// ------------------------------------------------------------------ interpolation (PCHIP)

namespace {

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

// ------------------------------------------------------------------ flux

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

}  // namespace

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
