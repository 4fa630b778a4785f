// The tabular UGR of a luminaire (CIE 190:2010, "Calculation and presentation of unified glare
// rating tables for indoor lighting luminaires"; the table of EN 12464-1 data sheets): a
// regular field of the luminaire at spacing 0.25 H in rooms X x Y from 2H x 2H to 12H x 8H,
// H = the luminaires' height above the eye (2 m; the result does not depend on it), the
// observer at the middle of the wall at y = 0 looking along +y (X across the line of sight,
// Y along it), five sets of reflectances (ceiling / walls / reference plane), the luminaires
// seen crosswise and endwise, all at the luminaire's own flux.
//
// Each cell is 8 log10(0.25 / Lb * sum L^2 omega / p^2) (core/glare/ugr.h) over the field,
// luminaires counted where CIE 117 Table 4.1 gives p and gamma <= 85 degrees. Lb = E_WID / pi
// with the indirect vertical illuminance at the eye from CIE 190's flux-transfer method:
//   E_WID = (flux N / A_w) (F_DF F_T,FW + F_DW F_T,WW-1 + F_DC F_T,CW),
// N luminaires, A_w = 2H(X + Y) the walls between eye and luminaire planes, F_DF the share of the
// flux reaching the floor (reference plane) directly (from the zonal fluxes through the
// geometric factors F_GL of CIE 190 Table 4), F_DW the rest of the downward flux (onto the
// walls), F_DC the upward flux, and the transfer factors F_T of CIE 190 Table 5. How much of
// that was verified against what is in docs/glare.md.
//
// Viewing: CIE 117 eq. 4.5 / 4.6 through the C planes. Crosswise: the line of sight lies in
// the luminaire's C0-C180 plane (C0 toward the observer); endwise: in its C90-C270 plane
// (C90 toward the observer). For a linear luminaire whose file puts C0-C180 across its axis
// (the CIE convention) crosswise means its axis runs across the line of sight.
#pragma once

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

#include "core/glare/position_index.h"
#include "core/glare/ugr.h"
#include "core/light/photometry.h"

namespace ilp {

struct UgrTableRoom {
  double x_h = 4, y_h = 8;  // across and along the line of sight, in units of H
};
struct RoomReflectances {
  double ceiling = 0.7, walls = 0.5, floor = 0.2;  // floor: the reference plane at eye height
};
enum class UgrViewing { crosswise, endwise };

// The 19 rooms of CIE 190 in table order (2H x 2H, 2H x 3H, ... 12H x 8H) and the 5 reflectance
// sets (0.7/0.5/0.2, 0.7/0.3/0.2, 0.5/0.5/0.2, 0.5/0.3/0.2, 0.3/0.3/0.2).
const std::vector<UgrTableRoom>& cie190_rooms();
const std::vector<RoomReflectances>& cie190_reflectances();

// Shares of the luminaire's flux by CIE 190's 10-degree zones (intensity averaged over C at
// gamma 5, 15, ... 175 degrees, times 2 pi sin(gamma) 10 degrees, normalised to sum to 1).
struct ZonalFlux {
  std::array<double, 18> zone{};
  double downward = 0, upward = 0;  // R_DLO and R_ULO as shares of the luminaire flux
  // Cumulative downward flux to cos(gamma) = 0.75, 0.5, 0.25, 0 (41.4, 60, 75.5, 90 degrees):
  // the 10-degree zones, splitting the 40-50 zone at 0.130 and the 70-80 zone at 0.547.
  std::array<double, 4> cumulative{};
};
ZonalFlux cie190_zonal_flux(const Photometry& photometry);

// F_DF, F_DW and F_DC (shares of the luminaire flux) for a room of the table.
struct FluxDistributionFactors {
  double floor = 0, walls = 0, ceiling = 0;
};
FluxDistributionFactors cie190_flux_factors(const ZonalFlux& zonal, const UgrTableRoom& room);

// The indirect vertical illuminance at the eye (lx) for `count` luminaires of `flux_lm` in a
// room of the table at height h_m, reflectances one of cie190_reflectances(). Throws for a
// room or reflectance set that CIE 190's tables do not hold.
double cie190_indirect_vertical_illuminance_lx(const ZonalFlux& zonal, const UgrTableRoom& room,
                                               const RoomReflectances& reflectances, double flux_lm,
                                               int count, double h_m);

struct UgrTableOptions {
  double spacing_h = 0.25;     // luminaire spacing, in H
  double h_m = 2.0;            // luminaires above the eye
  double max_gamma_deg = 85.0; // farther luminaires are left out
  PositionIndexMethod position_index = PositionIndexMethod::cie117_table;
};

// The luminaire field of a room of the table (opening centres, z = h_m above the eye at z = 0)
// and the observer's sum of L^2 omega / p^2 over it for one luminaire `prototype` (its
// placement is replaced).
std::vector<Eigen::Vector3d> ugr_table_field_m(const UgrTableRoom& room, const UgrTableOptions& options);
double ugr_table_glare_sum(const GlareSource& prototype, const UgrTableRoom& room, UgrViewing viewing,
                           const UgrTableOptions& options);

struct UgrTable {
  std::vector<UgrTableRoom> rooms;
  std::vector<RoomReflectances> reflectances;
  Eigen::MatrixXd crosswise, endwise;  // rooms x reflectances
  double flux_lm = 0;
};
UgrTable ugr_table(const Photometry& photometry, const UgrTableOptions& options = {});

// The table as text: one row per room, crosswise then endwise columns, one decimal.
std::string format_ugr_table(const UgrTable& table);

}  // namespace ilp
