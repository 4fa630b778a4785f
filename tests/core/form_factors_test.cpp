// Form-factor rows against closed forms, reciprocity, closure and determinism.
#include "core/transport/form_factors.h"
#include "core/transport/row_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <utility>
#include <vector>

#include "core/transport/ray_caster.h"
#include "core/scene/reference_scenes.h"

namespace ilp {
namespace {

using reference::QuadSpec;
using V = Eigen::Vector3d;

// Tolerance for a surface-to-surface form factor F estimated from `rays` rays:
// 3 standard deviations of the binomial estimate with independent rays. Our
// low-discrepancy rays measured an RMS error of 0.2 to 0.7 sigma and a worst of
// 1.5 sigma (20 seeds, 64 to 65536 rays; build/bench/form_factor_accuracy,
// docs/foundation.md), so a bias of a sigma or two is caught at 65536 rays.
double mc_tolerance(double F, double rays) { return 3.0 * std::sqrt(F * (1.0 - F) / rays); }

FormFactorRows all_rows(const Scene& scene, int rays, std::uint64_t seed = 1, int threads = 0) {
  const RayCaster caster(scene, threads);
  FormFactorOptions options;
  options.rays_per_patch = rays;
  options.seed = seed;
  options.threads = threads;
  return compute_form_factor_rows(scene, caster, scene.all_patches(), options);
}

Scene parallel_squares(double side, double separation) {
  return reference::make_quad_scene({{"bottom", V(0, 0, 0), V(side, 0, 0), V(side, side, 0), V(0, side, 0)},
                                {"top", V(0, 0, separation), V(0, side, separation), V(side, side, separation),
                                 V(side, 0, separation)}},
                               0.0);
}

TEST(FormFactor, ParallelSquaresMatchClosedFormWithinToleranceThatShrinksWithRays) {
  for (double separation : {0.5, 1.0, 2.0}) {
    const double exact = reference::parallel_rectangles_form_factor(1.0, 1.0, separation);
    const Scene scene = parallel_squares(1.0, separation);
    const auto source = reference::patches_of(scene, "bottom");
    double previous_tolerance = 1.0;
    for (int rays : {64, 1024, 16384, 65536}) {
      const double estimate = surface_form_factor(scene, all_rows(scene, rays), "bottom", "top");
      const double tolerance = mc_tolerance(exact, static_cast<double>(rays) * source.size());
      EXPECT_LT(tolerance, previous_tolerance);
      previous_tolerance = tolerance;
      EXPECT_NEAR(estimate, exact, tolerance) << "separation " << separation << " m, " << rays << " rays per patch";
    }
  }
  EXPECT_NEAR(reference::parallel_rectangles_form_factor(1.0, 1.0, 1.0), 0.199825, 1e-6);  // published value
}

TEST(FormFactor, PerpendicularRectanglesSharingAnEdgeMatchClosedForm) {
  EXPECT_NEAR(reference::perpendicular_rectangles_form_factor(1.0, 1.0, 1.0), 0.200044, 1e-6);  // published value
  struct Case { double l, w, h; };
  for (const Case& c : {Case{1.0, 1.0, 1.0}, Case{1.0, 0.5, 2.0}, Case{2.0, 1.0, 0.5}}) {
    // "from" lies in z = 0 (facing up), "to" in x = 0 (facing +x); shared edge along y.
    const Scene scene = reference::make_quad_scene(
        {{"from", V(0, 0, 0), V(c.w, 0, 0), V(c.w, c.l, 0), V(0, c.l, 0)},
         {"to", V(0, 0, 0), V(0, c.l, 0), V(0, c.l, c.h), V(0, 0, c.h)}},
        0.0);
    const double exact = reference::perpendicular_rectangles_form_factor(c.l, c.w, c.h);
    const int rays = 65536;
    const double estimate = surface_form_factor(scene, all_rows(scene, rays), "from", "to");
    EXPECT_NEAR(estimate, exact, mc_tolerance(exact, 2.0 * rays)) << "l " << c.l << " w " << c.w << " h " << c.h;
  }
}

TEST(FormFactor, ReciprocityHoldsOnRandomPairs) {
  const Scene scene = reference::make_closed_box(V::Zero(), V(2.0, 1.5, 1.0), 0.5, 0.5);
  const int rays = 8192;
  const FormFactorRows rows = all_rows(scene, rays);
  const Eigen::MatrixXd F(rows.F);  // small: dense is fine here
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(scene.patches.size()) - 1);
  int checked = 0;
  for (int attempt = 0; attempt < 2000 && checked < 200; ++attempt) {
    const int i = pick(rng), j = pick(rng);
    if (F(i, j) < 0.01 || F(j, i) < 0.01) continue;  // noise dominates tiny entries
    const double Ai = scene.patches[i].area_m2, Aj = scene.patches[j].area_m2;
    // Each side is an independent binomial estimate: combine their deviations.
    const double sigma = std::hypot(Ai * std::sqrt(F(i, j) * (1 - F(i, j)) / rays),
                                    Aj * std::sqrt(F(j, i) * (1 - F(j, i)) / rays));
    EXPECT_NEAR(Ai * F(i, j), Aj * F(j, i), 4.0 * sigma) << "patches " << i << " and " << j;
    ++checked;
  }
  EXPECT_GE(checked, 100);
}

TEST(FormFactor, ClosedBoxRowsSumToOne) {
  const Scene scene = reference::make_closed_box(V::Zero(), V(3.0, 2.0, 1.0), 0.5, 0.4);
  const FormFactorRows rows = all_rows(scene, 512);
  for (Eigen::Index r = 0; r < rows.F.rows(); ++r) {
    EXPECT_NEAR(rows.F.row(r).sum(), 1.0, 1e-12) << "row " << r;
    EXPECT_EQ(rows.escaped_fraction[r], 0.0) << "row " << r;
    EXPECT_EQ(rows.back_hit_fraction[r], 0.0) << "row " << r;
    EXPECT_EQ(rows.F.coeff(r, r), 0.0) << "a planar patch cannot see itself: row " << r;
  }
}

// The same box, far from the origin and modelled in millimetres, or the size of a
// shoebox: the ray offset follows the scene, so nothing leaks or self-intersects.
TEST(FormFactor, ClosedBoxStaysClosedAtAnyScaleAndPosition) {
  struct Case { V origin, size; };
  for (const Case& c : {Case{V(1e5, -2e5, 3e4), V(3000.0, 2000.0, 1000.0)}, Case{V(100.0, 100.0, 100.0), V(3, 2, 1)},
                       Case{V(0, 0, 0), V(0.03, 0.02, 0.01)}}) {
    const Scene scene = reference::make_closed_box(c.origin, c.size, 0.5, c.size.maxCoeff() / 6.0);
    const FormFactorRows rows = all_rows(scene, 256);
    double worst = 0.0;
    for (Eigen::Index r = 0; r < rows.F.rows(); ++r) {
      worst = std::max(worst, std::abs(rows.F.row(r).sum() - 1.0));
      EXPECT_EQ(rows.F.coeff(r, r), 0.0);
    }
    EXPECT_LT(worst, 1.0 / 256 + 1e-12) << "origin " << c.origin.transpose() << " size " << c.size.transpose();
    // The floor-to-ceiling factor does not depend on where the box is or its units.
    const double exact = reference::parallel_rectangles_form_factor(3.0, 2.0, 1.0);
    const auto floor_rows = reference::patches_of(scene, "floor");
    EXPECT_NEAR(surface_form_factor(scene, rows, "floor", "ceiling"), exact,
                mc_tolerance(exact, 256.0 * floor_rows.size()));
  }
}

TEST(FormFactor, SameSeedGivesBitIdenticalRowsWithOneAndTwoThreads) {
  const Scene scene = reference::make_closed_box(V::Zero(), V(3.0, 2.0, 1.0), 0.5, 0.3);
  const FormFactorRows one = all_rows(scene, 128, 42, 1);
  const FormFactorRows two = all_rows(scene, 128, 42, 2);
  ASSERT_EQ(one.F.nonZeros(), two.F.nonZeros());
  for (Eigen::Index k = 0; k < one.F.nonZeros(); ++k) {
    ASSERT_EQ(one.F.innerIndexPtr()[k], two.F.innerIndexPtr()[k]) << "entry " << k;
    ASSERT_EQ(one.F.valuePtr()[k], two.F.valuePtr()[k]) << "entry " << k;
  }
  for (Eigen::Index r = 0; r <= one.F.rows(); ++r) ASSERT_EQ(one.F.outerIndexPtr()[r], two.F.outerIndexPtr()[r]);
  // A different seed draws different rays: the comparison above is not vacuous.
  const FormFactorRows other = all_rows(scene, 128, 43, 2);
  EXPECT_NE(Eigen::MatrixXd(one.F), Eigen::MatrixXd(other.F));
}

TEST(FormFactor, RowsForChosenPatchesEqualThoseRowsOfTheFullMatrix) {
  const Scene scene = reference::make_closed_box(V::Zero(), V(2.0, 2.0, 2.0), 0.5, 0.5);
  const RayCaster caster(scene);
  FormFactorOptions options;
  options.rays_per_patch = 64;
  const FormFactorRows full = compute_form_factor_rows(scene, caster, scene.all_patches(), options);
  const std::vector<int> chosen = {5, 0, 17};
  const FormFactorRows some = compute_form_factor_rows(scene, caster, chosen, options);
  ASSERT_EQ(some.F.rows(), 3);
  for (int r = 0; r < 3; ++r)
    EXPECT_EQ(Eigen::RowVectorXd(some.F.row(r)), Eigen::RowVectorXd(full.F.row(chosen[r]))) << "patch " << chosen[r];
}

TEST(FormFactor, OpenSceneReportsEscapedLight) {
  const Scene scene = parallel_squares(1.0, 1.0);
  const FormFactorRows rows = all_rows(scene, 4096);
  for (Eigen::Index r = 0; r < rows.F.rows(); ++r)
    EXPECT_NEAR(rows.F.row(r).sum() + rows.escaped_fraction[r] + rows.back_hit_fraction[r], 1.0, 1e-12);
  EXPECT_GT(rows.escaped_fraction.mean(), 0.75);  // 1 - 0.1998
}

TEST(FormFactor, RejectsInvalidOptions) {
  const Scene scene = parallel_squares(1.0, 1.0);
  const RayCaster caster(scene);
  FormFactorOptions options;
  options.rays_per_patch = 0;
  EXPECT_THROW(compute_form_factor_rows(scene, caster, scene.all_patches(), options), std::invalid_argument);
  options.rays_per_patch = 16;
  const std::vector<int> outside = {0, static_cast<int>(scene.patches.size())};
  EXPECT_THROW(compute_form_factor_rows(scene, caster, outside, options), std::invalid_argument);
  EXPECT_EQ(compute_form_factor_rows(scene, caster, {}, options).F.rows(), 0);
}

}  // namespace
}  // namespace ilp

