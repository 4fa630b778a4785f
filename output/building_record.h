// A building job's record (docs/building.md): each room's summary, in the job's room
// order, and the building's totals computed from them. Written as the building's
// result.json (its rooms' own result.json files are in rooms/<name>/) and read back by
// `ilp print`. Like a room's, it holds no wall-clock times (timings.json does).
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "output/result_record.h"

namespace ilp {

struct BuildingRoomRecord {
  std::string name;
  std::string use;                      // rooms[].use, else its first goal preset
  std::string folder;                   // "rooms/<name>", relative to the building's result.json
  int luminaires = 0;
  double power_w = 0.0;
  double floor_area_m2 = 0.0;           // the room's power-density area (ResultRecord::floor_area_m2)
  double power_density_w_per_m2 = 0.0;
  std::optional<double> leni_kwh_per_m2;  // EN 15193-1 (absent without a layout)
  double energy_kwh = 0.0;              // per year: lighting + parasitic
  double energy_area_m2 = 0.0;          // LENI's area
  bool all_met = false;
  std::string not_met;                  // why not (failing_lines_text, or no layout's reason); "" when met
};

struct BuildingRecord {
  std::string program_version;
  std::string config;
  std::vector<BuildingRoomRecord> rooms;
  int luminaires = 0;
  double power_w = 0.0;                 // every room's
  double floor_area_m2 = 0.0;           // the rooms' power-density areas summed
  double power_density_w_per_m2 = 0.0;  // power_w / floor_area_m2 (the rooms' area-weighted W/m²)
  double energy_kwh = 0.0;              // per year
  double energy_area_m2 = 0.0;
  double leni_kwh_per_m2 = 0.0;         // energy_kwh / energy_area_m2 (the rooms' area-weighted LENI)
  std::vector<BillLine> bill_of_materials;  // over all rooms, one line per product (first seen order)
  int rooms_met = 0;
  bool all_met = false;
  std::vector<std::pair<std::string, double>> timings_s;  // timings.json only
};

// A building's result.json and timings.json; read_building_json reads the first (and
// timings.json beside it when present). Throws std::runtime_error naming the file.
void write_building_json(const std::string& path, const BuildingRecord& building);
void write_building_timings_json(const std::string& path, const BuildingRecord& building);
BuildingRecord read_building_json(const std::string& path);
// Is the result.json at `path` a building's (it has "rooms")?
bool is_building_json(const std::string& path);

// The console report: a line per room (name, use, luminaires, W, W/m², LENI, verdict),
// the building's totals and its bill of materials.
void print_building(std::ostream& os, const BuildingRecord& building);

}  // namespace ilp
