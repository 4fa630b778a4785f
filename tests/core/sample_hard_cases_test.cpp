// The sample-based operator on hard cases (reflectance near 1, patches that see no
// sample patch, slivers, coincident and coplanar surfaces, a far-off millimetre model,
// dark luminaires, NaN input) and the shortcuts it takes (direct light only, one
// colour channel, only the rows needed). Every yardstick is independent of the code
// under test: the exact solve with the same rays, closed forms built from the
// form-factor rows and the exact direct light, or conservation of flux.
#include "core/operator/sample_operator.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/base/error.h"
#include "core/exact/exact_solver.h"
#include "core/transport/form_factors.h"
#include "core/scene/mesh.h"
#include "core/scene/reference_scenes.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;
using reference::QuadSpec;

constexpr IndirectMethod kMethods[] = {IndirectMethod::sample_gather, IndirectMethod::exact_second_bounce};

SampleOperatorOptions options_with(int k, IndirectMethod method, int rays = 256) {
  SampleOperatorOptions o;
  o.sample_size = k;
  o.indirect = method;
  o.form_factors.rays_per_patch = rays;
  return o;
}

int all_patches_k(const Scene& scene) { return static_cast<int>(scene.patches.size()); }

SampleOperator build(const Scene& scene, std::span<const int> goals, const SampleOperatorOptions& o) {
  const RayCaster caster(scene);
  const GoalRows rows = compute_goal_rows(scene, caster, goals, scene_light_sources(scene), o);
  return build_sample_operator(scene, caster, rows, o);
}

// Total illuminance at the goal patches with the sources as the scene stands, lux.
Eigen::VectorXd lux(const Scene& scene, const SampleOperator& op) {
  return op.illuminance_lux(source_flux_lm(scene, op.sources));
}

// The exact reference with the same rays and direct-light points as the operator.
ExactSolution exact_solve(const Scene& scene, const SampleOperatorOptions& o) {
  ExactSolveOptions e;
  e.form_factors = o.form_factors;
  e.direct_light = o.direct_light;
  e.radiosity.relative_residual = 1e-12;
  return solve_exact(scene, e);
}

::testing::AssertionResult FiniteAndNonNegative(const Eigen::MatrixXd& m) {
  for (Eigen::Index c = 0; c < m.cols(); ++c)
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      if (!std::isfinite(m(r, c)) || m(r, c) < 0.0)
        return ::testing::AssertionFailure() << "entry (" << r << ", " << c << ") = " << m(r, c);
  return ::testing::AssertionSuccess();
}

// Area-weighted mean of values[g] (one per entry of `patches`) over the entries whose
// patch is on one of the surfaces named (all of them when `surfaces` is empty).
double area_mean(const Scene& scene, std::span<const int> patches, const Eigen::VectorXd& values,
                 std::initializer_list<const char*> surfaces = {}) {
  double sum = 0.0, area = 0.0;
  for (std::size_t g = 0; g < patches.size(); ++g) {
    const Patch& p = scene.patches[patches[g]];
    bool on = surfaces.size() == 0;
    for (const char* name : surfaces) on = on || scene.surfaces[p.surface].name == name;
    if (!on) continue;
    sum += p.area_m2 * values[static_cast<Eigen::Index>(g)];
    area += p.area_m2;
  }
  return sum / area;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& line : lines) out += line + "\n";
  return out;
}

// The inward faces of the box [o, o + s], named and oriented as make_closed_box's
// (ceiling last, or left out for the caller to build).
std::vector<QuadSpec> box_quads(const V& o, const V& s, const V& rho, bool with_ceiling = true) {
  const double x0 = o.x(), y0 = o.y(), z0 = o.z(), x1 = o.x() + s.x(), y1 = o.y() + s.y(), z1 = o.z() + s.z();
  std::vector<QuadSpec> quads = {{"floor", V(x0, y0, z0), V(x1, y0, z0), V(x1, y1, z0), V(x0, y1, z0), rho},
                                 {"wall_x0", V(x0, y0, z0), V(x0, y1, z0), V(x0, y1, z1), V(x0, y0, z1), rho},
                                 {"wall_x1", V(x1, y0, z0), V(x1, y0, z1), V(x1, y1, z1), V(x1, y1, z0), rho},
                                 {"wall_y0", V(x0, y0, z0), V(x0, y0, z1), V(x1, y0, z1), V(x1, y0, z0), rho},
                                 {"wall_y1", V(x0, y1, z0), V(x1, y1, z0), V(x1, y1, z1), V(x0, y1, z1), rho}};
  if (with_ceiling)
    quads.push_back({"ceiling", V(x0, y0, z1), V(x0, y1, z1), V(x1, y1, z1), V(x1, y0, z1), rho});
  return quads;
}

// A downward-facing ceiling rectangle [xa, xb] x [ya, yb] at height z.
QuadSpec ceiling_piece(double xa, double xb, double ya, double yb, double z, double rho) {
  return {"ceiling", V(xa, ya, z), V(xa, yb, z), V(xb, yb, z), V(xb, ya, z), V::Constant(rho)};
}

// A 2 m cube of uniform reflectance whose ceiling has a 0.2 m square opening filled
// by a luminaire facing down. Nothing is open and no luminaire back faces the room,
// so every lumen emitted ends up absorbed by the room (1 - rho per reflection) or by
// the luminaire's own front (reflectance 0).
Scene closed_room_with_ceiling_luminaire(double rho, double flux_lm, double max_edge_m = 0.6) {
  std::vector<QuadSpec> quads = box_quads(V::Zero(), V(2, 2, 2), V::Constant(rho), false);
  quads.push_back(ceiling_piece(0.0, 2.0, 0.0, 0.9, 2.0, rho));
  quads.push_back(ceiling_piece(0.0, 2.0, 1.1, 2.0, 2.0, rho));
  quads.push_back(ceiling_piece(0.0, 0.9, 0.9, 1.1, 2.0, rho));
  quads.push_back(ceiling_piece(1.1, 2.0, 0.9, 1.1, 2.0, rho));
  Scene scene = reference::make_quad_scene(quads, max_edge_m);
  add_square_luminaire(scene, "lamp", V(1, 1, 2), 0.2, flux_lm);
  return scene;
}

