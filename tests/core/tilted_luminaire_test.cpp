// Real mounting (issue 19): a luminaire turned about the vertical and tilted (aimed),
// against closed forms the tests compute themselves: the intensity of a photometric
// web in the test's own rotated frame (C and gamma from the aim and the tilt axis, not
// from luminaire_rotation), a fine point-source sum over a tilted Lambertian emitter,
// the half-space of an opening facing sideways, and the same light with the scene
// turned the other way instead of the luminaire.
#include "core/light/luminaire.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <sstream>

#include "core/base/key_hash.h"
#include "core/transport/direct_light.h"
#include "core/light/luminaire_product.h"
#include "core/transport/ray_caster.h"
#include "core/scene/reference_scenes.h"
#include "tests/core/asymmetric_web.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;
const std::string kData = std::string(ILP_SOURCE_DIR) + "/data/photometry/";
const std::string kShared = std::string(ILP_SOURCE_DIR) + "/../shared/photometry/";
constexpr double kDeg = std::numbers::pi / 180.0;

// The luminaire's axes in the scene, from the definition of the placement (not from
// luminaire_rotation): the tilt axis is local y turned by r; the nadir (aim) is
// (cos r sin t, sin r sin t, -cos t); local z is minus the aim; x = y cross z.
struct Axes {
  V x, y, z;
};
Axes axes(double rotation_deg, double tilt_deg) {
  const double r = rotation_deg * kDeg, t = tilt_deg * kDeg;
  Axes a;
  a.y = V(-std::sin(r), std::cos(r), 0.0);
  a.z = -V(std::cos(r) * std::sin(t), std::sin(r) * std::sin(t), -std::cos(t));
  a.x = a.y.cross(a.z);
  return a;
}

// The asymmetric web of tests/core/asymmetric_web.h.
double web_cd(double c_deg, double gamma_deg) { return test::asymmetric_web_cd(c_deg, gamma_deg); }
std::shared_ptr<const Photometry> synthetic_point_web() { return test::asymmetric_point_web(); }

// Illuminance per lumen at points from the scene's only luminaire.
Eigen::VectorXd lux_per_lm(const Scene& scene, const std::vector<ReceiverPoint>& points) {
  const RayCaster caster(scene);
  return compute_luminaire_light_at_points(scene, caster, points, luminaire_surfaces(scene), {}).lux_per_lm.col(0);
}

// A floor z = 0 and a wall x = 4 facing -x, both black.
Scene floor_and_wall() {
  return reference::make_quad_scene({{"floor", V(-20, -20, 0), V(20, -20, 0), V(20, 20, 0), V(-20, 20, 0)},
                                     {"wall", V(4, -20, 0), V(4, -20, 10), V(4, 20, 10), V(4, 20, 0)}},
                                    0.0);
}

// Illuminance from the point web placed `at` at each point against sum I(C, gamma)
// cos(incidence) / d^2 with C and gamma in the test's own frame; the largest relative error.
double check_point_web(const LuminairePlacement& at, const std::vector<ReceiverPoint>& points) {
  const auto web = synthetic_point_web();
  Scene scene = floor_and_wall();
  add_luminaire(scene, "spot", photometric_luminaire_type("spot", web), at, 1.0);
  const Eigen::VectorXd lux = web->luminaire_flux_lm * lux_per_lm(scene, points);
  const Axes a = axes(at.rotation_deg, at.tilt_deg);
  double worst = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const V d = points[k].position_m - at.position_m;
    const V local(d.dot(a.x), d.dot(a.y), d.dot(a.z));
    const double gamma = std::acos(-local.z() / local.norm()) / kDeg;
    const double c = std::atan2(local.y(), local.x()) / kDeg;
    const double cos_incidence = -points[k].normal.dot(d) / d.norm();
    const double expected = web_cd(c, gamma) * cos_incidence / d.squaredNorm();
    EXPECT_GT(expected, 0.5) << "a point the spot lights: " << points[k].position_m.transpose();
    EXPECT_NEAR(lux[static_cast<Eigen::Index>(k)], expected, 5e-3 * expected)
        << points[k].position_m.transpose() << " C " << c << " gamma " << gamma;
    worst = std::max(worst, std::abs(lux[static_cast<Eigen::Index>(k)] / expected - 1.0));
  }
  return worst;
}

TEST(TiltedLuminaire, APointWebTiltedThirtyAndTurnedFortyGivesSumOfICosOverDSquaredOnFloorAndWall) {
  std::vector<ReceiverPoint> points;
  for (const V& x : {V(0.5, -0.5, 0), V(2, 1, 0), V(3, -1, 0), V(1, 2.5, 0), V(-1, 0.5, 0), V(2.5, 3, 0)})
    points.push_back({x, V::UnitZ()});
  for (const V& x : {V(4, 0, 1), V(4, 1.5, 2), V(4, -1, 0.5), V(4, 2.5, 2.5)}) points.push_back({x, -V::UnitX()});
  const double worst = check_point_web({V(0.5, -0.5, 3.0), 40.0, 30.0}, points);
  std::cout << "tilted point web (30 deg, turned 40): largest relative error " << worst << " over " << points.size()
            << " points\n";
}

