// From a job configuration to a ready scene: loads the mesh, resolves every
// triangle's reflectance (config by surface name, else the MTL Kd, else the
// config's default), builds patches, sets emitting surfaces and adds luminaires.
// Names in the config that the mesh lacks are ConfigErrors pointing at the config.
#pragma once

#include <string>
#include <vector>

#include "job/config.h"
#include "core/scene/scene.h"

namespace ilp {

struct JobScene {
  Scene scene;
  std::vector<std::string> log;  // what was done to the input, for the run log
};

// `mesh_out`, when given, receives the mesh the scene was made from (file units, after
// surface splitting, exclusions and two-sided doubling), for `ilp inspect`.
JobScene load_job_scene(const JobConfig& job, TriangleMesh* mesh_out = nullptr);

}  // namespace ilp
