// The closed-form direct term against Howell's point-to-rectangle factor, and its
// shadow rays against blockers of known size.
#include "core/transport/direct_light.h"

#include <gtest/gtest.h>

#include <functional>
#include <numbers>
#include <optional>

#include "core/transport/ray_caster.h"
#include "core/scene/reference_scenes.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;

// An a x b emitting rectangle facing down at height c, corner above the origin.
Scene rectangle_above_origin(double a, double b, double c) {
  return reference::make_quad_scene({{"emitter", V(0, 0, c), V(0, b, c), V(a, b, c), V(a, 0, c)}}, 0.0);
}

TEST(DirectLight, PointToTriangleFormFactorsSumToTheRectangleClosedForm) {
  for (double c : {0.25, 1.0, 3.0}) {
    const Scene scene = rectangle_above_origin(1.0, 0.5, c);
    double sum = 0.0;
    for (const Patch& p : scene.patches) sum += point_to_triangle_form_factor(V::Zero(), V::UnitZ(), p);
    EXPECT_NEAR(sum, reference::point_to_corner_rectangle_form_factor(1.0, 0.5, c), 1e-12) << "height " << c;
  }
}

TEST(DirectLight, ClipsToTheReceiversHemisphereAndIgnoresTheEmittersBack) {
  const Scene scene = rectangle_above_origin(1.0, 1.0, 1.0);  // [0, 1] x [0, 1] at z = 1, facing down
  double facing_away = 0.0, above_emitter = 0.0, tilted = 0.0;
  for (const Patch& p : scene.patches) {
    facing_away += point_to_triangle_form_factor(V::Zero(), -V::UnitZ(), p);
    above_emitter += point_to_triangle_form_factor(V(0.5, 0.5, 2.0), V::UnitZ(), p);  // sees its back
    // A vertical receiver at x = 0.5 facing +x sees only the half x > 0.5.
    tilted += point_to_triangle_form_factor(V(0.5, 0.0, 0.0), V::UnitX(), p);
  }
  EXPECT_EQ(facing_away, 0.0);
  EXPECT_EQ(above_emitter, 0.0);
  // Independent value: (1/pi) * integral over the half of cos1 cos2 / r^2, where from
  // (0.5, 0, 0) to (x, y, 1): cos1 = (x - 0.5) / r, cos2 = 1 / r. Midpoint rule.
  constexpr int kCells = 1000;
  double integral = 0.0;
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) {
      const double dx = 0.5 * (i + 0.5) / kCells, y = (j + 0.5) / kCells;
      const double r2 = dx * dx + y * y + 1.0;
      integral += dx / (r2 * r2) * (0.5 / kCells) * (1.0 / kCells);
    }
  EXPECT_NEAR(tilted, integral / std::numbers::pi, 1e-6);
}

// A luminaire's light at the given points, lux per lm.
Eigen::VectorXd lux_at(const Scene& scene, const RayCaster& caster, const std::vector<ReceiverPoint>& points,
                       const DirectLightOptions& options = {}) {
  const std::vector<int> surfaces = luminaire_surfaces(scene);
  return compute_luminaire_light_at_points(scene, caster, points, surfaces, options).lux_per_lm.col(0);
}

// Unoccluded Lambertian light at x from the luminaire's opening, lux per lm: Lambert's
// closed form over its patches divided by its area.
double closed_form_lux_per_lm(const Scene& scene, const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
  double ff = 0.0, area = 0.0;
  for (const Patch& p : scene.patches)
    if (scene.surfaces[p.surface].is_luminaire()) {
      ff += point_to_triangle_form_factor(x, n, p);
      area += p.area_m2;
    }
  return ff / area;
}

// A distribution given by a function, for tests (not recognised as Lambertian, so the
// direct light takes the point-source path).
class FunctionDistribution final : public IntensityDistribution {
 public:
  explicit FunctionDistribution(std::function<double(const Eigen::Vector3d&)> f) : f_(std::move(f)) {}
  double cd_per_lm(const Eigen::Vector3d& d) const override { return f_(d); }
  std::string key() const override { return "function"; }

 private:
  std::function<double(const Eigen::Vector3d&)> f_;
};

LuminaireType typed(double length_m, double width_m, std::function<double(const Eigen::Vector3d&)> f) {
  LuminaireType t = LuminaireType::square_lambertian(length_m);
  t.width_m = width_m;
  t.name = "test";
  t.distribution = std::make_shared<FunctionDistribution>(std::move(f));
  return t;
}

