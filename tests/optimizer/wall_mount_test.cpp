// Wall mounting (issue 19, item 4): candidates on a wall's faces at a height above the
// floor, in front of the wall, each turned so that its C0 points into the room; the
// direct light of a luminaire mounted there and aimed (tilted) is its rotated intensity
// over the distance squared, in the test's own frame; regular layouts on a wall are one
// line along it.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <sstream>

#include "core/transport/direct_light.h"
#include "core/light/luminaire_product.h"
#include "core/transport/ray_caster.h"
#include "core/scene/reference_scenes.h"
#include "tests/core/asymmetric_web.h"
#include "optimizer/candidate_grid.h"
#include "optimizer/lighting_model.h"
#include "optimizer/regular_layout.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;
constexpr double kDeg = std::numbers::pi / 180.0;

// The office's size: a black box [0, 6] x [0, 4] x [0, 3], faces inwards.
Scene black_room() { return reference::make_closed_box(V::Zero(), V(6, 4, 3), 0.0, 0.5); }

// A linear opening 1.2 m long along C90 (its length along the wall when C0 points into the room).
LuminaireType linear_type() {
  LuminaireType t = LuminaireType::square_lambertian(0.6);
  t.length_m = 0.04;  // along C0 (local x)
  t.width_m = 1.2;    // along C90 (local y)
  return t;
}

CandidateGridOptions options_for(const LuminaireType& type, double rotation_deg, double tilt_deg) {
  return {.spacing_m = 0.25, .half_footprint_m = type.half_footprint_m(rotation_deg, tilt_deg), .mount_offset_m = 0.05};
}

TEST(WallMount, CandidatesLieOnALineInFrontOfTheWallAtTheHeight) {
  const Scene scene = black_room();
  const LuminaireType type = linear_type();
  struct Case {
    const char* wall;
    Eigen::Vector2d facing;
  };
  for (const Case& c : {Case{"wall_x0", Eigen::Vector2d(1, 0)}, Case{"wall_x1", Eigen::Vector2d(-1, 0)},
                        Case{"wall_y0", Eigen::Vector2d(0, 1)}, Case{"wall_y1", Eigen::Vector2d(0, -1)}}) {
    const double rotation = wall_facing_deg(c.facing), tilt = 60.0;
    const CandidateGridOptions options = options_for(type, rotation, tilt);
    const CandidateGrid grid(scene, scene.find_surface(c.wall), c.facing, 2.6, options);
    const int across = std::abs(c.facing.x()) > 0.5 ? 0 : 1, along = 1 - across;
    const double wall_at = c.facing[across] > 0 ? 0.0 : (across == 0 ? 6.0 : 4.0);
    const double expected = wall_at + c.facing[across] * (0.05 + options.half_footprint_m[across]);
    const double length = across == 0 ? 4.0 : 6.0, half = options.half_footprint_m[along];
    EXPECT_NEAR(options.half_footprint_m[along], 0.6, 1e-9) << c.wall << ": the length runs along the wall";
    ASSERT_GE(grid.size(), 2u) << c.wall;
    EXPECT_EQ(grid.lower_m()[across], grid.upper_m()[across]) << c.wall << ": one line";
    for (const V& p : grid.positions_m()) {
      EXPECT_NEAR(p[across], expected, 1e-12) << c.wall;
      EXPECT_NEAR(p.z(), 2.6, 1e-12) << c.wall;
      EXPECT_GE(p[along], half - 1e-9) << c.wall;
      EXPECT_LE(p[along], length - half + 1e-9) << c.wall;
    }
    EXPECT_NEAR(grid.positions_m().front()[along], half, 1e-9) << c.wall;
    EXPECT_NEAR(grid.positions_m().back()[along], length - half, 1e-9) << c.wall;
    // Between candidates the blend stays on the line, and a point on it is mountable.
    Eigen::Vector2d mid;
    mid[across] = expected;
    mid[along] = 0.5 * length + 0.1;
    EXPECT_NEAR(grid.mount_distance_m(mid), 0.0, 1e-12) << c.wall;
    const GridPoint g = grid.locate(mid);
    EXPECT_NEAR(g.position_m[across], expected, 1e-12) << c.wall;
    EXPECT_NEAR(g.position_m.z(), 2.6, 1e-12) << c.wall;
    double sum = 0.0;
    for (int k = 0; k < GridPoint::kMaxCandidates; ++k) sum += g.weights[k];
    EXPECT_NEAR(sum, 1.0, 1e-12) << c.wall;
  }
}

TEST(WallMount, AWallWithoutFacesThatWayOrAHeightOffItIsRefused) {
  const Scene scene = black_room();
  const LuminaireType type = linear_type();
  try {
    (void)CandidateGrid(scene, scene.find_surface("wall_x0"), Eigen::Vector2d(-1, 0), 2.6, options_for(type, 180, 0));
    ADD_FAILURE() << "a wall facing +x was taken as facing -x";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no patch facing -x"), std::string::npos) << e.what();
  }
  EXPECT_THROW(
      (void)CandidateGrid(scene, scene.find_surface("wall_x0"), Eigen::Vector2d(1, 0), 3.2, options_for(type, 0, 0)),
      std::out_of_range);
  CandidateGridOptions zone = options_for(type, 0, 0);
  zone.zone_m = Eigen::AlignedBox2d(Eigen::Vector2d(2, 7), Eigen::Vector2d(3, 9));  // beyond the wall's y in [0, 4]
  try {
    (void)CandidateGrid(scene, scene.find_surface("wall_x0"), Eigen::Vector2d(1, 0), 2.6, zone);
    ADD_FAILURE() << "a zone off the wall was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("zone"), std::string::npos) << e.what();
  }
}

