// What a rank of a distributed building run (mpirun -np N ilp run, docs/cluster.md)
// sends rank 0: each of its rooms' record, wall-clock time and output files (names
// relative to the building's output folder, their bytes as written), or the first
// failure it met. Plain bytes, so the seam to MPI (dist/) carries no type of ours.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "output/result_record.h"

namespace ilp {

struct RoomOutcome {
  std::size_t room = 0;    // index in the building's rooms
  double seconds = 0.0;    // its wall-clock time (timings.json)
  ResultRecord record;
  std::vector<std::pair<std::string, std::string>> files;  // "rooms/<name>/plan.svg", bytes
};

struct RoomFailure {
  std::size_t room = 0;    // the room being run (its rank's first failure)
  std::string message;
};

struct RankReport {
  std::vector<RoomOutcome> rooms;   // in room order
  std::optional<RoomFailure> failure;
};

std::string encode_rank_report(const RankReport& report);
// Throws std::runtime_error on bytes encode_rank_report did not write.
RankReport decode_rank_report(const std::string& bytes);

// The rank that runs room `room` of a building run over `ranks` ranks: room i on rank
// i mod N (deterministic; the same rooms on the same ranks every run).
int room_rank(std::size_t room, int ranks);

}  // namespace ilp
