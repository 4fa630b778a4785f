// The Guth position index p of a glare source seen from an eye looking horizontally:
// how much less a source glares the farther it sits from the line of sight (p = 1 on it).
//
// Geometry (CIE 117:1995, fig. 4.2): R is the source's distance along the line of sight,
// T its distance across it (either side) and H its height above the eye, all in the same
// unit. Only sources above the line of sight and in front of the eye have an index.
//
// Two ways to get p:
// - cie117_table: CIE 117:1995 section 4.5 finds p by interpolating its Table 4.1 (T/R 0..3
//   by 0.1, H/R 0..1.9 by 0.1; void cells are positions hidden by brow and forehead). This
//   is what CIE 117 and CIE 190 prescribe, and the default everywhere in core/glare.
// - levin_formula: Levin (1975, J. IES, "Position index in VCP calculations") fitted to
//   Guth's plot, as the IES handbook gives it for VCP:
//     ln p = (35.2 - 0.31889 a - 1.22 e^(-2a/9)) 1e-3 b + (21 + 0.26667 a - 0.002963 a^2) 1e-5 b^2
//   a = angle of the plane through the line of sight and the source from the vertical,
//   b = angle between the line of sight and the source, both in degrees. Levin reports it
//   up to ~12 % off Guth's plot (docs/glare.md compares it with Table 4.1).
#pragma once

#include <optional>

namespace ilp {

enum class PositionIndexMethod { cie117_table, levin_formula };

// p from CIE 117 Table 4.1 by bilinear interpolation, or nothing where the table says the
// source does not count: T/R > 3, H/R outside [0, 1.9], a cell next to a void one, or R <= 0.
std::optional<double> guth_index_table(double h_over_r, double t_over_r);

// p from Levin's formula at the angles of (R, T, H); nothing for R <= 0 or H < 0.
std::optional<double> guth_index_formula(double r, double t, double h);

std::optional<double> guth_position_index(double r, double t, double h, PositionIndexMethod method);

}  // namespace ilp
