// Real products: photometric luminaires in the direct light and the radiosity solve
// (against the inverse-square law, the file's own interpolant and conservation of
// flux), and the variants a job's products give.
#include "core/light/luminaire_product.h"
#include "job/plan.h"
#include "job/products.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "core/transport/direct_light.h"
#include "core/exact/exact_solver.h"
#include "core/transport/ray_caster.h"
#include "core/scene/reference_scenes.h"
#include "job/config.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;
const std::string kData = std::string(ILP_SOURCE_DIR) + "/data/photometry/";
const std::string kShared = std::string(ILP_SOURCE_DIR) + "/../shared/photometry/";

std::shared_ptr<const Photometry> photometry(const std::string& path) {
  return std::make_shared<const Photometry>(load_photometry(path));
}

// The distribution integrated over the sphere: 1 lm per lm.
double sphere_integral(const IntensityDistribution& d) {
  constexpr int kGamma = 720, kC = 720;
  double sum = 0.0;
  for (int i = 0; i < kGamma; ++i) {
    const double g0 = std::numbers::pi * i / kGamma, g1 = std::numbers::pi * (i + 1) / kGamma;
    const double solid = (std::cos(g0) - std::cos(g1)) * 2.0 * std::numbers::pi / kC;
    for (int j = 0; j < kC; ++j) {
      const double g = 0.5 * (g0 + g1), c = 2.0 * std::numbers::pi * (j + 0.5) / kC;
      sum += d.cd_per_lm(V(std::sin(g) * std::cos(c), std::sin(g) * std::sin(c), -std::cos(g))) * solid;
    }
  }
  return sum;
}

TEST(PhotometricDistribution, EmitsOneLumenPerLumenAndFollowsTheFilesInterpolant) {
  for (const char* file : {"erco_iku_downlight.ldt", "linear_led_2112lm.ldt", "ledalite_direct_indirect.ies"}) {
    const auto p = photometry(kData + file);
    const PhotometricDistribution d(p);
    EXPECT_NEAR(sphere_integral(d), 1.0, 5e-3) << file;
    // The table against the file's own (cubic) interpolant, between its nodes: within 1 %
    // of the value where it is (a cut-off's steep fall is read over a table step: the
    // linear LED at 88.8 degrees, 0.7 %; the whole sphere against the peak is below).
    for (double c : {7.3, 45.0, 101.9, 270.4})
      for (double g : {1.1, 33.3, 61.7, 88.8, 121.0}) {
        const double exact = p->intensity_cd(c, g) / p->luminaire_flux_lm;
        const V dir = c_gamma_to_direction(c, g);
        EXPECT_NEAR(d.cd_per_lm(dir), exact, 1e-2 * exact + 1e-9) << file << " C " << c << " gamma " << g;
      }
  }
}

// Every photometric file of the repository and of ../shared: the table read anywhere
// (off its nodes and the file's) is within 0.2 % of the file's peak of its own
// interpolant (the worst, 0.14 %, is an IES web of irregular C planes whose cubic bends
// between them, as bilinear reading of any table of this kind does there), and
// it is small enough for a core's cache (4.2 MB at most; the EULUMDAT web of 18 x 5
// degrees the classroom uses, under 1 MB: the former 8 MB table's lookups missed the
// cache, 17 % of the classroom's run, 10 % now).
TEST(PhotometricDistribution, ItsTableIsSmallAndWithinAFifthOfAPercentOfTheInterpolantEverywhere) {
  std::vector<std::filesystem::path> files;
  for (const std::string& root : {kData, kShared})
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".ies" || ext == ".ldt" || ext == ".IES" || ext == ".LDT") files.push_back(entry.path());
    }
  ASSERT_GE(files.size(), 10u);
  for (const auto& file : files) {
    const auto p = photometry(file.string());
    const PhotometricDistribution d(p);
    const double bytes = 4.0 * (d.c_steps() + 1) * (d.gamma_steps() + 1);
    EXPECT_LE(bytes, 4.2e6) << file;
    // A file cut off at a gamma inside the sphere (0 beyond it) is blurred over a table
    // step there: the half degree either side of a cut is not judged.
    const double front = p->gamma_angles_deg.front(), back = p->gamma_angles_deg.back();
    auto near_cut = [&](double g) {
      return (front > 0.0 && std::abs(g - front) < 0.5) || (back < 180.0 && std::abs(g - back) < 0.5);
    };
    double peak = 0.0, worst = 0.0, worst_c = 0.0, worst_g = 0.0;
    for (double c = 0.37; c < 360.0; c += 1.31)
      for (double g = 0.11; g < 180.0; g += 0.29) {
        const double exact = p->intensity_cd(c, g) / p->luminaire_flux_lm;
        peak = std::max(peak, exact);
        const double error = std::abs(d.cd_per_lm(c_gamma_to_direction(c, g)) - exact);
        if (!near_cut(g) && error > worst) {
          worst = error;
          worst_c = c;
          worst_g = g;
        }
      }
    EXPECT_LE(worst, 2e-3 * peak) << file << " C " << worst_c << " gamma " << worst_g;
  }
  const PhotometricDistribution classroom(photometry(kShared + "lidrs/example.ldt"));
  EXPECT_LT(4.0 * (classroom.c_steps() + 1) * (classroom.gamma_steps() + 1), 1e6);
}

