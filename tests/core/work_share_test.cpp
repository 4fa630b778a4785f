// A split operator build (core/operator/work_share.h) in one process: "virtual ranks"
// are threads meeting through an in-memory rendezvous, as mpirun's ranks meet through
// dist::agree. T must have the same bits whatever the number of shares.
#include "core/operator/work_share.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <thread>

#include "core/operator/sample_operator.h"
#include "job/config.h"
#include "job/job_scene.h"

namespace ilp {
namespace {

// What the ranks' gather and broadcast do, for `count` threads. `reverse` hands share 0
// a round's blocks in the wrong order and `drop` leaves share `drop`'s blocks out: the
// faults the byte-identity check must catch.
class Rendezvous {
 public:
  explicit Rendezvous(int count, bool reverse = false, int drop = -1)
      : count_(count), reverse_(reverse), drop_(drop), slots_(static_cast<std::size_t>(count)) {}

  std::vector<std::vector<double>> gather(int index, std::vector<double> mine) {
    std::unique_lock lock(mutex_);
    slots_[static_cast<std::size_t>(index)] = index == drop_ ? std::vector<double>() : std::move(mine);
    arrive(lock);
    std::vector<std::vector<double>> out;
    if (index == 0) {
      out = slots_;
      if (reverse_) std::reverse(out.begin(), out.end());
    }
    arrive(lock);  // everyone has read before the next round writes
    return out;
  }

  std::vector<double> broadcast(int index, std::vector<double> values) {
    std::unique_lock lock(mutex_);
    if (index == 0) root_ = std::move(values);
    arrive(lock);
    std::vector<double> out = root_;
    arrive(lock);
    return out;
  }

  WorkShare share(int index) {
    WorkShare s;
    s.index = index;
    s.count = count_;
    s.gather = [this, index](std::vector<double> mine) { return gather(index, std::move(mine)); };
    s.broadcast = [this, index](std::vector<double> values) { return broadcast(index, std::move(values)); };
    return s;
  }

 private:
  void arrive(std::unique_lock<std::mutex>& lock) {
    const std::size_t generation = generation_;
    if (++arrived_ == count_) {
      arrived_ = 0;
      ++generation_;
      changed_.notify_all();
    } else {
      changed_.wait(lock, [&] { return generation_ != generation; });
    }
  }