Scene floor_scene() {
  return reference::make_quad_scene({{"floor", V(-10, -10, 0), V(10, -10, 0), V(10, 10, 0), V(-10, 10, 0)}}, 0.0);
}

TEST(DirectLight, CoplanarPointsIncludingTheOpeningItselfReceiveNothing) {
  Scene scene = floor_scene();
  add_square_luminaire(scene, "panel", V(100, 200, 3), 2.0, 1000.0);
  const RayCaster caster(scene);
  std::vector<ReceiverPoint> points;
  for (double dx : {0.0, 0.5, 3.0}) points.push_back({V(100 + dx, 200, 3), V::UnitZ()});
  EXPECT_EQ(lux_at(scene, caster, points).cwiseAbs().maxCoeff(), 0.0);
}

TEST(DirectLight, PatchToSquareMatchesParallelPlatesClosedForm) {
  // Receiver: unit square at z = 0 facing up; luminaire: unit square at z = 1 facing down.
  Scene scene = reference::make_quad_scene({{"receiver", V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)}}, 0.0);
  add_square_luminaire(scene, "emitter", V(0.5, 0.5, 1), 1.0, 1.0);
  const RayCaster caster(scene);
  DirectLightOptions options;
  options.receiver_points = 256;
  const auto receivers = reference::patches_of(scene, "receiver");
  const LuminaireLight light = compute_luminaire_light(scene, caster, receivers, luminaire_surfaces(scene), options);
  double weighted = 0.0, ff = 0.0, area = 0.0;
  for (std::size_t r = 0; r < receivers.size(); ++r) {
    weighted += scene.patches[receivers[r]].area_m2 * light.lux_per_lm(static_cast<Eigen::Index>(r), 0);
    ff += scene.patches[receivers[r]].area_m2 * light.form_factor(static_cast<Eigen::Index>(r), 0);
    area += scene.patches[receivers[r]].area_m2;
  }
  // Only the quadrature over receiver points is approximate: no rays are blocked.
  // Lambertian: lux per lm x opening area (1 m2) is the form factor (reciprocity).
  EXPECT_NEAR(weighted / area, 0.199825, 2e-3);
  EXPECT_NEAR(ff / area, 0.199825, 2e-3);
}

// A small receiver under a unit luminaire; a blocker at z = 0.5 whose edge is at x1.
Scene blocked_scene(std::optional<double> blocker_x1) {
  std::vector<reference::QuadSpec> quads = {{"receiver", V(0.49, 0.49, 0), V(0.51, 0.49, 0), V(0.51, 0.51, 0), V(0.49, 0.51, 0)}};
  if (blocker_x1) quads.push_back({"blocker", V(-1, -1, 0.5), V(*blocker_x1, -1, 0.5), V(*blocker_x1, 2, 0.5), V(-1, 2, 0.5)});
  Scene scene = reference::make_quad_scene(quads, 0.0);
  add_square_luminaire(scene, "emitter", V(0.5, 0.5, 1), 1.0, 1.0);
  return scene;
}

TEST(DirectLight, ShadowRaysSeeBlockersOfKnownSize) {
  DirectLightOptions options;
  options.receiver_points = 4;
  options.shadow_rays = 256;
  auto direct = [&](const Scene& scene) {
    const RayCaster caster(scene);
    const auto receivers = reference::patches_of(scene, "receiver");
    return compute_luminaire_light(scene, caster, receivers, luminaire_surfaces(scene), options).lux_per_lm.sum();
  };
  EXPECT_EQ(direct(blocked_scene(2.0)), 0.0);
  // Blocker edge at x = 0.5 straight above the receiver: the rays to x < 0.5 are
  // blocked; by symmetry that half sends half the light.
  EXPECT_NEAR(direct(blocked_scene(0.5)) / direct(blocked_scene(std::nullopt)), 0.5, 0.03);
}

