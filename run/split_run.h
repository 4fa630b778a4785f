// A single room's operator build split over MPI ranks (mpirun -np N ilp run,
// docs/cluster.md): every rank reads the scene and builds the BVH and the rows, then
// computes its share of each operator build (its columns of T: the direct light at the
// sample and hit patches, the first reflection, the k x k solve; the goal patches'
// direct light by blocks; core/operator/work_share.h); rank 0 then searches and verifies
// alone while the others wait. The byte exchange goes through dist/ (dist::agree).
#pragma once

#include <string>
#include <vector>

#include "core/operator/work_share.h"
#include "dist/communicator.h"
#include "job/plan.h"
#include "run/room_run.h"

namespace ilp {

// This rank's share of an operator build: a round's partial sums gathered to rank 0 as
// raw doubles (the ranks of one job share a byte order), the total broadcast from it. A
// failure anywhere fails the step on every rank (dist::in_agreed_steps).
WorkShare operator_share(const dist::Communicator& comm);

// The ranks on one node share its memory: without --max-memory (run.max_memory_bytes),
// each may use its share of what the node has. `same_on_every_rank`: rank 0's figure on
// every rank (one broadcast, every rank takes part), so that every rank plans alike; else
// each rank's own. Rank 0 prints the figure.
void share_node_memory(RunOptions& run, const dist::Communicator& comm, bool same_on_every_rank);

// The plan's variants prepared with every operator build split over the ranks (each
// rank's share through operator_share): on rank 0 the prepared variants, logged through
// `root_hooks`; on the others none (they hold nothing once their shares are sent). A
// failure on any rank fails every rank (dist::in_agreed_steps).
std::vector<PreparedJob> prepare_split(const JobPlan& plan, RunOptions run, const dist::Communicator& comm,
                                       const RunHooks& root_hooks, const std::string& cache_dir);

// "peak memory per rank <when>: 0: 1.23 GB, 1: 0.98 GB" on rank 0: each rank's
// `peak_gb` (its resident peak so far), one gather.
void print_peak_memory_per_rank(const dist::Communicator& comm, const std::string& when, double peak_gb);

}  // namespace ilp
