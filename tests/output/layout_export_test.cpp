// The exports other tools read (output/layout_export.h): the Radiance luminaire checked
// against its photometric file by Radiance's own rules (source.cal, brightdata), the
// glTF read back through assimp, the DXF read back by dxflib, the schedule's columns.
#include <gtest/gtest.h>

#include <dl_creationadapter.h>
#include <dl_dxf.h>

#include <cmath>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/light/luminaire_product.h"
#include "core/light/photometry.h"
#include "core/scene/mesh.h"
#include "core/scene/reference_scenes.h"
#include "output/layout_export.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::TempDir;
constexpr double kPi = 3.14159265358979323846;

const std::string kPhotometry = std::string(ILP_SOURCE_DIR) + "/data/photometry/";

ExportLuminaire product_luminaire(const std::string& file, const std::string& id, LuminairePlacement at, double flux_lm) {
  auto photometry = std::make_shared<const Photometry>(load_photometry(kPhotometry + file));
  return ExportLuminaire{id, file, photometric_luminaire_type(file, photometry), at, flux_lm, photometry->luminaire_flux_lm, 30.0};
}

// A closed 4 x 3 x 2.5 m box of gray surfaces (floor, ceiling, walls).
Scene box_room() {
  TriangleMesh mesh;
  mesh.path = "box";
  mesh.surface_names = {"floor", "ceiling", "walls"};
  const double X = 4, Y = 3, Z = 2.5;
  const Eigen::Vector3d c[8] = {{0, 0, 0}, {X, 0, 0}, {X, Y, 0}, {0, Y, 0}, {0, 0, Z}, {X, 0, Z}, {X, Y, Z}, {0, Y, Z}};
  for (const auto& p : c) mesh.positions.push_back(p);
  auto quad = [&](int a, int b, int cc, int d, int s) {  // counter-clockwise seen from inside
    mesh.triangles.emplace_back(a, b, cc);
    mesh.triangles.emplace_back(a, cc, d);
    for (int k = 0; k < 2; ++k) {
      mesh.triangle_surface.push_back(s);
      mesh.triangle_material.push_back(-1);
    }
  };
  quad(0, 1, 2, 3, 0);
  quad(4, 7, 6, 5, 1);
  quad(0, 4, 5, 1, 2);
  quad(1, 5, 6, 2, 2);
  quad(2, 6, 7, 3, 2);
  quad(3, 7, 4, 0, 2);
  SceneOptions o;
  o.max_patch_edge_m = 0.5;
  return make_scene(mesh, TriangleReflectance(mesh.triangles.size(), Eigen::Vector3d::Constant(0.5)), o);
}

std::map<std::string, std::string> export_radiance(const Scene& scene, const std::vector<ExportLuminaire>& luminaires,
                                                   const std::vector<ExportGrid>& grids, const RadianceNames& names) {
  std::map<std::string, std::string> files;
  write_radiance_scene(scene, luminaires, grids, names, [&](const std::string& name, const std::function<void(std::ostream&)>& w) {
    std::ostringstream os;
    w(os);
    files[name] = os.str();
  });
  return files;
}

