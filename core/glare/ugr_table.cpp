#include "core/glare/ugr_table.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <sstream>

#include "core/base/error.h"
#include "core/light/luminaire_product.h"

namespace ilp {
namespace {

constexpr double kRad = std::numbers::pi / 180.0;

// CIE 190:2010 Table 4: geometric factors F_GL1..4 by room index k = XY / (H (X + Y)), and
// Table 5: transfer factors (F_T,FW, F_T,WW-1, F_T,CW) per room (cie190_rooms() order) and
// reflectance set (cie190_reflectances() order). Both as transcribed in eulumdat-ugr
// (github.com/123VincentB/eulumdat-ugr, src/eulumdat_ugr/background.py, MIT); not checked
// against the printed standard (docs/glare.md).
struct GeometricFactors {
  double k;
  std::array<double, 4> f;
};
constexpr std::array<GeometricFactors, 13> kFgl{{
    {1.00, {0.690, 0.109, 0.085, -0.016}}, {1.20, {0.578, 0.200, 0.127, -0.018}},
    {1.33, {0.528, 0.218, 0.170, -0.017}}, {1.50, {0.485, 0.215, 0.222, -0.012}},
    {1.60, {0.466, 0.207, 0.249, -0.006}}, {1.71, {0.448, 0.198, 0.272, 0.005}},
    {2.00, {0.338, 0.257, 0.351, -0.018}}, {2.40, {0.296, 0.203, 0.449, -0.006}},
    {2.67, {0.280, 0.165, 0.499, 0.006}},  {3.00, {0.264, 0.125, 0.541, 0.027}},
    {3.43, {0.248, 0.058, 0.628, 0.032}},  {4.00, {0.239, -0.012, 0.690, 0.058}},
    {4.80, {0.232, -0.084, 0.740, 0.098}},
}};

using Transfer = std::array<double, 3>;  // FW, WW-1, CW
constexpr int kRooms = 19, kReflectanceSets = 5;
constexpr std::array<std::array<Transfer, kRooms>, kReflectanceSets> kFt{{
    {{{0.220, 0.422, 0.646}, {0.199, 0.376, 0.571}, {0.187, 0.351, 0.531}, {0.174, 0.322, 0.488},
      {0.167, 0.307, 0.466}, {0.160, 0.290, 0.443}, {0.187, 0.351, 0.531}, {0.158, 0.295, 0.439},
      {0.142, 0.265, 0.389}, {0.124, 0.230, 0.335}, {0.115, 0.211, 0.307}, {0.105, 0.190, 0.279},
      {0.115, 0.211, 0.307}, {0.094, 0.175, 0.247}, {0.083, 0.155, 0.215}, {0.071, 0.133, 0.183},
      {0.105, 0.190, 0.279}, {0.083, 0.153, 0.216}, {0.071, 0.133, 0.183}}},
    {{{0.188, 0.217, 0.553}, {0.173, 0.196, 0.497}, {0.164, 0.184, 0.465}, {0.154, 0.171, 0.432},
      {0.149, 0.164, 0.415}, {0.143, 0.156, 0.397}, {0.164, 0.184, 0.465}, {0.142, 0.159, 0.393},
      {0.129, 0.144, 0.351}, {0.114, 0.127, 0.307}, {0.106, 0.117, 0.283}, {0.098, 0.106, 0.259},
      {0.106, 0.117, 0.283}, {0.088, 0.098, 0.231}, {0.078, 0.088, 0.203}, {0.067, 0.076, 0.174},
      {0.098, 0.106, 0.259}, {0.078, 0.086, 0.204}, {0.067, 0.076, 0.174}}},
    {{{0.198, 0.380, 0.445}, {0.178, 0.338, 0.393}, {0.166, 0.314, 0.365}, {0.154, 0.287, 0.335},
      {0.147, 0.273, 0.320}, {0.141, 0.257, 0.304}, {0.166, 0.314, 0.364}, {0.140, 0.263, 0.301},
      {0.125, 0.235, 0.267}, {0.108, 0.204, 0.230}, {0.100, 0.187, 0.211}, {0.091, 0.167, 0.191},
      {0.100, 0.187, 0.211}, {0.081, 0.154, 0.169}, {0.071, 0.137, 0.147}, {0.061, 0.117, 0.125},
      {0.091, 0.167, 0.191}, {0.071, 0.134, 0.148}, {0.061, 0.117, 0.125}}},
    {{{0.172, 0.198, 0.386}, {0.157, 0.179, 0.346}, {0.148, 0.167, 0.324}, {0.138, 0.155, 0.301},
      {0.133, 0.147, 0.288}, {0.128, 0.140, 0.276}, {0.148, 0.167, 0.324}, {0.126, 0.143, 0.272},
      {0.114, 0.129, 0.244}, {0.100, 0.113, 0.212}, {0.093, 0.104, 0.196}, {0.085, 0.094, 0.179},
      {0.093, 0.104, 0.196}, {0.076, 0.087, 0.158}, {0.067, 0.078, 0.140}, {0.058, 0.067, 0.120},
      {0.085, 0.094, 0.179}, {0.068, 0.077, 0.140}, {0.058, 0.067, 0.120}}},
    {{{0.157, 0.181, 0.227}, {0.141, 0.162, 0.203}, {0.132, 0.151, 0.190}, {0.123, 0.139, 0.176},
      {0.118, 0.132, 0.169}, {0.113, 0.124, 0.161}, {0.132, 0.151, 0.190}, {0.112, 0.128, 0.159},
      {0.100, 0.115, 0.142}, {0.087, 0.101, 0.124}, {0.081, 0.092, 0.114}, {0.074, 0.083, 0.104},
      {0.081, 0.092, 0.114}, {0.066, 0.077, 0.092}, {0.058, 0.069, 0.081}, {0.049, 0.059, 0.069},
      {0.074, 0.083, 0.104}, {0.058, 0.067, 0.081}, {0.049, 0.059, 0.069}}},
}};

int room_index(const UgrTableRoom& room) {
  const auto& rooms = cie190_rooms();
  for (std::size_t i = 0; i < rooms.size(); ++i)
    if (std::abs(rooms[i].x_h - room.x_h) < 1e-9 && std::abs(rooms[i].y_h - room.y_h) < 1e-9) return static_cast<int>(i);
  throw IlpError("UGR table: room " + std::to_string(room.x_h) + "H x " + std::to_string(room.y_h) +
                 "H is not one of CIE 190's rooms");
}

int reflectance_index(const RoomReflectances& r) {
  const auto& sets = cie190_reflectances();
  for (std::size_t i = 0; i < sets.size(); ++i)
    if (std::abs(sets[i].ceiling - r.ceiling) < 1e-9 && std::abs(sets[i].walls - r.walls) < 1e-9 &&
        std::abs(sets[i].floor - r.floor) < 1e-9)
      return static_cast<int>(i);
  throw IlpError("UGR table: reflectances " + std::to_string(r.ceiling) + "/" + std::to_string(r.walls) + "/" +
                 std::to_string(r.floor) + " are not one of CIE 190's sets");
}

const std::array<double, 4>& geometric_factors(const UgrTableRoom& room) {
  const double k = room.x_h * room.y_h / (room.x_h + room.y_h);
  for (const GeometricFactors& g : kFgl)
    if (std::abs(g.k - k) < 0.006) return g.f;
  throw IlpError("UGR table: no CIE 190 geometric factors for room index k = " + std::to_string(k));
}

double mean_intensity_over_c_cd(const Photometry& p, double gamma_deg) {
  constexpr int kCSamples = 360;
  double sum = 0.0;
  for (int c = 0; c < kCSamples; ++c) sum += p.intensity_cd(360.0 * c / kCSamples, gamma_deg);
  return sum / kCSamples;
}

// The luminaire frame turned so that C0 (crosswise) or C90 (endwise) points at the observer,
// who looks along +y: the frame's +x to -y, or its +y to -y.
double viewing_rotation_deg(UgrViewing viewing) { return viewing == UgrViewing::crosswise ? -90.0 : 180.0; }

}  // namespace

const std::vector<UgrTableRoom>& cie190_rooms() {
  static const std::vector<UgrTableRoom> rooms{{2, 2}, {2, 3}, {2, 4}, {2, 6}, {2, 8}, {2, 12}, {4, 2},
                                               {4, 3}, {4, 4}, {4, 6}, {4, 8}, {4, 12}, {8, 4}, {8, 6},
                                               {8, 8}, {8, 12}, {12, 4}, {12, 6}, {12, 8}};
  return rooms;
}

const std::vector<RoomReflectances>& cie190_reflectances() {
  static const std::vector<RoomReflectances> sets{
      {0.7, 0.5, 0.2}, {0.7, 0.3, 0.2}, {0.5, 0.5, 0.2}, {0.5, 0.3, 0.2}, {0.3, 0.3, 0.2}};
  return sets;
}

ZonalFlux cie190_zonal_flux(const Photometry& p) {
  ZonalFlux z;
  double total = 0.0;
  for (int i = 0; i < 18; ++i) {
    const double gamma = 5.0 + 10.0 * i;
    z.zone[i] = mean_intensity_over_c_cd(p, gamma) * 2.0 * std::numbers::pi * std::sin(gamma * kRad) * 10.0 * kRad;
    total += z.zone[i];
  }
  if (!(total > 0.0)) throw PhotometryError(p.path + ": no flux in CIE 190's zones");
  for (double& f : z.zone) f /= total;
  for (int i = 0; i < 18; ++i) (i < 9 ? z.downward : z.upward) += z.zone[i];
  const auto& f = z.zone;
  z.cumulative = {f[0] + f[1] + f[2] + f[3] + 0.130 * f[4], f[0] + f[1] + f[2] + f[3] + f[4] + f[5],
                  f[0] + f[1] + f[2] + f[3] + f[4] + f[5] + f[6] + 0.547 * f[7], z.downward};
  return z;
}

FluxDistributionFactors cie190_flux_factors(const ZonalFlux& zonal, const UgrTableRoom& room) {
  const std::array<double, 4>& g = geometric_factors(room);
  FluxDistributionFactors d;
  for (int i = 0; i < 4; ++i) d.floor += g[i] * zonal.cumulative[i];
  d.walls = zonal.downward - d.floor;
  d.ceiling = zonal.upward;
  return d;
}

double cie190_indirect_vertical_illuminance_lx(const ZonalFlux& zonal, const UgrTableRoom& room,
                                               const RoomReflectances& reflectances, double flux_lm, int count,
                                               double h_m) {
  const Transfer& t = kFt[reflectance_index(reflectances)][room_index(room)];
  const FluxDistributionFactors d = cie190_flux_factors(zonal, room);
  const double wall_area_m2 = 2.0 * h_m * h_m * (room.x_h + room.y_h);
  return flux_lm * count / wall_area_m2 * (d.floor * t[0] + d.walls * t[1] + d.ceiling * t[2]);
}

std::vector<Eigen::Vector3d> ugr_table_field_m(const UgrTableRoom& room, const UgrTableOptions& o) {
  const double s = o.spacing_h * o.h_m;
  const int across = static_cast<int>(std::lround(room.x_h / o.spacing_h));
  const int along = static_cast<int>(std::lround(room.y_h / o.spacing_h));
  std::vector<Eigen::Vector3d> field;
  field.reserve(static_cast<std::size_t>(across * along));
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < across; ++i)
      field.emplace_back((i + 0.5 - 0.5 * across) * s, (j + 0.5) * s, o.h_m);
  return field;
}

