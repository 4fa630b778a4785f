// Meshing along contact lines (core/scene/contact_cuts.h): the segments found where
// faces touch or cross, the patches cut along them, and the furnace that shows why.
#include "core/scene/contact_cuts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/exact/exact_solver.h"
#include "core/scene/reference_scenes.h"
#include "core/scene/scene.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;
using reference::QuadSpec;

// A box [x0, x1] x [y0, y1] x [0, h] standing on the floor: four sides, a top and a
// bottom in the floor's plane, faces pointing out.
std::vector<QuadSpec> box_on_floor(double x0, double y0, double x1, double y1, double h, double rho) {
  const V r = V::Constant(rho);
  return {{"box_top", V(x0, y0, h), V(x1, y0, h), V(x1, y1, h), V(x0, y1, h), r},
          {"box_bottom", V(x0, y0, 0), V(x0, y1, 0), V(x1, y1, 0), V(x1, y0, 0), r},
          {"box_sides", V(x0, y0, 0), V(x1, y0, 0), V(x1, y0, h), V(x0, y0, h), r},
          {"box_sides", V(x1, y0, 0), V(x1, y1, 0), V(x1, y1, h), V(x1, y0, h), r},
          {"box_sides", V(x1, y1, 0), V(x0, y1, 0), V(x0, y1, h), V(x1, y1, h), r},
          {"box_sides", V(x0, y1, 0), V(x0, y0, 0), V(x0, y0, h), V(x0, y1, h), r}};
}

// A closed 4 x 3 x 2.5 m room, faces pointing in, every reflectance rho.
std::vector<QuadSpec> room(double rho) {
  const V r = V::Constant(rho);
  const double X = 4, Y = 3, Z = 2.5;
  return {{"floor", V(0, 0, 0), V(X, 0, 0), V(X, Y, 0), V(0, Y, 0), r},
          {"ceiling", V(0, 0, Z), V(0, Y, Z), V(X, Y, Z), V(X, 0, Z), r},
          {"walls", V(0, 0, 0), V(0, Y, 0), V(0, Y, Z), V(0, 0, Z), r},
          {"walls", V(X, 0, 0), V(X, 0, Z), V(X, Y, Z), V(X, Y, 0), r},
          {"walls", V(0, 0, 0), V(0, 0, Z), V(X, 0, Z), V(X, 0, 0), r},
          {"walls", V(0, Y, 0), V(X, Y, 0), V(X, Y, Z), V(0, Y, Z), r}};
}

Scene scene_of(const std::vector<QuadSpec>& quads, double edge_m, bool cut) {
  SceneOptions options;
  options.max_patch_edge_m = edge_m;
  options.cut_at_contacts = cut;
  return reference::make_quad_scene(quads, options);
}

// The box's footprint, off the 0.25 m patch grid so that uniform patches straddle it.
constexpr double kX0 = 1.13, kY0 = 0.71, kX1 = 2.07, kY1 = 1.59, kH = 0.77;

bool under_box(const V& p) { return p.z() < 1e-9 && p.x() > kX0 && p.x() < kX1 && p.y() > kY0 && p.y() < kY1; }

std::vector<QuadSpec> room_with_box(double rho) {
  std::vector<QuadSpec> quads = room(rho);
  for (const QuadSpec& q : box_on_floor(kX0, kY0, kX1, kY1, kH, rho)) quads.push_back(q);
  return quads;
}

TEST(ContactCuts, NoFloorPatchLiesHalfUnderABoxStandingOnIt) {
  for (bool cut : {true, false}) {
    const Scene scene = scene_of(room_with_box(0.5), 0.25, cut);
    const int floor = scene.find_surface("floor");
    int straddling = 0;
    double area = 0.0;
    for (const Patch& p : scene.patches) {
      if (p.surface != floor) continue;
      area += p.area_m2;
      int inside = 0, outside = 0;
      for (const V& v : p.vertices_m) {
        const double margin = std::min({v.x() - kX0, kX1 - v.x(), v.y() - kY0, kY1 - v.y()});
        inside += margin > 1e-9;
        outside += margin < -1e-9;
      }
      straddling += inside > 0 && outside > 0;
    }
    EXPECT_NEAR(area, 12.0, 1e-9) << "cutting keeps the floor's area";
    if (cut) EXPECT_EQ(straddling, 0);
    else EXPECT_GT(straddling, 0) << "the footprint is off the patch grid, so uniform patches straddle it";
  }
}

TEST(ContactCuts, FacesMeetingOnlyAtTheirEdgesAreNotCut) {
  // A closed room: every face meets its neighbours at shared edges only.
  const Scene cut = scene_of(room(0.5), 0.5, true), plain = scene_of(room(0.5), 0.5, false);
  EXPECT_EQ(cut.patches.size(), plain.patches.size());
  EXPECT_EQ(cut.stats.contact_segments, 0u);
}

TEST(ContactCuts, APartitionThroughTheFloorCutsItWhereItCrosses) {
  // A vertical partition x = 1.37 from below the floor to 2 m, across part of the floor.
  std::vector<QuadSpec> quads = {{"floor", V(0, 0, 0), V(4, 0, 0), V(4, 3, 0), V(0, 3, 0)},
                                 {"partition", V(1.37, 0.5, -0.1), V(1.37, 2.21, -0.1), V(1.37, 2.21, 2), V(1.37, 0.5, 2)}};
  const Scene scene = scene_of(quads, 0.5, true);
  const int floor = scene.find_surface("floor");
  for (const Patch& p : scene.patches) {
    if (p.surface != floor) continue;
    // No floor patch along the partition's foot has points on both sides of it.
    double lo = 0.0, hi = 0.0;
    for (const V& v : p.vertices_m) {
      lo = std::min(lo, v.x() - 1.37);
      hi = std::max(hi, v.x() - 1.37);
    }
    const V c = p.centroid_m;
    if (c.y() > 0.5 && c.y() < 2.21) {
      EXPECT_FALSE(lo < -1e-9 && hi > 1e-9) << "patch at " << c.transpose();
    }
  }
}