// A 2 m closed box of reflectance rho with a 0.4 m luminaire hanging 0.2 m below the ceiling.
Scene box_with_hanging_luminaire(double rho, double max_edge_m = 0.6) {
  Scene scene = reference::make_closed_box(V::Zero(), V(2, 2, 2), rho, max_edge_m);
  add_square_luminaire(scene, "lamp", V(1, 1, 1.8), 0.4, 1000.0);
  return scene;
}

// ---------------------------------------------------------------------------------
// SampleHardCases
// ---------------------------------------------------------------------------------

// Flux bookkeeping of a closed scene from the operator's answer at every patch.
struct FluxAccount {
  double absorbed = 0.0;   // sum A_i (1 - rho_i) H_i: the luminaire (rho 0) absorbs all it receives
  double incident = 0.0;   // sum A_i H_i
  double reflected = 0.0;  // sum A_i (rho H)_i as the operator reports it
};

FluxAccount account(const Scene& scene, const SampleOperator& op) {
  const Eigen::VectorXd flux = source_flux_lm(scene, op.sources);
  const Eigen::VectorXd H = op.illuminance_lux(flux);
  const Eigen::VectorXd reflected = op.reflected_lm_per_m2_per_lm * flux;
  FluxAccount a;
  for (std::size_t g = 0; g < op.goal_patches.size(); ++g) {
    const Patch& p = scene.patches[op.goal_patches[g]];
    const auto r = static_cast<Eigen::Index>(g);
    a.absorbed += p.area_m2 * (1.0 - p.reflectance[0]) * H[r];
    a.incident += p.area_m2 * H[r];
    a.reflected += p.area_m2 * reflected[r];
  }
  return a;
}

// Reflectance 0.99 and 0.999 in a closed room: light is reflected hundreds of times
// and I - K is nearly singular. The answer stays finite and non-negative, the
// condition estimate is logged, and flux is conserved: what the room absorbs is
// what the luminaire emits, reflected flux never exceeds incident, and the incident
// total stays below the furnace bound emitted / (1 - rho). At k = n only ray noise
// remains (measured 0.1 % and 0.9 % at 1024 rays per row); at k = 20 the sample adds
// its own error (spread over 10 seeds measured at 9-12 % with 4096 rays per row).
TEST(SampleHardCases, ReflectanceNearOneInAClosedRoomConservesFlux) {
  const double flux = 1000.0;
  for (IndirectMethod method : kMethods) {
    double previous_condition = 0.0;
    for (double rho : {0.99, 0.999}) {
      const Scene scene = closed_room_with_ceiling_luminaire(rho, flux);
      const std::vector<int> goals = scene.all_patches();
      for (int k : {all_patches_k(scene), 20}) {
        SCOPED_TRACE(::testing::Message() << "rho " << rho << ", " << to_string(method) << ", k = " << k);
        const bool census = k == all_patches_k(scene);
        const SampleOperator op = build(scene, goals, options_with(k, method, census ? 1024 : 4096));
        ASSERT_TRUE(FiniteAndNonNegative(op.total_lux_per_lm));
        ASSERT_TRUE(FiniteAndNonNegative(op.reflected_lm_per_m2_per_lm));

        EXPECT_TRUE(test::Contains(joined(op.log), "condition estimate", "run log"));
        // ||I - K||_1 >= 1 and ||(I - K)^-1||_1 >= 1 / (1 - rho min_a s_a), with s_a
        // close to 1 in a closed room: of order 1 / (1 - rho). Measured 280 and 1250
        // at k = n, 730 and 4700 at k = 20.
        EXPECT_TRUE(std::isfinite(op.stats.condition_estimate));
        EXPECT_GT(op.stats.condition_estimate, 0.1 / (1.0 - rho));
        EXPECT_LT(op.stats.condition_estimate, 1e3 / (1.0 - rho));
        if (census) {
          EXPECT_GT(op.stats.condition_estimate, previous_condition) << "rho nearer 1, worse conditioned";
          previous_condition = op.stats.condition_estimate;
        }

        const FluxAccount a = account(scene, op);
        const double tolerance = census ? 0.03 : 0.3;
        EXPECT_NEAR(a.absorbed, flux, tolerance * flux);
        EXPECT_LE(a.reflected, a.incident);
        EXPECT_LE(a.incident, (1.0 + tolerance) * flux / (1.0 - rho));
      }
    }
  }
}

// The same room at rho 0.999 with the default 256 rays per row and k = 20 must
// still conserve flux to within the sample's own error (30 %). FAILS as of this
// test: each sample row's share of light lost to the luminaire (1 - s_a, 0.002 on
// average) is counted from ray hits, 0, 1 or 2 of 256, and the solve amplifies that
// noise by 1 / (1 - rho s): the absorbed flux comes out at 0.68 to 2.1 times the
// emitted flux over seeds 1 to 10 (1.74 at seed 1). The closed-form factor from the
// row's patch to the luminaire, computed for the direct light anyway, gives that
// share without ray noise; taking it instead of the ray hits, in the operator's s_a
// and in the exact solver's rows alike (so that k = n still is the exact solve),
// brings the same seeds to 0.86 to 1.19 and k = n to 1.0008 (now 1.025).
TEST(SampleHardCases, SmallSampleNearRhoOneIsNotRuledByRayNoiseInTheLoss) {
  const double flux = 1000.0;
  const Scene scene = closed_room_with_ceiling_luminaire(0.999, flux);
  const std::vector<int> goals = scene.all_patches();
  const RayCaster caster(scene);
  for (IndirectMethod method : kMethods) {
    SampleOperatorOptions o = options_with(20, method);
    const GoalRows rows = compute_goal_rows(scene, caster, goals, scene_light_sources(scene), o);
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      o.sample_seed = seed;
      const SampleOperator op = build_sample_operator(scene, caster, rows, o);
      EXPECT_NEAR(account(scene, op).absorbed, flux, 0.3 * flux) << to_string(method) << ", seed " << seed;
    }
  }
}