TEST(DirectLight, APenumbraIsWeightedByTheLightOfEachPartNotByItsArea) {
  // A point at the origin; a 2 x 2 luminaire at z = 1 over x in [0, 2]; a blocker
  // hides the part x < 1 (the nearer, brighter half). Exact: the closed form of the
  // far half, a 1 x 2 rectangle. Weighting by area would give half the whole.
  Scene scene = reference::make_quad_scene(
      {{"blocker", V(-1, -2, 0.5), V(0.5, -2, 0.5), V(0.5, 2, 0.5), V(-1, 2, 0.5)}}, 0.0);
  add_square_luminaire(scene, "panel", V(1, 0, 1), 2.0, 1.0);
  const RayCaster caster(scene);
  DirectLightOptions options;
  options.shadow_rays = 1024;
  const double lux = lux_at(scene, caster, {{V::Zero(), V::UnitZ()}}, options)[0];
  // The far half x in [1, 2], y in [-1, 1], at height 1: two corner rectangles minus two.
  const auto corner = reference::point_to_corner_rectangle_form_factor;
  const double far_half = 2.0 * (corner(2.0, 1.0, 1.0) - corner(1.0, 1.0, 1.0));
  const double whole = 2.0 * corner(2.0, 1.0, 1.0);
  EXPECT_NEAR(lux * 4.0, far_half, 0.02 * far_half);
  EXPECT_GT(std::abs(0.5 * whole - far_half), 0.1 * far_half);  // the area weighting would fail
}

TEST(DirectLight, AFaceWhosePlaneCutsTheLuminaireIsNotShadedByItself) {
  // A vertical board in the plane x = 0 facing +x passes through the centre of a
  // 0.6 m panel at z = 2.8. Rays from the board toward the half x < 0 would strike the
  // board itself; they carry no light to it and must not count as shadow.
  Scene scene = reference::make_quad_scene({{"board", V(0, -1, 0), V(0, 1, 0), V(0, 1, 3.5), V(0, -1, 3.5)}}, 0.0);
  add_square_luminaire(scene, "panel", V(0, 0, 2.8), 0.6, 1.0);
  // The quad's winding decides its facing; the points below face +x either way.
  const RayCaster caster(scene);
  std::vector<ReceiverPoint> points;
  for (double z : {0.5, 1.5, 2.5, 2.75}) points.push_back({V(0, 0.1, z), V::UnitX()});
  const Eigen::VectorXd lux = lux_at(scene, caster, points);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double exact = closed_form_lux_per_lm(scene, points[k].position_m, points[k].normal);
    ASSERT_GT(exact, 0.0);
    EXPECT_NEAR(lux[static_cast<Eigen::Index>(k)], exact, 1e-12 * exact) << "z " << points[k].position_m.z();
  }
}

TEST(DirectLight, APointSourceFollowsTheInverseSquareCosineCubedLaw) {
  // A 1 mm opening with an asymmetric distribution: E = I(C, gamma) cos^3(gamma) / h^2.
  auto intensity = [](const Eigen::Vector3d& d) {
    const double c = std::atan2(d.y(), d.x());
    return d.z() < 0.0 ? (-d.z()) * (1.0 + 0.5 * std::cos(2.0 * c)) * (1.0 + 0.3 * std::cos(c)) / std::numbers::pi : 0.0;
  };
  Scene scene = floor_scene();
  const double h = 2.5;
  add_luminaire(scene, "spot", typed(0.001, 0.001, intensity), {V(0, 0, h), 0.0}, 1000.0);
  const RayCaster caster(scene);
  std::vector<ReceiverPoint> points;
  for (const V& p : {V(0, 0, 0), V(1, 0, 0), V(0, 1.5, 0), V(-2, -1, 0), V(3, 3, 0)}) points.push_back({p, V::UnitZ()});
  const Eigen::VectorXd lux = lux_at(scene, caster, points);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const V d = (points[k].position_m - V(0, 0, h)).normalized();
    const double cos_gamma = -d.z();
    const double expected = intensity(d) * std::pow(cos_gamma, 3) / (h * h);
    EXPECT_NEAR(lux[static_cast<Eigen::Index>(k)], expected, 5e-3 * expected) << points[k].position_m.transpose();
  }
}