TEST(ContactCuts, SegmentsAreTheFootprintOfABoxAndLieInTheFace) {
  const std::vector<Triangle3> floor = {{V(0, 0, 0), V(4, 0, 0), V(4, 3, 0)}, {V(0, 0, 0), V(4, 3, 0), V(0, 3, 0)}};
  std::vector<Triangle3> triangles = floor;
  // One side of a box standing on the floor (its bottom edge from (1, 1) to (2, 1)).
  triangles.push_back({V(1, 1, 0), V(2, 1, 0), V(2, 1, 1)});
  triangles.push_back({V(1, 1, 0), V(2, 1, 1), V(1, 1, 1)});
  const auto segments = contact_segments(triangles, {0, 0, 1, 1});
  ASSERT_EQ(segments.size(), 4u);
  double length = 0.0;
  for (int t = 0; t < 2; ++t)
    for (const ContactSegment& s : segments[static_cast<std::size_t>(t)]) {
      EXPECT_NEAR(s.a.z(), 0.0, 1e-12);
      EXPECT_NEAR(s.b.z(), 0.0, 1e-12);
      EXPECT_NEAR(s.a.y(), 1.0, 1e-12);
      length += (s.b - s.a).norm();
    }
  // The foot lies in the floor once (the side's other triangle touches it at a point
  // only), split between the floor's triangles where the diagonal y = 0.75 x crosses.
  EXPECT_NEAR(length, 1.0, 1e-9);
  EXPECT_TRUE(segments[2].empty() && segments[3].empty()) << "the side meets the floor along its own edge";
}

TEST(ContactCuts, CuttingAPatchKeepsItsAreaAndWinding) {
  const Triangle3 patch{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
  std::vector<Triangle3> pieces;
  // Two segments crossing inside the patch: a corner of a footprint.
  EXPECT_TRUE(cut_along_segments(patch, {{V(0.2, 0.3, 0), V(0.2, 5, 0)}, {V(0.2, 0.3, 0), V(5, 0.3, 0)}}, pieces));
  double area = 0.0;
  for (const Triangle3& t : pieces) {
    const V n = (t[1] - t[0]).cross(t[2] - t[0]);
    EXPECT_GT(n.z(), 0.0) << "wound as the patch";
    area += 0.5 * n.norm();
  }
  EXPECT_NEAR(area, 0.5, 1e-12);
  // Nothing passing through: the patch itself.
  pieces.clear();
  EXPECT_FALSE(cut_along_segments(patch, {{V(2, 2, 0), V(3, 2, 0)}, {V(0, 0, 0), V(1, 0, 0)}}, pieces));
  ASSERT_EQ(pieces.size(), 1u);
}

// Issue 21: a furnace (closed room, every face emitting E with reflectance rho) with a
// box on the floor. Every face the room's air touches has B = E / (1 - rho): each ray
// from it lands on another such face. A patch half under the box gathers half its
// rays from the box's inside (back faces, lost), so it and everything that sees it
// fall short: light is lost. Cut along the footprint, no patch is half under.
struct FurnaceShortfall {
  double near_box = 0.0;  // the largest relative shortfall of B within 0.5 m of the box
  double lost = 0.0;      // sum A (B0 - B) / sum A B0 over every patch the air touches
};

FurnaceShortfall furnace_shortfall(bool cut) {
  constexpr double kRho = 0.5, kE = 100.0, kB0 = kE / (1.0 - kRho);
  Scene scene = scene_of(room_with_box(kRho), 0.25, cut);
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) set_surface_exitance(scene, static_cast<int>(s), kE);
  ExactSolveOptions options;
  options.form_factors.rays_per_patch = 256;
  options.radiosity.relative_residual = 1e-12;
  const ExactSolution solution = solve_exact(scene, options);
  FurnaceShortfall out;
  double area = 0.0;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    if (under_box(p.centroid_m)) continue;  // hidden under the box, or the box's bottom
    const double b = solution.radiosity.radiosity_lm_per_m2(static_cast<Eigen::Index>(i), 0);
    const V c = p.centroid_m;
    if (c.x() > kX0 - 0.5 && c.x() < kX1 + 0.5 && c.y() > kY0 - 0.5 && c.y() < kY1 + 0.5 && c.z() < kH + 0.5)
      out.near_box = std::max(out.near_box, (kB0 - b) / kB0);
    out.lost += p.area_m2 * (kB0 - b);
    area += p.area_m2;
  }
  out.lost /= area * kB0;
  return out;
}

TEST(ContactCuts, AFurnaceWithABoxOnTheFloorLosesNoLight) {
  const FurnaceShortfall cut = furnace_shortfall(true), uniform = furnace_shortfall(false);
  // Cut: B = E / (1 - rho) at the box but for what a ray slipping through the crack of
  // the room's own corners takes from everyone (0.2 % of one ceiling patch, 1 ray of
  // its 256; seen from the box, 4.5e-6).
  EXPECT_LT(cut.near_box, 1e-5) << "B = E / (1 - rho) around the box";
  EXPECT_LT(std::abs(cut.lost), 1e-5);
  // Uniform patches straddling the footprint: a quarter short, and light lost.
  EXPECT_GT(uniform.near_box, 0.2);
  EXPECT_GT(uniform.lost, 20.0 * std::abs(cut.lost) + 1e-4) << "lost " << uniform.lost << " against " << cut.lost;
}

}  // namespace
}  // namespace ilp