// k = n on the near-singular room is the exact solve (same rays, Gauss-Seidel to
// 1e-12) at every reflecting patch; the luminaire's own patches, which are never
// sampled, gather through reciprocity instead of their own row and agree to ray
// noise. k = 5 stays within 30 % of the exact averages at rho 0.99 (measured -16 %
// overall); at rho 0.999 see the test above.
TEST(SampleHardCases, TinyAndFullSamplesAgreeWithTheExactSolveNearRhoOne) {
  for (double rho : {0.99, 0.999}) {
    const Scene scene = closed_room_with_ceiling_luminaire(rho, 1000.0);
    const std::vector<int> goals = scene.all_patches();
    for (IndirectMethod method : kMethods) {
      SCOPED_TRACE(::testing::Message() << "rho " << rho << ", " << to_string(method));
      const SampleOperatorOptions full = options_with(all_patches_k(scene), method);
      const ExactSolution exact = exact_solve(scene, full);
      const Eigen::VectorXd census = lux(scene, build(scene, goals, full));
      ASSERT_TRUE(FiniteAndNonNegative(census));
      for (std::size_t g = 0; g < goals.size(); ++g) {
        const int i = goals[g];
        const double reference = exact.radiosity.total_lux[i];
        const double tolerance = scene.surfaces[scene.patches[i].surface].is_luminaire() ? 0.02 : 1e-8;  // measured 0.4 %
        ASSERT_NEAR(census[static_cast<Eigen::Index>(g)], reference, tolerance * reference) << "patch " << i;
      }
      const Eigen::VectorXd small = lux(scene, build(scene, goals, options_with(5, method)));
      ASSERT_TRUE(FiniteAndNonNegative(small));
      if (rho > 0.99) continue;
      const double exact_mean = area_mean(scene, goals, exact.radiosity.total_lux);
      EXPECT_NEAR(area_mean(scene, goals, small), exact_mean, 0.3 * exact_mean);
      for (const char* surface : {"floor", "ceiling", "wall_x0"}) {
        const double m = area_mean(scene, goals, exact.radiosity.total_lux, {surface});
        EXPECT_NEAR(area_mean(scene, goals, small, {surface}), m, 0.3 * m) << surface;
      }
    }
  }
}

// An open corner, floor 3 x 2 m (patches of 0.047 m2) and a wall 2 x 2 m (0.056 m2),
// lit by a luminaire: many patches see only a few others, so small samples leave
// most goals seeing no sample patch.
Scene open_corner() {
  Scene scene = reference::make_quad_scene(
      {{"floor", V(0, 0, 0), V(3, 0, 0), V(3, 2, 0), V(0, 2, 0), V::Constant(0.5)},
       {"wall", V(0, 0, 0), V(0, 2, 0), V(0, 2, 2), V(0, 0, 2), V::Constant(0.8)}},
      0.5);
  add_square_luminaire(scene, "lamp", V(1, 1, 1.5), 0.4, 1000.0);
  return scene;
}

// What the operator is made of, from independent code: every patch's full row (the
// same rays the operator casts), s_i (front hits on reflecting patches), the first
// reflection through the full row G_i = sum_j F_ij rho_j D_j, and the exact
// solver's direct light D per lumen. s_i and G_i are scaled so that each row loses
// the closed-form share D_i A_lamp to the lamp instead of its ray hits on it.
struct Ingredients {
  FormFactorRows rows;
  Eigen::VectorXd s, first, D;
};

Ingredients ingredients(const Scene& scene, const SampleOperatorOptions& o, double flux_lm) {
  const RayCaster caster(scene);
  Ingredients in{compute_form_factor_rows(scene, caster, scene.all_patches(), o.form_factors), {}, {}, {}};
  in.D = exact_solve(scene, o).radiosity.direct_lux / flux_lm;
  const auto n = static_cast<Eigen::Index>(scene.patches.size());
  in.s = in.first = Eigen::VectorXd::Zero(n);
  double lamp_area_m2 = 0.0;
  for (const Patch& p : scene.patches)
    if (scene.surfaces[p.surface].is_luminaire()) lamp_area_m2 += p.area_m2;
  for (Eigen::Index i = 0; i < n; ++i) {
    double kept = 0.0, struck = 0.0;
    for (SparseRows::InnerIterator it(in.rows.F, i); it; ++it) {
      const Patch& j = scene.patches[it.col()];
      (scene.surfaces[j.surface].is_luminaire() ? struck : kept) += it.value();
      if (scene.surfaces[j.surface].is_luminaire() || j.reflectance[0] == 0.0) continue;
      in.s[i] += it.value();
      in.first[i] += it.value() * j.reflectance[0] * in.D[it.col()];
    }
    // The row loses the closed-form share D_i A_lamp to the lamp, not its ray hits.
    const double scale = kept > 0.0 ? std::max(0.0, kept + struck - in.D[i] * lamp_area_m2) / kept : 1.0;
    in.s[i] *= scale;
    in.first[i] *= scale;
  }
  return in;
}

