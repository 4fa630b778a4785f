#include <cstdio>
#include "job/config.h"
#include "job/job_scene.h"
#include "core/transport/ray_caster.h"
using namespace ilp;
int main(int argc, char** argv) {
  const JobConfig job = load_job_config(argv[1]);
  JobScene js = load_job_scene(job);
  RayCaster c(js.scene);
  for (int i = 3; i + 1 < argc; i += 2) {
    Eigen::Vector3d p(atof(argv[i]), atof(argv[i+1]), atof(argv[2]));
    for (auto d : {Eigen::Vector3d(0,0,-1), Eigen::Vector3d(0,0,1), Eigen::Vector3d(0,1,0), Eigen::Vector3d(0,-1,0), Eigen::Vector3d(1,0,0), Eigen::Vector3d(-1,0,0)}) {
      RayHit h = c.first_hit(p, d, 10);
      printf("(%.3f %.3f %.3f) dir (%g %g %g): %s t=%.3f\n", p.x(), p.y(), p.z(), d.x(), d.y(), d.z(), h.patch>=0? js.scene.surfaces[js.scene.patches[h.patch].surface].name.c_str():"-", h.t);
    }
  }
}