namespace ilp {
namespace {

// Embree's flush-to-zero and denormals-are-zero modes stay with the rays: the thread
// that built the BVH and took part in casting (a TBB body runs on the caller's thread
// too) reads a subnormal number as such afterwards. Before, a product's file read after
// the first variant's operator (the same thread) saw its 1e-310 cd as 0.
TEST(RayCasterThreadModes, TheCallersFloatingPointModesAreRestored) {
  const Scene scene = reference::make_closed_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 1.0, 1.0), 0.5, 0.5);
  {
    const RayCaster caster(scene, 1);
    FormFactorOptions options;
    options.rays_per_patch = 16;
    options.threads = 1;
    (void)compute_form_factor_rows(scene, caster, scene.all_patches(), options);
  }
  volatile double tiny = std::strtod("1e-310", nullptr);
  EXPECT_GT(tiny, 0.0) << "flush-to-zero leaked to the caller's thread";
  volatile double half = tiny * 0.5;
  EXPECT_GT(half, 0.0);
}

}  // namespace
}  // namespace ilp

namespace ilp {
namespace {

// build_rows (core/transport/row_builder.h): a matrix written row by row from counts and a
// fill on several threads is the matrix the same entries give through Eigen's triplets,
// empty rows and a dense row included, on one thread or two.
TEST(BuildRows, GivesTheMatrixOfItsEntriesOnAnyThreadCount) {
  constexpr Eigen::Index kRows = 5000, kCols = 300;
  auto entries_of = [](Eigen::Index r) {
    std::vector<std::pair<int, double>> out;
    if (r % 7 == 3) return out;  // empty rows
    const int step = r == 11 ? 1 : 1 + static_cast<int>(r % 13);
    for (int c = static_cast<int>(r % 5); c < kCols; c += step) out.emplace_back(c, 0.25 + 1e-3 * static_cast<double>(r + c));
    return out;
  };
  std::vector<Eigen::Triplet<double>> triplets;
  for (Eigen::Index r = 0; r < kRows; ++r)
    for (const auto& [c, v] : entries_of(r)) triplets.emplace_back(static_cast<int>(r), c, v);
  SparseRows expected(kRows, kCols);
  expected.setFromTriplets(triplets.begin(), triplets.end());
  for (int threads : {1, 2}) {
    const SparseRows built = build_rows(kRows, kCols, threads, [&](Eigen::Index r, const auto& emit) {
      for (const auto& [c, v] : entries_of(r)) emit(c, v);
    });
    ASSERT_TRUE(built.isCompressed());
    ASSERT_EQ(built.nonZeros(), expected.nonZeros()) << threads << " threads";
    EXPECT_EQ(Eigen::MatrixXd(built), Eigen::MatrixXd(expected)) << threads << " threads";
    for (Eigen::Index r = 0; r <= kRows; ++r) ASSERT_EQ(built.outerIndexPtr()[r], expected.outerIndexPtr()[r]);
  }
  EXPECT_EQ(build_rows(0, 4, 2, [](Eigen::Index, const auto&) {}).nonZeros(), 0);
}

}  // namespace
}  // namespace ilp

