// A 4 x 4 x 2.5 m box (floor, ceiling, walls) for job files whose loading a test
// checks, and the ConfigError such a job file raises.
#pragma once

#include <string>

#include "job/config.h"
#include "tests/test_support.h"

namespace ilp::test {

inline const char* kRoomObj =
    "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 0 0 2.5\nv 4 0 2.5\nv 4 4 2.5\nv 0 4 2.5\n"
    "g floor\nf 1 2 3 4\ng ceiling\nf 5 8 7 6\ng walls\nf 1 4 8 5\nf 2 6 7 3\nf 1 5 6 2\nf 4 3 7 8\n";

inline const std::string kRoomScene = "scene:\n  mesh: room.obj\n  default_reflectance: 0.5\n";

// The message of the ConfigError loading `yaml` (beside room.obj) raises.
inline std::string config_error(const TempDir& dir, const std::string& yaml) {
  dir.write("room.obj", kRoomObj);
  const std::string path = dir.write("job.yaml", yaml);
  return error_of<ConfigError>([&] { (void)load_job_config(path); }, "load_job_config");
}

}  // namespace ilp::test
