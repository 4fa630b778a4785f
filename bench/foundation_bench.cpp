// Benchmarks of the foundation and the sample-based operator: form-factor rows
// against plain Embree tracing the very same rays (the baseline, measured in the
// same run), the exact solve, and the operator's build and per-configuration cost
// (which replaces one exact solve per configuration).
// Scene: configs/office_fixed.yaml, or the job in $ILP_BENCH_CONFIG. Argument: threads.
//
//   ./build/bench/ilp_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Embree is used directly here only for the baseline; the library keeps it in
// core/transport/ray_caster.cpp.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <vector>

#include "job/config.h"
#include "core/exact/exact_solver.h"
#include "job/plan.h"
#include "core/transport/form_factors.h"
#include "job/job_scene.h"
#include "core/transport/ray_caster.h"
#include "core/operator/sample_operator.h"
#include "core/transport/sampling.h"

namespace {

struct Fixture {
  ilp::JobConfig job;
  ilp::Scene scene;
};

const Fixture& fixture() {
  static const std::unique_ptr<Fixture> f = [] {
    const char* env = std::getenv("ILP_BENCH_CONFIG");
    auto out = std::make_unique<Fixture>();
    out->job = ilp::load_job_config(env ? env : ILP_SOURCE_DIR "/configs/office_fixed.yaml");
    out->scene = ilp::load_job_scene(scene_spec(out->job)).scene;
    return out;
  }();
  return *f;
}

void BM_FormFactorRows(benchmark::State& state) {
  const Fixture& f = fixture();
  ilp::FormFactorOptions options = f.job.form_factors;
  options.threads = static_cast<int>(state.range(0));
  const ilp::RayCaster caster(f.scene, options.threads);
  std::uint64_t rays = 0;
  for (auto _ : state) {
    const ilp::FormFactorRows rows = ilp::compute_form_factor_rows(f.scene, caster, f.scene.all_patches(), options);
    benchmark::DoNotOptimize(rows.F.nonZeros());
    rays += rows.rays_cast;
  }
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["patches"] = static_cast<double>(f.scene.patches.size());
}

// The same rays as BM_FormFactorRows (same points, directions and offsets),
// generated before timing, traced with bare rtcIntersect1 calls.
void BM_PlainEmbreeSameRays(benchmark::State& state) {
  const Fixture& f = fixture();
  const int threads = static_cast<int>(state.range(0));
  const ilp::FormFactorOptions& options = f.job.form_factors;
  const ilp::RayCaster caster(f.scene, threads);  // for the scene's ray offset only
  const Eigen::Vector3d center = f.scene.bounds_m.center();

  const std::size_t n = f.scene.patches.size(), per_row = static_cast<std::size_t>(options.rays_per_patch);
  std::vector<float> rays(6 * n * per_row);
  for (std::size_t i = 0; i < n; ++i) {
    const ilp::Patch& p = f.scene.patches[i];
    Eigen::Vector3d t, s;
    ilp::orthonormal_basis(p.normal, t, s);
    const ilp::RotatedHalton4 sequence(options.seed, i);
    for (std::size_t r = 0; r < per_row; ++r) {
      const auto u = sequence.point(static_cast<std::uint32_t>(r));
      const Eigen::Vector3d o = ilp::sample_triangle(p.vertices_m[0], p.vertices_m[1], p.vertices_m[2], u[0], u[1]) +
                                p.normal * caster.ray_offset_m() - center;
      const Eigen::Vector3d d = ilp::sample_cosine_hemisphere(p.normal, t, s, u[2], u[3]);
      float* ray = &rays[6 * (i * per_row + r)];
      for (int c = 0; c < 3; ++c) {
        ray[c] = static_cast<float>(o[c]);
        ray[3 + c] = static_cast<float>(d[c]);
      }
    }
  }

  RTCDevice device = rtcNewDevice(("threads=" + std::to_string(threads)).c_str());
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* idx = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = f.scene.patches[i].vertices_m[k] - center;
      for (int c = 0; c < 3; ++c) v[9 * i + 3 * k + c] = static_cast<float>(p[c]);
      idx[3 * i + k] = static_cast<unsigned>(3 * i + k);
    }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);

  std::vector<unsigned> hit(n * per_row);
  tbb::task_arena arena(threads);
  std::uint64_t traced = 0;
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n * per_row, 64 * per_row), [&](const auto& range) {
        const auto ray_modes = ilp::RayCaster::prepare_thread();
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          const float* ray = &rays[6 * k];
          RTCRayHit rh;
          rh.ray.org_x = ray[0], rh.ray.org_y = ray[1], rh.ray.org_z = ray[2];
          rh.ray.dir_x = ray[3], rh.ray.dir_y = ray[4], rh.ray.dir_z = ray[5];
          rh.ray.tnear = 0.0f;
          rh.ray.tfar = std::numeric_limits<float>::infinity();
          rh.ray.mask = 0xFFFFFFFFu;
          rh.ray.flags = 0;
          rh.ray.time = 0.0f;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(scene, &context, &rh);
          hit[k] = rh.hit.primID;
        }
      });
    });
    benchmark::DoNotOptimize(hit.data());
    traced += n * per_row;
  }
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(traced), benchmark::Counter::kIsRate);
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
}

