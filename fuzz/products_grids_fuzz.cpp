// libFuzzer harness: products and calculation grids of a job on a fixed room. The input
// is the job file (seeds hold products and grids; the room is room.obj, a 4 x 4 x 2.5 m
// box with a desk); from a line "#ies" on it is the photometric file a.ies beside it
// (b.ldt beside it is a valid EULUMDAT file). Each input goes through load_job_config,
// plan_job (the products' files), load_job_scene and, per variant, costed_geometry
// within 64 MB (the cost of every grid point, the refusal before laying, the grids laid).
// Every input must end in a model or an IlpError; std::invalid_argument is what the
// model's geometry throws for a job without goals, as `ilp run` reports it. Anything
// else is a finding.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "core/base/error.h"
#include "fuzz/fuzz_file.h"
#include "fuzz/fuzz_photometry_seed.h"
#include "job/config.h"
#include "job/job_cost.h"
#include "job/job_scene.h"
#include "job/plan.h"

namespace {

constexpr const char* kRoom =
    "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 0 0 2.5\nv 4 0 2.5\nv 4 4 2.5\nv 0 4 2.5\n"
    "v 1 1 0.7\nv 2 1 0.7\nv 2 2 0.7\nv 1 2 0.7\n"
    "g floor\nf 1 2 3 4\ng ceiling\nf 5 8 7 6\ng walls\nf 1 4 8 5\nf 2 6 7 3\nf 1 5 6 2\nf 4 3 7 8\n"
    "g desk\nf 9 10 11 12\n";

void run(const std::string& path) {
  ilp::JobConfig job = ilp::load_job_config(path);
  job.form_factors.threads = 1;
  job.scene.max_patches = std::min<std::size_t>(job.scene.max_patches, 20000);  // as a small budget would
  ilp::RunOptions options;
  options.threads = 1;
  const std::vector<ilp::VariantPlan> plans = ilp::plan_job(job, options).variants;
  const ilp::JobScene loaded = ilp::load_job_scene(scene_spec(job));
  const ilp::MemoryBudget budget{64e6, "the harness"};
  for (const ilp::VariantPlan& plan : plans) {
    if (!job.search || job.goals.empty()) break;
    const ilp::CostedGeometry costed =
        ilp::costed_geometry(plan, loaded.scene, budget, ilp::job_machine_costs(plan.model.threads, options));
    (void)costed;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool room = [] {
    const std::uint8_t* bytes = reinterpret_cast<const std::uint8_t*>(kRoom);
    ilp::fuzz::write_input("room.obj", bytes, std::string_view(kRoom).size());
    return true;
  }();
  (void)room;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::size_t split = std::min(text.find("\n#ies\n"), size);
  const std::string path = ilp::fuzz::write_input("job.yaml", data, split);
  const std::size_t ies_start = std::min(size, split + 6);
  ilp::fuzz::write_input("a.ies", data + ies_start, size - ies_start);
  ilp::fuzz::write_valid_ldt("b.ldt");
  try {
    run(path);
  } catch (const ilp::IlpError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