// A Radiance data file, read as Radiance reads it: dimensions "first last n" or "0 0 n"
// and a list, values with the first dimension slowest; linear interpolation between nodes.
struct RadianceData {
  std::vector<std::vector<double>> axes;
  std::vector<double> values;
  static RadianceData parse(const std::string& text) {
    std::istringstream in(text);
    RadianceData d;
    int dims = 0;
    in >> dims;
    for (int k = 0; k < dims; ++k) {
      double first = 0, last = 0;
      int n = 0;
      in >> first >> last >> n;
      std::vector<double> axis(static_cast<std::size_t>(n));
      if (first == 0.0 && last == 0.0) {
        for (double& a : axis) in >> a;
      } else {
        for (int j = 0; j < n; ++j) axis[static_cast<std::size_t>(j)] = first + (last - first) * j / (n - 1);
      }
      d.axes.push_back(axis);
    }
    for (double v; in >> v;) d.values.push_back(v);
    return d;
  }
  // At the coordinates (one per dimension), multilinear.
  double at(const std::vector<double>& x) const {
    std::vector<std::size_t> lo(axes.size());
    std::vector<double> t(axes.size());
    for (std::size_t k = 0; k < axes.size(); ++k) {
      const auto& a = axes[k];
      std::size_t i = 0;
      while (i + 2 < a.size() && x[k] > a[i + 1]) ++i;
      lo[k] = i;
      t[k] = std::clamp((x[k] - a[i]) / (a[i + 1] - a[i]), 0.0, 1.0);
    }
    double sum = 0.0;
    for (unsigned corner = 0; corner < (1u << axes.size()); ++corner) {
      double w = 1.0;
      std::size_t index = 0;
      for (std::size_t k = 0; k < axes.size(); ++k) {
        const bool up = corner & (1u << k);
        w *= up ? t[k] : 1.0 - t[k];
        index = index * axes[k].size() + lo[k] + (up ? 1 : 0);
      }
      sum += w * values[index];
    }
    return sum;
  }
};

// The words of the primitive after "void brightdata ID" in a .rad text: string args,
// then the real args.
struct Brightdata {
  std::vector<std::string> strings;
  std::vector<double> reals;
};
Brightdata brightdata(const std::string& rad, const std::string& id) {
  const std::size_t at = rad.find("void brightdata " + id + "\n");
  EXPECT_NE(at, std::string::npos) << id;
  std::istringstream in(rad.substr(at + std::string("void brightdata ").size() + id.size()));
  Brightdata b;
  int n = 0;
  in >> n;
  b.strings.resize(static_cast<std::size_t>(n));
  for (std::string& s : b.strings) in >> s;
  in >> n;  // integer args: 0
  in >> n;
  b.reals.resize(static_cast<std::size_t>(n));
  for (double& r : b.reals) in >> r;
  return b;
}

// The rotation an xform word list ("-ry A -rz B -t x y z") applies, as Radiance's xform does.
Eigen::Matrix3d xform_rotation(const std::vector<std::string>& words) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  for (std::size_t k = 0; k + 1 < words.size(); ++k) {
    const double a = std::atof(words[k + 1].c_str()) * kPi / 180.0;
    if (words[k] == "-rx") r = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix() * r;
    if (words[k] == "-ry") r = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix() * r;
    if (words[k] == "-rz") r = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix() * r;
  }
  return r;
}

// Intensity (cd) the Radiance description sends toward world direction `w`: source.cal's
// src_phi = atan2(-Dy, -Dx), src_theta = acos(Dz) of the ray direction D = -w in the
// pattern's frame; flatcorr's luminance A1 v / |cos| over the polygon's projected area
// A |cos|, times 179 lm/W.
double radiance_intensity_cd(const Brightdata& b, const RadianceData& data, const Eigen::Vector3d& w, double area_m2) {
  // flatcorr FILE source.cal [src_phi] src_theta, then the transform words.
  const bool rotational = b.strings[3] == "src_theta";
  const std::size_t first_transform = rotational ? 4 : 5;
  const Eigen::Matrix3d r = xform_rotation({b.strings.begin() + static_cast<std::ptrdiff_t>(first_transform), b.strings.end()});
  const Eigen::Vector3d d = r.transpose() * (-w);
  const double theta = std::acos(std::clamp(d.z(), -1.0, 1.0)) * 180.0 / kPi;
  double phi = std::atan2(-d.y(), -d.x()) * 180.0 / kPi;
  if (phi < 0) phi += 360.0;
  const double v = rotational ? data.at({theta}) : data.at({phi, theta});
  return b.reals[0] * v * area_m2 * 179.0;
}

