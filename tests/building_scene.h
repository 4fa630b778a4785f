// Two rooms side by side for the building tests (tests/job/building_test.cpp,
// tests/apps/ilp_building_test.cpp): room a (x 0..3 m) and room b (x 3.1..6.1 m), each
// 3 m deep and 2.5 m high with its own surfaces a_floor, a_ceiling, a_walls (b_...),
// faces pointing into their room, the 0.1 m between them a wall. `door`: a 1 x 2 m hole
// through both faces of that wall, so light passes between the rooms.
#pragma once

#include <Eigen/Dense>
#include <sstream>
#include <string>
#include <vector>

namespace ilp::test {

inline std::string two_rooms_obj(bool door = false) {
  std::ostringstream obj;
  int vertices = 0;
  using V = Eigen::Vector3d;
  auto quad = [&](const std::string& group, std::vector<V> v, const V& normal) {
    if ((v[1] - v[0]).cross(v[2] - v[0]).dot(normal) < 0.0) std::swap(v[1], v[3]);
    obj << "g " << group << "\n";
    for (const V& p : v) obj << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    obj << "f " << vertices + 1 << " " << vertices + 2 << " " << vertices + 3 << " " << vertices + 4 << "\n";
    vertices += 4;
  };
  const double d = 3.0, h = 2.5;
  // A wall face in the plane x = at facing `normal`, with the door's hole (y 1..2, z 0..2) when asked.
  auto x_wall = [&](const std::string& group, double at, const V& normal, bool hole) {
    if (!hole) {
      quad(group, {V(at, 0, 0), V(at, d, 0), V(at, d, h), V(at, 0, h)}, normal);
      return;
    }
    quad(group, {V(at, 0, 0), V(at, 1, 0), V(at, 1, h), V(at, 0, h)}, normal);
    quad(group, {V(at, 2, 0), V(at, d, 0), V(at, d, h), V(at, 2, h)}, normal);
    quad(group, {V(at, 1, 2), V(at, 2, 2), V(at, 2, h), V(at, 1, h)}, normal);
  };
  auto room = [&](const std::string& name, double x0, double x1, bool hole_west, bool hole_east) {
    quad(name + "_floor", {V(x0, 0, 0), V(x1, 0, 0), V(x1, d, 0), V(x0, d, 0)}, V::UnitZ());
    quad(name + "_ceiling", {V(x0, 0, h), V(x1, 0, h), V(x1, d, h), V(x0, d, h)}, -V::UnitZ());
    x_wall(name + "_walls", x0, V::UnitX(), hole_west);
    x_wall(name + "_walls", x1, -V::UnitX(), hole_east);
    quad(name + "_walls", {V(x0, 0, 0), V(x1, 0, 0), V(x1, 0, h), V(x0, 0, h)}, V::UnitY());
    quad(name + "_walls", {V(x0, d, 0), V(x1, d, 0), V(x1, d, h), V(x0, d, h)}, -V::UnitY());
  };
  room("a", 0.0, 3.0, false, door);
  room("b", 3.1, 6.1, door, false);
  return obj.str();
}

// A room's single-room keys for a building job (indented as a rooms entry): the plain
// panel searched on its ceiling, its floor at `average_lux` (maintained, MF 0.8 by the
// building's default). `extra`: more keys of the entry, indented by 4.
inline std::string two_rooms_room(const std::string& name, double average_lux, const std::string& extra = "") {
  std::ostringstream os;
  os << "  - name: " << name << "\n"
     << "    surfaces: [" << name << "_*]\n"
     << "    luminaires:\n"
     << "      size_m: 0.3\n      flux_lm: [100, 4000]\n      efficacy_lm_per_w: 100\n"
     << "      mounting_surface: " << name << "_ceiling\n      candidate_spacing_m: 0.5\n"
     << "      layout: field\n      field: {rows: [1, 2], columns: [1, 2]}\n"
     << "    goals:\n      - {surface: " << name << "_floor, average_lux: " << average_lux << "}\n"
     << extra;
  return os.str();
}

// The shared keys of a building job over two_rooms_obj (mesh rooms.obj), then `rooms`.
inline std::string two_rooms_job(const std::string& rooms, const std::string& shared = "") {
  return "scene:\n  mesh: rooms.obj\n  max_patch_edge_m: 0.5\n  default_reflectance: 0.5\n"
         "maintenance_factor: 0.8\n"
         "solver:\n  rays_per_patch: 64\n  seed: 3\n  sample_fraction: 0.2\n"
         "optimizer:\n  max_evaluations: 200\n  local_max_evaluations: 100\n  seed: 2\n"
         "verification:\n  method: exact\n  rays_per_patch: 128\n"
         "output:\n  formats: [json, csv, svg]\n" +
         shared + "rooms:\n" + rooms;
}

}  // namespace ilp::test
