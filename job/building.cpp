#include "job/building.h"

#include "job/config.h"

#include <algorithm>
#include <stdexcept>

namespace ilp {
namespace {

// Lines of one product (and model) are summed: the same name, file, rated output and power.
bool same_product(const BillLine& a, const BillLine& b) {
  return a.product == b.product && a.source == b.source && a.rated_flux_lm == b.rated_flux_lm &&
         a.unit_power_w == b.unit_power_w;
}

void add_bill(std::vector<BillLine>& bill, const BillLine& line) {
  auto it = std::find_if(bill.begin(), bill.end(), [&](const BillLine& b) { return same_product(b, line); });
  if (it == bill.end()) {
    BillLine first = line;
    first.group.clear();
    bill.push_back(first);
    return;
  }
  it->count += line.count;
  it->total_power_w += line.total_power_w;
  // The mean output the lines are set to: their power as set over their power at full output.
  const double full_w = it->unit_power_w * it->count;
  it->output_fraction = full_w > 0.0 ? it->total_power_w / full_w : 1.0;
}

}  // namespace

const JobConfig& room_job(const JobConfig& building, std::size_t r) { return building.rooms.at(r).job; }

std::string room_folder(const JobConfig& building, std::size_t r) { return "rooms/" + building.rooms.at(r).name; }

BuildingRoomRecord building_room_record(const RoomSetting& room, const ResultRecord& record) {
  BuildingRoomRecord out;
  out.name = room.name;
  out.use = room.use;
  out.folder = "rooms/" + room.name;
  out.luminaires = static_cast<int>(record.luminaires.size());
  out.power_w = record.power_w;
  out.floor_area_m2 = record.floor_area_m2;
  out.power_density_w_per_m2 = record.power_density_w_per_m2;
  if (record.energy) {
    out.leni_kwh_per_m2 = record.energy->leni_kwh_per_m2;
    out.energy_kwh = record.energy->total_kwh;
    out.energy_area_m2 = record.energy->area_m2;
  }
  out.all_met = record.all_met && record.no_layout.empty();
  out.not_met = !record.no_layout.empty() ? record.no_layout : out.all_met ? std::string() : failing_lines_text(record);
  return out;
}

BuildingRecord summarize_building(const std::string& program_version, const JobConfig& building,
                                  const std::vector<ResultRecord>& rooms) {
  if (rooms.size() != building.rooms.size())
    throw std::invalid_argument("summarize_building: " + std::to_string(rooms.size()) + " records for " +
                                std::to_string(building.rooms.size()) + " rooms");
  BuildingRecord b;
  b.program_version = program_version;
  b.config = building.path;
  for (std::size_t r = 0; r < rooms.size(); ++r) {
    const BuildingRoomRecord line = building_room_record(building.rooms[r], rooms[r]);
    b.luminaires += line.luminaires;
    b.power_w += line.power_w;
    b.floor_area_m2 += line.floor_area_m2;
    b.energy_kwh += line.energy_kwh;
    b.energy_area_m2 += line.energy_area_m2;
    b.rooms_met += line.all_met ? 1 : 0;
    for (const BillLine& l : rooms[r].bill_of_materials) add_bill(b.bill_of_materials, l);
    b.rooms.push_back(line);
  }
  b.power_density_w_per_m2 = b.floor_area_m2 > 0.0 ? b.power_w / b.floor_area_m2 : 0.0;
  b.leni_kwh_per_m2 = b.energy_area_m2 > 0.0 ? b.energy_kwh / b.energy_area_m2 : 0.0;
  b.all_met = b.rooms_met == static_cast<int>(rooms.size());
  return b;
}

}  // namespace ilp
