// The operator cache's key from the stage inputs (core/base/key_hash.h): the canonical
// text is unambiguous and exact, field_count counts every field, and each core options
// struct's hash_fields sees every field that changes the operator and none of those
// it leaves out on purpose (threads, progress, file locations, refusal limits).
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/key_hash.h"
#include "core/grid/calc_grid.h"
#include "core/transport/direct_light.h"
#include "core/light/luminaire.h"
#include "core/operator/sample_operator.h"
#include "core/operator/sample_size.h"
#include "core/transport/form_factors.h"
#include "core/scene/mesh.h"
#include "core/scene/scene.h"
#include "core/scene/surface_split.h"
#include "tests/key_coverage.h"

namespace ilp {
namespace {

using test::expect_key_covers_fields;
using test::left_out;

// ---- The vocabulary.

struct Plain {
  int a = 0;
  double b = 0.0;
  std::string c;
};

struct Awkward {  // field types a brace-initialisation probe can trip on
  std::optional<Eigen::Vector3d> rgb;
  std::optional<int> count;
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  std::function<void()> callback;
  std::shared_ptr<const int> shared;
  std::vector<Eigen::Vector2d> polygon;
  std::optional<std::pair<double, double>> range;
  Plain nested;
  FileLoc loc;
  std::optional<std::string> name;
};

struct Empty {};

static_assert(field_count<Empty>() == 0);
static_assert(field_count<Plain>() == 3);
static_assert(field_count<Awkward>() == 10);

template <class... T>
std::string text_of(const T&... values) {
  KeyWriter k;
  (k.value(values), ...);
  return k.text();
}

TEST(KeyWriter, StringsAreLengthPrefixed) {
  EXPECT_NE(text_of(std::string("ab"), std::string("c")), text_of(std::string("a"), std::string("bc")));
  EXPECT_NE(text_of(std::vector<std::string>{"a\nb"}), text_of(std::vector<std::string>{"a", "b"}));
  EXPECT_NE(text_of(std::vector<std::string>{}), text_of(std::vector<std::string>{""}));
  EXPECT_EQ(text_of(std::string("ab")), "s2:ab\n");
}

TEST(KeyWriter, OptionalsAreMarked) {
  EXPECT_NE(text_of(std::optional<double>()), text_of(std::optional<double>(0.0)));
  EXPECT_NE(text_of(std::optional<int>(), 0), text_of(std::optional<int>(0)));
  EXPECT_NE(text_of(std::optional<std::string>()), text_of(std::optional<std::string>("")));
}

TEST(KeyWriter, DoublesAreExact) {
  const double x = 0.1, next = std::nextafter(0.1, 1.0);
  EXPECT_NE(text_of(x), text_of(next));
  EXPECT_NE(text_of(0.0), text_of(-0.0));
  for (double v : {x, next, 1e-300, 6.02214076e23, 1.0 / 3.0}) {
    const std::string t = text_of(v);  // "d<shortest form>\n"
    double back = 0.0;
    std::from_chars(t.data() + 1, t.data() + t.size() - 1, back);
    EXPECT_EQ(back, v) << t;
  }
}

TEST(KeyWriter, KindsAndNamesAreDistinct) {
  EXPECT_NE(text_of(1), text_of(1.0));
  EXPECT_NE(text_of(1), text_of(true));
  EXPECT_NE(text_of(1), text_of(1u));
  EXPECT_NE(text_of(std::vector<int>{1, 2}), text_of(std::vector<int>{1}, 2));
  KeyWriter a, b;
  a.field("rays", 1);
  b.field("seed", 1);
  EXPECT_NE(a.text(), b.text());
  EXPECT_NE(text_of(Eigen::Vector2d(1, 2)), text_of(Eigen::Vector3d(1, 2, 0)));
  EXPECT_NE(text_of(Eigen::Vector2d(1, 2)), text_of(Eigen::Vector2d(2, 1)));
}

// ---- Each core options struct: every field has a case.

TEST(KeyHash, MeshReadOptionsCoverEveryField) {
  expect_key_covers_fields<MeshReadOptions>("MeshReadOptions", {}, {
      {"surface_naming", [](MeshReadOptions& o) { o.surface_naming = SurfaceNaming::material; }},
      left_out<MeshReadOptions>("import_limits", [](MeshReadOptions& o) { o.import_limits.max_time_s = 1.0; }),
  });
}

TEST(KeyHash, SceneOptionsCoverEveryField) {
  expect_key_covers_fields<SceneOptions>("SceneOptions", {}, {
      {"up_axis", [](SceneOptions& o) { o.up_axis = UpAxis::y; }},
      {"scale_to_m", [](SceneOptions& o) { o.scale_to_m = 0.001; }},
      {"max_patch_edge_m", [](SceneOptions& o) { o.max_patch_edge_m = 0.25; }},
      {"cut_at_contacts", [](SceneOptions& o) { o.cut_at_contacts = true; }},
      left_out<SceneOptions>("max_patches", [](SceneOptions& o) { o.max_patches = 1000; }),
  });
}

TEST(KeyHash, SurfaceSplitOptionsCoverEveryField) {
  RegionRule rule;
  rule.name = "desk";
  rule.facing = Facing::up;
  rule.height_m = std::pair(0.5, 1.0);
  rule.min_area_m2 = 0.2;
  expect_key_covers_fields<RegionRule>("RegionRule", rule, {
      {"name", [](RegionRule& r) { r.name = "table"; }},
      {"facing", [](RegionRule& r) { r.facing = Facing::down; }},
      {"height_m", [](RegionRule& r) { r.height_m->second = 1.1; }},
      {"min_area_m2", [](RegionRule& r) { r.min_area_m2 = 0.3; }},
      left_out<RegionRule>("loc", [](RegionRule& r) { r.loc = {"job.yaml", 12, 5}; }),
  });
  RegionRule any_facing = rule;
  any_facing.facing.reset();
  EXPECT_NE(key_text_of(any_facing), key_text_of(rule)) << "facing absent (any) is not facing up";

  SurfaceSplitOptions split;
  split.regions = {rule};
  expect_key_covers_fields<SurfaceSplitOptions>("SurfaceSplitOptions", split, {
      {"connected", [](SurfaceSplitOptions& o) { o.connected = true; }},
      {"weld_tolerance_m", [](SurfaceSplitOptions& o) { o.weld_tolerance_m = 2e-3; }},
      {"regions", [](SurfaceSplitOptions& o) { o.regions[0].min_area_m2 = 0.5; }},
  });
}

// A distribution that only its key tells apart.
class KeyedDistribution final : public IntensityDistribution {
 public:
  explicit KeyedDistribution(std::string key) : key_(std::move(key)) {}
  double cd_per_lm(const Eigen::Vector3d&) const override { return 0.0; }
  std::string key() const override { return key_; }

