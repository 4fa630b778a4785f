// The exact reference solver against conservation laws and closed forms.
#include "core/exact/radiosity.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "core/base/error.h"
#include "core/exact/exact_solver.h"
#include "job/config.h"
#include "job/plan.h"
#include "job/job_scene.h"
#include "core/transport/direct_light.h"
#include "core/transport/ray_caster.h"
#include "core/scene/reference_scenes.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;

ExactSolveOptions exact_options(int rays) {
  ExactSolveOptions options;
  options.form_factors.rays_per_patch = rays;
  options.radiosity.relative_residual = 1e-10;
  return options;
}

// Furnace: a closed box with uniform reflectance and uniform emission has
// B = E / (1 - rho) on every patch, whatever the form factors, because every row sums to 1.
TEST(Radiosity, FurnaceClosedCubeGivesEOverOneMinusRho) {
  for (double rho : {0.5, 0.9, 0.99}) {
    Scene scene = reference::make_closed_box(V::Zero(), V(1, 1, 1), rho, 0.25);
    const double E = 100.0;
    for (std::size_t s = 0; s < scene.surfaces.size(); ++s) set_surface_exitance(scene, static_cast<int>(s), E);
    const ExactSolution solution = solve_exact(scene, exact_options(128));
    for (Eigen::Index i = 0; i < solution.radiosity.radiosity_lm_per_m2.rows(); ++i)
      ASSERT_NEAR(solution.radiosity.radiosity_lm_per_m2(i, 0), E / (1 - rho), 1e-3 * E / (1 - rho))
          << "rho " << rho << ", patch " << i;
    EXPECT_LE(solution.radiosity.relative_residual, 1e-10);
  }
}

// In any closed scene of uniform reflectance, all emitted flux is eventually absorbed:
// sum A_i B_i = sum A_i E_i / (1 - rho). Emission here is far from uniform.
TEST(Radiosity, ClosedSceneConservesEnergyWithLocalisedEmission) {
  const double rho = 0.7;
  Scene scene = reference::make_closed_box(V::Zero(), V(4, 3, 2.5), rho, 0.5);
  set_surface_exitance(scene, scene.find_surface("wall_x0"), 500.0);
  const ExactSolution solution = solve_exact(scene, exact_options(1024));
  double emitted = 0.0, leaving = 0.0;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    emitted += scene.patches[i].area_m2 * scene.patches[i].exitance_lm_per_m2;
    leaving += scene.patches[i].area_m2 * solution.radiosity.radiosity_lm_per_m2(static_cast<Eigen::Index>(i), 0);
  }
  // Reciprocity holds only to Monte Carlo noise; 1024 rays per patch keep it under 1 %.
  EXPECT_NEAR(leaving, emitted / (1 - rho), 0.01 * emitted / (1 - rho));
  // The solver's own account agrees: a closed box loses nothing and absorbs it all.
  const ExactSolveSummary& s = solution.summary;
  EXPECT_NEAR(s.emitted_lm, emitted, 1e-9 * emitted);
  EXPECT_EQ(s.lost_lm, 0.0);
  EXPECT_NEAR(s.absorbed_lm, emitted, 0.01 * emitted);
}

TEST(Radiosity, AllReflectancesZeroGiveExactlyTheDirectLight) {
  Scene scene = reference::make_closed_box(V::Zero(), V(4, 3, 3), 0.0, 0.5);
  add_square_luminaire(scene, "lamp", V(2, 1.5, 2.9), 0.6, 3000.0);
  set_surface_exitance(scene, scene.find_surface("wall_y0"), 50.0);
  const ExactSolution solution = solve_exact(scene, exact_options(64));
  const RadiositySolution& r = solution.radiosity;
  for (Eigen::Index i = 0; i < r.total_lux.size(); ++i) {
    ASSERT_EQ(r.radiosity_lm_per_m2(i, 0), scene.patches[i].exitance_lm_per_m2) << "patch " << i;
    ASSERT_EQ(r.total_lux[i], r.direct_lux[i]) << "patch " << i;
  }
  EXPECT_GT(r.direct_lux.maxCoeff(), 0.0);
}

// Under a square Lambertian luminaire of exitance M at height h, a small floor patch
// receives E = M * F(point -> square), the closed form for a parallel rectangle.
TEST(Radiosity, IlluminanceUnderALuminaireMatchesClosedForm) {
  Scene scene = reference::make_quad_scene({{"floor", V(-0.02, -0.02, 0), V(0.02, -0.02, 0), V(0.02, 0.02, 0),
                                        V(-0.02, 0.02, 0)}},
                                      0.0);
  const double size = 0.6, flux = 3600.0, height = 2.0;
  add_square_luminaire(scene, "lamp", V(0, 0, height), size, flux);
  ExactSolveOptions options = exact_options(16);
  options.direct_light.receiver_points = 64;
  const ExactSolution solution = solve_exact(scene, options);
  const double exitance = flux / (size * size);
  const double expected = exitance * 4.0 * reference::point_to_corner_rectangle_form_factor(size / 2, size / 2, height);
  for (int i : reference::patches_of(scene, "floor"))
    EXPECT_NEAR(solution.radiosity.total_lux[i], expected, 2e-3 * expected) << "patch " << i;
  // Far-field check of the units: E ~ I cos / d^2 with I = flux / pi for a Lambertian panel.
  EXPECT_NEAR(expected, flux / std::numbers::pi / (height * height), 0.03 * expected);
}

