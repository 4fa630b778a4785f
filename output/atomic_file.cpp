#include "output/atomic_file.h"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/error.h"

namespace ilp {

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string tmp = path + ".tmp";
  try {
    std::ofstream out(tmp);
    if (!out) throw IlpError(path + ": cannot write");
    write(out);
    if (!out.flush()) throw IlpError(path + ": write failed");
    out.close();  // can still fail: some file systems report write errors only on close
    if (!out) throw IlpError(path + ": write failed");
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);  // atomic on POSIX when both are on one file system
    if (ec) throw IlpError(path + ": write failed (" + ec.message() + ")");
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

}  // namespace ilp
