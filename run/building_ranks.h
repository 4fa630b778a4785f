// A building's rooms over MPI ranks (mpirun -np N ilp run of a building job,
// docs/cluster.md): room r runs on rank room_rank(r, N) (job/room_exchange.h); each rank
// sends rank 0 its rooms' outcomes (record, time, files) or its first failure in one
// gather; rank 0 finishes when every room ran, in room order, so the files are the
// single-process run's bytes; one broadcast of the exit code ends every rank alike.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "dist/communicator.h"
#include "job/room_exchange.h"

namespace ilp {

struct BuildingRun {
  std::vector<std::string> room_names;  // in room order
  // Rank 0's own set-up (its output folder): a failure there counts as room 0's.
  std::function<void()> setup_on_root;
  // Runs room r on this rank: its outcome, with its files unless rank 0 kept them itself.
  std::function<RoomOutcome(std::size_t room)> run_room;
  // On rank 0, every room run: their outcomes in room order; returns the exit code (0 or 2).
  std::function<int(const std::vector<const RoomOutcome*>& by_room)> finish_on_root;
};

// Every rank takes part in the one gather and the one broadcast whatever fails, so a
// failure anywhere ends every rank: rank 0 rethrows the failure of the lowest room, the
// others throw dist::FailedElsewhere. Returns the exit code on every rank.
int run_rooms_over_ranks(const dist::Communicator& comm, const BuildingRun& building);

}  // namespace ilp