// The asymmetric web of tests/core/asymmetric_web.h.
double web_cd(double c_deg, double gamma_deg) { return test::asymmetric_web_cd(c_deg, gamma_deg); }
std::shared_ptr<const Photometry> synthetic_point_web() { return test::asymmetric_point_web(); }

TEST(WallMount, AWallMountedAimedWebLightsTheRoomAsItsRotatedIntensityOverDistanceSquared) {
  // On the wall y = 4 (facing -y) at 2.6 m, aimed 50 degrees up from the nadir into the room.
  Scene scene = black_room();
  const auto web = synthetic_point_web();
  const LuminaireType type = photometric_luminaire_type("spot", web);
  const Eigen::Vector2d facing(0, -1);
  const double rotation = wall_facing_deg(facing), tilt = 50.0;
  const CandidateGrid grid(scene, scene.find_surface("wall_y1"), facing, 2.6, options_for(type, rotation, tilt));
  const V at = grid.locate(Eigen::Vector2d(3.0, 0.0)).position_m;
  ASSERT_NEAR(at.x(), 3.0, 1e-9);
  ASSERT_NEAR(at.y(), 4.0 - 0.05 - type.half_footprint_m(rotation, tilt).y(), 1e-9);
  ASSERT_NEAR(at.z(), 2.6, 1e-9);
  add_luminaire(scene, "spot", type, {at, rotation, tilt}, 1.0);

  // The luminaire's axes from the wall alone: C0 points into the room (-y), the tilt
  // axis (C90) runs along the wall, the nadir swings from -z toward -y.
  const double t = tilt * kDeg;
  const V into(0, -1, 0), c90 = V::UnitZ().cross(into);  // C90: a quarter turn counter-clockwise from C0, seen from above
  const V aim = std::sin(t) * into - std::cos(t) * V::UnitZ();
  const V up = -aim, x_axis = c90.cross(up);
  ASSERT_NEAR((luminaire_rotation(rotation, tilt) * V(0, 0, -1) - aim).norm(), 0.0, 1e-12);

  std::vector<ReceiverPoint> points;
  for (const V& x : {V(3, 2, 0), V(1.5, 1, 0), V(4.5, 2.5, 0), V(2, 3, 0), V(5, 0.5, 0)}) points.push_back({x, V::UnitZ()});
  for (const V& x : {V(3, 0, 1.5), V(1, 0, 1), V(5, 0, 2.2)}) points.push_back({x, V::UnitY()});  // the opposite wall
  for (const V& x : {V(6, 2, 1.2), V(0, 1.5, 0.8)}) points.push_back({x, x.x() > 3 ? V(-1, 0, 0) : V(1, 0, 0)});
  const RayCaster caster(scene);
  const Eigen::VectorXd lux =
      web->luminaire_flux_lm *
      compute_luminaire_light_at_points(scene, caster, points, luminaire_surfaces(scene), {}).lux_per_lm.col(0);
  double worst = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const V d = points[k].position_m - at;
    const V local(d.dot(x_axis), d.dot(c90), d.dot(up));
    const double gamma = std::acos(-local.z() / local.norm()) / kDeg;
    const double c = std::atan2(local.y(), local.x()) / kDeg;
    const double expected = web_cd(c, gamma) * (-points[k].normal.dot(d) / d.norm()) / d.squaredNorm();
    ASSERT_GT(expected, 0.5) << "a point the luminaire lights: " << points[k].position_m.transpose();
    EXPECT_NEAR(lux[static_cast<Eigen::Index>(k)], expected, 5e-3 * expected)
        << points[k].position_m.transpose() << " C " << c << " gamma " << gamma;
    worst = std::max(worst, std::abs(lux[static_cast<Eigen::Index>(k)] / expected - 1.0));
  }
  std::cout << "wall-mounted web (wall facing -y, tilt 50): largest relative error " << worst << " over "
            << points.size() << " points\n";
}

TEST(WallMount, RegularLayoutsOnAWallAreOneLineAlongIt) {
  // A zone that is a line along y (a wall facing +-x): rows run along it whatever the
  // luminaire's outline, a field keeps one column.
  ArrangementFrame frame;
  frame.zone_m = Eigen::AlignedBox2d(Eigen::Vector2d(0.07, 0.5), Eigen::Vector2d(0.07, 3.5));
  frame.luminaire_extent_m = Eigen::Vector2d(1.2, 0.04);  // longer across the line: rows still run along it
  LayoutSpec rows;
  rows.family = LayoutFamily::rows;
  rows.count_min = 1;
  rows.count_max = 100;
  rows.regular.rows = {1, 3};
  rows.regular.columns = {1, 4};
  LayoutSpec field = rows;
  field.family = LayoutFamily::field;
  field.regular.rows = {1, 4};  // a field's rows lie along y, its columns along x
  field.regular.columns = {1, 3};
  for (const LayoutSpec& layout : {rows, field}) {
    const std::vector<Arrangement> all = regular_arrangements(layout, frame);
    ASSERT_EQ(all.size(), 4u) << layout_family_key(layout.family);
    for (const Arrangement& a : all)
      for (const Eigen::Vector2d& xy : a.xy_m) {
        EXPECT_EQ(xy.x(), 0.07) << a.label;
        EXPECT_GE(xy.y(), 0.5) << a.label;
        EXPECT_LE(xy.y(), 3.5) << a.label;
      }
    EXPECT_EQ(all.back().xy_m.size(), 4u);
    EXPECT_NEAR(all.back().xy_m[1].y() - all.back().xy_m[0].y(), 0.75, 1e-12) << all.back().label;
  }
}

}  // namespace
}  // namespace ilp