// T for one luminaire and every goal patch (all patches), written out from the
// header of core/operator/sample_operator.h for a gray scene:
//   W_ab = s_a w_b F_ab / sum_c w_c F_ac for a sample row (own row),
//   W_ib = s_i w_b A_b F_bi / sum_c w_c A_c F_ci for other goals (reciprocity; with
//          the exact second bounce A_b F_bi + A_i F_ib, adding the goal's own row),
//   W_ib = s_i A_b w_b / sum_c A_c w_c where the sum is 0 (ambient fallback),
//   sample_gather:       B = (I - R W_PP)^-1 R D_P,              T = D + W B
//   exact_second_bounce: B = (I - R W_PP)^-1 (R D_P + R (G_P - W_PP R D_P)),
//                        T = D + G + W (B - R D_P).
Eigen::VectorXd documented_T(const Scene& scene, const Ingredients& in, const PatchSample& sample,
                             IndirectMethod method, std::size_t* fallback_goals) {
  const auto n = static_cast<Eigen::Index>(scene.patches.size());
  const auto k = static_cast<Eigen::Index>(sample.patches.size());
  const Eigen::MatrixXd F(in.rows.F);
  Eigen::VectorXd ambient(k), rho(k), D_P(k), G_P(k);
  for (Eigen::Index b = 0; b < k; ++b) {
    const int p = sample.patches[b];
    ambient[b] = scene.patches[p].area_m2 * sample.weight[b];
    rho[b] = scene.patches[p].reflectance[0];
    D_P[b] = in.D[p];
    G_P[b] = in.first[p];
  }
  ambient /= ambient.sum();
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n, k);
  *fallback_goals = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto own = std::find(sample.patches.begin(), sample.patches.end(), static_cast<int>(i));
    Eigen::VectorXd a(k);
    for (Eigen::Index b = 0; b < k; ++b) {
      const int p = sample.patches[b];
      // Outside the sample: reciprocity from p's row, plus i's own row where the
      // exact second bounce keeps the goal rows.
      const double own_row = method == IndirectMethod::exact_second_bounce ? scene.patches[i].area_m2 * F(i, p) : 0.0;
      a[b] = sample.weight[b] * (own != sample.patches.end() ? F(i, p) : scene.patches[p].area_m2 * F(p, i) + own_row);
    }
    if (a.sum() > 0.0) {
      W.row(i) = in.s[i] * a.transpose() / a.sum();
    } else {
      W.row(i) = in.s[i] * ambient.transpose();
      if (in.s[i] > 0.0) ++*fallback_goals;  // a patch that sees nothing reflecting needs no fallback
    }
  }
  Eigen::MatrixXd W_PP(k, k);
  for (Eigen::Index b = 0; b < k; ++b) W_PP.row(b) = W.row(sample.patches[b]);
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(k, k) - rho.asDiagonal() * W_PP;
  const Eigen::VectorXd B1 = rho.cwiseProduct(D_P);
  if (method == IndirectMethod::sample_gather) return in.D + W * A.partialPivLu().solve(B1);
  const Eigen::VectorXd B = A.partialPivLu().solve(B1 + rho.cwiseProduct(G_P - W_PP * B1));
  return in.D + in.first + W * (B - B1);
}

// Goals that see no sample patch take the ambient rule of the header, W_ip = s_i A_p
// w_p / sum_q A_q w_q: the operator's T equals T written out from the header with
// independent ingredients, at k = 1 (every goal takes s_i times the one sample
// patch's reflected radiosity, fallback or not), k = 3 stratified (weights 1: the
// ambient term weighs sample patches by area) and k = 3 drawn by area (weights
// 1 / A_p: it weighs them equally). Goals with s_i > 0 get indirect light.
TEST(SampleHardCases, PatchesThatSeeNoSamplePatchGetTheAmbientRule) {
  const Scene scene = open_corner();
  const std::vector<int> goals = scene.all_patches();
  const Ingredients in = ingredients(scene, options_with(1, IndirectMethod::sample_gather), 1000.0);
  for (IndirectMethod method : kMethods)
    for (auto [k, strategy] : {std::pair{1, SampleStrategy::stratified}, std::pair{3, SampleStrategy::stratified},
                               std::pair{3, SampleStrategy::area}}) {
      SCOPED_TRACE(::testing::Message() << to_string(method) << ", k = " << k << " " << to_string(strategy));
      SampleOperatorOptions o = options_with(k, method);
      o.strategy = strategy;
      o.sample_direct_light = o.direct_light;  // the documented T takes the goals' direct light at the sample
      const SampleOperator op = build(scene, goals, o);
      ASSERT_TRUE(FiniteAndNonNegative(op.total_lux_per_lm));
      ASSERT_FALSE(op.sample.patches.empty());
      for (int p : op.sample.patches) ASSERT_GT(in.D[p], 0.0) << "the fixture's sample patches must be lit";
      if (k == 3) {
        double smallest = INFINITY, largest = 0.0;  // the ambient weights must differ for the test to bite
        for (Eigen::Index b = 0; b < op.sample.weight.size(); ++b) {
          const double aw = scene.patches[op.sample.patches[b]].area_m2 * op.sample.weight[b];
          smallest = std::min(smallest, aw);
          largest = std::max(largest, aw);
        }
        if (strategy == SampleStrategy::stratified) {
          EXPECT_GT(largest, 1.1 * smallest);
        }
      }

      std::size_t fallback = 0;
      const Eigen::VectorXd expected = documented_T(scene, in, op.sample, method, &fallback);
      EXPECT_EQ(op.stats.goal_fallback_rows, fallback);
      EXPECT_GT(op.stats.goal_fallback_rows, goals.size() / 4);  // the fallback is exercised
      EXPECT_TRUE(test::Contains(joined(op.log), "ambient fallback", "run log"));
      for (Eigen::Index i = 0; i < expected.size(); ++i) {
        const double got = op.total_lux_per_lm(i, 0);
        ASSERT_NEAR(got, expected[i], 1e-9 * expected[i] + 1e-15) << "patch " << i << ", s_i " << in.s[i];
        if (in.s[i] > 0.0) {
          ASSERT_GT(got - in.D[i], 0.0) << "patch " << i << " sees reflecting patches but gets no indirect light";
        }
      }
    }
}