void BM_ExactSolve(benchmark::State& state) {
  const Fixture& f = fixture();
  ilp::ExactSolveOptions options = ilp::exact_options(f.job, {});
  options.form_factors.threads = options.direct_light.threads = static_cast<int>(state.range(0));
  ilp::ExactSolveSummary last;
  for (auto _ : state) last = ilp::solve_exact(f.scene, options).summary;
  state.counters["patches"] = static_cast<double>(last.patches);
  state.counters["form_factor_s"] = last.form_factor_seconds;
  state.counters["direct_light_s"] = last.direct_light_seconds;
  state.counters["gauss_seidel_s"] = last.solve_seconds;
  state.counters["sweeps"] = last.iterations;
}

// The sample-based operator for the job's report surfaces as goals, built at the
// job's sample size: what replaces one exact solve per configuration.
ilp::SampleOperatorOptions sample_options(const Fixture& f, int threads) {
  ilp::SampleOperatorOptions o;
  o.strategy = f.job.sample.strategy;
  o.sample_seed = f.job.sample.seed;
  o.indirect = f.job.sample.indirect;
  o.form_factors = f.job.form_factors;
  o.direct_light = f.job.direct_light;
  o.form_factors.threads = o.direct_light.threads = threads;
  o.sample_size = f.job.sample.size_for(ilp::reflecting_patches(f.scene).size());
  return o;
}

void BM_SampleOperatorBuild(benchmark::State& state) {
  const Fixture& f = fixture();
  const ilp::SampleOperatorOptions o = sample_options(f, static_cast<int>(state.range(0)));
  const std::vector<int> goals = f.scene.patches_of(f.job.report_surfaces);
  ilp::SampleOperatorStats last;
  for (auto _ : state) {
    const ilp::RayCaster caster(f.scene, o.form_factors.threads);
    const ilp::GoalRows rows = ilp::compute_goal_rows(f.scene, caster, goals, ilp::scene_light_sources(f.scene), o);
    last = ilp::build_sample_operator(f.scene, caster, rows, o).stats;
  }
  state.counters["k"] = static_cast<double>(last.sample_patches);
  state.counters["goal_patches"] = static_cast<double>(last.goal_patches);
  state.counters["goal_rows_s"] = last.goal_seconds;
  state.counters["sample_rows_s"] = last.sample_row_seconds;
  state.counters["direct_s"] = last.direct_seconds;
  state.counters["solve_s"] = last.solve_seconds;
}

// One configuration through the built operator: H_G = T phi.
void BM_EvaluateConfiguration(benchmark::State& state) {
  const Fixture& f = fixture();
  const ilp::SampleOperatorOptions o = sample_options(f, 0);
  const ilp::RayCaster caster(f.scene, 0);
  const ilp::GoalRows rows = ilp::compute_goal_rows(f.scene, caster, f.scene.patches_of(f.job.report_surfaces), ilp::scene_light_sources(f.scene), o);
  const ilp::SampleOperator op = ilp::build_sample_operator(f.scene, caster, rows, o);
  Eigen::VectorXd flux = ilp::source_flux_lm(f.scene, op.sources);
  Eigen::VectorXd H(op.total_lux_per_lm.rows());
  for (auto _ : state) {
    flux[0] += 1e-9;  // a new configuration each time
    H.noalias() = op.total_lux_per_lm * flux;
    benchmark::DoNotOptimize(H.data());
  }
  state.counters["goal_patches"] = static_cast<double>(H.size());
  state.counters["sources"] = static_cast<double>(flux.size());
}

}  // namespace

BENCHMARK(BM_SampleOperatorBuild)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EvaluateConfiguration)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FormFactorRows)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PlainEmbreeSameRays)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ExactSolve)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