TEST(TiltedLuminaire, APointWebAimedSidewaysAndTurnedGivesTheSameClosedForm) {
  // Tilt 90, turned -120: it aims at (-0.5, -0.866, 0). Points 1.5 m away in directions
  // (C, gamma) of its own frame (C0 now points up), each on a plane tilted toward it.
  const LuminairePlacement at{V(0.5, -0.5, 1.5), -120.0, 90.0};
  const Axes a = axes(at.rotation_deg, at.tilt_deg);
  std::vector<ReceiverPoint> points;
  for (double c : {7.3, 71.1, 152.6, 223.9, 301.7})  // between the web's nodes
    for (double gamma : {11.3, 33.7, 48.2}) {
      const V dir = std::sin(gamma * kDeg) * (std::cos(c * kDeg) * a.x + std::sin(c * kDeg) * a.y) - std::cos(gamma * kDeg) * a.z;
      points.push_back({at.position_m + 1.5 * dir, (-dir + V(0.2, -0.1, 0.3)).normalized()});
    }
  const double worst = check_point_web(at, points);
  std::cout << "point web aimed sideways (90 deg, turned -120): largest relative error " << worst << " over "
            << points.size() << " points\n";
}

// Illuminance per lumen of a Lambertian rectangle (length along `a.x`, width along
// `a.y`, emitting toward -a.z) at x with normal n: (1 / (pi A)) sum cos_e cos_r / d^2 dA,
// midpoint rule on n x n cells.
double lambertian_point_sum(const V& centre, const Axes& a, double length_m, double width_m, const V& x, const V& n,
                            int cells) {
  double sum = 0.0;
  const double dA = length_m * width_m / (static_cast<double>(cells) * cells);
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const V y = centre + a.x * ((i + 0.5) / cells - 0.5) * length_m + a.y * ((j + 0.5) / cells - 0.5) * width_m;
      const V u = x - y;
      const double d2 = u.squaredNorm(), d = std::sqrt(d2);
      const double cos_e = -a.z.dot(u) / d, cos_r = -n.dot(u) / d;
      if (cos_e > 0.0 && cos_r > 0.0) sum += cos_e * cos_r / d2 * dA;
    }
  return sum / (std::numbers::pi * length_m * width_m);
}

TEST(TiltedLuminaire, ALambertianPanelTiltedAndTurnedMatchesAFinePointSumOverItsTiltedOpening) {
  LuminaireType panel = LuminaireType::square_lambertian(0.6);
  panel.length_m = 1.2;
  panel.width_m = 0.3;
  const double rotation = 25.0, tilt = 35.0;
  const V at(0.0, 0.0, 2.5);
  Scene scene = floor_and_wall();
  add_luminaire(scene, "panel", panel, {at, rotation, tilt}, 1.0);
  std::vector<ReceiverPoint> points;
  for (const V& x : {V(0, 0, 0), V(1.5, 1, 0), V(-1, 0.5, 0), V(3, -2, 0), V(0.3, 0.2, 1.9)}) points.push_back({x, V::UnitZ()});
  // On the wall, and one point whose plane cuts the panel (only part of it is in front).
  for (const V& x : {V(4, 0, 1), V(4, 2, 2.4), V(0.35, 0.1, 2.5)}) points.push_back({x, -V::UnitX()});
  const Eigen::VectorXd lux = lux_per_lm(scene, points);
  const Axes a = axes(rotation, tilt);
  double worst = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double expected = lambertian_point_sum(at, a, 1.2, 0.3, points[k].position_m, points[k].normal, 400);
    ASSERT_GT(expected, 1e-3) << points[k].position_m.transpose();
    EXPECT_NEAR(lux[static_cast<Eigen::Index>(k)], expected, 1e-3 * expected) << points[k].position_m.transpose();
    worst = std::max(worst, std::abs(lux[static_cast<Eigen::Index>(k)] / expected - 1.0));
  }
  std::cout << "tilted Lambertian panel: largest relative error " << worst << " over " << points.size() << " points\n";
}