TEST(PhotometricLuminaire, AnIesPointSourceFollowsTheInverseSquareLawUnderAndOffAxis) {
  // medium_scatter.ies: an asymmetric wash light, 0.103 x 0.059 m; 3 m above a floor it
  // is one point source: E = I(C, gamma) cos^3(gamma) / h^2.
  const auto p = photometry(kShared + "renderpipeline/medium_scatter.ies");
  Scene scene = reference::make_quad_scene({{"floor", V(-20, -20, 0), V(20, -20, 0), V(20, 20, 0), V(-20, 20, 0)}}, 0.0);
  const double h = 3.0, flux = 1000.0;
  add_luminaire(scene, "wash", photometric_luminaire_type("wash", p), {V(0, 0, h), 0.0}, flux);
  const RayCaster caster(scene);
  std::vector<ReceiverPoint> points;
  for (const V& x : {V(0, 0, 0), V(1, 0, 0), V(0, 2, 0), V(-1.5, 0.5, 0), V(2, -2, 0)}) points.push_back({x, V::UnitZ()});
  const Eigen::VectorXd lux =
      flux * compute_luminaire_light_at_points(scene, caster, points, luminaire_surfaces(scene), {}).lux_per_lm.col(0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const V d = points[k].position_m - V(0, 0, h);
    const Eigen::Vector2d cg = direction_to_c_gamma_deg(d);
    const double cos_gamma = h / d.norm();
    const double expected = flux / p->luminaire_flux_lm * p->intensity_cd(cg[0], cg[1]) * std::pow(cos_gamma, 3) / (h * h);
    EXPECT_NEAR(lux[static_cast<Eigen::Index>(k)], expected, 5e-3 * expected) << points[k].position_m.transpose();
  }
}

TEST(PhotometricLuminaire, RotatedNinetyDegreesItsPatternTurnsWithIt) {
  const auto p = photometry(kShared + "renderpipeline/medium_scatter.ies");
  const LuminaireType type = photometric_luminaire_type("wash", p);
  auto lux_at = [&](double rotation_deg, const V& x) {
    Scene scene = reference::make_quad_scene({{"floor", V(-20, -20, 0), V(20, -20, 0), V(20, 20, 0), V(-20, 20, 0)}}, 0.0);
    add_luminaire(scene, "wash", type, {V(0, 0, 3), rotation_deg}, 1.0);
    const RayCaster caster(scene);
    const std::vector<ReceiverPoint> points{{x, V::UnitZ()}};
    return compute_luminaire_light_at_points(scene, caster, points, luminaire_surfaces(scene), {}).lux_per_lm(0, 0);
  };
  for (const V& x : {V(1.5, 0.3, 0), V(-0.7, 1.9, 0), V(0.2, -2.5, 0)}) {
    const V turned(-x.y(), x.x(), 0);
    EXPECT_NEAR(lux_at(90.0, turned), lux_at(0.0, x), 1e-6 * lux_at(0.0, x));
  }
  EXPECT_GT(std::abs(lux_at(0.0, V(1.5, 0, 0)) - lux_at(0.0, V(-1.5, 0, 0))), 0.1 * lux_at(0.0, V(1.5, 0, 0)));
}

