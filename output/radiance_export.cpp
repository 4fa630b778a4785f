// The Radiance scene of a layout: materials and patches, luminaires as ies2rad writes
// them (brightdata on a .dat of the candela web, source.cal's flatcorr), grid points.
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <locale>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/light/luminaire_product.h"
#include "core/light/photometry.h"
#include "output/layout_export.h"

namespace ilp {
namespace {

// Radiance's luminous efficacy of its white light (lm per W): what ies2rad divides candela by.
constexpr double kRadianceWhiteEfficacy = 179.0;
constexpr double kPi = 3.14159265358979323846;

std::string g(double v) {
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os << std::setprecision(9) << (v == 0.0 ? 0.0 : v);
  return os.str();
}

// "\tx\ty\tz\n" (a stream, not string +: GCC 12 warns falsely of -Wrestrict on "\t" + ...).
std::string point(const Eigen::Vector3d& p) {
  std::ostringstream os;
  os << '\t' << g(p.x()) << '\t' << g(p.y()) << '\t' << g(p.z()) << '\n';
  return os.str();
}

// One dimension of a Radiance data file as ies2rad's cvdata writes it: "first last n"
// for evenly spaced angles, else "0 0 n" and the angles, four to a line.
void write_dimension(std::ostream& out, const std::vector<double>& angles) {
  bool even = true;
  for (std::size_t j = 1; j + 1 < angles.size(); ++j)
    even = even && std::abs((angles[j] - angles[j - 1]) - (angles[j + 1] - angles[j])) <= 1e-6;
  if (even) {
    out << g(angles.front()) << ' ' << g(angles.back()) << ' ' << angles.size() << '\n';
    return;
  }
  out << "0 0 " << angles.size();
  for (std::size_t j = 0; j < angles.size(); ++j) out << (j % 4 == 0 ? "\n" : "") << '\t' << g(angles[j]);
  out << '\n';
}

const Photometry* photometry_of(const LuminaireType& type) {
  const auto* d = dynamic_cast<const PhotometricDistribution*>(type.distribution.get());
  return d ? &d->photometry() : nullptr;
}

// Does the web send light above the horizontal (ies2rad's doupper)?
bool emits_upward(const Photometry& p) {
  for (Eigen::Index c = 0; c < p.candela_cd.rows(); ++c)
    for (std::size_t k = 0; k < p.gamma_angles_deg.size(); ++k)
      if (p.gamma_angles_deg[k] > 90.0 + 1e-6 && p.candela_cd(c, static_cast<Eigen::Index>(k)) > 0.0) return true;
  return false;
}

// A polygon of the outline, facing `down` (reversed, ies2rad's ".d") or up (".u").
void write_polygon(std::ostream& out, const std::string& modifier, const std::string& name,
                   std::vector<Eigen::Vector3d> outline, bool down) {
  if (down) std::reverse(outline.begin(), outline.end());
  out << modifier << " polygon " << name << "\n0\n0\n" << 3 * outline.size() << '\n';
  for (const Eigen::Vector3d& v : outline) out << point(v);
}

void write_luminaire(std::ostream& out, const ExportLuminaire& l, const RadianceNames& names) {
  const std::string id = file_safe_name(l.id);
  const std::vector<Eigen::Vector3d> outline = luminaire_outline_m(l.type, l.placement);
  const double area_m2 = l.type.opening_area_m2();
  const Eigen::Vector3d& p = l.placement.position_m;
  out << "\n# " << l.id << ": " << (l.product.empty() ? l.type.name : l.product) << ", " << g(l.flux_lm)
      << " lm, opening centre (" << g(p.x()) << ", " << g(p.y()) << ", " << g(p.z()) << ") m, rotated "
      << g(l.placement.rotation_deg) << " deg, tilted " << g(l.placement.tilt_deg) << " deg\n";
  const Photometry* photometry = photometry_of(l.type);
  if (!photometry) {  // a Lambertian opening: plain light of its luminance
    const double radiance = l.flux_lm / (kPi * area_m2) / kRadianceWhiteEfficacy;
    out << "void light " << id << "_light\n0\n0\n3 " << g(radiance) << ' ' << g(radiance) << ' ' << g(radiance) << '\n';
    write_polygon(out, id + "_light", id + ".d", outline, true);
    return;
  }
  std::string dat;
  for (const auto& [product, file] : names.product_dat)
    if (product == l.product) dat = file;
  if (dat.empty()) throw std::invalid_argument("radiance export: no .dat file named for product '" + l.product + "'");
  const bool rotational = photometry->c_angles_deg.size() < 2;
  const std::string transform = "-ry " + g(-l.placement.tilt_deg) + " -rz " + g(l.placement.rotation_deg) + " -t " +
                                g(p.x()) + ' ' + g(p.y()) + ' ' + g(p.z());
  const int transform_words = 8;  // -ry A -rz B -t X Y Z
  // A1: the .dat holds the file's candela at its own flux; scale to this luminaire's output.
  const double a1 = l.flux_lm / photometry->luminaire_flux_lm / area_m2;
  out << "void brightdata " << id << "_dist\n"
      << (rotational ? 4 : 5) + transform_words << " flatcorr " << dat << " source.cal "
      << (rotational ? "src_theta " : "src_phi src_theta ") << transform << "\n0\n1 " << g(a1) << '\n';
  out << id << "_dist light " << id << "_light\n0\n0\n3 1 1 1\n";
  write_polygon(out, id + "_light", id + ".d", outline, true);
  if (emits_upward(*photometry)) write_polygon(out, id + "_light", id + ".u", outline, false);
}

}  // namespace

void write_radiance_distribution(std::ostream& out, const Photometry& p) {
  const bool rotational = p.c_angles_deg.size() < 2;
  out << (rotational ? 1 : 2) << '\n';
  if (!rotational) write_dimension(out, p.c_angles_deg);
  write_dimension(out, p.gamma_angles_deg);
  std::size_t n = 0;
  for (Eigen::Index c = 0; c < p.candela_cd.rows(); ++c)
    for (Eigen::Index k = 0; k < p.candela_cd.cols(); ++k)
      out << (n++ % 4 == 0 ? "\n" : "") << '\t' << g(p.candela_cd(c, k) / kRadianceWhiteEfficacy);
  out << '\n';
}

void write_radiance_scene(const Scene& scene, const std::vector<ExportLuminaire>& luminaires,
                          const std::vector<ExportGrid>& grids, const RadianceNames& names, const FileWriter& write) {
  write(names.scene, [&](std::ostream& out) {
    out << "# Radiance scene of an ilp layout: metres, z up; the light is initial (new luminaires):\n"
           "# multiply by the maintenance factor for maintained values.\n"
           "# oconv " << names.scene << " > scene.oct     (source.cal comes with Radiance, on RAYPATH)\n";
    for (const auto& [grid, file] : names.grid_pts)
      out << "# rtrace -h -I+ -w -ab 8 -ad 4096 -as 1024 -aa 0.05 -ar 512 -lw 1e-5 scene.oct < " << file
          << " | rcalc -e '$1=179*(0.265*$1+0.670*$2+0.065*$3)'    (lux at grid '" << grid << "')\n";
    // One plastic per surface and reflectance, then the patches.
    std::map<std::pair<int, std::array<double, 3>>, std::string> materials;
    for (std::size_t i = 0; i < scene.patches.size(); ++i) {
      const Patch& patch = scene.patches[i];
      const Surface& surface = scene.surfaces[static_cast<std::size_t>(patch.surface)];
      if (surface.is_luminaire() || surface.is_virtual) continue;
      const std::array<double, 3> rho{patch.reflectance[0], patch.reflectance[1], patch.reflectance[2]};
      const auto key = std::make_pair(patch.surface, rho);
      auto it = materials.find(key);
      if (it == materials.end()) {
        std::ostringstream material;  // a stream: GCC 12 warns falsely (-Wrestrict) of "m" + std::to_string(...)
        material << 'm' << materials.size() << '_' << file_safe_name(surface.name);
        const std::string name = material.str();
        it = materials.emplace(key, name).first;
        out << "\n# surface '" << surface.name << "'\n";
        if (patch.exitance_lm_per_m2 > 0.0) {  // an emitting surface: Lambertian light
          const double radiance = patch.exitance_lm_per_m2 / kPi / kRadianceWhiteEfficacy;
          out << "void light " << name << "\n0\n0\n3 " << g(radiance) << ' ' << g(radiance) << ' ' << g(radiance) << '\n';
        } else {
          const Eigen::Vector3d r = scene.channels == 1 ? Eigen::Vector3d::Constant(rho[0]) : patch.reflectance;
          out << "void plastic " << name << "\n0\n0\n5 " << g(r[0]) << ' ' << g(r[1]) << ' ' << g(r[2]) << " 0 0\n";
        }
      }
      out << it->second << " polygon p" << i << "\n0\n0\n9\n";
      for (const Eigen::Vector3d& v : patch.vertices_m) out << point(v);
    }
    for (const ExportLuminaire& l : luminaires) write_luminaire(out, l, names);
  });
  for (const auto& [product, file] : names.product_dat) {
    const Photometry* photometry = nullptr;
    for (const ExportLuminaire& l : luminaires)
      if (l.product == product && !photometry) photometry = photometry_of(l.type);
    if (photometry) write(file, [&](std::ostream& out) { write_radiance_distribution(out, *photometry); });
  }
  for (const ExportGrid& grid : grids)
    for (const auto& [name, file] : names.grid_pts)
      if (name == grid.name)
        write(file, [&](std::ostream& out) {
          for (std::size_t k = 0; k < grid.positions_m.size(); ++k) {
            const Eigen::Vector3d& p = grid.positions_m[k];
            const Eigen::Vector3d& n = grid.normals[k];
            out << g(p.x()) << ' ' << g(p.y()) << ' ' << g(p.z()) << ' ' << g(n.x()) << ' ' << g(n.y()) << ' '
                << g(n.z()) << '\n';
          }
        });
}

}  // namespace ilp
