// libFuzzer harness: the job config loader (job/config.cpp, yaml-cpp) on any bytes,
// then plan_job, which reads the products' photometric files. The input is the job
// file; from a line "#ies" on it is the photometric file a.ies beside it (seeds name
// it as a product's photometry; b.ldt beside it is always a valid EULUMDAT file).
// Every input must give a plan or an IlpError (ConfigError, PhotometryError); anything
// else (a crash, a sanitizer report, another exception) is a finding.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/base/error.h"
#include "fuzz/fuzz_file.h"
#include "fuzz/fuzz_photometry_seed.h"
#include "job/config.h"
#include "job/plan.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::size_t split = std::min(text.find("\n#ies\n"), size);
  const std::string path = ilp::fuzz::write_input("job.yaml", data, split);
  const std::size_t ies_start = std::min(size, split + 6);
  ilp::fuzz::write_input("a.ies", data + ies_start, size - ies_start);
  ilp::fuzz::write_valid_ldt("b.ldt");
  try {
    const ilp::JobConfig job = ilp::load_job_config(path);
    (void)ilp::plan_job(job);
  } catch (const ilp::IlpError&) {
  }
  return 0;
}