TEST(PhotometricLuminaire, ItsDirectLightLandsWhollyInAClosedRoomAndTheFurnaceBalances) {
  // A direct/indirect pendant (69 % up) in a closed 4 x 3 x 3 m grey box: every lumen
  // lands on some wall (sum of A E_direct = flux), and the exact solve's absorbed plus
  // lost flux equals the emitted flux whatever the distribution.
  for (const char* file : {"ledalite_direct_indirect.ies", "linear_led_2112lm.ldt"}) {
    Scene scene = reference::make_closed_box(V(0, 0, 0), V(4, 3, 3), 0.6, 0.25);
    const double flux = 5000.0;
    add_luminaire(scene, "pendant", photometric_luminaire_type("pendant", photometry(kData + file)), {V(2, 1.5, 2.2), 30.0},
                  flux);
    const RayCaster caster(scene);
    std::vector<int> walls;
    for (std::size_t i = 0; i < scene.patches.size(); ++i)
      if (!scene.surfaces[scene.patches[i].surface].is_luminaire()) walls.push_back(static_cast<int>(i));
    DirectLightOptions options;
    options.receiver_points = 16;
    const LuminaireLight light = compute_luminaire_light(scene, caster, walls, luminaire_surfaces(scene), options);
    double landed = 0.0;
    for (std::size_t r = 0; r < walls.size(); ++r)
      landed += scene.patches[static_cast<std::size_t>(walls[r])].area_m2 * light.lux_per_lm(static_cast<Eigen::Index>(r), 0);
    EXPECT_NEAR(landed, 1.0, 0.01) << file;

    ExactSolveOptions exact;
    exact.form_factors.rays_per_patch = 256;
    const ExactSolution solution = solve_exact(scene, exact);
    const ExactSolveSummary& s = solution.summary;
    EXPECT_NEAR(s.emitted_lm, flux, 1e-6 * flux);
    EXPECT_NEAR(s.absorbed_lm + s.lost_lm, s.emitted_lm, 0.015 * s.emitted_lm) << file;
  }
}

// A product of a name and a photometric file, every other setting at its default.
ProductSetting product(const std::string& name, const std::string& path) {
  ProductSetting p;
  p.name = name;
  p.photometry_path = path;
  return p;
}

// Where only the light is read (the patches the operator's rows hit), a photometric
// opening's form factors are left out: the light is bit for bit the same, the form
// factors 0; a Lambertian opening's light is its form factor, so it keeps them.
TEST(PhotometricLuminaire, LeavingOutTheFormFactorsKeepsTheLight) {
  for (bool lambertian : {false, true}) {
    Scene scene = reference::make_closed_box(V(0, 0, 0), V(4, 3, 3), 0.6, 0.5);
    const LuminaireType type = lambertian ? LuminaireType::square_lambertian(0.6)
                                          : photometric_luminaire_type("pendant", photometry(kData + "linear_led_2112lm.ldt"));
    add_luminaire(scene, "lamp", type, {V(2, 1.5, 2.2), 30.0}, 2000.0);
    const RayCaster caster(scene);
    std::vector<int> walls;
    for (std::size_t i = 0; i < scene.patches.size(); ++i)
      if (!scene.surfaces[scene.patches[i].surface].is_luminaire()) walls.push_back(static_cast<int>(i));
    DirectLightOptions with = cheap_direct_light_options(), without = with;
    without.form_factors = false;
    const LuminaireLight a = compute_luminaire_light(scene, caster, walls, luminaire_surfaces(scene), with);
    const LuminaireLight b = compute_luminaire_light(scene, caster, walls, luminaire_surfaces(scene), without);
    EXPECT_EQ(a.lux_per_lm, b.lux_per_lm) << (lambertian ? "Lambertian" : "photometric");
    ASSERT_GT(a.form_factor.sum(), 0.0);
    if (lambertian) EXPECT_EQ(b.form_factor, a.form_factor);
    else EXPECT_EQ(b.form_factor.sum(), 0.0);
  }
}

