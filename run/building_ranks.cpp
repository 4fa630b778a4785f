#include "run/building_ranks.h"

#include <exception>
#include <iostream>
#include <stdexcept>

namespace ilp {
namespace {

// This rank's rooms run, or its first failure.
RankReport run_my_rooms(const dist::Communicator& comm, const BuildingRun& building) {
  RankReport mine;
  try {
    if (comm.is_root() && building.setup_on_root) building.setup_on_root();
  } catch (...) {
    mine.failure = RoomFailure{0, dist::failure_message(std::current_exception())};
  }
  for (std::size_t r = 0; r < building.room_names.size() && !mine.failure; ++r) {
    if (room_rank(r, comm.size()) != comm.rank()) continue;
    try {
      mine.rooms.push_back(building.run_room(r));
    } catch (...) {
      mine.failure = RoomFailure{r, dist::failure_message(std::current_exception())};
    }
  }
  return mine;
}

// What a rank other than 0 sends: its report, or (when even that cannot be encoded) a failure.
std::string report_bytes(const RankReport& mine) {
  try {
    return encode_rank_report(mine);
  } catch (...) {
    RankReport failed;
    failed.failure =
        RoomFailure{mine.rooms.empty() ? 0 : mine.rooms.front().room, dist::failure_message(std::current_exception())};
    return encode_rank_report(failed);
  }
}

// On rank 0: every rank's report, the lowest room's failure thrown, else the outcomes
// in room order finished.
int finish(const BuildingRun& building, RankReport mine, const std::vector<std::string>& reports) {
  std::vector<RankReport> all{std::move(mine)};
  std::size_t received = 0;
  for (std::size_t k = 1; k < reports.size(); ++k) {
    received += reports[k].size();
    all.push_back(decode_rank_report(reports[k]));
  }
  std::cerr << "gathered " << received << " bytes of rooms' results from " << reports.size() - 1 << " ranks\n";
  const RoomFailure* first = nullptr;
  for (const RankReport& report : all)
    if (report.failure && (first == nullptr || report.failure->room < first->room)) first = &*report.failure;
  if (first != nullptr) throw std::runtime_error(first->message);
  std::vector<const RoomOutcome*> by_room(building.room_names.size(), nullptr);
  for (const RankReport& report : all)
    for (const RoomOutcome& o : report.rooms)
      if (o.room < by_room.size()) by_room[o.room] = &o;
  for (std::size_t r = 0; r < by_room.size(); ++r)
    if (by_room[r] == nullptr) throw std::runtime_error("room " + building.room_names[r] + ": no rank sent its result");
  return building.finish_on_root(by_room);
}

}  // namespace

int run_rooms_over_ranks(const dist::Communicator& comm, const BuildingRun& building) {
  RankReport mine = run_my_rooms(comm, building);
  const std::vector<std::string> reports = comm.gather(comm.is_root() ? std::string() : report_bytes(mine));
  if (!comm.is_root()) {
    const std::string code = comm.broadcast(std::string());
    if (code != "0" && code != "2") throw dist::FailedElsewhere();
    return std::stoi(code);
  }
  int code = 1;
  std::exception_ptr failure;
  try {
    code = finish(building, std::move(mine), reports);
  } catch (...) {
    failure = std::current_exception();
  }
  comm.broadcast(std::to_string(failure ? 1 : code));
  if (failure) std::rethrow_exception(failure);
  return code;
}

}  // namespace ilp