// A sliver of 1e-10 m2 (two triangles 0.5 m by 4e-10 m, 1 cm above the floor) among
// patches of 0.06 m2 and more: 1e9 times smaller, narrower than float resolution, so
// no ray ever strikes it. Everything stays finite, the sliver gets about what the
// floor under it gets (measured 3-5 % more), and the room is exactly what it is
// without the sliver: at k = n, where the sliver is a sample patch with its own row
// in K, and at k = 20 drawn by area (the same draw with or without the sliver, which
// is then a goal that no sample row reaches: the ambient fallback).
TEST(SampleHardCases, SliverBesidePatchesABillionTimesLarger) {
  const V rho = V::Constant(0.5);
  const double w = 4e-10;
  const std::vector<QuadSpec> box = box_quads(V::Zero(), V(2, 2, 2), rho);
  const auto make = [&](bool with_sliver) {  // without: the surface stays, its point quad is dropped
    const double length = with_sliver ? 0.5 : 0.0, width = with_sliver ? w : 0.0;
    std::vector<QuadSpec> quads = box;
    quads.push_back({"sliver", V(0.75, 0.5, 0.01), V(0.75 + length, 0.5, 0.01), V(0.75 + length, 0.5 + width, 0.01),
                     V(0.75, 0.5 + width, 0.01), rho});
    Scene s = reference::make_quad_scene(quads, 0.6);
    add_square_luminaire(s, "lamp", V(1, 1, 1.8), 0.4, 1000.0);
    return s;
  };
  const Scene scene = make(true), plain = make(false);
  ASSERT_EQ(plain.stats.degenerate_dropped, 2u);
  ASSERT_EQ(scene.stats.degenerate_dropped, 0u);
  const std::vector<int> sliver = reference::patches_of(scene, "sliver");
  ASSERT_EQ(sliver.size(), 2u) << "make_scene keeps the sliver whole";
  for (int i : sliver) ASSERT_NEAR(scene.patches[i].area_m2, 1e-10, 1e-12);
  const std::size_t room = plain.stats.mesh_patches;  // the box's patches: same indices in both scenes

  std::vector<int> floor_below;
  for (int i : reference::patches_of(scene, "floor"))
    if ((scene.patches[i].centroid_m - V(1.0, 0.5, 0.0)).head<2>().norm() < 0.4) floor_below.push_back(i);
  ASSERT_GE(floor_below.size(), 3u);

  for (IndirectMethod method : kMethods)
    for (int k : {all_patches_k(scene), 20}) {
      SCOPED_TRACE(::testing::Message() << to_string(method) << ", k = " << k);
      SampleOperatorOptions o = options_with(k, method);
      o.strategy = SampleStrategy::area;
      const SampleOperator op = build(scene, scene.all_patches(), o);
      const SampleOperator base = build(plain, plain.all_patches(), o);
      ASSERT_TRUE(FiniteAndNonNegative(op.total_lux_per_lm));
      ASSERT_TRUE(FiniteAndNonNegative(op.reflected_lm_per_m2_per_lm));
      EXPECT_EQ(op.stats.census, k == all_patches_k(scene));
      if (k < all_patches_k(scene)) {
        ASSERT_EQ(op.sample.patches, base.sample.patches);
      }
      const Eigen::VectorXd H = lux(scene, op), H0 = lux(plain, base);
      double floor_mean = 0.0;
      for (int i : floor_below) floor_mean += H[i] / static_cast<double>(floor_below.size());
      for (int i : sliver) {
        EXPECT_GT(H[i], 0.7 * floor_mean) << "sliver patch " << i;
        EXPECT_LT(H[i], 1.4 * floor_mean) << "sliver patch " << i;
      }
      for (std::size_t i = 0; i < room; ++i) {
        const auto r = static_cast<Eigen::Index>(i);
        ASSERT_NEAR(H[r], H0[r], 1e-9 * H0[r]) << "patch " << i;
      }
    }
}

// A paper sheet exactly coincident with the desk top (same quad, same side, same
// reflectance) and the many coplanar patches of each face: no patch sees itself or a
// patch in its own plane (F = 0), and the answer is that of the room without the
// paper: rays reaching the desk top strike one copy or the other, both reflecting
// alike. Room patches keep their indices (the paper is added last), so only noise
// separates the two answers.
TEST(SampleHardCases, CoincidentAndCoplanarSurfacesExchangeNoLight) {
  const V rho = V::Constant(0.5), desk_rho = V::Constant(0.6);
  std::vector<QuadSpec> quads = box_quads(V::Zero(), V(2, 2, 2), rho);
  quads.push_back({"desk", V(0.5, 0.5, 0.7), V(1.5, 0.5, 0.7), V(1.5, 1.5, 0.7), V(0.5, 1.5, 0.7), desk_rho});
  // Without the paper, its surface stays as a point quad that meshing drops: the
  // luminaire keeps its surface index and so its shadow rays.
  const Scene plain = [&] {
    std::vector<QuadSpec> q = quads;
    q.push_back({"paper", V(1, 1, 0.7), V(1, 1, 0.7), V(1, 1, 0.7), V(1, 1, 0.7), desk_rho});
    Scene s = reference::make_quad_scene(q, 0.6);
    add_square_luminaire(s, "lamp", V(1, 1, 1.8), 0.4, 1000.0);
    return s;
  }();
  ASSERT_EQ(plain.stats.degenerate_dropped, 2u);
  quads.push_back({"paper", V(0.5, 0.5, 0.7), V(1.5, 0.5, 0.7), V(1.5, 1.5, 0.7), V(0.5, 1.5, 0.7), desk_rho});
  Scene scene = reference::make_quad_scene(quads, 0.6);
  add_square_luminaire(scene, "lamp", V(1, 1, 1.8), 0.4, 1000.0);
  const std::vector<int> desk = reference::patches_of(scene, "desk"), paper = reference::patches_of(scene, "paper");
  ASSERT_EQ(desk.size(), paper.size());

  // F between coplanar patches facing the same way (desk and paper included) is 0.
  const RayCaster caster(scene);
  const FormFactorRows rows = compute_form_factor_rows(scene, caster, scene.all_patches(), FormFactorOptions{});
  std::size_t coplanar_pairs = 0;
  for (Eigen::Index i = 0; i < rows.F.rows(); ++i) {
    const Patch& a = scene.patches[i];
    for (SparseRows::InnerIterator it(rows.F, i); it; ++it) {
      const Patch& b = scene.patches[it.col()];
      const bool coplanar = a.normal.dot(b.normal) > 1 - 1e-12 && std::abs(a.normal.dot(b.centroid_m - a.centroid_m)) < 1e-9;
      ASSERT_FALSE(coplanar) << "patch " << i << " sees patch " << it.col() << " in its own plane";
    }
    for (std::size_t j = 0; j < scene.patches.size(); ++j)
      if (a.normal.dot(scene.patches[j].normal) > 1 - 1e-12 &&
          std::abs(a.normal.dot(scene.patches[j].centroid_m - a.centroid_m)) < 1e-9)
        ++coplanar_pairs;
  }
  EXPECT_GT(coplanar_pairs, 2 * scene.patches.size()) << "the scene has coplanar neighbours to test";

  for (IndirectMethod method : kMethods) {
    SCOPED_TRACE(to_string(method));
    const SampleOperatorOptions o = options_with(all_patches_k(scene), method);
    const SampleOperator op = build(scene, scene.all_patches(), o);
    ASSERT_TRUE(FiniteAndNonNegative(op.total_lux_per_lm));
    const Eigen::VectorXd H = lux(scene, op), H0 = lux(plain, build(plain, plain.all_patches(), o));
    const std::size_t common = plain.stats.mesh_patches;
    double worst = 0.0;
    for (std::size_t i = 0; i < common; ++i) worst = std::max(worst, std::abs(H[i] / H0[i] - 1.0));
    EXPECT_LT(worst, 0.01) << "largest relative change of a room or desk patch";  // measured 0.14 %
    double paper_mean = 0.0, desk_mean = 0.0;
    for (std::size_t m = 0; m < desk.size(); ++m) {
      paper_mean += H[paper[m]] / static_cast<double>(desk.size());
      desk_mean += H0[desk[m]] / static_cast<double>(desk.size());
    }
    EXPECT_NEAR(paper_mean, desk_mean, 0.01 * desk_mean);
  }
}