TEST(ProductVariants, RotationsWattsAndFluxComeFromTheFileUnlessGiven) {
  ProductSetting iku = product("iku", kData + "erco_iku_downlight.ldt");
  ProductSetting linear = product("linear", kData + "linear_led_2112lm.ldt");
  linear.flux_lm = 4222.4;  // twice the file's: the watts scale with it
  linear.dim_min = 0.3;
  const std::vector<ProductVariant> v = product_variants({iku, linear});
  ASSERT_EQ(v.size(), 3u);  // the round downlight once, the linear one at 0 and 90 degrees
  EXPECT_EQ(v[0].product, "iku");
  EXPECT_NEAR(v[0].rated_flux_lm, 611.8, 0.1);
  EXPECT_NEAR(v[0].power_w, 6.9, 1e-9);
  EXPECT_EQ(v[0].type.shape, OutlineShape::disc);
  EXPECT_EQ(v[1].rotation_deg, 0.0);
  EXPECT_EQ(v[2].rotation_deg, 90.0);
  EXPECT_NEAR(v[1].rated_flux_lm, 4222.4, 1e-9);
  EXPECT_NEAR(v[1].power_w, 2.0 * 22.3, 0.05);
  // Its 1.201 m length runs along C90 (local y): photometric_opening, OpeningAxis.* tests.
  EXPECT_NEAR(v[1].type.length_m, 0.038, 1e-9);
  EXPECT_NEAR(v[1].type.width_m, 1.201, 1e-9);

  JobConfig job;
  job.search.emplace();
  job.search->mounting_surface = "ceiling";
  job.products = {iku, linear};
  job.goals.push_back(GoalSetting{});
  const std::vector<VariantPlan> plans = plan_job(job).variants;
  ASSERT_EQ(plans.size(), 3u);
  const SearchLuminaire& l = plans[2].search.luminaire;
  EXPECT_TRUE(l.uniform_output);
  EXPECT_EQ(l.rotation_deg, 90.0);
  EXPECT_EQ(plans[2].model.candidates.rotation_deg, 90.0);
  EXPECT_NEAR(l.flux_min_lm, 0.3 * 4222.4, 1e-9);
  EXPECT_NEAR(l.flux_max_lm, 4222.4, 1e-9);
  EXPECT_NEAR(l.flux_max_lm / l.efficacy_lm_per_w, v[2].power_w, 1e-9);
  EXPECT_EQ(l.product, "linear");
}

TEST(ProductVariants, ThePlainPanelIsAProductWhoseLuminairesEachTakeTheirOwnFlux) {
  JobConfig job;
  job.search.emplace();
  job.search->mounting_surface = "ceiling";
  job.search->flux_min_lm = 1000.0;
  job.search->flux_max_lm = 5000.0;
  job.search->efficacy_lm_per_w = 125.0;
  job.luminaire_size_m = 0.6;
  job.maintenance_factor = 0.8;
  GoalSetting goal;
  goal.name = "desk";
  goal.surfaces = {"desk"};
  goal.target = 500.0;
  job.goals.push_back(goal);
  const std::vector<VariantPlan> plans = plan_job(job).variants;
  ASSERT_EQ(plans.size(), 1u);
  EXPECT_FALSE(plans[0].listed);
  EXPECT_EQ(plans[0].product.product, "square Lambertian panel 0.6 m");
  EXPECT_NEAR(plans[0].product.power_w, 40.0, 1e-12);
  const SearchLuminaire& l = plans[0].search.luminaire;
  EXPECT_TRUE(l.uniform_output) << "dimmed together unless output: individual";
  EXPECT_EQ(l.product, "");
  EXPECT_EQ(l.flux_min_lm, 1000.0);
  EXPECT_EQ(l.flux_max_lm, 5000.0);
  EXPECT_EQ(l.efficacy_lm_per_w, 125.0);
  ASSERT_EQ(plans[0].search.goals.size(), 1u);
  EXPECT_DOUBLE_EQ(plans[0].search.goals[0].target, 625.0) << "searched at the initial target, 500 / 0.8";
}