namespace ilp {
namespace {

// Where the escaping rays go (EscapeBins, the room left for a sky's patches): a patch
// under an open sky sends its cosine-weighted rays within theta of the zenith with
// probability sin^2 theta (a closed form), every escaping ray lands in some bin when the
// bins cover the hemisphere, and a bin of -1 drops a ray from the bins, not from the row.
TEST(FormFactor, EscapingRaysAreBinnedByDirectionAsTheCosineLawSays) {
  const Scene sky = reference::make_quad_scene({{"roof", V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)}}, 0.0);
  const RayCaster caster(sky, 1);
  FormFactorOptions options;
  options.rays_per_patch = 4096;
  options.threads = 1;
  const double cos45 = std::sqrt(0.5);
  const EscapeBins halves{2, [&](const V& d) { return d.z() > cos45 ? 0 : 1; }};
  const std::vector<int> patches = sky.all_patches();
  const FormFactorRows rows = compute_form_factor_rows(sky, caster, patches, std::vector<int>(patches.size(), 4096),
                                                       options, {}, &halves);
  ASSERT_EQ(rows.escaped_by_bin.rows(), static_cast<Eigen::Index>(patches.size()));
  ASSERT_EQ(rows.escaped_by_bin.cols(), 2);
  for (Eigen::Index r = 0; r < rows.escaped_by_bin.rows(); ++r) {
    EXPECT_DOUBLE_EQ(rows.escaped_fraction[r], 1.0);  // nothing above a lone patch
    EXPECT_NEAR(rows.escaped_by_bin.coeff(r, 0) + rows.escaped_by_bin.coeff(r, 1), 1.0, 1e-12);
    EXPECT_NEAR(rows.escaped_by_bin.coeff(r, 0), 0.5, 0.01);  // sin^2(45 deg)
  }
  // A closed box lets nothing out: no bin gets a ray.
  const Scene box = reference::make_closed_box(V::Zero(), V(2, 2, 2), 0.5, 1.0);
  const RayCaster box_caster(box, 1);
  const std::vector<int> all = box.all_patches();
  const FormFactorRows closed = compute_form_factor_rows(box, box_caster, all, std::vector<int>(all.size(), 256),
                                                         options, {}, &halves);
  EXPECT_EQ(closed.escaped_by_bin.nonZeros(), 0);
  // Only the zenith bin kept: the rest escape still, outside every bin; the rows are the
  // same rays with or without bins.
  const EscapeBins zenith{1, [&](const V& d) { return d.z() > cos45 ? 0 : -1; }};
  const FormFactorRows some = compute_form_factor_rows(sky, caster, patches, std::vector<int>(patches.size(), 4096),
                                                       options, {}, &zenith);
  const FormFactorRows none = compute_form_factor_rows(sky, caster, patches, options);
  EXPECT_EQ(none.escaped_by_bin.size(), 0);
  for (Eigen::Index r = 0; r < some.escaped_by_bin.rows(); ++r) {
    EXPECT_DOUBLE_EQ(some.escaped_by_bin.coeff(r, 0), rows.escaped_by_bin.coeff(r, 0));
    EXPECT_DOUBLE_EQ(some.escaped_fraction[r], none.escaped_fraction[r]);
  }
}

}  // namespace
}  // namespace ilp
