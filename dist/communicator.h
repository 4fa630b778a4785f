// The one seam to MPI (docs/cluster.md): ilp's ranks, byte buffers gathered to rank 0 and
// broadcast from it, and an abort that ends every rank. Nothing else includes <mpi.h>;
// job/ and apps/ use this header only.
//
// MPI is initialised only when the environment says the program was started by an MPI
// launcher (mpirun/mpiexec of Open MPI: OMPI_COMM_WORLD_SIZE; srun with PMIx/PMI:
// PMIX_RANK, PMI_RANK). Otherwise there is one rank and no MPI call is made at all, so a
// plain `ilp run` starts and behaves exactly as before.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ilp::dist {

class Communicator {
 public:
  // The processes of this run (initialises MPI on first use when under a launcher).
  static Communicator& world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }
  bool distributed() const { return size_ > 1; }
  // The ranks on this node (sharing its memory), this one included.
  int node_size() const { return node_size_; }

  // Every rank gives its bytes; rank 0 gets them all in rank order, others an empty vector.
  std::vector<std::string> gather(const std::string& bytes) const;
  // Rank 0's `bytes` on every rank.
  std::string broadcast(const std::string& bytes) const;
  // Prints "error: <message>" (from this rank) and ends every rank of the job, exit 1.
  [[noreturn]] void abort(const std::string& message) const;
  // MPI_Finalize when MPI was initialised (every rank, at the end of main).
  void finalize();

 private:
  Communicator();
  int rank_ = 0;
  int size_ = 1;
  int node_size_ = 1;
  bool mpi_ = false;
};

// Thrown on the ranks other than 0 when a coordinated step failed somewhere: rank 0
// prints the one message, the others exit 1 without a word.
struct FailedElsewhere : std::runtime_error {
  FailedElsewhere() : std::runtime_error("failed on another rank") {}
};

// Thrown on rank 0 when a step agreed on by every rank (agree) failed somewhere: the
// message is the lowest failed rank's; the other ranks throw FailedElsewhere.
struct AgreedFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The message a failure shows (std::bad_alloc as out of memory).
std::string failure_message(const std::exception_ptr& failure);

// Runs `step` on every rank, then agrees: when it threw anywhere, rank 0 throws
// std::runtime_error with the message of the lowest rank that failed and every other
// rank throws FailedElsewhere. One rank: `step` as is.
void on_every_rank(const Communicator& comm, const std::function<void()>& step);

// One step every rank reaches, done or failed: each rank gives its bytes (ok) or the
// message of its failure (!ok). When every rank is ok, rank 0 maps their bytes (in rank
// order) with `combine` and every rank gets the result; otherwise, or when `combine`
// throws, rank 0 throws AgreedFailure (the lowest failed rank's message) and the others
// FailedElsewhere. Always one gather and one broadcast, so a rank that failed before the
// step the others are in meets them there with its failure. One rank: combine({bytes}).
struct StepPart {
  bool ok = true;
  std::string bytes;  // the failure's message when !ok
};
std::string agree(const Communicator& comm, const StepPart& mine,
                  const std::function<std::string(std::vector<std::string> all)>& combine);

// Runs `work`, a sequence of agree() steps that every rank takes alike (a split operator
// build), on every rank. A throw that is not an agreed failure meets the other ranks at
// their current step as a failure; on success every rank meets at a closing step. So a
// failure anywhere ends `work` on every rank: rank 0 throws AgreedFailure, the others
// FailedElsewhere, and no rank is left waiting. One rank: `work` as is.
void in_agreed_steps(const Communicator& comm, const std::function<void()>& work);

// Runs `work` on rank 0 only (a command not spread over ranks) and gives its exit code
// to every rank; a throw on rank 0 is rethrown there, FailedElsewhere elsewhere.
int on_root_only(const Communicator& comm, const std::function<int()>& work);

}  // namespace ilp::dist
