// The candidates' reflected light computed at every second grid node and blended
// between (core/operator/reflected_blend.h, optimizer/candidate_grid.h): the blend's
// weights against the grid's geometry, the blended operator against the one that
// computes every candidate, and the blend's checks.
#include "core/operator/reflected_blend.h"

#include <gtest/gtest.h>

#include <cmath>

#include "job/config.h"
#include "job/plan.h"
#include "job/job_runner.h"
#include "job/job_scene.h"
#include "optimizer/layout_search.h"
#include "optimizer/candidate_grid.h"
#include "optimizer/lighting_model.h"
#include "tests/optimizer/optimizer_test_scenes.h"

namespace ilp {
namespace {

using test::room_job;
using test::room_obj;
using test::TempDir;

// A grey room (rho 0.5) with a floor grid and a ceiling of candidates 0.5 m apart.
JobConfig grey_room(const TempDir& dir, const std::string& obj) {
  dir.write("room.obj", obj);
  const std::string luminaires =
      "  size_m: 0.3\n  flux_lm: [100, 20000]\n  efficacy_lm_per_w: 100\n  mounting_surface: ceiling\n"
      "  candidate_spacing_m: 0.5\n  count: [1, 4]\n";
  return load_job_config(dir.write(
      "job.yaml", room_job("0.5", luminaires, "  - surface: floor\n    average_lux: 200\n",
                           "grids:\n  - {name: plane, over_surface: floor, height_m: 0.8, border_m: 0.3}\n")));
}

LightingModel model_with_stride(const JobConfig& job, const JobScene& loaded, const RayCaster& caster, int stride) {
  ModelSpec spec = test::model_spec(job);
  spec.reflected_stride = stride;
  LightingModel model = lighting_model_geometry(loaded.scene, spec, &caster);
  compute_lighting_operator(model, loaded.scene, caster, spec);
  return model;
}

TEST(ReflectedBlend, ABlendedCandidateSitsWhereItsWeightsPutIt) {
  // On a regular grid the bilinear weights of the computed nodes reproduce a blended
  // candidate's own position: each is the mean of its two (or four) computed neighbours.
  TempDir dir;
  const JobConfig job = grey_room(dir, room_obj({}));
  const JobScene loaded = load_job_scene(scene_spec(job));
  const LightingModel model = lighting_model_geometry(loaded.scene, test::model_spec(job));
  const CandidateGrid& grid = model.grid;
  ASSERT_GE(grid.nodes_x(), 5);
  const ReflectedBlend blend = candidate_reflected_blend(grid, 0, 2);
  std::size_t blended = 0;
  for (Eigen::Index s = 0; s < blend.weights.outerSize(); ++s) {
    Eigen::Vector3d at = Eigen::Vector3d::Zero();
    int terms = 0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(blend.weights, s); it; ++it) {
      at += it.value() * grid.positions_m()[static_cast<std::size_t>(blend.computed[static_cast<std::size_t>(it.row())])];
      ++terms;
    }
    EXPECT_LT((at - grid.positions_m()[static_cast<std::size_t>(s)]).norm(), 1e-9) << "candidate " << s;
    if (terms > 1) ++blended;
  }
  // Every second node along each axis (and the last): about a quarter are computed.
  const auto nx = static_cast<std::size_t>(grid.nodes_x()), ny = static_cast<std::size_t>(grid.nodes_y());
  EXPECT_EQ(blend.computed.size(), ((nx + 2) / 2) * ((ny + 2) / 2)) << nx << " x " << ny << " nodes";
  EXPECT_EQ(blended + blend.computed.size(), grid.size());
  // Stride 1: every candidate computed; an empty grid: the fixed sources alone.
  EXPECT_EQ(candidate_reflected_blend(grid, 3, 1).computed.size(), grid.size() + 3);
  EXPECT_EQ(candidate_reflected_blend(CandidateGrid(), 2, 2).computed.size(), 2u);
  EXPECT_EQ(CandidateGrid().candidate_at_node(0, 0), -1);
}

TEST(ReflectedBlend, CandidatesBesideAHoleAreComputed) {
  // A ceiling with a 0.8 x 1.2 m hole (a skylight well, x 1.4 to 2.2 m): the nodes over
  // it hold no candidate, among them one of the computed lattice's (x 2.0 m), so the
  // node beside it that would blend from it (x 2.46 m) is computed itself, and every
  // weight points at a candidate that exists.
  std::string obj = room_obj({});
  TempDir dir;
  // The room's ceiling replaced by four strips around the hole (y 1.4 to 2.6 m).
  const std::string ceiling = "g ceiling\n";
  const std::size_t at = obj.find(ceiling);
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = obj.find("g walls", at);
  // Each strip's vertices counter-clockwise seen from above, its face the other way
  // round (facing down), by indices counted from the end.
  std::string strips = "g ceiling\n";
  for (const std::string& line : {std::string("v 0 0 2.5\nv 4 0 2.5\nv 4 1.4 2.5\nv 0 1.4 2.5\n"),
                                  std::string("v 0 2.6 2.5\nv 4 2.6 2.5\nv 4 4 2.5\nv 0 4 2.5\n"),
                                  std::string("v 0 1.4 2.5\nv 1.4 1.4 2.5\nv 1.4 2.6 2.5\nv 0 2.6 2.5\n"),
                                  std::string("v 2.2 1.4 2.5\nv 4 1.4 2.5\nv 4 2.6 2.5\nv 2.2 2.6 2.5\n")})
    strips += line + "f -1 -2 -3 -4\n";
  obj.replace(at, end - at, strips);
  const JobConfig job = grey_room(dir, obj);
  const JobScene loaded = load_job_scene(scene_spec(job));
  const LightingModel model = lighting_model_geometry(loaded.scene, test::model_spec(job));
  const CandidateGrid& grid = model.grid;
  int missing = 0;
  for (int j = 0; j < grid.nodes_y(); ++j)
    for (int i = 0; i < grid.nodes_x(); ++i) missing += grid.candidate_at_node(i, j) < 0;
  ASSERT_GT(missing, 0) << "the hole leaves nodes without a candidate";
  const ReflectedBlend blend = candidate_reflected_blend(grid, 0, 2);  // check_blend inside
  // What the plain lattice would compute: nodes on every second line that hold a candidate.
  std::size_t on_lattice = 0;
  for (int j = 0; j < grid.nodes_y(); ++j)
    for (int i = 0; i < grid.nodes_x(); ++i)
      on_lattice += (i % 2 == 0 || i == grid.nodes_x() - 1) && (j % 2 == 0 || j == grid.nodes_y() - 1) &&
                    grid.candidate_at_node(i, j) >= 0;
  EXPECT_GT(blend.computed.size(), on_lattice) << "candidates beside the hole are computed too";
  EXPECT_LT(blend.computed.size(), grid.size());
}

TEST(ReflectedBlend, TheBlendedOperatorKeepsDirectLightAndComputedColumns) {
  TempDir dir;
  const JobConfig job = grey_room(dir, room_obj({}));
  const JobScene loaded = load_job_scene(scene_spec(job));
  const RayCaster caster(loaded.scene);
  const LightingModel every = model_with_stride(job, loaded, caster, 1);
  const LightingModel blended = model_with_stride(job, loaded, caster, 2);
  const ReflectedBlend blend = candidate_reflected_blend(every.grid, 0, 2);
  ASSERT_LT(blend.computed.size(), every.grid.size());
  ASSERT_EQ(every.candidate_lux_per_lm.rows(), blended.candidate_lux_per_lm.rows());
  // Direct light is every candidate's own, bit for bit.
  EXPECT_EQ(every.candidate_direct_lux_per_lm, blended.candidate_direct_lux_per_lm);
  const Eigen::MatrixXd reflected_every = every.candidate_lux_per_lm - every.candidate_direct_lux_per_lm;
  const Eigen::MatrixXd reflected_blended = blended.candidate_lux_per_lm - blended.candidate_direct_lux_per_lm;
  std::vector<bool> computed(every.grid.size(), false);
  for (int c : blend.computed) computed[static_cast<std::size_t>(c)] = true;
  double blended_gap = 0.0;
  for (Eigen::Index c = 0; c < reflected_every.cols(); ++c) {
    const double scale = reflected_every.col(c).cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    const double diff = (reflected_blended.col(c) - reflected_every.col(c)).cwiseAbs().maxCoeff() / scale;
    // The same sample, rows and rays: the same column up to the iterative solve's tolerance.
    if (computed[static_cast<std::size_t>(c)]) EXPECT_LT(diff, 1e-7) << "computed candidate " << c;
    else blended_gap = std::max(blended_gap, diff);
  }
  EXPECT_GT(blended_gap, 1e-6) << "the blended columns are blends, not the candidates' own";
}

TEST(ReflectedBlend, PredictionsAgainstTheExactSolveAreNoWorseThanComputingEveryCandidate) {
  // The operator's own noise (its sample, rows and cheap direct light at the patches the
  // rows hit) moves a candidate's reflected light by about 5-10 % from seed to seed in
  // this small room, more than the blend of its neighbours does; what matters is the
  // prediction of a layout against the exact solve. Four luminaires off the grid's
  // nodes, predicted with every candidate computed and with every second one: the
  // blended prediction's error at the grid points and on the floor's average is within
  // half a percent of the plain one's.
  TempDir dir;
  JobConfig job = grey_room(dir, room_obj({}));
  job.sample.reflected_stride = 1;
  const PreparedJob every = test::prepare(job);
  job.sample.reflected_stride = 2;
  const PreparedJob blended = test::prepare(job);
  const SearchSpec spec = test::spec(job);
  const std::vector<Eigen::Vector2d> xy{{1.15, 1.3}, {2.85, 1.3}, {1.15, 2.7}, {2.85, 2.7}};
  const std::vector<double> w(4, 1.0);
  const LayoutEvaluation a = evaluate_layout(every.model, spec, xy, w);
  const LayoutEvaluation b = evaluate_layout(blended.model, spec, xy, w);
  const Verification exact = verify_layout(every, a.luminaires);
  const Eigen::VectorXd reference = verified_goal_lux(every.model, exact);
  const Eigen::Index Q = static_cast<Eigen::Index>(every.model.goal_points.size()), G = reference.size() - Q;
  ASSERT_GT(Q, 10);
  auto point_error = [&](const Eigen::VectorXd& lux) {
    return ((lux.tail(Q) - reference.tail(Q)).array() / reference.tail(Q).array()).abs().mean();
  };
  auto floor_error = [&](const Eigen::VectorXd& lux) {
    return std::abs(lux.head(G).mean() / reference.head(G).mean() - 1.0);
  };
  EXPECT_LT(point_error(b.lux), point_error(a.lux) + 0.005)
      << "blended " << point_error(b.lux) << ", every candidate " << point_error(a.lux);
  EXPECT_LT(floor_error(b.lux), floor_error(a.lux) + 0.005)
      << "blended " << floor_error(b.lux) << ", every candidate " << floor_error(a.lux);
  EXPECT_LT(point_error(b.lux), 0.03);
}

TEST(ReflectedBlend, TheIdentityBlendIsThePlainOperator) {
  TempDir dir;
  const JobConfig job = grey_room(dir, room_obj({}));
  const JobScene loaded = load_job_scene(scene_spec(job));
  const RayCaster caster(loaded.scene);
  const ModelSpec spec = test::model_spec(job);
  LightingModel model = lighting_model_geometry(loaded.scene, spec, &caster);
  SampleOperatorOptions o = spec.operator_options;
  o.sample_size = 200;
  const std::vector<LightSource> sources = scene_light_sources(model.scene);
  const GoalRows rows = compute_goal_rows(model.scene, caster, model.goal_patches, model.goal_points, sources, o);
  const SampleOperator plain = build_sample_operator(model.scene, caster, rows, o);
  const SampleOperator same = build_blended_sample_operator(model.scene, caster, rows, o, identity_blend(sources.size()));
  EXPECT_EQ(plain.total_lux_per_lm, same.total_lux_per_lm);
  EXPECT_EQ(plain.reflected_lm_per_m2_per_lm, same.reflected_lm_per_m2_per_lm);
  // A blend that computes every source but through the general path (two sources'
  // weights listed the other way round is not allowed: each computed source is its own).
  ReflectedBlend every = identity_blend(sources.size());
  every.computed.pop_back();  // the last source now blended from... nothing: refused
  EXPECT_THROW(build_blended_sample_operator(model.scene, caster, rows, o, every), std::invalid_argument);
}

TEST(ReflectedBlend, BadBlendsAreRefused) {
  ReflectedBlend b = identity_blend(3);
  EXPECT_NO_THROW(check_blend(b, 3));
  EXPECT_THROW(check_blend(b, 4), std::invalid_argument);  // wrong size
  // Source 2 from sources 0 and 1, weights 0.5 and 0.6: not summing to 1.
  ReflectedBlend off;
  off.computed = {0, 1};
  off.weights.resize(2, 3);
  off.weights.insert(0, 0) = 1.0;
  off.weights.insert(1, 1) = 1.0;
  off.weights.insert(0, 2) = 0.5;
  off.weights.insert(1, 2) = 0.6;
  EXPECT_THROW(check_blend(off, 3), std::invalid_argument);
  off.weights.coeffRef(1, 2) = 0.5;
  EXPECT_NO_THROW(check_blend(off, 3));
  off.weights.coeffRef(0, 2) = 1.5;  // negative partner
  off.weights.coeffRef(1, 2) = -0.5;
  EXPECT_THROW(check_blend(off, 3), std::invalid_argument);
  off.weights.coeffRef(0, 2) = 0.5;
  off.weights.coeffRef(1, 2) = 0.5;
  off.weights.coeffRef(0, 0) = 0.5;  // a computed source that is not its own blend
  off.weights.insert(1, 0) = 0.5;
  EXPECT_THROW(check_blend(off, 3), std::invalid_argument);
  off.computed = {1, 0};  // not ascending
  EXPECT_THROW(check_blend(off, 3), std::invalid_argument);
}

}  // namespace
}  // namespace ilp
