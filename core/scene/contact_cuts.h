// Contact lines: where a face of the mesh is touched or crossed by another (a desk's
// foot or a box standing on the floor, a partition's foot, a shelf against a wall), so
// that meshing cuts the touched face there and no patch lies half under a solid. A
// patch half under a box gathers half its light from the box's inside (back faces),
// and every patch that sees it is then short of light too.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

namespace ilp {

// Faces within this distance of a face's plane touch it: modelling slack (a desk
// modelled a fraction of a millimetre above the floor), far below any real gap.
inline constexpr double kContactTolerance_m = 1e-3;

// A piece of a contact line: in the plane of the face it cuts, inside that face.
struct ContactSegment {
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
};

using Triangle3 = std::array<Eigen::Vector3d, 3>;

// For each triangle, the segments along which triangles of other surfaces touch or
// cross it on its front side: another triangle's edge lying in its plane (a box's
// foot on the floor, a coplanar sheet's outline) or the line where another triangle
// passes through its plane, each clipped to the triangle. Left out: triangles of the
// same surface (a chair's parts meeting each other: many small cuts, little light),
// triangles wholly behind it, segments along the triangle's own edges (its mesh
// neighbours) and shorter than the tolerance. `surface` gives each triangle's surface.
// Deterministic (segments in the order of the other triangle's index); `threads` 0:
// all cores.
std::vector<std::vector<ContactSegment>> contact_segments(const std::vector<Triangle3>& triangles,
                                                          const std::vector<int>& surface,
                                                          double tolerance_m = kContactTolerance_m, int threads = 0);

// Cuts `patch` (a triangle in the plane of its segments) along every segment that
// passes through it and is at least a tenth of the patch's longest edge long (shorter
// ones, a thin leg's many-sided outline, would make dozens of pieces for a few per
// cent of its area): each piece is split by the segment's line where the segment
// enters it. Appends the pieces (triangles, wound as `patch`, together exactly its
// area) to `out`; `patch` itself when nothing cuts it. Returns whether it was cut.
bool cut_along_segments(const Triangle3& patch, const std::vector<ContactSegment>& segments,
                        std::vector<Triangle3>& out);

}  // namespace ilp