// The faces of box_quads as a mesh in file units, for make_scene.
TriangleMesh box_mesh(const V& origin, const V& size) {
  TriangleMesh mesh;
  mesh.path = "<box>";
  for (const QuadSpec& q : box_quads(origin, size, V::Constant(0.5))) {
    mesh.surface_names.push_back(q.surface);
    const int base = static_cast<int>(mesh.positions.size());
    for (const V& p : {q.a, q.b, q.c, q.d}) mesh.positions.push_back(p);
    for (const Eigen::Vector3i& t : {Eigen::Vector3i(base, base + 1, base + 2), Eigen::Vector3i(base, base + 2, base + 3)}) {
      mesh.triangles.push_back(t);
      mesh.triangle_surface.push_back(static_cast<int>(mesh.surface_names.size()) - 1);
      mesh.triangle_material.push_back(-1);
    }
    ++mesh.faces_read;
  }
  return mesh;
}

// The room as a metre model at the origin and as a millimetre model whose file
// coordinates are near 1e5 (100 m from the origin), converted with scale_to_m =
// 0.001: the same patches in the same order. The rays are not quite the same (a
// wall normal's z of +0 or -1e-17 flips its tangent frame), so per patch they agree
// to ray noise (measured 1.0 %), per surface to 1 %; nothing becomes non-finite.
TEST(SampleHardCases, MillimetreModelFarFromTheOriginMatchesMetres) {
  const auto make = [](const V& origin, const V& size, double scale, const V& offset_m) {
    const TriangleMesh mesh = box_mesh(origin, size);
    SceneOptions options;
    options.scale_to_m = scale;
    options.max_patch_edge_m = 0.6;
    Scene scene = make_scene(mesh, TriangleReflectance(mesh.triangles.size(), V::Constant(0.5)), options);
    add_square_luminaire(scene, "lamp", offset_m + V(1, 1, 1.8), 0.4, 1000.0);
    return scene;
  };
  const Scene metres = make(V::Zero(), V(2, 2, 2), 1.0, V::Zero());
  const Scene millimetres = make(V::Constant(1e5), V(2000, 2000, 2000), 0.001, V::Constant(100));
  ASSERT_EQ(metres.patches.size(), millimetres.patches.size());
  ASSERT_NEAR(millimetres.bounds_m.min().x(), 100.0, 1e-9);
  for (IndirectMethod method : kMethods)
    for (int k : {all_patches_k(metres), 20}) {
      SCOPED_TRACE(::testing::Message() << to_string(method) << ", k = " << k);
      const SampleOperatorOptions o = options_with(k, method);
      const SampleOperator a = build(metres, metres.all_patches(), o);
      const SampleOperator b = build(millimetres, millimetres.all_patches(), o);
      ASSERT_TRUE(FiniteAndNonNegative(b.total_lux_per_lm));
      ASSERT_EQ(a.sample.patches, b.sample.patches);
      const Eigen::VectorXd Ha = lux(metres, a), Hb = lux(millimetres, b);
      const std::vector<int> all = metres.all_patches();
      for (const char* surface : {"floor", "ceiling", "wall_x0", "wall_x1", "wall_y0", "wall_y1"}) {
        const double m = area_mean(metres, all, Ha, {surface});
        EXPECT_NEAR(area_mean(millimetres, all, Hb, {surface}), m, 0.01 * m) << surface;
      }
      double worst = 0.0;
      for (Eigen::Index i = 0; i < Ha.size(); ++i) worst = std::max(worst, std::abs(Hb[i] / Ha[i] - 1.0));
      EXPECT_LT(worst, 0.03) << "largest per-patch difference";  // measured 1.0 %
    }
}