 private:
  std::string key_;
};

TEST(KeyHash, LuminaireTypeCoversEveryField) {
  expect_key_covers_fields<LuminaireType>("LuminaireType", LuminaireType::square_lambertian(0.6), {
      {"name", [](LuminaireType& t) { t.name = "panel"; }},
      {"shape", [](LuminaireType& t) { t.shape = OutlineShape::disc; }},
      {"length_m", [](LuminaireType& t) { t.length_m = 1.2; }},
      {"width_m", [](LuminaireType& t) { t.width_m = 0.3; }},
      {"distribution", [](LuminaireType& t) { t.distribution = std::make_shared<KeyedDistribution>("batwing"); }},
  });
}

TEST(KeyHash, CalcGridSettingCoversEveryField) {
  CalcGridSetting grid;
  grid.name = "desks";
  grid.over_surface = "floor";
  const FileLoc at{"job.yaml", 30, 3};
  expect_key_covers_fields<CalcGridSetting>("CalcGridSetting", grid, {
      {"name", [](CalcGridSetting& s) { s.name = "task"; }},
      left_out<CalcGridSetting>("loc", [&](CalcGridSetting& s) { s.loc = at; }),
      {"kind", [](CalcGridSetting& s) { s.kind = GridKind::vertical; }},
      {"over_surface", [](CalcGridSetting& s) { s.over_surface = "desk"; }},
      {"polygon_m", [](CalcGridSetting& s) { s.polygon_m = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)}; }},
      left_out<CalcGridSetting>("shape_loc", [&](CalcGridSetting& s) { s.shape_loc = at; }),
      {"height_m", [](CalcGridSetting& s) { s.height_m = 0.75; }},
      left_out<CalcGridSetting>("height_loc", [&](CalcGridSetting& s) { s.height_loc = at; }),
      {"from_m", [](CalcGridSetting& s) { s.from_m.x() = 1.0; }},
      {"to_m", [](CalcGridSetting& s) { s.to_m.y() = 2.0; }},
      {"bottom_m", [](CalcGridSetting& s) { s.bottom_m = 0.1; }},
      {"top_m", [](CalcGridSetting& s) { s.top_m = 2.0; }},
      {"facing_left", [](CalcGridSetting& s) { s.facing_left = false; }},
      {"border_m", [](CalcGridSetting& s) { s.border_m = 0.3; }},
      left_out<CalcGridSetting>("border_loc", [&](CalcGridSetting& s) { s.border_loc = at; }),
      {"spacing_m", [](CalcGridSetting& s) { s.spacing_m = 0.25; }},
      left_out<CalcGridSetting>("spacing_loc", [&](CalcGridSetting& s) { s.spacing_loc = at; }),
      left_out<CalcGridSetting>("max_points", [](CalcGridSetting& s) { s.max_points = 500; }),
      left_out<CalcGridSetting>("max_points_loc", [&](CalcGridSetting& s) { s.max_points_loc = at; }),
      {"band_width_m", [](CalcGridSetting& s) { s.band_width_m = 0.5; }},
      left_out<CalcGridSetting>("band_loc", [&](CalcGridSetting& s) { s.band_loc = at; }),
  });
}

