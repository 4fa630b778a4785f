// Placed luminaires of real products through the real program: `ilp solve` on an
// installation of photometric luminaires gives each grid point the closed form of
// point sources, sum of I(C, gamma) cos^3(gamma) / h^2, with C and gamma worked out here
// from the point, the luminaire and its rotation; the layout placed as `ilp run`'s
// verification places it (add_layout, verify_layout) gives the same values; and a bad
// product key is an error at its file:line:key with exit status 1.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "core/light/photometry.h"
#include "job/config.h"
#include "job/plan.h"
#include "job/job_runner.h"
#include "job/job_scene.h"
#include "tests/apps/cli_runner.h"
#include "tests/optimizer/optimizer_test_scenes.h"
#include "tests/test_support.h"

namespace fs = std::filesystem;

namespace {

using ilp::test::OutputContains;
using ilp::test::read_file;
using ilp::test::run_ilp;
using ilp::test::RunResult;
using ilp::test::TempDir;

constexpr double kDeg = std::numbers::pi / 180.0;

// The synthetic product: I(C, gamma) = 1000 cos(gamma) (1 + sin(gamma) (0.6 cos C + 0.2 sin 2C)) cd,
// brighter toward C0 and lopsided between C90 and C270, so that a rotation shows; gamma 0..90 by
// 5 degrees, C 0..360 by 30; absolute photometry; a 0.16 x 0.04 m opening (length along C0).
double synthetic_cd(double c_deg, double gamma_deg) {
  const double g = gamma_deg * kDeg, c = c_deg * kDeg;
  return 1000.0 * std::cos(g) * (1.0 + std::sin(g) * (0.6 * std::cos(c) + 0.2 * std::sin(2.0 * c)));
}

std::string synthetic_ies() {
  std::ostringstream ies;
  ies << "IESNA:LM-63-2002\n[TEST] ilp placed-product test\n[TESTLAB] none\n[ISSUEDATE] 2026-12-02\n"
         "[MANUFAC] ilp tests\n[LUMINAIRE] synthetic asymmetric downlight\nTILT=NONE\n"
         "1 -1 1 19 13 1 2 0.04 0.16 0\n1 1 20\n";
  for (int g = 0; g <= 90; g += 5) ies << g << ' ';
  ies << '\n';
  for (int c = 0; c <= 360; c += 30) ies << c << ' ';
  ies << '\n';
  ies.precision(9);
  for (int c = 0; c <= 360; c += 30) {
    for (int g = 0; g <= 90; g += 5) ies << synthetic_cd(c, g) << ' ';
    ies << '\n';
  }
  return ies.str();
}

const std::string kIku = std::string(ILP_SOURCE_DIR) + "/data/photometry/erco_iku_downlight.ldt";

// The 4 x 4 x 2.5 m room of the search tests, every reflectance 0 (direct light only),
// and the work plane 0.8 m up: 6 x 6 points at 0.75 .. 3.25 m.
const char* kPlane =
    "grids:\n"
    "  - name: plane\n"
    "    over_surface: floor\n"
    "    height_m: 0.8\n"
    "    border_m: 0.5\n"
    "    spacing_m: 0.5\n";
constexpr double kPlaneZ_m = 0.8, kLuminaireZ_m = 2.4;

std::string products_yaml() {
  return "  products:\n"
         "    - {name: iku, photometry: " + kIku + "}\n"
         "    - {name: spot, photometry: spot.ies, dimming: [0.2, 1], rotations_deg: [30]}\n";
}

std::string solve_job(const TempDir& dir, const std::string& placed) {
  dir.write("room.obj", ilp::test::room_obj({}));
  dir.write("spot.ies", synthetic_ies());
  return dir.write("solve.yaml", "scene:\n  mesh: room.obj\n  max_patch_edge_m: 0.5\n  default_reflectance: 0\n"
                                 "luminaires:\n" + products_yaml() + "  placed:\n" + placed + kPlane +
                                     "solver:\n  rays_per_patch: 16\n");
}

struct CsvPoint {
  Eigen::Vector3d at;
  double direct_lux = 0.0, total_lux = 0.0;
};

std::vector<CsvPoint> read_points(const std::string& path) {
  std::vector<CsvPoint> out;
  const std::vector<std::string> rows = ilp::test::lines_of(read_file(path));
  for (std::size_t i = 1; i < rows.size(); ++i) {
    std::vector<std::string> f;
    std::istringstream in(rows[i]);
    for (std::string field; std::getline(in, field, ',');) f.push_back(field);
    EXPECT_EQ(f.size(), 10u) << rows[i];
    if (f.size() != 10u) continue;
    out.push_back({{std::stod(f[2]), std::stod(f[3]), std::stod(f[4])}, std::stod(f[5]), std::stod(f[6])});
  }
  return out;
}

// One luminaire for the closed form: its file, where it is, how it is turned, and
// its output as a share of the file's lumens.
struct Source {
  const ilp::Photometry* photometry;
  Eigen::Vector3d centre_m;
  double rotation_deg;
  double output;
};

// Horizontal illuminance at p from point sources: I(C, gamma) cos^3(gamma) / h^2, C the
// point's azimuth seen from the luminaire, less its rotation, gamma from the nadir.
double closed_form_lux(const std::vector<Source>& sources, const Eigen::Vector3d& p) {
  double lux = 0.0;
  for (const Source& s : sources) {
    const double dx = p.x() - s.centre_m.x(), dy = p.y() - s.centre_m.y(), h = s.centre_m.z() - p.z();
    const double gamma_deg = std::atan2(std::hypot(dx, dy), h) / kDeg;
    double c_deg = (dx == 0.0 && dy == 0.0) ? 0.0 : std::atan2(dy, dx) / kDeg - s.rotation_deg;
    c_deg = std::fmod(c_deg + 720.0, 360.0);
    const double cos_gamma = std::cos(gamma_deg * kDeg);
    lux += s.output * s.photometry->intensity_cd(c_deg, gamma_deg) * cos_gamma * cos_gamma * cos_gamma / (h * h);
  }
  return lux;
}

const CsvPoint* point_at(const std::vector<CsvPoint>& points, double x, double y) {
  for (const CsvPoint& q : points)
    if (std::abs(q.at.x() - x) < 1e-6 && std::abs(q.at.y() - y) < 1e-6) return &q;
  return nullptr;
}

// The tolerance of the closed form. Both openings (a 76 mm disc, 0.16 x 0.04 m) are at
// most 0.12 x the 1.6 m height: the direct light takes each as one point source at its
// centre (core/transport/direct_light.cpp), so the closed form is the code's model, not an
// approximation of it. What is left: grid.csv rounds lux to 0.01 (0.005), and the direct
// light reads the intensity from a table of the file's interpolant every 0.5 degree of C
// and 0.125 of gamma, bilinearly (core/light/luminaire_product.h). Measured on these 36
// points (18.7 to 199.3 lx): at most 0.00504 lx off, the rounding and < 1e-4 lx more.
// Leaving out the spot's rotation would put points up to 294 tolerances off.
double tolerance_lux(double lux) { return 0.006 + 2e-4 * lux; }

TEST(IlpPlacedProducts, SolveGivesTheClosedFormOfThePhotometricFiles) {
  TempDir dir;
  const std::string job = solve_job(dir, "    - {name: D1, product: iku, position_m: [1.25, 1.25, 2.4]}\n"
                                         "    - {name: S1, product: spot, position_m: [2.75, 2.75, 2.4], "
                                         "rotation_deg: 30, output: 0.5}\n");
  const ilp::Photometry iku = ilp::load_photometry(kIku), spot = ilp::load_photometry(dir.file("spot.ies"));
  // The synthetic file's own numbers: its nadir and a node off it (C 30, gamma 40) as written.
  ASSERT_NEAR(spot.intensity_cd(123.0, 0.0), 1000.0, 1e-6);
  ASSERT_NEAR(spot.intensity_cd(30.0, 40.0), synthetic_cd(30.0, 40.0), 1e-5);
  ASSERT_NEAR(spot.luminaire_flux_lm, 1000.0 * std::numbers::pi, 0.02 * 1000.0 * std::numbers::pi)
      << "the integral of I0 cos(gamma) is pi I0; the C terms integrate to 0";
  // output: the share of the file's lumens (iku at its rated output, the spot at half).
  const std::vector<Source> sources{{&iku, {1.25, 1.25, kLuminaireZ_m}, 0.0, 1.0},
                                    {&spot, {2.75, 2.75, kLuminaireZ_m}, 30.0, 0.5}};

  for (const char* method : {"sample", "exact"}) {
    SCOPED_TRACE(method);
    const std::string out = dir.file(std::string("out_") + method);
    const RunResult r = run_ilp(dir, {"solve", job, "--method", method, "--out", out, "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_TRUE(OutputContains(r.err, "luminaires.placed 'S1': product 'spot', rectangular 0.16 x 0.04 m, rotated 30 deg"));
    const std::vector<CsvPoint> points = read_points((fs::path(out) / "grid.csv").string());
    ASSERT_EQ(points.size(), 36u);
    for (const CsvPoint& q : points) {
      ASSERT_NEAR(q.at.z(), kPlaneZ_m, 1e-9);
      const double expected = closed_form_lux(sources, q.at);
      EXPECT_NEAR(q.direct_lux, expected, tolerance_lux(expected)) << q.at.transpose();
      EXPECT_EQ(q.total_lux, q.direct_lux) << "every reflectance 0: nothing but direct light";
    }
    // Straight under the spot its nadir value, 1000 cd x 0.5 / 1.6^2 = 195.3 lx, plus the downlight's light from aside.
    const CsvPoint* under_spot = point_at(points, 2.75, 2.75);
    ASSERT_NE(under_spot, nullptr);
    EXPECT_NEAR(under_spot->direct_lux - closed_form_lux({sources[0]}, under_spot->at), 500.0 / (1.6 * 1.6),
                tolerance_lux(under_spot->direct_lux));
    const CsvPoint* under_iku = point_at(points, 1.25, 1.25);
    ASSERT_NE(under_iku, nullptr);
    EXPECT_NEAR(under_iku->direct_lux - closed_form_lux({sources[1]}, under_iku->at),
                iku.intensity_cd(0.0, 0.0) / (1.6 * 1.6), tolerance_lux(under_iku->direct_lux));
    // Beside the spot, one grid step along +x and along +y: the rotation decides which is brighter
    // (C -30 and C 60 of the spot's web), which a square Lambertian panel would light alike.
    const CsvPoint *east = point_at(points, 3.25, 2.75), *north = point_at(points, 2.75, 3.25);
    ASSERT_NE(east, nullptr);
    ASSERT_NE(north, nullptr);
    EXPECT_GT(std::abs(east->direct_lux - north->direct_lux), 1.0);

    // The isolux plan draws each luminaire's real outline: the 76 mm disc and the turned 0.16 x 0.04 m rectangle.
    const std::string svg = read_file((fs::path(out) / "isolux_plane.svg").string());
    EXPECT_TRUE(OutputContains(svg, "D1 (iku): disc 0.076 m"));
    EXPECT_TRUE(OutputContains(svg, "S1 (spot): 0.16 x 0.04 m at 30 deg"));
  }
}

// The installation of `ilp solve` and the same layout as `ilp run`'s verification places
// it (prepare_job, the product's variant, verify_layout, which adds it by add_layout):
// the same luminaires in the same scene, and the same light at every grid point.
TEST(IlpPlacedProducts, SolveGivesWhatTheVerificationGivesForTheSameLayout) {
  TempDir dir;
  const std::string solve = solve_job(dir, "    - {name: S1, product: spot, position_m: [1.25, 1.25, 2.4], rotation_deg: 30}\n"
                                           "    - {name: S2, product: spot, position_m: [2.75, 2.75, 2.4], rotation_deg: 30, "
                                           "output: 0.5}\n");
  const std::string run = dir.write(
      "run.yaml", "scene:\n  mesh: room.obj\n  max_patch_edge_m: 0.5\n  default_reflectance: 0\n"
                  "luminaires:\n" + products_yaml() +
                      "  mounting_surface: ceiling\n  mount_offset_m: 0.1\n  candidate_spacing_m: 0.5\n  count: 2\n" +
                      kPlane + "goals:\n  - {grid: plane, average_lux: 100}\n"
                      "solver:\n  rays_per_patch: 16\nverification:\n  method: exact\n  rays_per_patch: 16\n");
  const ilp::JobConfig run_job = ilp::load_job_config(run);
  const std::vector<ilp::VariantPlan> variants = ilp::plan_job(run_job).variants;
  ASSERT_EQ(variants.size(), 2u);  // iku at 0, spot at 30
  const ilp::VariantPlan& v = variants[1];
  ASSERT_EQ(v.product.product, "spot");
  ASSERT_EQ(v.search.luminaire.rotation_deg, 30.0);
  const ilp::PreparedJob prepared = ilp::prepare_job(scene_spec(run_job), v);
  const double rated_lm = v.product.rated_flux_lm;
  const std::vector<ilp::PlacedLuminaire> layout{{{1.25, 1.25, kLuminaireZ_m}, rated_lm, 0.0, {}},
                                                 {{2.75, 2.75, kLuminaireZ_m}, 0.5 * rated_lm, 0.0, {}}};

  // The scenes: the solve job's placed luminaires, and the layout added to the run job's scene.
  const ilp::JobScene placed = ilp::load_job_scene(scene_spec(ilp::load_job_config(solve)));
  ilp::Scene laid = prepared.loaded.scene;
  ilp::add_layout(laid, v.search.luminaire, layout);
  ASSERT_EQ(placed.scene.luminaires.size(), 2u);
  ASSERT_EQ(laid.luminaires.size(), 2u);
  ASSERT_EQ(placed.scene.patches.size(), laid.patches.size());
  for (std::size_t j = 0; j < 2; ++j) {
    const ilp::SceneLuminaire &a = placed.scene.luminaires[j], &b = laid.luminaires[j];
    EXPECT_EQ(a.type.key(), b.type.key()) << j;
    EXPECT_EQ(a.placement.position_m, b.placement.position_m) << j;
    EXPECT_EQ(a.placement.rotation_deg, b.placement.rotation_deg) << j;
    EXPECT_EQ(a.flux_lm, b.flux_lm) << j;
  }
  for (std::size_t i = 0; i < laid.patches.size(); ++i) {
    EXPECT_EQ(placed.scene.patches[i].vertices_m, laid.patches[i].vertices_m) << i;
    EXPECT_EQ(placed.scene.patches[i].exitance_lm_per_m2, laid.patches[i].exitance_lm_per_m2) << i;
  }

  const ilp::Verification verified = ilp::verify_layout(prepared, layout);
  ASSERT_EQ(verified.method, "exact");
  const std::vector<ilp::ReceiverPoint>& goal_points = prepared.model.goal_points;
  ASSERT_EQ(goal_points.size(), 36u);
  for (const char* method : {"sample", "exact"}) {
    SCOPED_TRACE(method);
    const std::string out = dir.file(std::string("out_") + method);
    const RunResult r = run_ilp(dir, {"solve", solve, "--method", method, "--out", out, "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    const std::vector<CsvPoint> points = read_points((fs::path(out) / "grid.csv").string());
    ASSERT_EQ(points.size(), goal_points.size());
    for (std::size_t q = 0; q < goal_points.size(); ++q) {
      const Eigen::Vector3d at = goal_points[q].position_m;
      const CsvPoint* p = point_at(points, std::round(at.x() * 1e4) / 1e4, std::round(at.y() * 1e4) / 1e4);
      ASSERT_NE(p, nullptr) << at.transpose();
      // grid.csv holds 2 decimals.
      EXPECT_NEAR(p->direct_lux, verified.point_direct_lux[static_cast<Eigen::Index>(q)], 0.0051) << at.transpose();
      EXPECT_NEAR(p->total_lux, verified.point_lux[static_cast<Eigen::Index>(q)], 0.0051) << at.transpose();
    }
  }
}

// Bad placed-product keys stop `ilp solve` before any work: exit status 1, one line
// naming the file, line and key.
TEST(IlpPlacedProducts, BadProductKeysAreErrorsAtTheirLine) {
  struct Case {
    const char* entry;
    const char* says;
  };
  const Case cases[] = {
      {"    - {name: S1, product: lamp, position_m: [2, 2, 2.4]}\n",
       "luminaires.placed[0].product = lamp: unknown product (luminaires.products has iku, spot)"},
      {"    - {name: S1, product: spot, position_m: [2, 2, 2.4], output: 0.1}\n",
       "luminaires.placed[0].output = 0.1: must be within product 'spot''s dimming range [0.2, 1]"},
      {"    - {name: S1, product: spot, position_m: [2, 2, 2.4], output: 0.5, flux_lm: 1000}\n",
       "luminaires.placed[0].output = 0.5: not with flux_lm"},
      {"    - {name: S1, position_m: [2, 2, 2.4], flux_lm: 1000, output: 0.5}\n",
       "luminaires.placed[0].output = 0.5: needs product:"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.entry);
    TempDir dir;
    const std::string job = solve_job(dir, c.entry);
    const int line = 10;  // scene (4 lines), luminaires, products (3), placed, the entry
    ASSERT_NE(ilp::test::lines_of(read_file(job)).at(line - 1).find("S1"), std::string::npos);
    const RunResult r = run_ilp(dir, {"solve", job, "--out", dir.file("out")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(OutputContains(r.err, "error: " + job + ":" + std::to_string(line) + ":")) << r.err;
    EXPECT_TRUE(OutputContains(r.err, c.says)) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("out")));
  }
}

}  // namespace