double polygon_area(const std::string& rad, const std::string& name) {
  const std::size_t at = rad.find(" polygon " + name + "\n");
  EXPECT_NE(at, std::string::npos) << name;
  std::istringstream in(rad.substr(at + 9 + name.size()));
  int n = 0;
  in >> n >> n >> n;
  std::vector<Eigen::Vector3d> v(static_cast<std::size_t>(n / 3));
  for (auto& p : v) in >> p.x() >> p.y() >> p.z();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t k = 1; k + 1 < v.size(); ++k) sum += (v[k] - v[0]).cross(v[k + 1] - v[0]);
  return 0.5 * sum.norm();
}

// The exported luminaire sends, toward 20 directions at the file's own angles, the
// intensity the photometric file gives at the luminaire's output, turned and tilted as
// placed (the directions go through ilp's placement, Radiance's side through the
// exported transform words).
TEST(RadianceExport, LuminaireIntensitiesMatchThePhotometricFileAt20Directions) {
  for (const std::string file : {"ledalite_direct_indirect.ies", "linear_led_2112lm.ldt", "erco_iku_downlight.ldt"}) {
    SCOPED_TRACE(file);
    const LuminairePlacement at{Eigen::Vector3d(1.2, 2.1, 2.4), 30.0, 20.0};
    const ExportLuminaire l = product_luminaire(file, "L1", at, 2500.0);
    const RadianceNames names = radiance_names({file}, {});
    const auto files = export_radiance(box_room(), {l}, {}, names);
    const std::string& rad = files.at(names.scene);
    const RadianceData data = RadianceData::parse(files.at(names.product_dat[0].second));
    const Brightdata b = brightdata(rad, "L1_dist");
    ASSERT_GE(b.strings.size(), 5u);
    EXPECT_EQ(b.strings[0], "flatcorr");
    EXPECT_EQ(b.strings[2], "source.cal");
    const double area_m2 = polygon_area(rad, "L1.d");
    EXPECT_NEAR(area_m2, l.type.opening_area_m2(), 1e-6);
    const Photometry& p = dynamic_cast<const PhotometricDistribution&>(*l.type.distribution).photometry();
    const Eigen::Matrix3d placed = luminaire_rotation(at);
    int checked = 0;
    for (int k = 0; k < 20; ++k) {
      const double c = p.c_angles_deg[static_cast<std::size_t>(k * 7) % p.c_angles_deg.size()];
      const double gamma = p.gamma_angles_deg[static_cast<std::size_t>(k * 5 + 1) % p.gamma_angles_deg.size()];
      const Eigen::Vector3d world = placed * c_gamma_to_direction(c, gamma);
      const double expected = l.flux_lm / p.luminaire_flux_lm * p.intensity_cd(c, gamma);
      const double got = radiance_intensity_cd(b, data, world, area_m2);
      EXPECT_NEAR(got, expected, 1e-6 * std::max(1.0, expected)) << "C " << c << ", gamma " << gamma;
      ++checked;
    }
    EXPECT_EQ(checked, 20);
    // An uplight gets ies2rad's upper polygon too.
    EXPECT_EQ(rad.find("L1.u") != std::string::npos, p.upward_fraction > 0.0);
  }
}