TEST(DirectLight, RotatingAnAsymmetricLuminaireRotatesItsPattern) {
  auto intensity = [](const Eigen::Vector3d& d) {
    return d.z() < 0.0 ? (-d.z()) * (1.2 + std::tanh(3.0 * d.x())) / std::numbers::pi : 0.0;  // throws toward +x
  };
  const LuminaireType type = typed(1.2, 0.3, intensity);
  std::vector<ReceiverPoint> points, rotated;
  for (const V& p : {V(1, 0.2, 0), V(-1, 0.5, 0), V(0.3, -2, 0), V(2, 2, 0)}) {
    points.push_back({p, V::UnitZ()});
    rotated.push_back({V(-p.y(), p.x(), 0), V::UnitZ()});  // p turned 90 degrees counter-clockwise
  }
  Scene a = floor_scene(), b = floor_scene();
  add_luminaire(a, "L", type, {V(0, 0, 2.8), 0.0}, 1.0);
  add_luminaire(b, "L", type, {V(0, 0, 2.8), 90.0}, 1.0);
  const RayCaster ca(a), cb(b);
  const Eigen::VectorXd ea = lux_at(a, ca, points), eb = lux_at(b, cb, rotated);
  EXPECT_GT(ea[0], 1.5 * ea[1]);  // the pattern is asymmetric
  for (Eigen::Index k = 0; k < ea.size(); ++k) EXPECT_NEAR(eb[k], ea[k], 1e-9 * ea[k]);
}

TEST(DirectLight, ALambertianDistributionByPointSourcesMatchesTheClosedFormBeyondOnePanelSize) {
  auto lambert = [](const Eigen::Vector3d& d) { return std::max(0.0, -d.z()) / std::numbers::pi; };
  Scene scene = floor_scene();
  const double size = 0.6;
  add_luminaire(scene, "L", typed(size, size, lambert), {V(0, 0, 2.8), 30.0}, 1.0);
  const RayCaster caster(scene);
  std::vector<ReceiverPoint> points;
  // Floor points, and points on vertical and tilted faces one panel size away and more.
  for (double x : {0.0, 0.6, 1.5, 4.0}) points.push_back({V(x, 0.2, 0), V::UnitZ()});
  for (double z : {0.5, 2.0, 2.8}) points.push_back({V(0.9, 0, z), V(-1, 0, 0)});
  points.push_back({V(0, 0, 2.2), V::UnitZ()});  // 0.6 m straight below
  points.push_back({V(0.7, 0.4, 2.4), V(-1, 0, 1).normalized()});
  const Eigen::VectorXd lux = lux_at(scene, caster, points);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double exact = closed_form_lux_per_lm(scene, points[k].position_m, points[k].normal);
    EXPECT_NEAR(lux[static_cast<Eigen::Index>(k)], exact, 0.01 * exact) << points[k].position_m.transpose();
  }
}

TEST(DirectLight, ADiscOpeningUnderItsAxisMatchesTheDiscClosedForm) {
  // E = pi L R^2 / (R^2 + h^2) with L = 1 / (pi A): lux per lm = R^2 / (A (R^2 + h^2)).
  Scene scene = floor_scene();
  LuminaireType disc = LuminaireType::square_lambertian(1.0);
  disc.shape = OutlineShape::disc;
  add_luminaire(scene, "disc", disc, {V(0, 0, 1.0), 0.0}, 1.0);
  const RayCaster caster(scene);
  const double R = 0.5, A = std::numbers::pi * R * R;
  for (double h : {0.25, 1.0}) {
    const double lux = lux_at(scene, caster, {{V(0, 0, 1.0 - h), V::UnitZ()}})[0];
    EXPECT_NEAR(lux, R * R / (A * (R * R + h * h)), 2e-3 * lux) << "h " << h;  // the 24-gon of equal area
  }
}

// Issue 21: a point that sees a small part of a panel, or has a small part of it
// hidden, gets that part's light. An opaque sheet at z = 1 over x > c hides, from the
// point (px, py, 0), the part of a panel at z = 2 with x > 2c - px (similar triangles).
struct StripCase {
  const char* name;
  double rotation_deg;
  double edge_x;     // the panel's parts with x > edge_x are hidden
};

