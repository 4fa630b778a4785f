// The building's result.json and its console report (output/building_record.h).
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "output/atomic_file.h"
#include "output/building_record.h"

namespace ilp {
namespace {

using json = nlohmann::ordered_json;

json room_json(const BuildingRoomRecord& r) {
  return {{"name", r.name},
          {"use", r.use},
          {"folder", r.folder},
          {"luminaires", r.luminaires},
          {"power_w", r.power_w},
          {"floor_area_m2", r.floor_area_m2},
          {"power_density_w_per_m2", r.power_density_w_per_m2},
          {"leni_kwh_per_m2", r.leni_kwh_per_m2 ? json(*r.leni_kwh_per_m2) : json(nullptr)},
          {"energy_kwh", r.energy_kwh},
          {"energy_area_m2", r.energy_area_m2},
          {"all_met", r.all_met},
          {"not_met", r.not_met}};
}

BuildingRoomRecord room_from_json(const json& j) {
  BuildingRoomRecord r;
  r.name = j.at("name").get<std::string>();
  r.use = j.at("use").get<std::string>();
  r.folder = j.at("folder").get<std::string>();
  r.luminaires = j.at("luminaires").get<int>();
  r.power_w = j.at("power_w").get<double>();
  r.floor_area_m2 = j.at("floor_area_m2").get<double>();
  r.power_density_w_per_m2 = j.at("power_density_w_per_m2").get<double>();
  if (!j.at("leni_kwh_per_m2").is_null()) r.leni_kwh_per_m2 = j.at("leni_kwh_per_m2").get<double>();
  r.energy_kwh = j.at("energy_kwh").get<double>();
  r.energy_area_m2 = j.at("energy_area_m2").get<double>();
  r.all_met = j.at("all_met").get<bool>();
  r.not_met = j.at("not_met").get<std::string>();
  return r;
}

json bill_json(const BillLine& b) {
  return {{"product", b.product},         {"source", b.source},
          {"count", b.count},             {"rated_flux_lm", b.rated_flux_lm},
          {"unit_power_w", b.unit_power_w}, {"output_fraction", b.output_fraction},
          {"total_power_w", b.total_power_w}};
}

BillLine bill_from_json(const json& j) {
  BillLine b;
  b.product = j.at("product").get<std::string>();
  b.source = j.at("source").get<std::string>();
  b.count = j.at("count").get<int>();
  b.rated_flux_lm = j.at("rated_flux_lm").get<double>();
  b.unit_power_w = j.at("unit_power_w").get<double>();
  b.output_fraction = j.at("output_fraction").get<double>();
  b.total_power_w = j.at("total_power_w").get<double>();
  return b;
}

json to_json(const BuildingRecord& b) {
  json j;
  j["program_version"] = b.program_version;
  j["config"] = b.config;
  j["all_met"] = b.all_met;
  j["rooms_met"] = b.rooms_met;
  j["building"] = {{"rooms", b.rooms.size()},
                   {"luminaires", b.luminaires},
                   {"power_w", b.power_w},
                   {"floor_area_m2", b.floor_area_m2},
                   {"power_density_w_per_m2", b.power_density_w_per_m2},
                   {"energy_kwh", b.energy_kwh},
                   {"energy_area_m2", b.energy_area_m2},
                   {"leni_kwh_per_m2", b.leni_kwh_per_m2}};
  j["rooms"] = json::array();
  for (const BuildingRoomRecord& r : b.rooms) j["rooms"].push_back(room_json(r));
  j["bill_of_materials"] = json::array();
  for (const BillLine& l : b.bill_of_materials) j["bill_of_materials"].push_back(bill_json(l));
  return j;
}

BuildingRecord from_json(const json& j) {
  BuildingRecord b;
  b.program_version = j.at("program_version").get<std::string>();
  b.config = j.at("config").get<std::string>();
  b.all_met = j.at("all_met").get<bool>();
  b.rooms_met = j.at("rooms_met").get<int>();
  const json& t = j.at("building");
  b.luminaires = t.at("luminaires").get<int>();
  b.power_w = t.at("power_w").get<double>();
  b.floor_area_m2 = t.at("floor_area_m2").get<double>();
  b.power_density_w_per_m2 = t.at("power_density_w_per_m2").get<double>();
  b.energy_kwh = t.at("energy_kwh").get<double>();
  b.energy_area_m2 = t.at("energy_area_m2").get<double>();
  b.leni_kwh_per_m2 = t.at("leni_kwh_per_m2").get<double>();
  for (const json& r : j.at("rooms")) b.rooms.push_back(room_from_json(r));
  for (const json& l : j.at("bill_of_materials")) b.bill_of_materials.push_back(bill_from_json(l));
  return b;
}

json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the result file");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw std::runtime_error(path + ": not valid JSON: " + std::string(e.what()));
  }
}

