// libFuzzer harness: the job config loader (job/config.cpp, yaml-cpp) on any bytes.
// Every input must give a JobConfig or an IlpError (ConfigError); anything else (a
// crash, a sanitizer report, another exception) is a finding.
#include <cstddef>
#include <cstdint>

#include "job/config.h"
#include "core/base/error.h"
#include "fuzz/fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = ilp::fuzz::write_input("job.yaml", data, size);
  try {
    const ilp::JobConfig job = ilp::load_job_config(path);
    (void)job;
  } catch (const ilp::IlpError&) {
  }
  return 0;
}