double ugr_table_glare_sum(const GlareSource& prototype, const UgrTableRoom& room, UgrViewing viewing,
                           const UgrTableOptions& o) {
  const UgrObserver eye{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY()};
  const double max_horizontal_m = o.h_m * std::tan(o.max_gamma_deg * kRad);
  GlareSource s = prototype;
  s.placement.rotation_deg = viewing_rotation_deg(viewing);
  double sum = 0.0;
  for (const Eigen::Vector3d& at : ugr_table_field_m(room, o)) {
    if (std::hypot(at.x(), at.y()) > max_horizontal_m) continue;
    s.placement.position_m = at;
    sum += glare_term(s, eye, o.position_index);
  }
  return sum;
}

UgrTable ugr_table(const Photometry& photometry, const UgrTableOptions& o) {
  auto shared = std::make_shared<const Photometry>(photometry);
  const GlareSource prototype{glare_opening(photometry.opening), std::make_shared<PhotometricDistribution>(shared),
                              LuminairePlacement{}, photometry.luminaire_flux_lm};
  const ZonalFlux zonal = cie190_zonal_flux(photometry);
  UgrTable t{cie190_rooms(), cie190_reflectances(), {}, {}, photometry.luminaire_flux_lm};
  t.crosswise.resize(static_cast<Eigen::Index>(t.rooms.size()), static_cast<Eigen::Index>(t.reflectances.size()));
  t.endwise.resizeLike(t.crosswise);
  for (std::size_t r = 0; r < t.rooms.size(); ++r) {
    const double cross = ugr_table_glare_sum(prototype, t.rooms[r], UgrViewing::crosswise, o);
    const double end = ugr_table_glare_sum(prototype, t.rooms[r], UgrViewing::endwise, o);
    const int count = static_cast<int>(ugr_table_field_m(t.rooms[r], o).size());
    for (std::size_t f = 0; f < t.reflectances.size(); ++f) {
      const double e_lx = cie190_indirect_vertical_illuminance_lx(zonal, t.rooms[r], t.reflectances[f],
                                                                  t.flux_lm, count, o.h_m);
      const double lb = e_lx / std::numbers::pi;
      t.crosswise(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(f)) = ugr_from_terms(cross, lb);
      t.endwise(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(f)) = ugr_from_terms(end, lb);
    }
  }
  return t;
}

std::string format_ugr_table(const UgrTable& t) {
  std::ostringstream os;
  char buf[32];
  os << "room      crosswise (ceiling/walls/floor)         endwise (ceiling/walls/floor)\n  X x Y  ";
  for (int view = 0; view < 2; ++view)
    for (const RoomReflectances& f : t.reflectances) {
      std::snprintf(buf, sizeof buf, " %2.0f/%2.0f/%2.0f", f.ceiling * 100, f.walls * 100, f.floor * 100);
      os << buf;
    }
  os << '\n';
  for (std::size_t r = 0; r < t.rooms.size(); ++r) {
    std::snprintf(buf, sizeof buf, "%3.0fH x%3.0fH", t.rooms[r].x_h, t.rooms[r].y_h);
    os << buf;
    for (const Eigen::MatrixXd* m : {&t.crosswise, &t.endwise})
      for (Eigen::Index f = 0; f < m->cols(); ++f) {
        std::snprintf(buf, sizeof buf, " %8.1f", (*m)(static_cast<Eigen::Index>(r), f));
        os << buf;
      }
    os << '\n';
  }
  return os.str();
}

}  // namespace ilp