// Flux conservation on the shipped office with its furniture and partition: with
// nothing reflecting, every lumen the four panels emit lands on some surface of the
// closed room, so the area-weighted direct illuminance adds up to their flux.
TEST(Radiosity, OfficeSurfacesReceiveAllLuminaireFluxWhenNothingReflects) {
  const JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office_fixed.yaml");
  Scene scene = load_job_scene(scene_spec(job)).scene;
  double flux_lm = 0.0;
  for (Patch& p : scene.patches) {
    p.reflectance.setZero();
    flux_lm += p.area_m2 * p.exitance_lm_per_m2;
  }
  ASSERT_NEAR(flux_lm, 4 * 3400.0, 1e-6);
  ExactSolveOptions options = exact_options(16);  // the gathered rows carry no light here
  const ExactSolution solution = solve_exact(scene, options);
  double received_lm = 0.0;
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    received_lm += scene.patches[i].area_m2 * solution.radiosity.direct_lux[static_cast<Eigen::Index>(i)];
  // The closed-form factor is exact; 8 points per patch and 8 shadow rays leave ~0.1 %.
  EXPECT_NEAR(received_lm, flux_lm, 0.005 * flux_lm);
}

// The same office with its real reflectances: what the surfaces absorb, plus what
// strikes the back of one-sided patches (the luminaires' upper sides) and what
// escapes, adds up to the emitted flux. Reciprocity holds only to ray noise: measured
// 0.1 % off at 128 rays per patch, allowed 0.5 %.
TEST(Radiosity, OfficeAbsorbsTheFluxItsLuminairesEmit) {
  const JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office_fixed.yaml");
  const Scene scene = load_job_scene(scene_spec(job)).scene;
  const RayCaster caster(scene);
  FormFactorOptions ff;
  ff.rays_per_patch = 128;
  FormFactorRows rows = compute_form_factor_rows(scene, caster, scene.all_patches(), ff);
  replace_emitter_columns(scene, caster, DirectLightOptions{}, rows);
  const RadiositySolution solution = solve_radiosity(scene, rows.F, RadiosityOptions{});
  double emitted = 0.0, absorbed = 0.0, lost = 0.0;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    const auto row = static_cast<Eigen::Index>(i);
    emitted += p.area_m2 * p.exitance_lm_per_m2;
    absorbed += p.area_m2 * (1.0 - p.reflectance[0]) * solution.illuminance_lux(row, 0);
    // A luminaire's own light is carried by its closed-form column, not its gathered row.
    if (!scene.surfaces[p.surface].is_luminaire())
      lost += p.area_m2 * solution.radiosity_lm_per_m2(row, 0) * (rows.back_hit_fraction[row] + rows.escaped_fraction[row]);
  }
  EXPECT_GT(lost, 0.0);
  EXPECT_NEAR(absorbed + lost, emitted, 0.005 * emitted) << "absorbed " << absorbed << " lm, lost " << lost << " lm";
}

TEST(Radiosity, ResidualReportedIsTheResidualOfTheAnswer) {
  Scene scene = reference::make_closed_box(V::Zero(), V(2, 2, 2), 0.8, 0.5);
  set_surface_exitance(scene, scene.find_surface("ceiling"), 1000.0);
  const RayCaster caster(scene);
  FormFactorOptions ff;
  ff.rays_per_patch = 128;
  const FormFactorRows rows = compute_form_factor_rows(scene, caster, scene.all_patches(), ff);
  RadiosityOptions options;
  options.relative_residual = 1e-9;
  const RadiositySolution solution = solve_radiosity(scene, rows.F, options);
  Eigen::VectorXd E(scene.patches.size()), rho(scene.patches.size());
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    E[static_cast<Eigen::Index>(i)] = scene.patches[i].exitance_lm_per_m2;
    rho[static_cast<Eigen::Index>(i)] = scene.patches[i].reflectance[0];
  }
  const Eigen::VectorXd B = solution.radiosity_lm_per_m2.col(0);
  const double residual = (E - (B - rho.cwiseProduct(rows.F * B))).norm() / E.norm();
  EXPECT_LE(residual, 1e-9);
  EXPECT_NEAR(residual, solution.relative_residual, 1e-12);
  EXPECT_TRUE((solution.illuminance_lux.col(0) - rows.F * B).isZero(1e-9));
}

