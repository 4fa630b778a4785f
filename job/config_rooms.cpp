// rooms: a building job's rooms (docs/building.md), each read over a copy of the
// building's shared keys into the single-room job it runs as.
#include <algorithm>
#include <set>

#include "job/config_yaml.h"

namespace ilp {

bool valid_room_name(const std::string& name) {
  if (name.empty() || name == "." || name == "..") return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
  });
}

namespace config_yaml {
namespace {

const std::vector<std::string>& room_keys() {
  static const std::vector<std::string> keys{"name",  "use",   "surfaces",           "coupled_with", "luminaires",
                                             "grids", "goals", "maintenance_factor", "constraints",  "objective",
                                             "energy"};
  return keys;
}

// surfaces: [NAME or PREFIX*, ...]: the room's part of the model.
std::vector<SurfacePattern> read_surfaces(const Value& v) {
  std::vector<SurfacePattern> out;
  for (const Value& item : v.list()) {
    const std::string text = item.text();
    if (text.empty() || text == "*") item.fail("must name a surface or a prefix followed by '*'");
    if (text.find('*') != std::string::npos && text.find('*') != text.size() - 1)
      item.fail("'*' may only end a name (a prefix: office_1_*)");
    out.push_back({text, item.key(), item.loc()});
  }
  if (out.empty()) v.fail("must list at least one surface (or leave the key out: the whole model)");
  return out;
}

// The first goals entry's preset (what the room is used for, when `use` is not given).
std::string first_preset(const Map& room) {
  const auto goals = room.get("goals");
  if (!goals || !goals->node().IsSequence()) return {};
  for (const Value& entry : goals->list())
    if (entry.node().IsMap() && entry.node()["preset"] && entry.node()["preset"].IsScalar())
      return entry.node()["preset"].Scalar();
  return {};
}

RoomSetting read_room(const Value& item, const JobConfig& building) {
  const Map room(item, room_keys());
  RoomSetting out;
  out.loc = item.loc();
  const Value name = room.require("name");
  out.name = name.text();
  if (!valid_room_name(out.name))
    name.fail("must be letters, digits, '_', '-' or '.' (it names the room's folder rooms/<name>)");
  out.job = building;
  out.job.rooms.clear();
  read_room_keys(room, out.job, true);
  if (!out.job.search && out.job.groups.empty())
    throw ConfigError(located(item.loc(), item.key() + " (" + out.name +
                                              "): needs luminaires.mounting_surface (or suspended, on_wall, groups)"));
  if (out.job.goals.empty()) throw ConfigError(located(item.loc(), item.key() + " (" + out.name + "): needs goals"));
  if (auto v = room.get("use")) out.use = v->text();
  else out.use = first_preset(room);
  if (auto v = room.get("surfaces")) out.job.keep_surfaces = read_surfaces(*v);
  if (auto v = room.get("coupled_with"))
    for (const Value& other : v->list()) out.coupled_with.push_back(other.text());
  return out;
}

// coupled_with: each name another room with surfaces of its own, whose surfaces join
// this room's scene.
void couple_rooms(const Value& rooms, std::vector<RoomSetting>& out) {
  const std::vector<Value> items = rooms.list();
  std::vector<std::vector<SurfacePattern>> own;
  for (const RoomSetting& r : out) own.push_back(r.job.keep_surfaces);
  for (std::size_t r = 0; r < out.size(); ++r) {
    if (out[r].coupled_with.empty()) continue;
    const Map room(items[r], room_keys());
    const std::vector<Value> names = room.require("coupled_with").list();
    if (own[r].empty()) names.front().fail("coupling joins rooms' parts of the model: this room needs surfaces");
    for (std::size_t k = 0; k < names.size(); ++k) {
      const auto it = std::find_if(out.begin(), out.end(), [&](const RoomSetting& o) { return o.name == out[r].coupled_with[k]; });
      if (it == out.end()) names[k].fail("no room of this name");
      if (it == out.begin() + static_cast<std::ptrdiff_t>(r)) names[k].fail("a room is not coupled to itself");
      const std::vector<SurfacePattern>& theirs = own[static_cast<std::size_t>(it - out.begin())];
      if (theirs.empty()) names[k].fail("that room has no surfaces (the whole model): nothing to join");
      out[r].job.keep_surfaces.insert(out[r].job.keep_surfaces.end(), theirs.begin(), theirs.end());
    }
  }
}

}  // namespace

void read_rooms(const Value& rooms, JobConfig& building) {
  const std::vector<Value> items = rooms.list();
  if (items.empty()) rooms.fail("must list at least one room");
  std::set<std::string> names;
  std::vector<RoomSetting> out;
  for (const Value& item : items) {
    RoomSetting room = read_room(item, building);
    if (!names.insert(room.name).second) Map(item, room_keys()).require("name").fail("another room has this name");
    out.push_back(std::move(room));
  }
  couple_rooms(rooms, out);
  building.rooms = std::move(out);
}

}  // namespace config_yaml
}  // namespace ilp