// The plain panel is a Lambertian light: radiance x pi x area x 179 = its flux.
TEST(RadianceExport, LambertianPanelEmitsItsFlux) {
  const ExportLuminaire l{"P1", "", LuminaireType::square_lambertian(0.6), {Eigen::Vector3d(2, 1.5, 2.45), 0, 0}, 3000.0};
  const RadianceNames names = radiance_names({}, {"work_plane"});
  ExportGrid grid{"work_plane", {Eigen::Vector3d(1, 1, 0.8), Eigen::Vector3d(2, 1, 0.8)}, {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()}};
  const auto files = export_radiance(box_room(), {l}, {grid}, names);
  const std::string& rad = files.at(names.scene);
  std::istringstream in(rad.substr(rad.find("void light P1_light\n") + 20));
  int n = 0;
  double r = 0, g = 0, b = 0;
  in >> n >> n >> n >> r >> g >> b;
  EXPECT_NEAR(r * kPi * 0.36 * 179.0, 3000.0, 1e-4);
  EXPECT_EQ(r, g);
  EXPECT_EQ(g, b);
  EXPECT_EQ(files.at("radiance_work_plane.pts"), "1 1 0.8 0 0 1\n2 1 0.8 0 0 1\n");
  // Every patch of the room is a polygon with its surface's plastic.
  std::size_t polygons = 0;
  for (std::size_t at = rad.find(" polygon p"); at != std::string::npos; at = rad.find(" polygon p", at + 1)) ++polygons;
  EXPECT_EQ(polygons, box_room().patches.size());
  EXPECT_NE(rad.find("void plastic m0_floor\n0\n0\n5 0.5 0.5 0.5 0 0\n"), std::string::npos);
}

TEST(RadianceExport, NamesOfProductsAndGridsAreFileSafeAndUnique) {
  const RadianceNames names = radiance_names({"Panel 600/600", "Panel_600_600"}, {"work plane"});
  ASSERT_EQ(names.product_dat.size(), 2u);
  EXPECT_EQ(names.product_dat[0].second, "radiance_Panel_600_600.dat");
  EXPECT_EQ(names.product_dat[1].second, "radiance_Panel_600_600_2.dat");
  EXPECT_EQ(names.grid_pts[0].second, "radiance_work_plane.pts");
  EXPECT_EQ(names.all().size(), 4u);
}

// The glTF loads back through assimp (ilp's importer) with a node per surface and per
// luminaire, in the same place (glTF's y up turned back to z up).
TEST(GltfExport, LoadsBackWithNamedNodes) {
  TempDir dir;
  const Scene scene = box_room();
  const std::vector<ExportLuminaire> luminaires{
      {"L1", "", LuminaireType::square_lambertian(0.6), {Eigen::Vector3d(1, 1, 2.45), 0, 0}, 3000.0},
      {"L2", "", LuminaireType::square_lambertian(0.6), {Eigen::Vector3d(3, 2, 2.45), 45, 0}, 3000.0}};
  Eigen::VectorXd lux = Eigen::VectorXd::LinSpaced(static_cast<Eigen::Index>(scene.patches.size()), 0.0, 500.0);
  lux[0] = std::numeric_limits<double>::quiet_NaN();
  const std::string path = dir.file("scene.glb");
  write_illuminance_gltf(path, scene, lux, ColourScale{0.0, 500.0}, luminaires);
  const TriangleMesh back = load_mesh(path);
  std::vector<std::string> names = back.surface_names;
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"L1", "L2", "ceiling", "floor", "walls"}));
  ASSERT_TRUE(back.frame.up_axis.has_value());
  SceneOptions frame;
  frame.up_axis = *back.frame.up_axis;
  Eigen::AlignedBox3d bounds;
  for (const Eigen::Vector3d& p : back.positions) bounds.extend(to_scene_frame(p, frame));
  EXPECT_LT((bounds.min() - scene.bounds_m.min()).norm(), 1e-6) << bounds.min().transpose();
  EXPECT_LT((bounds.max() - scene.bounds_m.max()).norm(), 1e-6) << bounds.max().transpose();
  EXPECT_EQ(back.triangles.size(), scene.patches.size() + 4) << "every patch, and two triangles per panel";
  EXPECT_THROW(write_illuminance_gltf(path, scene, Eigen::VectorXd::Zero(3), ColourScale{}, luminaires), std::invalid_argument);
}

