#include "output/polar_curve.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "output/svg_text.h"

namespace ilp {
namespace {

using svg::cat;

constexpr double kDeg = std::numbers::pi / 180.0;

std::string num(double v, int digits = 2) {
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

// The smallest 1-2-5 step that needs at most `rings` rings to reach `max`.
double ring_step(double max, int rings) {
  if (!(max > 0.0)) return 1.0;
  const double raw = max / rings;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= raw) return m * decade;
  return 10.0 * decade;
}

PolarPlane sample_plane(const Photometry& p, double c_deg, double step_deg, double per_klm) {
  PolarPlane plane;
  plane.c_deg = c_deg;
  const int steps = static_cast<int>(std::lround(180.0 / step_deg));
  for (int k = 0; k <= steps; ++k) {
    const double g = std::min(180.0, k * step_deg);
    plane.gamma_deg.push_back(g);
    plane.cd_per_klm.push_back(p.intensity_cd(c_deg, g) * per_klm);
    plane.cd_per_klm_opposite.push_back(p.intensity_cd(c_deg + 180.0, g) * per_klm);
  }
  return plane;
}

// The polyline's points: the first plane right of the axis from nadir to zenith, then
// the opposite plane left of it back from zenith to nadir.
std::string curve_points(const PolarPlane& plane, double cx, double cy, double px_per_unit) {
  std::string out;
  const std::size_t n = plane.gamma_deg.size();
  auto point = [&](double g, double v, double side) {
    out += cat(out.empty() ? "" : " ", num(cx + side * v * px_per_unit * std::sin(g * kDeg)), ",",
               num(cy + v * px_per_unit * std::cos(g * kDeg)));
  };
  for (std::size_t k = 0; k < n; ++k) point(plane.gamma_deg[k], plane.cd_per_klm[k], 1.0);
  for (std::size_t k = n; k-- > 0;) point(plane.gamma_deg[k], plane.cd_per_klm_opposite[k], -1.0);
  return out;
}

}  // namespace

PolarCurve polar_curve(const Photometry& photometry, double gamma_step_deg) {
  if (!(gamma_step_deg > 0.0 && gamma_step_deg <= 45.0))
    throw std::invalid_argument("polar_curve: the gamma step must be in (0, 45] degrees");
  if (!(photometry.luminaire_flux_lm > 0.0))
    throw std::invalid_argument("polar_curve: " + photometry.path + " has no luminaire flux to scale by");
  const double per_klm = 1000.0 / photometry.luminaire_flux_lm;
  PolarCurve c;
  c.c0_c180 = sample_plane(photometry, 0.0, gamma_step_deg, per_klm);
  c.c90_c270 = sample_plane(photometry, 90.0, gamma_step_deg, per_klm);
  for (const PolarPlane* p : {&c.c0_c180, &c.c90_c270})
    for (const std::vector<double>* v : {&p->cd_per_klm, &p->cd_per_klm_opposite})
      c.max_cd_per_klm = std::max(c.max_cd_per_klm, *std::max_element(v->begin(), v->end()));
  c.ring_step_cd_per_klm = ring_step(c.max_cd_per_klm, 5);
  return c;
}

std::string polar_curve_svg(const PolarCurve& curve, double size_px) {
  const double legend_px = 40.0, w = size_px, h = size_px + legend_px;
  const double cx = w / 2.0, cy = size_px / 2.0, radius = size_px / 2.0 - 24.0;
  const double step = curve.ring_step_cd_per_klm > 0.0 ? curve.ring_step_cd_per_klm : 1.0;
  const int rings = std::max(1, static_cast<int>(std::ceil(curve.max_cd_per_klm / step - 1e-9)));
  const double px_per_unit = radius / (rings * step);
  std::string s = cat("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"", num(w, 0), "\" height=\"", num(h, 0),
                      "\" viewBox=\"0 0 ", num(w, 0), " ", num(h, 0), "\" font-family=\"DejaVu Sans, sans-serif\">\n",
                      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
  for (int k = 1; k <= rings; ++k) {
    const double r = k * step * px_per_unit;
    s += cat("<circle cx=\"", num(cx), "\" cy=\"", num(cy), "\" r=\"", num(r), "\" fill=\"none\" stroke=\"#bbbbbb\" stroke-width=\"0.7\"/>\n");
    s += cat("<text x=\"", num(cx + 3.0), "\" y=\"", num(cy + r - 3.0), "\" font-size=\"9\" fill=\"#555555\">",
             num(k * step, step < 1.0 ? 1 : 0), "</text>\n");
  }
  for (int a = 0; a < 360; a += 30) {  // spokes, labelled with gamma (0 at the bottom)
    const double t = a * kDeg;
    const double x = cx + radius * std::sin(t), y = cy + radius * std::cos(t);
    s += cat("<line x1=\"", num(cx), "\" y1=\"", num(cy), "\" x2=\"", num(x), "\" y2=\"", num(y),
             "\" stroke=\"#dddddd\" stroke-width=\"0.7\"/>\n");
    const int gamma = a <= 180 ? a : 360 - a;
    const double lx = cx + (radius + 12.0) * std::sin(t), ly = cy + (radius + 12.0) * std::cos(t) + 3.0;
    s += cat("<text x=\"", num(lx), "\" y=\"", num(ly), "\" font-size=\"9\" text-anchor=\"middle\" fill=\"#555555\">",
             std::to_string(gamma), "°</text>\n");
  }
  s += cat("<polyline class=\"c0_c180\" fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.6\" points=\"",
           curve_points(curve.c0_c180, cx, cy, px_per_unit), "\"/>\n");
  s += cat("<polyline class=\"c90_c270\" fill=\"none\" stroke=\"#1f5fa8\" stroke-width=\"1.6\" stroke-dasharray=\"5,3\" points=\"",
           curve_points(curve.c90_c270, cx, cy, px_per_unit), "\"/>\n");
  const double ly = size_px + 16.0;
  s += cat("<line x1=\"10\" y1=\"", num(ly - 4.0), "\" x2=\"34\" y2=\"", num(ly - 4.0),
           "\" stroke=\"#c0392b\" stroke-width=\"1.6\"/><text x=\"38\" y=\"", num(ly), "\" font-size=\"10\">C0–C180 (C0 right)</text>\n");
  s += cat("<line x1=\"", num(w / 2.0 + 10.0), "\" y1=\"", num(ly - 4.0), "\" x2=\"", num(w / 2.0 + 34.0), "\" y2=\"",
           num(ly - 4.0), "\" stroke=\"#1f5fa8\" stroke-width=\"1.6\" stroke-dasharray=\"5,3\"/><text x=\"",
           num(w / 2.0 + 38.0), "\" y=\"", num(ly), "\" font-size=\"10\">C90–C270 (C90 right)</text>\n");
  s += cat("<text x=\"10\" y=\"", num(ly + 16.0), "\" font-size=\"10\" fill=\"#555555\">cd/klm (per 1000 lm of the luminaire's output); 0° = nadir</text>\n");
  s += "</svg>\n";
  return s;
}

}  // namespace ilp
