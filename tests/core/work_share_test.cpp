// A split operator build (core/operator/work_share.h) in one process: "virtual ranks"
// are threads meeting through an in-memory rendezvous, as mpirun's ranks meet through
// dist::agree. T must have the same bits whatever the number of shares.
#include "core/operator/work_share.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>

#include "core/transport/direct_light.h"
#include "core/operator/sample_operator.h"
#include "job/config.h"
#include "job/plan.h"
#include "job/job_scene.h"

namespace ilp {
namespace {

// What the ranks' gather and broadcast do, for `count` threads. `reverse` hands share 0
// a round's blocks (or the shares' columns) in the wrong order and `drop` leaves share
// `drop`'s blocks (or columns) out: the faults the byte-identity check must catch. A
// gather of 2 values or fewer (the split solve's stopping test) is never dropped.
class Rendezvous {
 public:
  explicit Rendezvous(int count, bool reverse = false, int drop = -1)
      : count_(count), reverse_(reverse), drop_(drop), slots_(static_cast<std::size_t>(count)) {}

  std::vector<std::vector<double>> gather(int index, std::vector<double> mine) {
    std::unique_lock lock(mutex_);
    slots_[static_cast<std::size_t>(index)] = index == drop_ && mine.size() > 2 ? std::vector<double>() : std::move(mine);
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
    f->scene = load_job_scene(scene_spec(job)).scene;
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

// T built by `count` virtual ranks (threads); every rank's T must be the same. A rank
// that throws gives its message in `errors` (T empty).
Eigen::MatrixXd split_build(int count, bool reverse = false, int drop = -1, std::vector<std::string>* errors = nullptr,
                            IndirectMethod indirect = IndirectMethod::exact_second_bounce) {
  const Fixture& f = fixture();
  Rendezvous rendezvous(count, reverse, drop);
  std::vector<Eigen::MatrixXd> T(static_cast<std::size_t>(count));
  std::vector<std::string> failed(static_cast<std::size_t>(count));
  std::vector<std::thread> ranks;
  for (int r = 0; r < count; ++r)
    ranks.emplace_back([&, r] {
      SampleOperatorOptions o = f.options;
      o.indirect = indirect;
      o.share = rendezvous.share(r);
      try {
        T[static_cast<std::size_t>(r)] = build_sample_operator(f.scene, *f.caster, f.goals, o).total_lux_per_lm;
      } catch (const std::exception& e) {
        failed[static_cast<std::size_t>(r)] = e.what();
      }
    });
  for (std::thread& t : ranks) t.join();
  if (errors) *errors = failed;
  else
    for (int r = 0; r < count; ++r) EXPECT_EQ(failed[static_cast<std::size_t>(r)], "") << "rank " << r << " of " << count;
  for (int r = 1; r < count; ++r) EXPECT_TRUE(T[static_cast<std::size_t>(r)] == T[0]) << "rank " << r << " of " << count;
  return T[0];
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}

// The shares split T's columns (the office's four luminaires): 5 shares leave one
// without a column, which must still take part in every exchange.
TEST(WorkShare, SplitBuildHasTheSameBitsForOneToFiveShares) {
  const Fixture& f = fixture();
  const SampleOperator one = build_sample_operator(f.scene, *f.caster, f.goals, f.options);
  ASSERT_GT(one.stats.cheap_direct_rows, 3u * 97u) << "the test needs several blocks of hit patches";
  ASSERT_GT(f.goals.points.size(), 0u);
  ASSERT_EQ(f.goals.sources.size(), 4u);
  ASSERT_EQ(one.total_lux_per_lm.rows(), static_cast<Eigen::Index>(f.goals.patches.size() + f.goals.points.size()));
  for (int count : {1, 2, 3, 4, 5}) {
    const Eigen::MatrixXd T = split_build(count);
    EXPECT_TRUE(same_bits(T, one.total_lux_per_lm)) << count << " shares: max difference "
                                                    << (T - one.total_lux_per_lm).cwiseAbs().maxCoeff();
  }
  // Without the refinement (no hit blocks): the solve alone is split.
  SampleOperatorOptions plain = f.options;
  plain.indirect = IndirectMethod::sample_gather;
  const SampleOperator plain_one = build_sample_operator(f.scene, *f.caster, f.goals, plain);
  for (int count : {2, 3})
    EXPECT_TRUE(same_bits(split_build(count, false, -1, nullptr, IndirectMethod::sample_gather), plain_one.total_lux_per_lm))
        << count << " shares, sample_gather";
}

// The identity above means something only if the order of the shares' columns shows in
// T and a share's columns left out are caught (every share stops with the same error,
// none waits for the others).
TEST(WorkShare, SharesColumnsInAnotherOrderOrAShareLeftOutAreCaught) {
  const Eigen::MatrixXd T = split_build(1);
  const Eigen::MatrixXd reversed = split_build(2, true);
  EXPECT_FALSE(same_bits(reversed, T)) << "the shares' columns concatenated in reverse gave the same bits";
  EXPECT_GT((reversed - T).cwiseAbs().maxCoeff(), 1e-4 * T.cwiseAbs().maxCoeff()) << "columns swapped";
  std::vector<std::string> errors;
  split_build(3, false, 1, &errors);
  for (std::size_t r = 0; r < errors.size(); ++r)
    EXPECT_NE(errors[r].find("values gathered"), std::string::npos) << "rank " << r << ": '" << errors[r] << "'";
  ASSERT_EQ(errors.size(), 3u);
}

// The order of the hit blocks shows in the bits (so the identity above, which adds them
// in block order on every share, is a real check): the first reflection's sum over the
// blocks in reverse differs in the last bits only.
TEST(WorkShare, HitBlocksInAnotherOrderChangeTheLastBits) {
  std::vector<std::vector<double>> blocks{{0.1, 1e16}, {0.2, 1.0}, {0.3, -1e16}};
  std::vector<double> forward, backward;
  add_blocks_in_order(forward, blocks);
  std::reverse(blocks.begin(), blocks.end());
  add_blocks_in_order(backward, blocks);
  EXPECT_NE(forward, backward);
  std::vector<double> missing;
  add_blocks_in_order(missing, {blocks[0], blocks[2]});
  EXPECT_NE(missing, forward);
}

TEST(WorkShare, ColumnRangesCoverEveryColumnOnceInShareOrder) {
  for (std::size_t columns : {0u, 1u, 3u, 4u, 150u, 151u})
    for (int count = 1; count <= 7; ++count) {
      std::size_t next = 0;
      for (int index = 0; index < count; ++index) {
        WorkShare s;
        s.index = index;
        s.count = count;
        const auto [first, last] = s.column_range(columns);
        EXPECT_EQ(first, next) << columns << " columns, share " << index << " of " << count;
        EXPECT_LE(first, last);
        EXPECT_LE(last - first, columns / static_cast<std::size_t>(count) + 1);
        next = last;
      }
      EXPECT_EQ(next, columns) << columns << " columns, " << count << " shares";
    }
}

TEST(WorkShare, GatherSharesConcatenatesAndMaxOverSharesTakesTheLargest) {
  EXPECT_EQ(gather_shares(WorkShare{}, {1.0, 2.0}), (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(max_over_shares(WorkShare{}, {1.0, 2.0}), (std::vector<double>{1.0, 2.0}));
  for (int count : {2, 3, 4}) {
    Rendezvous rendezvous(count);
    std::vector<std::vector<double>> gathered(static_cast<std::size_t>(count)), most(gathered.size());
    std::vector<std::thread> ranks;
    for (int r = 0; r < count; ++r)
      ranks.emplace_back([&, r] {
        const auto i = static_cast<std::size_t>(r);
        // Share r passes r values (share 0 none), and {r, -r} to the maximum.
        gathered[i] = gather_shares(rendezvous.share(r), std::vector<double>(i, static_cast<double>(r)));
        most[i] = max_over_shares(rendezvous.share(r), {static_cast<double>(r), -static_cast<double>(r)});
      });
    for (std::thread& t : ranks) t.join();
    std::vector<double> expected;
    for (int r = 0; r < count; ++r) expected.insert(expected.end(), static_cast<std::size_t>(r), static_cast<double>(r));
    for (int r = 0; r < count; ++r) {
      EXPECT_EQ(gathered[static_cast<std::size_t>(r)], expected) << count << " shares, share " << r;
      EXPECT_EQ(most[static_cast<std::size_t>(r)], (std::vector<double>{count - 1.0, 0.0})) << count << " shares";
    }
  }
}

// A share's luminaires alone have the bits they have among every luminaire (what is
// negligible is judged against the brightest of all of them, computed or not).
TEST(WorkShare, SomeLuminairesAloneHaveTheirBitsAmongAll) {
  const Fixture& f = fixture();
  const std::vector<int> surfaces = luminaire_surfaces(f.scene);
  ASSERT_EQ(surfaces.size(), 4u);
  std::vector<int> receivers;
  for (int p = 0; p < static_cast<int>(f.scene.patches.size()); p += 7) receivers.push_back(p);
  DirectLightOptions cheap = f.options.hit_direct_light;
  cheap.threads = 1;
  const LuminaireLight all = compute_luminaire_light(f.scene, *f.caster, receivers, surfaces, cheap);
  for (const std::vector<int>& some : {std::vector<int>{2}, std::vector<int>{1, 3}, std::vector<int>{0, 1, 2, 3}}) {
    const LuminaireLight part = compute_luminaire_light(f.scene, *f.caster, receivers, surfaces, some, cheap);
    ASSERT_EQ(part.lux_per_lm.cols(), static_cast<Eigen::Index>(some.size()));
    for (std::size_t c = 0; c < some.size(); ++c) {
      EXPECT_TRUE(same_bits(part.lux_per_lm.col(static_cast<Eigen::Index>(c)), all.lux_per_lm.col(some[c])))
          << "luminaire " << some[c];
      EXPECT_TRUE(same_bits(part.form_factor.col(static_cast<Eigen::Index>(c)), all.form_factor.col(some[c])))
          << "luminaire " << some[c];
    }
  }
  EXPECT_THROW(compute_luminaire_light(f.scene, *f.caster, receivers, surfaces, std::vector<int>{4}, cheap),
               std::invalid_argument);
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