// What dxflib reads of the plan.
struct DxfContents : DL_CreationAdapter {
  std::vector<std::string> layers;
  std::map<std::string, int> lines;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> wall_lines;
  int polylines = 0, vertices = 0;
  std::vector<std::string> texts;
  void addLayer(const DL_LayerData& d) override { layers.push_back(d.name); }
  void addLine(const DL_LineData& d) override {
    ++lines[attributes.getLayer()];
    if (attributes.getLayer() == "ILP_WALLS") wall_lines.emplace_back(Eigen::Vector2d(d.x1, d.y1), Eigen::Vector2d(d.x2, d.y2));
  }
  void addPolyline(const DL_PolylineData&) override { polylines += attributes.getLayer() == "ILP_LUMINAIRES"; }
  void addVertex(const DL_VertexData&) override { vertices += attributes.getLayer() == "ILP_LUMINAIRES"; }
  void addText(const DL_TextData& d) override {
    if (attributes.getLayer() == "ILP_LABELS") texts.push_back(d.text);
  }
};

// dxflib (a packaged DXF reader, the one LibreCAD grew from) reads the plan's layers,
// the box's four walls cut at 1 m (each one line, merged over its patches), a closed
// outline of four vertices and a label per luminaire.
TEST(DxfPlan, DxflibReadsItsLayersWallsAndLuminaires) {
  TempDir dir;
  const Scene scene = box_room();
  std::vector<ExportLuminaire> luminaires{
      {"L1", "Panel", LuminaireType::square_lambertian(0.6), {Eigen::Vector3d(1, 1, 2.45), 0, 0}, 3000.0},
      {"L2", "Panel", LuminaireType::square_lambertian(0.6), {Eigen::Vector3d(3, 2, 2.45), 90, 0}, 3000.0}};
  luminaires[0].above_floor_m = 2.45;
  std::ostringstream os;
  write_dxf_plan(os, scene, luminaires, 0.0, 1.0);
  const std::string path = dir.write("plan.dxf", os.str());
  DxfContents c;
  DL_Dxf dxf;
  ASSERT_TRUE(dxf.in(path, &c));
  std::sort(c.layers.begin(), c.layers.end());
  EXPECT_EQ(c.layers, (std::vector<std::string>{"ILP_FURNITURE", "ILP_LABELS", "ILP_LUMINAIRES", "ILP_WALLS"}));
  ASSERT_EQ(c.wall_lines.size(), 4u);
  double length = 0.0;
  for (const auto& [a, b] : c.wall_lines) length += (b - a).norm();
  EXPECT_NEAR(length, 14.0, 1e-9) << "the box's perimeter";
  EXPECT_EQ(c.polylines, 2);
  EXPECT_EQ(c.vertices, 8);
  EXPECT_EQ(c.texts, (std::vector<std::string>{"L1 Panel h=2.45 m", "L2 Panel"}));
}

TEST(Schedule, OneRowPerLuminaireWithUnitsInTheHeader) {
  std::vector<ExportLuminaire> luminaires{
      {"L1", "Panel, 600", LuminaireType::square_lambertian(0.6), {Eigen::Vector3d(1, 1.25, 2.45), 90, 15}, 2400.0, 3000.0, 24.0},
      {"old", "", LuminaireType::square_lambertian(0.6), {Eigen::Vector3d(3, 2, 2.45), 0, 0}, 1000.0}};
  luminaires[0].above_floor_m = 2.45;
  luminaires[1].placed_by_job = true;
  std::ostringstream os;
  write_schedule_csv(os, luminaires);
  EXPECT_EQ(os.str(),
            "id,product,x_m,y_m,z_m,height_above_floor_m,rotation_deg,tilt_deg,flux_lm,output_percent,power_w,source\n"
            "L1,\"Panel, 600\",1.000,1.250,2.450,2.450,90.0,15.0,2400,80.0,24.0,layout\n"
            "old,square_lambertian,3.000,2.000,2.450,,0.0,0.0,1000,,,placed\n");
}

}  // namespace
}  // namespace ilp