std::string fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

}  // namespace

void write_building_json(const std::string& path, const BuildingRecord& building) {
  const json j = to_json(building);
  write_file_atomically(path, [&](std::ostream& out) { out << j.dump(2, ' ', false, json::error_handler_t::replace) << "\n"; });
}

void write_building_timings_json(const std::string& path, const BuildingRecord& building) {
  json j = json::object();
  for (const auto& [phase, seconds] : building.timings_s) j[phase] = seconds;
  write_file_atomically(path, [&](std::ostream& out) { out << json{{"timings_s", j}}.dump(2) << "\n"; });
}

// Anything else (a folder, a FIFO, unreadable or malformed) is left to read_result_json,
// whose errors say what is wrong.
bool is_building_json(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  try {
    std::ifstream in(path);
    if (!in) return false;
    const json j = json::parse(in, nullptr, false);
    return j.is_object() && j.contains("rooms") && j.contains("building");
  } catch (const std::exception&) {
    return false;
  }
}

BuildingRecord read_building_json(const std::string& path) {
  try {
    return from_json(read_json(path));
  } catch (const json::exception& e) {
    throw std::runtime_error(path + ": not an ilp building result (" + std::string(e.what()) + ")");
  }
}

void print_building(std::ostream& os, const BuildingRecord& b) {
  os << std::left << std::setw(16) << "room" << std::setw(22) << "use" << std::right << std::setw(11) << "luminaires"
     << std::setw(10) << "power W" << std::setw(9) << "m²" << std::setw(8) << "W/m²" << std::setw(8) << "LENI"
     << "  verdict\n";
  for (const BuildingRoomRecord& r : b.rooms)
    os << std::left << std::setw(16) << r.name << std::setw(22) << (r.use.empty() ? "-" : r.use) << std::right
       << std::setw(11) << r.luminaires << std::setw(10) << fixed(r.power_w, 1) << std::setw(9)
       << fixed(r.floor_area_m2, 1) << std::setw(8) << fixed(r.power_density_w_per_m2, 2) << std::setw(8)
       << (r.leni_kwh_per_m2 ? fixed(*r.leni_kwh_per_m2, 1) : "-") << "  "
       << (r.all_met ? "every goal met" : "NOT MET: " + r.not_met) << "\n";
  os << std::left << std::setw(38) << ("building: " + std::to_string(b.rooms.size()) + " rooms") << std::right
     << std::setw(11) << b.luminaires << std::setw(10) << fixed(b.power_w, 1) << std::setw(9)
     << fixed(b.floor_area_m2, 1) << std::setw(8) << fixed(b.power_density_w_per_m2, 2) << std::setw(8)
     << fixed(b.leni_kwh_per_m2, 1) << "  " << b.rooms_met << " of " << b.rooms.size() << " rooms meet their goals\n";
  os << "LENI (EN 15193-1) " << fixed(b.leni_kwh_per_m2, 2) << " kWh/(m²·a): " << fixed(b.energy_kwh, 0)
     << " kWh per year over " << fixed(b.energy_area_m2, 1) << " m²\n";
  os << "bill of materials (all rooms):\n";
  for (const BillLine& l : b.bill_of_materials)
    os << "  " << std::setw(4) << l.count << " x " << (l.product.empty() ? l.source : l.product) << " ("
       << fixed(l.rated_flux_lm, 0) << " lm, " << fixed(l.unit_power_w, 1) << " W at full output), "
       << fixed(l.total_power_w, 1) << " W as set\n";
}

}  // namespace ilp