TEST(Radiosity, ExactSolveIsBitIdenticalWithOneAndTwoThreads) {
  Scene scene = reference::make_closed_box(V::Zero(), V(3, 2, 2.5), 0.6, 0.4);
  add_square_luminaire(scene, "lamp", V(1.5, 1, 2.4), 0.6, 3000.0);
  auto solve_with = [&](int threads) {
    ExactSolveOptions options = exact_options(64);
    options.form_factors.threads = options.direct_light.threads = threads;
    return solve_exact(scene, options).radiosity.total_lux;
  };
  const Eigen::VectorXd one = solve_with(1), two = solve_with(2);
  ASSERT_EQ(one.size(), two.size());
  for (Eigen::Index i = 0; i < one.size(); ++i) ASSERT_EQ(one[i], two[i]) << "patch " << i;
}

// Gauss-Seidel against an independent dense LU solve of (I - R F) B = E, on an open,
// coloured scene with a luminaire and a surface emitter.
TEST(Radiosity, GaussSeidelAgreesWithDenseLU) {
  Scene scene = reference::make_quad_scene(
      {{"floor", V(0, 0, 0), V(2, 0, 0), V(2, 2, 0), V(0, 2, 0), V(0.3, 0.5, 0.7)},
       {"wall", V(0, 0, 0), V(0, 2, 0), V(0, 2, 2), V(0, 0, 2), V(0.8, 0.6, 0.4)},
       {"ceiling", V(0, 0, 2), V(0, 2, 2), V(2, 2, 2), V(2, 0, 2), V(0.9, 0.9, 0.9)}},
      0.5);
  scene.channels = 3;
  add_square_luminaire(scene, "lamp", V(1, 1, 1.9), 0.5, 2000.0);
  set_surface_exitance(scene, scene.find_surface("wall"), 30.0);
  const RayCaster caster(scene);
  FormFactorOptions ff;
  ff.rays_per_patch = 256;
  FormFactorRows rows = compute_form_factor_rows(scene, caster, scene.all_patches(), ff);
  replace_emitter_columns(scene, caster, DirectLightOptions{}, rows);
  RadiosityOptions options;
  options.relative_residual = 1e-12;
  const RadiositySolution solution = solve_radiosity(scene, rows.F, options);

  const Eigen::MatrixXd F(rows.F);
  const Eigen::Index n = F.rows();
  Eigen::VectorXd E(n);
  for (Eigen::Index i = 0; i < n; ++i) E[i] = scene.patches[i].exitance_lm_per_m2;
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd rho(n);
    for (Eigen::Index i = 0; i < n; ++i) rho[i] = scene.patches[i].reflectance[c];
    const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n) - rho.asDiagonal() * F;
    const Eigen::VectorXd B = A.partialPivLu().solve(E);
    EXPECT_LT((solution.radiosity_lm_per_m2.col(c) - B).norm(), 1e-10 * B.norm()) << "channel " << c;
    EXPECT_LT((solution.illuminance_lux.col(c) - F * B).norm(), 1e-10 * (F * B).norm()) << "channel " << c;
  }
}

TEST(Radiosity, NonConvergenceIsANumericalError) {
  Scene scene = reference::make_closed_box(V::Zero(), V(1, 1, 1), 0.99, 0.5);
  set_surface_exitance(scene, scene.find_surface("floor"), 100.0);
  ExactSolveOptions options = exact_options(64);
  options.radiosity.max_iterations = 3;
  EXPECT_THROW(solve_exact(scene, options), NumericalError);
}

TEST(Radiosity, ColouredReflectanceSolvesEachChannel) {
  Scene scene = reference::make_closed_box(V::Zero(), V(1, 1, 1), 0.5, 0.5);
  for (Patch& p : scene.patches) p.reflectance = V(0.2, 0.5, 0.8);
  scene.channels = 3;
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) set_surface_exitance(scene, static_cast<int>(s), 10.0);
  const ExactSolution solution = solve_exact(scene, exact_options(64));
  for (int c = 0; c < 3; ++c) {
    const double rho = V(0.2, 0.5, 0.8)[c];
    EXPECT_NEAR(solution.radiosity.radiosity_lm_per_m2(0, c), 10.0 / (1 - rho), 1e-6);
  }
  // Photometric value: luminance-weighted channels (all channels carry white light).
  const Eigen::RowVectorXd h = solution.radiosity.illuminance_lux.row(0);
  EXPECT_NEAR(solution.radiosity.total_lux[0], h.dot(kLuminanceWeights.transpose()), 1e-9);
}

}  // namespace
}  // namespace ilp