// A dark luminaire (0 lm) beside a bright one (1000 lm): its column of T is still
// the response per lumen (every lumen it would emit lands in the closed room, and
// the column matches the exact solve of the room with the fluxes swapped); the
// configuration's answer is the exact solve of the room as it stands and, within
// the dark panel's own shading (measured 1.5 % on the ceiling, under 0.5 % elsewhere),
// the room without it; all zeros give exactly 0.
TEST(SampleHardCases, LuminaireOfZeroFluxKeepsAMeaningfulColumn) {
  const auto room = [](double bright_lm, std::optional<double> dark_lm) {
    Scene s = reference::make_closed_box(V::Zero(), V(2, 2, 2), 0.5, 0.6);
    add_square_luminaire(s, "bright", V(1.4, 1, 1.8), 0.4, bright_lm);
    if (dark_lm) add_square_luminaire(s, "dark", V(0.6, 1, 1.8), 0.2, *dark_lm);
    return s;
  };
  const Scene scene = room(1000.0, 0.0), swapped = room(0.0, 1000.0), without = room(1000.0, std::nullopt);
  const std::vector<int> goals = scene.all_patches();
  const std::size_t mesh_patches = scene.stats.mesh_patches;
  for (IndirectMethod method : kMethods)
    for (int k : {all_patches_k(scene), 20}) {
      SCOPED_TRACE(::testing::Message() << to_string(method) << ", k = " << k);
      const SampleOperatorOptions o = options_with(k, method);
      const SampleOperator op = build(scene, goals, o);
      ASSERT_EQ(op.sources.size(), 2u);
      ASSERT_EQ(op.sources[1].name, "dark");
      ASSERT_TRUE(FiniteAndNonNegative(op.total_lux_per_lm));
      const Eigen::VectorXd flux = source_flux_lm(scene, op.sources);
      ASSERT_EQ(flux[1], 0.0);

      double landed = 0.0;  // lm per lm of the dark luminaire reaching the room directly
      for (std::size_t g = 0; g < goals.size(); ++g) landed += scene.patches[goals[g]].area_m2 * op.direct_lux_per_lm(g, 1);
      EXPECT_NEAR(landed, 1.0, 0.01);
      EXPECT_GT(area_mean(scene, goals, op.total_lux_per_lm.col(1)), area_mean(scene, goals, op.direct_lux_per_lm.col(1)));

      const Eigen::VectorXd H = op.illuminance_lux(flux);
      const Eigen::VectorXd zero = op.illuminance_lux(Eigen::VectorXd::Zero(2));
      for (Eigen::Index g = 0; g < zero.size(); ++g) ASSERT_EQ(zero[g], 0.0) << "goal " << g;

      if (k == all_patches_k(scene)) {
        const ExactSolution as_is = exact_solve(scene, o), dark_lit = exact_solve(swapped, o);
        for (std::size_t i = 0; i < mesh_patches; ++i) {
          const auto r = static_cast<Eigen::Index>(i);
          ASSERT_NEAR(H[r], as_is.radiosity.total_lux[r], 1e-8 * as_is.radiosity.total_lux[r]) << "patch " << i;
          ASSERT_NEAR(1000.0 * op.total_lux_per_lm(r, 1), dark_lit.radiosity.total_lux[r],
                      1e-8 * dark_lit.radiosity.total_lux[r])
              << "patch " << i;
        }
      }
      const SampleOperator op0 = build(without, without.all_patches(), o);
      const Eigen::VectorXd H0 = lux(without, op0);
      std::vector<int> room_patches(mesh_patches);
      std::iota(room_patches.begin(), room_patches.end(), 0);
      for (const char* surface : {"floor", "ceiling", "wall_x0", "wall_x1"}) {
        const double m0 = area_mean(without, room_patches, H0.head(static_cast<Eigen::Index>(mesh_patches)), {surface});
        EXPECT_NEAR(area_mean(scene, room_patches, H.head(static_cast<Eigen::Index>(mesh_patches)), {surface}), m0,
                    0.03 * m0)
            << surface;
      }
    }
}

// A reflectance that is not a finite number, set on a built scene's floor patch that
// is in the sample (k = n), must stop the build with a NumericalError whose message
// names the stage ("stage: ...") and that patch.
void expect_bad_reflectance_stops_the_build(double bad) {
  for (IndirectMethod method : kMethods) {
    SCOPED_TRACE(::testing::Message() << "reflectance " << bad << ", " << to_string(method));
    Scene scene = box_with_hanging_luminaire(0.5);
    ASSERT_EQ(scene.surfaces[scene.patches[5].surface].name, "floor");
    scene.patches[5].reflectance = V::Constant(bad);
    const std::vector<int> goals = scene.all_patches();
    const std::string message = test::error_of<NumericalError>(
        [&] { build(scene, goals, options_with(all_patches_k(scene), method)); }, "build_sample_operator");
    const std::size_t colon = message.find(": ");
    EXPECT_TRUE(colon != std::string::npos && colon > 0) << "no stage in \"" << message << "\"";
    EXPECT_TRUE(test::Contains(message, "patch 5 (floor)"));
  }
}

// FAILS as of this test: is_reflecting() asks maxCoeff() > 0, false for NaN, so the
// patch silently leaves the population, is treated as black, and its NaN reaches
// reflected_lm_per_m2_per_lm (T itself stays finite).
TEST(SampleHardCases, NanReflectanceIsANumericalErrorNamingThePatch) {
  expect_bad_reflectance_stops_the_build(std::numeric_limits<double>::quiet_NaN());
}

// Caught by the check that every row of K sums to rho_a s_a < 1.
TEST(SampleHardCases, InfiniteReflectanceIsANumericalErrorNamingThePatch) {
  expect_bad_reflectance_stops_the_build(std::numeric_limits<double>::infinity());
}

// ---------------------------------------------------------------------------------
// SampleShortcuts
// ---------------------------------------------------------------------------------

// Every reflectance 0: no sample, no rows cast for a luminaire-only room (rows only
// to count a gathered emitter's light when there is one), the log says so, and the
// answer is the exact solve's, which is its direct light.
TEST(SampleShortcuts, NothingReflectsGivesDirectLightWithoutASample) {
  for (bool with_emitting_wall : {false, true}) {
    Scene scene = box_with_hanging_luminaire(0.0);
    if (with_emitting_wall) set_surface_exitance(scene, scene.find_surface("wall_y0"), 50.0);
    const std::vector<int> goals = scene.all_patches();
    for (IndirectMethod method : kMethods) {
      SCOPED_TRACE(::testing::Message() << to_string(method) << (with_emitting_wall ? ", emitting wall" : ""));
      const SampleOperatorOptions o = options_with(50, method);
      const SampleOperator op = build(scene, goals, o);
      EXPECT_TRUE(op.stats.direct_only);
      EXPECT_EQ(op.stats.sample_patches, 0u);
      EXPECT_TRUE(op.sample.patches.empty());
      EXPECT_EQ(op.stats.rays_cast, with_emitting_wall ? goals.size() * 256u : 0u);
      EXPECT_TRUE(test::Contains(joined(op.log), "direct light only", "run log"));
      EXPECT_TRUE(test::Contains(joined(op.log), "no sample", "run log"));
      const ExactSolution exact = exact_solve(scene, o);
      const Eigen::VectorXd H = lux(scene, op);
      for (std::size_t g = 0; g < goals.size(); ++g) {
        const double reference = exact.radiosity.total_lux[goals[g]];
        ASSERT_EQ(reference, exact.radiosity.direct_lux[goals[g]]);
        ASSERT_NEAR(H[static_cast<Eigen::Index>(g)], reference, 1e-9 * reference + 1e-12) << "patch " << goals[g];
      }
      EXPECT_GT(H.maxCoeff(), 0.0);
    }
  }
}