TEST(TiltedLuminaire, FacingSidewaysAtNinetyDegreesItLightsTheWallInFrontAndNothingBehindItsPlane) {
  const auto web = synthetic_point_web();
  for (const LuminaireType& type : {LuminaireType::square_lambertian(0.6), photometric_luminaire_type("spot", web)}) {
    Scene scene = reference::make_quad_scene({{"far", V(-50, -50, -50), V(-49, -50, -50), V(-49, -49, -50), V(-50, -49, -50)}}, 0.0);
    const V at(0, 0, 2);
    add_luminaire(scene, "washer", type, {at, 0.0, 90.0}, 1.0);  // faces +x
    std::vector<ReceiverPoint> front, behind;
    for (const V& x : {V(2, 0, 2), V(2, 1, 1), V(3, -1.5, 2.5)}) front.push_back({x, -V::UnitX()});
    for (const V& x : {V(-2, 0, 2), V(-2, 1, 1), V(-0.5, 0, 2)}) behind.push_back({x, V::UnitX()});
    // A floor below it: lit in front of the opening's plane, dark behind it.
    front.push_back({V(1.5, 0.5, 0), V::UnitZ()});
    behind.push_back({V(-1.5, 0.5, 0), V::UnitZ()});
    behind.push_back({V(-0.05, 0, 0), V::UnitZ()});
    const Eigen::VectorXd lit = lux_per_lm(scene, front), dark = lux_per_lm(scene, behind);
    const Axes a = axes(0.0, 90.0);
    EXPECT_NEAR(a.z.x(), -1.0, 1e-12);  // the opening faces +x: local z = -x
    for (std::size_t k = 0; k < front.size(); ++k) {
      const V d = front[k].position_m - at;
      double expected = 0.0;
      if (type.lambertian()) {
        expected = lambertian_point_sum(at, a, 0.6, 0.6, front[k].position_m, front[k].normal, 300);
      } else {
        const V local(d.dot(a.x), d.dot(a.y), d.dot(a.z));
        const double gamma = std::acos(-local.z() / local.norm()) / kDeg, c = std::atan2(local.y(), local.x()) / kDeg;
        expected = web_cd(c, gamma) * (-front[k].normal.dot(d) / d.norm()) / d.squaredNorm() / web->luminaire_flux_lm;
      }
      ASSERT_GT(expected, 0.0);
      EXPECT_NEAR(lit[static_cast<Eigen::Index>(k)], expected, 5e-3 * expected) << type.name << " " << front[k].position_m.transpose();
    }
    for (Eigen::Index k = 0; k < dark.size(); ++k) EXPECT_EQ(dark[k], 0.0) << type.name << " " << behind[k].position_m.transpose();
  }
}

TEST(TiltedLuminaire, ASidewaysOpeningIsShadedByWhatStandsInFrontOfIt) {
  // A panel at tilt 90 (facing +x) at height 2, a 1 x 1 m blocker at x = 1 in front of it:
  // the wall point straight ahead gets nothing, one beside the blocker's shadow all of the
  // closed form, one in the penumbra part of it.
  Scene scene = reference::make_quad_scene(
      {{"blocker", V(1, -0.5, 1.5), V(1, 0.5, 1.5), V(1, 0.5, 2.5), V(1, -0.5, 2.5)},
       {"blocker", V(1, 0.5, 1.5), V(1, -0.5, 1.5), V(1, -0.5, 2.5), V(1, 0.5, 2.5)}},
      0.0);
  const V at(0, 0, 2);
  add_luminaire(scene, "washer", LuminaireType::square_lambertian(0.6), {at, 0.0, 90.0}, 1.0);
  const std::vector<ReceiverPoint> points{{V(2, 0, 2), -V::UnitX()}, {V(2, 2.5, 2), -V::UnitX()}, {V(2, 0.95, 2), -V::UnitX()}};
  const Eigen::VectorXd lux = lux_per_lm(scene, points);
  const Axes a = axes(0.0, 90.0);
  const double open_beside = lambertian_point_sum(at, a, 0.6, 0.6, points[1].position_m, points[1].normal, 300);
  const double open_penumbra = lambertian_point_sum(at, a, 0.6, 0.6, points[2].position_m, points[2].normal, 300);
  EXPECT_EQ(lux[0], 0.0);
  EXPECT_NEAR(lux[1], open_beside, 1e-3 * open_beside);
  EXPECT_GT(lux[2], 0.05 * open_penumbra);
  EXPECT_LT(lux[2], 0.95 * open_penumbra);
}

