// The settings core/ and optimizer/ messages name (core/base/setting.h): by their
// description until the job layer registers its keys, then as the job file spells them.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/base/setting.h"
#include "core/scene/surface_split.h"
#include "job/setting_keys.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

constexpr int kSettings = static_cast<int>(Setting::goal_cylindrical_lux) + 1;

// Restores the namer a test replaced.
struct NamerRestore {
  SettingNamer saved;
  ~NamerRestore() { register_setting_names(saved); }
};

TEST(SettingKeys, EverySettingHasItsOwnKeyAndADescriptionWithoutTheJobLayer) {
  const NamerRestore restore{register_setting_names(nullptr)};
  std::set<std::string> keys, descriptions;
  for (int i = 0; i < kSettings; ++i) {
    const auto s = static_cast<Setting>(i);
    const std::string key = setting_key(s, "desks"), description = setting_name(s, "desks");
    EXPECT_TRUE(keys.insert(key).second) << "two settings share the key " << key;
    EXPECT_TRUE(descriptions.insert(description).second) << "two settings share the description " << description;
    EXPECT_NE(key, description);
    EXPECT_EQ(key.find(' '), std::string::npos) << key;  // a key, not words
    EXPECT_NE(description.find(' '), std::string::npos) << description;
  }
  EXPECT_EQ(setting_key(Setting::grid_height, "work"), "grids.work.height_m");
  EXPECT_EQ(setting_key(Setting::grid_spacing), "grids[].spacing_m");
  EXPECT_EQ(setting_key(Setting::goal_ugr_max, "desks"), "goals.desks.ugr_max");
  name_settings_by_key();
  for (int i = 0; i < kSettings; ++i)
    EXPECT_EQ(setting_name(static_cast<Setting>(i), "desks"), setting_key(static_cast<Setting>(i), "desks"));
}

// A core stage's message names the setting as the registered namer does: the job
// file's key with the job layer, the description without it.
TEST(SettingKeys, ACoreMessageNamesTheSettingAsRegistered) {
  const NamerRestore restore{register_setting_names(nullptr)};
  SurfaceSplitOptions options;
  options.regions = {{"table", Facing::up, std::pair{0.6, 0.8}, 0.0, {"job.yaml", 7, 5}}};
  auto message = [&] {
    TriangleMesh mesh;
    mesh.path = "<test>";
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}};
    mesh.triangle_surface = {0};
    mesh.triangle_material = {-1};
    mesh.surface_names = {"floor"};
    return test::error_of<ConfigError>([&] { split_surfaces(mesh, {}, options); });
  };
  EXPECT_TRUE(test::Contains(message(), "the named regions[0] 'table'")) << message();
  name_settings_by_key();
  EXPECT_TRUE(test::Contains(message(), "scene.regions[0] 'table'")) << message();
}

}  // namespace
}  // namespace ilp