TEST(ProductVariants, AProductsMaintenanceFactorAndMountOffsetReplaceTheJobsOnlyWhenGiven) {
  ProductSetting clean = product("clean", kData + "erco_iku_downlight.ldt");
  ProductSetting dusty = clean;
  dusty.name = "dusty";
  dusty.maintenance_factor = 0.67;
  dusty.mount_offset_m = 0.6;
  const std::vector<ProductVariant> v = product_variants({clean, dusty});
  ASSERT_EQ(v.size(), 2u);
  JobConfig job;
  job.search.emplace();
  job.search->mounting_surface = "ceiling";
  job.products = {clean, dusty};
  GoalSetting goal;
  goal.name = "desk";
  goal.surfaces = {"desk"};
  goal.target = 500.0;
  job.goals.push_back(goal);
  job.maintenance_factor = 0.8;
  job.search->mount_offset_m = 0.05;
  const std::vector<VariantPlan> plans = plan_job(job).variants;
  ASSERT_EQ(plans.size(), 2u);
  EXPECT_EQ(plans[0].maintenance_factor, 0.8) << "no factor of its own: the job's";
  EXPECT_EQ(plans[1].maintenance_factor, 0.67) << "the product's own";
  EXPECT_DOUBLE_EQ(plans[1].search.goals[0].target, 500.0 / 0.67) << "its targets follow its own factor";
  EXPECT_EQ(plans[0].model.candidates.mount_offset_m, 0.05);
  EXPECT_EQ(plans[1].model.candidates.mount_offset_m, 0.6) << "hung on its own suspension";
}

TEST(ProductVariants, AFileThatCannotBeReadNamesTheConfigAndTheFile) {
  const std::string bad = ::testing::TempDir() + "/ilp_truncated.ies";
  std::ofstream(bad) << "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 1 2 0.5 0.5 0\n";
  ProductSetting p = product("broken", bad);
  p.photometry_loc = {"job.yaml", 12, 5};
  try {
    product_variants({p});
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("job.yaml:12:5"), std::string::npos) << what;
    EXPECT_NE(what.find(bad), std::string::npos) << what;
  }
}

// The cost model's count of point sources per receiver and luminaire (mean_point_sources):
// one receiver and one luminaire give that pair's count, ceil(side / (0.12 d)) along and
// across the opening (at least 1, at most 24 a side); nearer receivers evaluate more, and
// a Lambertian panel none (its closed form).
TEST(MeanPointSources, CountsThePointSourcesOfAReceiverNearALongOpening) {
  Scene scene = reference::make_closed_box(V::Zero(), V(4.0, 3.0, 2.5), 0.5, 0.25);
  const LuminaireType type = photometric_luminaire_type("linear", photometry(kData + "linear_led_2112lm.ldt"));
  ASSERT_GT(std::max(type.length_m, type.width_m), 1.0);
  const int linear = add_luminaire(scene, "linear", type, {V(2.0, 1.5, 2.2), 0.0}, 2000.0);
  const int panel = add_square_luminaire(scene, "panel", V(1.0, 1.0, 2.45), 0.6, 1000.0);
  const std::vector<int> floor = reference::patches_of(scene, "floor");
  ASSERT_FALSE(floor.empty());
  auto expected = [&](int patch) {
    const Patch& p = scene.patches[static_cast<std::size_t>(patch)];
    const double d = ((p.vertices_m[0] + p.vertices_m[1] + p.vertices_m[2]) / 3.0 - V(2.0, 1.5, 2.2)).norm();
    auto along = [&](double side) { return std::clamp(std::ceil(side / (0.12 * d)), 1.0, 24.0); };
    return along(type.length_m) * along(type.width_m);
  };
  for (int patch : {floor.front(), floor[floor.size() / 2]}) {
    const std::vector<int> one = {patch}, lum = {linear};
    EXPECT_DOUBLE_EQ(mean_point_sources(scene, one, lum), expected(patch)) << "patch " << patch;
  }
  EXPECT_EQ(mean_point_sources(scene, floor, std::vector<int>{panel}), 0.0);
  EXPECT_EQ(mean_point_sources(scene, std::vector<int>{}, std::vector<int>{linear}), 0.0);
  // The ceiling, 0.3 m above the opening, is nearer than the floor: more sources a pair.
  const std::vector<int> ceiling = reference::patches_of(scene, "ceiling");
  const double near = mean_point_sources(scene, ceiling, std::vector<int>{linear});
  const double far = mean_point_sources(scene, floor, std::vector<int>{linear});
  EXPECT_GT(near, 1.5 * far);
  EXPECT_GE(far, 1.0);
  // Both luminaires: the panel's pairs count none, so the mean falls between.
  const double both = mean_point_sources(scene, floor, std::vector<int>{linear, panel});
  EXPECT_GT(both, 0.3 * far);
  EXPECT_LT(both, 0.7 * far);
}

}  // namespace
}  // namespace ilp