TEST(TiltedLuminaire, ATurnedLuminairesLightEqualsTheSameLuminaireWithTheSceneTurnedTheOtherWay) {
  // Issue 19: "a rotated luminaire's direct light matches the same luminaire turned in
  // the scene". Luminaire turned by r: points x; luminaire not turned: points turned
  // by -r about its centre (normals too). Both tilted 30 degrees.
  const double r = 40.0;
  const V at(1.0, 2.0, 3.0);
  const Eigen::Matrix3d back = Eigen::AngleAxisd(-r * kDeg, V::UnitZ()).toRotationMatrix();
  for (const std::string& file : {kData + "linear_led_2112lm.ldt", kShared + "renderpipeline/medium_scatter.ies",
                                  kData + "ledalite_direct_indirect.ies"}) {
    const LuminaireType type = photometric_luminaire_type("l", std::make_shared<const Photometry>(load_photometry(file)));
    auto light = [&](double rotation, const std::vector<ReceiverPoint>& points) {
      Scene scene = reference::make_quad_scene({{"far", V(-90, -90, -90), V(-89, -90, -90), V(-89, -89, -90), V(-90, -89, -90)}}, 0.0);
      add_luminaire(scene, "l", type, {at, rotation, 30.0}, 1.0);
      return lux_per_lm(scene, points);
    };
    std::vector<ReceiverPoint> points, turned;
    for (const ReceiverPoint& p : std::vector<ReceiverPoint>{{V(1, 2, 0), V::UnitZ()},
                                                             {V(3, 2.5, 0), V::UnitZ()},
                                                             {V(-0.5, 3, 0.8), V::UnitZ()},
                                                             {V(2.5, 0.5, 0), V::UnitZ()},
                                                             {V(4, 2, 1.5), -V::UnitX()},
                                                             {V(1.5, 5, 2), V(0, -0.8, 0.6)},
                                                             {V(1.2, 2.1, 3.5), -V::UnitZ()}}) {
      points.push_back(p);
      turned.push_back({at + back * (p.position_m - at), back * p.normal});
    }
    const Eigen::VectorXd a = light(r, points), b = light(0.0, turned);
    EXPECT_GE((a.array() > 0.0).count(), 5) << file << ": most points are lit";
    for (Eigen::Index k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-7 * std::max(a[k], b[k])) << file << " point " << k;
  }
}

TEST(TiltedLuminaire, OutlinePatchesAndFootprintFollowTheTiltedFrame) {
  LuminaireType t = LuminaireType::square_lambertian(0.6);
  t.length_m = 1.2;
  t.width_m = 0.3;
  const LuminairePlacement at{V(1, 2, 3), 40.0, 30.0};
  const Axes a = axes(40.0, 30.0);
  const std::vector<V> outline = luminaire_outline_m(t, at);
  ASSERT_EQ(outline.size(), 4u);
  const V expected[4] = {at.position_m - 0.6 * a.x - 0.15 * a.y, at.position_m + 0.6 * a.x - 0.15 * a.y,
                         at.position_m + 0.6 * a.x + 0.15 * a.y, at.position_m - 0.6 * a.x + 0.15 * a.y};
  for (int k = 0; k < 4; ++k) EXPECT_LT((outline[static_cast<std::size_t>(k)] - expected[k]).norm(), 1e-12) << k;
  // The opening's patches face the aim and cover its area.
  Scene scene = floor_and_wall();
  const int surface = add_luminaire(scene, "panel", t, at, 1.0);
  double area = 0.0;
  for (const Patch& p : scene.patches)
    if (p.surface == surface) {
      EXPECT_LT((p.normal - (-a.z)).norm(), 1e-12);
      area += p.area_m2;
    }
  EXPECT_NEAR(area, 0.36, 1e-12);
  // Footprint on the plan: the length foreshortened by cos(tilt), then turned.
  const Eigen::Vector2d half = t.half_footprint_m(0.0, 60.0);
  EXPECT_NEAR(half.x(), 0.6 * 0.5, 1e-12);
  EXPECT_NEAR(half.y(), 0.15, 1e-12);
  EXPECT_NEAR(t.half_footprint_m(0.0, 90.0).x(), 0.0, 1e-12);
  // Untilted: the old rotation about z exactly.
  EXPECT_EQ(luminaire_rotation(33.0, 0.0), Eigen::Matrix3d(Eigen::AngleAxisd(33.0 * kDeg, V::UnitZ())));
  EXPECT_THROW(luminaire_rotation(0.0, -1.0), std::invalid_argument);
  EXPECT_THROW(luminaire_rotation(0.0, 90.5), std::invalid_argument);
  EXPECT_THROW(luminaire_rotation(std::nan(""), 10.0), std::invalid_argument);
}

TEST(TiltedLuminaire, ThePlacementsCacheKeyChangesWithTheTilt) {
  auto key = [](const LuminairePlacement& p) {
    KeyWriter k;
    k.value(p);
    return k.text();
  };
  const LuminairePlacement flat{V(1, 2, 3), 40.0, 0.0}, tilted{V(1, 2, 3), 40.0, 30.0};
  EXPECT_NE(key(flat), key(tilted));
  EXPECT_NE(key(tilted).find("tilt_deg=d30"), std::string::npos) << key(tilted);
}

}  // namespace
}  // namespace ilp
