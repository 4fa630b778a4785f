// A building job (rooms:, docs/building.md): each room runs as a single-room job of its
// own, a self-contained function of (building job, room index), and the building's
// summary is computed from the rooms' records in room order, so it does not depend on
// where or in which order the rooms ran (a later MPI run spreads rooms over ranks).
#pragma once

#include <string>
#include <vector>

#include "job/config.h"
#include "output/building_record.h"
#include "output/result_record.h"

namespace ilp {

// The single-room job room `r` of `building` runs as: the building's shared keys with
// the room's own read over them (job/config.h, RoomSetting), its part of the model in
// keep_surfaces, its outputs in <output folder>/rooms/<name>. Throws std::out_of_range
// for r past the rooms.
const JobConfig& room_job(const JobConfig& building, std::size_t r);

// "rooms/<name>": room r's folder under the building's output folder.
std::string room_folder(const JobConfig& building, std::size_t r);

// One room's line of the building record, from its result record.
BuildingRoomRecord building_room_record(const RoomSetting& room, const ResultRecord& record);

// The building's record from its rooms' records (one per room of building.rooms, in that
// order): totals of power and areas, W/m² and LENI as the area-weighted means (total
// power over total area, total energy over total area), the bill of materials summed by
// product (first seen order), met when every room is. Throws std::invalid_argument when
// the counts differ.
BuildingRecord summarize_building(const std::string& program_version, const JobConfig& building,
                                  const std::vector<ResultRecord>& rooms);

}  // namespace ilp