  int count_;
  bool reverse_;
  int drop_;
  std::vector<std::vector<double>> slots_;
  std::vector<double> root_;
  std::mutex mutex_;
  std::condition_variable changed_;
  int arrived_ = 0;
  std::size_t generation_ = 0;
};

struct Fixture {
  Scene scene;
  std::unique_ptr<RayCaster> caster;
  GoalRows goals;
  SampleOperatorOptions options;
};

// The shipped office, coarse (about 1,900 patches), a sample, goal patches and a few
// goal points, and blocks of 97 hit patches: about 20 blocks, several per share.
// Built in place (the caster refers to the scene, which must not move).
const Fixture& fixture() {
  static const Fixture* built = [] {
    auto* f = new Fixture;
    JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office_fixed.yaml");
    job.scene.max_patch_edge_m = 0.6;
    f->scene = load_job_scene(job).scene;
    f->caster = std::make_unique<RayCaster>(f->scene, 1);
    f->options.sample_size = 150;
    f->options.form_factors.rays_per_patch = 64;
    f->options.form_factors.threads = f->options.direct_light.threads = 1;
    f->options.hit_block_patches = 97;
    const std::vector<int> goal_patches = f->scene.patches_of({"desk_1", "floor"});
    std::vector<ReceiverPoint> points;
    for (int i = 0; i < 6; ++i) points.push_back({Eigen::Vector3d(0.5 + 0.4 * i, 1.5, 0.8), Eigen::Vector3d::UnitZ()});
    f->goals = compute_goal_rows(f->scene, *f->caster, goal_patches, points, scene_light_sources(f->scene), f->options);
    return f;
  }();
  return *built;
}

// T built by `count` virtual ranks (threads); every rank's T must be the same.
Eigen::MatrixXd split_build(int count, bool reverse = false, int drop = -1) {
  const Fixture& f = fixture();
  Rendezvous rendezvous(count, reverse, drop);
  std::vector<Eigen::MatrixXd> T(static_cast<std::size_t>(count));
  std::vector<std::thread> ranks;
  for (int r = 0; r < count; ++r)
    ranks.emplace_back([&, r] {
      SampleOperatorOptions o = f.options;
      o.share = rendezvous.share(r);
      T[static_cast<std::size_t>(r)] = build_sample_operator(f.scene, *f.caster, f.goals, o).total_lux_per_lm;
    });
  for (std::thread& t : ranks) t.join();
  for (int r = 1; r < count; ++r) EXPECT_TRUE(T[static_cast<std::size_t>(r)] == T[0]) << "rank " << r << " of " << count;
  return T[0];
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}

TEST(WorkShare, SplitBuildHasTheSameBitsForOneTwoAndThreeShares) {
  const Fixture& f = fixture();
  const SampleOperator one = build_sample_operator(f.scene, *f.caster, f.goals, f.options);
  ASSERT_GT(one.stats.cheap_direct_rows, 3u * 97u) << "the test needs several blocks per share";
  ASSERT_GT(f.goals.points.size(), 0u);
  ASSERT_EQ(one.total_lux_per_lm.rows(), static_cast<Eigen::Index>(f.goals.patches.size() + f.goals.points.size()));
  for (int count : {1, 2, 3}) {
    const Eigen::MatrixXd T = split_build(count);
    EXPECT_TRUE(same_bits(T, one.total_lux_per_lm)) << count << " shares: max difference "
                                                    << (T - one.total_lux_per_lm).cwiseAbs().maxCoeff();
  }
}

// The identity above means something only if the order of the blocks shows in the bits,
// and a share left out shows in the light.
TEST(WorkShare, BlocksInAnotherOrderOrAShareLeftOutChangeT) {
  const Eigen::MatrixXd T = split_build(1);
  const Eigen::MatrixXd reversed = split_build(3, true);
  EXPECT_FALSE(same_bits(reversed, T)) << "adding a round's blocks in reverse gave the same bits";
  EXPECT_LT((reversed - T).cwiseAbs().maxCoeff(), 1e-12 * T.cwiseAbs().maxCoeff()) << "only round-off may differ";
  const Eigen::MatrixXd dropped = split_build(2, false, 1);
  EXPECT_GT((dropped - T).cwiseAbs().maxCoeff(), 1e-4 * T.cwiseAbs().maxCoeff()) << "share 1's blocks left out";
}

// The blocks only change how the sums are ordered: one block of every hit gives T to
// round-off, and the stats count every block's patches on every share.
TEST(WorkShare, BlockSizeChangesOnlyRoundOff) {
  const Fixture& f = fixture();
  SampleOperatorOptions whole = f.options;
  whole.hit_block_patches = 1 << 30;
  const SampleOperator a = build_sample_operator(f.scene, *f.caster, f.goals, whole);
  const SampleOperator b = build_sample_operator(f.scene, *f.caster, f.goals, f.options);
  EXPECT_EQ(a.stats.cheap_direct_rows, b.stats.cheap_direct_rows);
  EXPECT_LT((a.total_lux_per_lm - b.total_lux_per_lm).cwiseAbs().maxCoeff(), 1e-12 * a.total_lux_per_lm.cwiseAbs().maxCoeff());
}

TEST(WorkShare, ReduceBlocksAddsInBlockOrderWhateverTheShares) {
  // 0.1 + 0.2 + 0.3 is not 0.1 + (0.2 + 0.3) in binary: the order shows.
  const std::vector<double> parts{1e16, 1.0, -1e16, 1.0, 0.1, 0.2, 0.3};
  auto partial = [&](std::size_t b) { return std::vector<double>{parts[b]}; };
  const std::vector<double> one = reduce_blocks(parts.size(), WorkShare{}, partial);
  for (int count : {2, 3, 4, 8}) {
    Rendezvous rendezvous(count);
    std::vector<std::vector<double>> totals(static_cast<std::size_t>(count));
    std::vector<std::thread> ranks;
    for (int r = 0; r < count; ++r)
      ranks.emplace_back([&, r] { totals[static_cast<std::size_t>(r)] = reduce_blocks(parts.size(), rendezvous.share(r), partial); });
    for (std::thread& t : ranks) t.join();
    for (const std::vector<double>& t : totals) EXPECT_EQ(t, one) << count << " shares";
  }
  double sequential = 0.0;
  for (double p : parts) sequential += p;
  EXPECT_EQ(one, std::vector<double>{sequential});
  WorkShare bad;
  bad.count = 2;
  EXPECT_THROW(reduce_blocks(1, bad, partial), std::invalid_argument);
}

}  // namespace
}  // namespace ilp