namespace ilp {
namespace {

// Verifying a layout needs precise direct light only at its goal patches; elsewhere
// it is read through reflections. The goal patches' direct light is unchanged bit for
// bit, and their total moves by the noise of the cheaper estimate elsewhere.
TEST(Radiosity, PreciseDirectLightOnlyWhereAsked) {
  const JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office_fixed.yaml");
  const Scene scene = load_job_scene(scene_spec(job)).scene;
  ExactSolveOptions full;
  full.form_factors.rays_per_patch = 64;
  ExactSolveOptions split = full;
  split.precise_patches = scene.patches_of({"desk_1", "desk_2"});
  const ExactSolution a = solve_exact(scene, full), b = solve_exact(scene, split);
  double sum_a = 0.0, sum_b = 0.0, area = 0.0;
  for (int p : *split.precise_patches) {
    const auto i = static_cast<Eigen::Index>(p);
    ASSERT_EQ(a.radiosity.direct_lux[i], b.radiosity.direct_lux[i]) << "patch " << p;
    sum_a += scene.patches[static_cast<std::size_t>(p)].area_m2 * a.radiosity.total_lux[i];
    sum_b += scene.patches[static_cast<std::size_t>(p)].area_m2 * b.radiosity.total_lux[i];
    area += scene.patches[static_cast<std::size_t>(p)].area_m2;
  }
  EXPECT_NEAR(sum_b / sum_a, 1.0, 0.01) << "the desks' average";
  // Elsewhere the estimate is the cheap one: not the same numbers.
  const int wall = scene.patches_of({"walls"}).front();
  EXPECT_NE(a.radiosity.direct_lux[wall], b.radiosity.direct_lux[wall]);
  // Every patch precise is the default.
  ExactSolveOptions all = full;
  all.precise_patches = scene.all_patches();
  const ExactSolution c = solve_exact(scene, all);
  EXPECT_TRUE((c.radiosity.total_lux.array() == a.radiosity.total_lux.array()).all());
}

// An empty list of precise patches (a job whose goals are all on grids) makes every
// patch cheap; the old code took an empty list for "every patch precise".
TEST(Radiosity, NoPrecisePatchesMakesEveryPatchCheap) {
  const JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office_fixed.yaml");
  const Scene scene = load_job_scene(scene_spec(job)).scene;
  ExactSolveOptions cheap_everywhere;
  cheap_everywhere.form_factors.rays_per_patch = 32;
  cheap_everywhere.precise_patches = std::vector<int>{};
  ExactSolveOptions one_wall_precise = cheap_everywhere;
  const int wall = scene.patches_of({"walls"}).front();
  one_wall_precise.precise_patches = std::vector<int>{wall};
  const ExactSolution a = solve_exact(scene, cheap_everywhere), b = solve_exact(scene, one_wall_precise);
  EXPECT_NE(a.radiosity.direct_lux[wall], b.radiosity.direct_lux[wall]);
  const int other = scene.patches_of({"walls"}).back();
  EXPECT_EQ(a.radiosity.direct_lux[other], b.radiosity.direct_lux[other]);
}

// Rows of patches that are not precise cast other_rays_per_patch rays: the rays
// counted drop to that, the precise rows keep every ray (bit for bit the rows of a
// full solve), and the desks' average moves only by the noise of the indirect light.
TEST(Radiosity, FewerRaysWhereOnlyReflectionsAreRead) {
  const JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office_fixed.yaml");
  const Scene scene = load_job_scene(scene_spec(job)).scene;
  ExactSolveOptions full;
  full.form_factors.rays_per_patch = 256;
  const std::vector<int> desks = scene.patches_of({"desk_1", "desk_2"});
  full.precise_patches = desks;
  ExactSolveOptions fewer = full;
  fewer.other_rays_per_patch = 32;
  const ExactSolution a = solve_exact(scene, full), b = solve_exact(scene, fewer);
  const std::uint64_t n = scene.patches.size(), d = desks.size();
  EXPECT_EQ(a.summary.rays_cast, n * 256);
  EXPECT_EQ(b.summary.rays_cast, d * 256 + (n - d) * 32);
  double sum_a = 0.0, sum_b = 0.0;
  for (int p : desks) {
    const auto i = static_cast<Eigen::Index>(p);
    EXPECT_EQ(a.radiosity.direct_lux[i], b.radiosity.direct_lux[i]) << "patch " << p;
    sum_a += scene.patches[static_cast<std::size_t>(p)].area_m2 * a.radiosity.total_lux[i];
    sum_b += scene.patches[static_cast<std::size_t>(p)].area_m2 * b.radiosity.total_lux[i];
  }
  EXPECT_NEAR(sum_b / sum_a, 1.0, 0.005) << "the desks' average";
  EXPECT_NE(sum_b, sum_a) << "the other rows did change";
}

}  // namespace
}  // namespace ilp