// The Lambertian light per lm at (px, py, 0) facing up from the visible part (x <
// edge_x) of a side x side panel centred at (0, 0, h), rotated by rotation_deg about z:
// a midpoint rule over cells of side / kCells (independent of Lambert's formula).
double visible_panel_lux_per_lm(double px, double py, double h, double side, double rotation_deg, double edge_x) {
  constexpr int kCells = 2000;
  const double c = std::cos(rotation_deg * std::numbers::pi / 180.0), s = std::sin(rotation_deg * std::numbers::pi / 180.0);
  const double cell = side / kCells;
  double sum = 0.0;
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) {
      const double lu = -0.5 * side + (i + 0.5) * cell, lv = -0.5 * side + (j + 0.5) * cell;
      const double x = c * lu - s * lv, y = s * lu + c * lv;
      if (x > edge_x) continue;
      const double dx = x - px, dy = y - py, r2 = dx * dx + dy * dy + h * h;
      sum += h * h / (r2 * r2) * cell * cell;  // cos at the point x cos at the panel / r^2
    }
  return sum / std::numbers::pi / (side * side);  // E = M F, M = 1 lm / area
}

TEST(DirectLight, APointSeeingOrMissingFivePercentOfAPanelGetsTheVisiblePartsLight) {
  constexpr double kSide = 0.6, kHeight = 2.0;
  const double px = 0.35, py = -0.2;
  for (const StripCase& k : {StripCase{"5 % seen", 0.0, -0.27}, StripCase{"5 % hidden", 0.0, 0.27},
                             StripCase{"5 % seen, rotated 30 deg", 30.0, -0.285}, StripCase{"5 % hidden, rotated 30 deg", 30.0, 0.285}}) {
    const double c = 0.5 * (k.edge_x + px);  // the sheet's edge
    Scene scene = reference::make_quad_scene({{"sheet", V(c, -5, 1), V(5, -5, 1), V(5, 5, 1), V(c, 5, 1)}}, 0.0);
    LuminaireType panel = LuminaireType::square_lambertian(kSide);
    add_luminaire(scene, "panel", panel, {V(0, 0, kHeight), k.rotation_deg}, 1.0);
    const RayCaster caster(scene);
    const double lux = lux_at(scene, caster, {{V(px, py, 0), V::UnitZ()}})[0];
    const double exact = visible_panel_lux_per_lm(px, py, kHeight, kSide, k.rotation_deg, k.edge_x);
    const double whole = visible_panel_lux_per_lm(px, py, kHeight, kSide, k.rotation_deg, 1.0);
    ASSERT_GT(exact, 0.0);
    EXPECT_NEAR(lux, exact, 0.01 * exact) << k.name << ": the visible part's share " << exact / whole;
  }
}

TEST(DirectLight, ShadowRaysWhereAPanelIsWhollySeenAreTheGridsVerticesOnly) {
  // No occluder: 3 x 3 vertices of the default grid (8 rays asked), nothing refined.
  Scene scene = floor_scene();
  add_square_luminaire(scene, "panel", V(0, 0, 2), 0.6, 1.0);
  const RayCaster caster(scene);
  const std::vector<ReceiverPoint> point{{V(0.2, 0.1, 0.8), V::UnitZ()}};
  const LuminaireLight light =
      compute_luminaire_light_at_points(scene, caster, point, luminaire_surfaces(scene), DirectLightOptions{});
  EXPECT_EQ(light.shadow_rays_cast, 9u);
  EXPECT_NEAR(light.lux_per_lm(0, 0), closed_form_lux_per_lm(scene, V(0.2, 0.1, 0.8), V::UnitZ()), 1e-15);
}

TEST(DirectLight, PenumbraLightIsTheSameForAnyThreadCount) {
  // Points along a line under a sheet's edge: every one in a penumbra.
  Scene scene = reference::make_quad_scene({{"sheet", V(0.0, -5, 1), V(5, -5, 1), V(5, 5, 1), V(0.0, 5, 1)}}, 0.0);
  add_square_luminaire(scene, "panel", V(0, 0, 2), 0.6, 1.0);
  const RayCaster caster(scene);
  std::vector<ReceiverPoint> points;
  for (int k = 0; k < 200; ++k) points.push_back({V(-0.3 + 0.003 * k, 0.001 * k, 0), V::UnitZ()});
  DirectLightOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const LuminaireLight a = compute_luminaire_light_at_points(scene, caster, points, luminaire_surfaces(scene), one);
  const LuminaireLight b = compute_luminaire_light_at_points(scene, caster, points, luminaire_surfaces(scene), two);
  EXPECT_EQ(a.lux_per_lm, b.lux_per_lm);
  EXPECT_EQ(a.shadow_rays_cast, b.shadow_rays_cast);
  EXPECT_GT(a.shadow_rays_cast, 9u * points.size()) << "the penumbra is refined";
}

}  // namespace
}  // namespace ilp