TEST(KeyHash, FormFactorOptionsCoverEveryField) {
  expect_key_covers_fields<FormFactorOptions>("FormFactorOptions", {}, {
      {"rays_per_patch", [](FormFactorOptions& o) { o.rays_per_patch = 128; }},
      {"seed", [](FormFactorOptions& o) { o.seed = 7; }},
      left_out<FormFactorOptions>("threads", [](FormFactorOptions& o) { o.threads = 3; }),
  });
}

TEST(KeyHash, DirectLightOptionsCoverEveryField) {
  expect_key_covers_fields<DirectLightOptions>("DirectLightOptions", {}, {
      {"receiver_points", [](DirectLightOptions& o) { o.receiver_points = 4; }},
      {"shadow_rays", [](DirectLightOptions& o) { o.shadow_rays = 16; }},
      {"seed", [](DirectLightOptions& o) { o.seed = 9; }},
      left_out<DirectLightOptions>("threads", [](DirectLightOptions& o) { o.threads = 3; }),
      left_out<DirectLightOptions>("form_factors", [](DirectLightOptions& o) { o.form_factors = false; }),
      left_out<DirectLightOptions>("progress",
                                   [](DirectLightOptions& o) { o.progress = [](std::string_view, std::size_t, std::size_t) {}; }),
      left_out<DirectLightOptions>("progress_label", [](DirectLightOptions& o) { o.progress_label = "goal points"; }),
  });
}

TEST(KeyHash, SampleOperatorOptionsCoverEveryField) {
  expect_key_covers_fields<SampleOperatorOptions>("SampleOperatorOptions", {}, {
      {"sample_size", [](SampleOperatorOptions& o) { o.sample_size = 50; }},
      {"strategy", [](SampleOperatorOptions& o) { o.strategy = SampleStrategy::uniform; }},
      {"sample_seed", [](SampleOperatorOptions& o) { o.sample_seed = 5; }},
      {"indirect", [](SampleOperatorOptions& o) { o.indirect = IndirectMethod::sample_gather; }},
      {"form_factors", [](SampleOperatorOptions& o) { o.form_factors.rays_per_patch = 512; }},
      {"direct_light", [](SampleOperatorOptions& o) { o.direct_light.shadow_rays = 2; }},
      {"hit_direct_light", [](SampleOperatorOptions& o) { o.hit_direct_light.receiver_points = 2; }},
      {"sample_direct_light", [](SampleOperatorOptions& o) { o.sample_direct_light.shadow_rays = 9; }},
      {"hit_block_patches", [](SampleOperatorOptions& o) { o.hit_block_patches = 97; }},
      left_out<SampleOperatorOptions>("share", [](SampleOperatorOptions& o) { o.share.count = 2; }),
  });
  // The nested options' threads and progress stay out.
  const SampleOperatorOptions base;
  SampleOperatorOptions other;
  other.form_factors.threads = other.direct_light.threads = other.hit_direct_light.threads =
      other.sample_direct_light.threads = 1;
  other.direct_light.progress = [](std::string_view, std::size_t, std::size_t) {};
  EXPECT_EQ(key_text_of(other), key_text_of(base));
}

TEST(KeyHash, SampleSizeRuleCoversEveryField) {
  expect_key_covers_fields<SampleSizeRule>("SampleSizeRule", {}, {
      {"size", [](SampleSizeRule& r) { r.size = 200; }},
      {"fraction", [](SampleSizeRule& r) { r.fraction = 0.1; }},
      {"max_size", [](SampleSizeRule& r) { r.max_size = 100; }},
      {"target_error", [](SampleSizeRule& r) { r.target_error = 0.05; }},
      {"error_samples", [](SampleSizeRule& r) { r.error_samples = 8; }},
      {"pilot_fraction", [](SampleSizeRule& r) { r.pilot_fraction = 0.04; }},
  });
}

}  // namespace
}  // namespace ilp