// Gray materials are solved in one channel; forcing three equal channels changes
// nothing but the work (T equal to round-off). Coloured materials take three, and at
// k = n their photometric answer is the exact solve's.
TEST(SampleShortcuts, GrayScenesUseOneChannelAndGiveTheSameAnswerAsThree) {
  Scene gray = reference::make_quad_scene(
      [] {
        std::vector<QuadSpec> q = box_quads(V::Zero(), V(2, 2, 2), V::Constant(0.6));
        q.push_back({"desk", V(0.5, 0.5, 0.7), V(1.5, 0.5, 0.7), V(1.5, 1.5, 0.7), V(0.5, 1.5, 0.7), V::Constant(0.3)});
        return q;
      }(),
      0.6);
  add_square_luminaire(gray, "lamp", V(1, 1, 1.8), 0.4, 1000.0);
  ASSERT_EQ(gray.channels, 1);
  Scene forced = gray;
  forced.channels = 3;
  const std::vector<int> goals = gray.all_patches();
  for (IndirectMethod method : kMethods)
    for (int k : {all_patches_k(gray), 20}) {
      SCOPED_TRACE(::testing::Message() << to_string(method) << ", k = " << k);
      const SampleOperatorOptions o = options_with(k, method);
      const SampleOperator one = build(gray, goals, o), three = build(forced, goals, o);
      EXPECT_EQ(one.stats.channels, 1);
      EXPECT_EQ(three.stats.channels, 3);
      EXPECT_TRUE(test::Contains(joined(one.log), "1 colour channel", "run log"));
      const double scale = one.total_lux_per_lm.cwiseAbs().maxCoeff();
      ASSERT_GT(scale, 0.0);
      EXPECT_LE((one.total_lux_per_lm - three.total_lux_per_lm).cwiseAbs().maxCoeff(), 1e-12 * scale);
      EXPECT_LE((one.reflected_lm_per_m2_per_lm - three.reflected_lm_per_m2_per_lm).cwiseAbs().maxCoeff(),
                1e-12 * scale);
    }

  Scene coloured = reference::make_quad_scene(
      [] {
        std::vector<QuadSpec> q = box_quads(V::Zero(), V(2, 2, 2), V(0.7, 0.5, 0.3));
        q.push_back({"desk", V(0.5, 0.5, 0.7), V(1.5, 0.5, 0.7), V(1.5, 1.5, 0.7), V(0.5, 1.5, 0.7), V(0.2, 0.4, 0.8)});
        return q;
      }(),
      0.6);
  add_square_luminaire(coloured, "lamp", V(1, 1, 1.8), 0.4, 1000.0);
  ASSERT_EQ(coloured.channels, 3);
  for (IndirectMethod method : kMethods) {
    SCOPED_TRACE(to_string(method));
    const SampleOperatorOptions o = options_with(all_patches_k(coloured), method);
    const SampleOperator op = build(coloured, coloured.all_patches(), o);
    EXPECT_EQ(op.stats.channels, 3);
    EXPECT_TRUE(test::Contains(joined(op.log), "3 colour channels", "run log"));
    const ExactSolution exact = exact_solve(coloured, o);
    const Eigen::VectorXd H = lux(coloured, op);
    for (std::size_t i = 0; i < coloured.stats.mesh_patches; ++i)
      ASSERT_NEAR(H[static_cast<Eigen::Index>(i)], exact.radiosity.total_lux[static_cast<Eigen::Index>(i)],
                  1e-8 * exact.radiosity.total_lux[static_cast<Eigen::Index>(i)])
          << "patch " << i;
  }
}

// Goals on the floor only: the operator casts the sample rows and the floor's rows
// and nothing else, and its rows of T are those of the operator for every patch
// (same sample, rays and seeds). Exact to round-off where the goal set cannot
// matter (sample_gather; exact_second_bounce at k = n, where every patch a row hits
// is a sample patch); with exact_second_bounce at k < n, first reflections at patches
// that are neither goal nor sample use the cheaper hit_direct_light estimate, so the
// two agree to its noise.
TEST(SampleShortcuts, OnlyTheRowsNeededGiveTheSameRowsOfT) {
  Scene scene = box_with_hanging_luminaire(0.6);
  const std::vector<int> floor = reference::patches_of(scene, "floor"), all = scene.all_patches();
  const std::size_t n = scene.patches.size();
  for (IndirectMethod method : kMethods)
    for (int k : {all_patches_k(scene), 20}) {
      SCOPED_TRACE(::testing::Message() << to_string(method) << ", k = " << k);
      const SampleOperatorOptions o = options_with(k, method);
      const SampleOperator part = build(scene, floor, o), whole = build(scene, all, o);
      ASSERT_EQ(part.sample.patches, whole.sample.patches);
      EXPECT_EQ(part.stats.rays_cast, (part.stats.sample_patches + floor.size()) * 256u);
      if (k < all_patches_k(scene)) {
        EXPECT_LT(part.stats.rays_cast, n * 256u);
      }
      // Full direct light at the goals and the sample only; the refinement adds cheap
      // estimates at the other patches the rows hit, fewer than the scene has.
      EXPECT_LE(part.stats.direct_rows, floor.size() + part.stats.sample_patches);
      if (method == IndirectMethod::sample_gather) {
        EXPECT_EQ(part.stats.cheap_direct_rows, 0u);
      } else {
        // Each patch once, but a sample patch that is a goal twice: the sample's direct light
        // is its own estimate (sample_direct_light), whatever the goals.
        EXPECT_LE(part.stats.cheap_direct_rows + part.stats.direct_rows, n + part.stats.sample_patches);
      }
      EXPECT_EQ(part.stats.goal_patches, floor.size());
      const bool exact_same = method == IndirectMethod::sample_gather || k == all_patches_k(scene);
      double worst = 0.0;
      for (std::size_t g = 0; g < floor.size(); ++g)
        for (Eigen::Index l = 0; l < part.total_lux_per_lm.cols(); ++l) {
          const double a = part.total_lux_per_lm(static_cast<Eigen::Index>(g), l);
          const double b = whole.total_lux_per_lm(floor[g], l);
          if (exact_same) {
            ASSERT_NEAR(a, b, 1e-12 * b) << "floor patch " << floor[g];
          }
          worst = std::max(worst, std::abs(a / b - 1.0));
        }
      EXPECT_LT(worst, 0.03) << "hit_direct_light against the full direct light";  // measured 1.1 %
    }
}

}  // namespace
}  // namespace ilp
