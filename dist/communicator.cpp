#include "dist/communicator.h"

#include <mpi.h>

#include <climits>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <new>

namespace ilp::dist {
namespace {

bool under_mpi_launcher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  std::cerr << "error: MPI " << what << " failed (code " << code << ")\n";
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::_Exit(1);
}

}  // namespace

Communicator::Communicator() {
  if (!under_mpi_launcher()) return;
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "init");
  mpi_ = true;
  check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "rank");
  check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "size");
  MPI_Comm node;
  check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node), "split by node");
  check(MPI_Comm_size(node, &node_size_), "node size");
  MPI_Comm_free(&node);
  // Errors end the job (the default), they are not returned: a lost rank ends every rank.
}

Communicator& Communicator::world() {
  static Communicator world;
  return world;
}

std::vector<std::string> Communicator::gather(const std::string& bytes) const {
  if (!mpi_ || size_ == 1) return {bytes};
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) abort("a rank's results exceed 2 GiB");
  int mine = static_cast<int>(bytes.size());
  std::vector<int> sizes(is_root() ? size_ : 0);
  check(MPI_Gather(&mine, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "gather");
  std::vector<int> offsets(sizes.size());
  long long total = 0;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    offsets[i] = static_cast<int>(total);
    total += sizes[i];
    if (total > INT_MAX) abort("the ranks' results exceed 2 GiB");
  }
  std::string all(static_cast<std::size_t>(total), '\0');
  check(MPI_Gatherv(bytes.data(), mine, MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE, 0, MPI_COMM_WORLD),
        "gatherv");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < sizes.size(); ++i) out.push_back(all.substr(offsets[i], sizes[i]));
  return out;
}

std::string Communicator::broadcast(const std::string& bytes) const {
  if (!mpi_ || size_ == 1) return bytes;
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) abort("a broadcast exceeds 2 GiB");
  int n = static_cast<int>(bytes.size());
  check(MPI_Bcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD), "broadcast");
  std::string out = is_root() ? bytes : std::string(static_cast<std::size_t>(n), '\0');
  check(MPI_Bcast(out.data(), n, MPI_BYTE, 0, MPI_COMM_WORLD), "broadcast");
  return out;
}

void Communicator::abort(const std::string& message) const {
  std::cerr << "error: " << message << (size_ > 1 ? " (rank " + std::to_string(rank_) + "; ending every rank)" : "")
            << "\n" << std::flush;
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, 1);
  std::_Exit(1);
}

void Communicator::finalize() {
  if (!mpi_) return;
  mpi_ = false;
  MPI_Finalize();
}

std::string failure_message(const std::exception_ptr& failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const std::bad_alloc&) {
    return "out of memory (a smaller job: larger scene.max_patch_edge_m, fewer rays or candidates)";
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "an unexpected failure (please report it with the job file)";
  }
}

void on_every_rank(const Communicator& comm, const std::function<void()>& step) {
  if (!comm.distributed()) return step();
  std::string status = "ok";
  try {
    step();
  } catch (const FailedElsewhere&) {
    status = "failed";
  } catch (...) {
    status = "error" + failure_message(std::current_exception());
  }
  const std::vector<std::string> all = comm.gather(status);
  std::string verdict = "ok";
  for (const std::string& s : all)
    if (s != "ok") {
      verdict = s.rfind("error", 0) == 0 ? s.substr(5) : "failed on another rank";
      break;
    }
  verdict = comm.broadcast(comm.is_root() ? verdict : std::string());
  if (verdict == "ok") return;
  if (comm.is_root()) throw std::runtime_error(verdict);
  throw FailedElsewhere();
}

std::string agree(const Communicator& comm, const StepPart& mine,
                  const std::function<std::string(std::vector<std::string> all)>& combine) {
  if (!comm.distributed()) {
    if (!mine.ok) throw AgreedFailure(mine.bytes);
    return combine({mine.bytes});
  }
  std::vector<std::string> all = comm.gather((mine.ok ? "o" : "e") + mine.bytes);
  std::string verdict;
  if (comm.is_root()) {
    for (const std::string& part : all)
      if (part.empty() || part[0] != 'o') {
        verdict = part.empty() ? "ea rank sent nothing" : part;
        break;
      }
    if (verdict.empty()) {
      for (std::string& part : all) part.erase(0, 1);
      try {
        verdict = "o" + combine(std::move(all));
      } catch (...) {
        verdict = "e" + failure_message(std::current_exception());
      }
    }
  }
  verdict = comm.broadcast(verdict);
  if (!verdict.empty() && verdict[0] == 'o') return verdict.substr(1);
  if (comm.is_root()) throw AgreedFailure(verdict.substr(1));
  throw FailedElsewhere();
}

void in_agreed_steps(const Communicator& comm, const std::function<void()>& work) {
  if (!comm.distributed()) return work();
  const auto nothing = [](const std::vector<std::string>&) { return std::string(); };
  try {
    work();
  } catch (const AgreedFailure&) {
    throw;  // every rank knows already
  } catch (const FailedElsewhere&) {
    throw;
  } catch (...) {
    agree(comm, {false, failure_message(std::current_exception())}, nothing);  // throws
  }
  agree(comm, {true, ""}, nothing);
}

int on_root_only(const Communicator& comm, const std::function<int()>& work) {
  if (!comm.distributed()) return work();
  int code = 1;
  std::exception_ptr failure;
  if (comm.is_root()) {
    try {
      code = work();
    } catch (...) {
      failure = std::current_exception();
    }
  }
  const std::string agreed = comm.broadcast(comm.is_root() ? std::to_string(failure ? 1 : code) : std::string());
  if (failure) std::rethrow_exception(failure);
  if (!comm.is_root() && agreed != "0" && agreed != "2") throw FailedElsewhere();
  return std::stoi(agreed);
}

}  // namespace ilp::dist
