// Discomfort glare at an observer: the unified glare rating of CIE 117:1995,
//   UGR = 8 log10( 0.25 / Lb * sum over sources of L^2 omega / p^2 ),
// L the luminance of a luminaire's luminous opening toward the eye (cd/m2), omega the solid
// angle of that opening seen from the eye (sr), p its Guth position index
// (core/glare/position_index.h) and Lb the background luminance (cd/m2), which CIE 117 takes
// as the indirect vertical illuminance at the eye over pi. Only sources above the eye and in
// the field the position index covers count. docs/glare.md gives the sources and a worked case.
//
// Each source's term L^2 omega / p^2 = I^2 / (A_p d^2 p^2) grows with the square of its
// flux, so a search can keep glare_term_per_lm2 per candidate and observer and scale it.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/glare/position_index.h"
#include "core/light/luminaire.h"
#include "core/light/photometry.h"

namespace ilp {

// The luminous opening as glare sees it, in the luminaire's frame (length along local x =
// C0-C180, width along y): a flat bottom plus luminous sides of height height_m.
struct GlareOpening {
  OutlineShape shape = OutlineShape::rectangle;
  double length_m = 0.6;  // a disc's diameter
  double width_m = 0.6;   // a disc's diameter
  double height_m = 0.0;  // luminous sides (0: flat)
};
GlareOpening glare_opening(const LuminaireType& type);
// From a photometric file's opening; a point opening gets a 0.1 m disc (as the scene does).
GlareOpening glare_opening(const LuminousOpening& opening);

// Area of the opening projected on the plane normal to `toward_eye_local` (the direction from
// the opening's centre to the eye in the luminaire's frame; need not be unit length), m2.
// Only the faces that face the eye count: the bottom when the eye is below, each side when
// the eye is on its side.
double projected_area_m2(const GlareOpening& opening, const Eigen::Vector3d& toward_eye_local);

// One luminaire as a glare source.
struct GlareSource {
  GlareOpening opening;
  std::shared_ptr<const IntensityDistribution> distribution;
  LuminairePlacement placement;  // centre of the opening, rotation about +z
  double flux_lm = 0.0;
};
GlareSource glare_source(const LuminaireType& type, const LuminairePlacement& at, double flux_lm);

// An eye and where it looks. The line of sight is horizontal (CIE 117): view_direction's
// vertical part is ignored.
struct UgrObserver {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d view_direction = Eigen::Vector3d::UnitX();
};

// What the eye sees of one source.
struct GlareView {
  double r_m = 0, t_m = 0, h_m = 0;  // along, across (signed, left +) and above the line of sight
  double distance_m = 0;
  double intensity_cd = 0;           // toward the eye
  double projected_area_m2 = 0;
  double luminance_cd_m2 = 0;        // intensity / projected area
  double solid_angle_sr = 0;         // projected area / distance^2
  std::optional<double> position_index;  // nothing: the source does not count (behind, below, outside the field)
  double term = 0;                   // L^2 omega / p^2, 0 when it does not count
};
GlareView glare_view(const GlareSource& source, const UgrObserver& observer,
                     PositionIndexMethod method = PositionIndexMethod::cie117_table);

// L^2 omega / p^2 of one source (cd2 m-4 sr); glare_term_per_lm2 is the same at 1 lm, so
// glare_term = flux_lm^2 * glare_term_per_lm2.
double glare_term(const GlareSource& source, const UgrObserver& observer,
                  PositionIndexMethod method = PositionIndexMethod::cie117_table);
double glare_term_per_lm2(const GlareSource& source, const UgrObserver& observer,
                          PositionIndexMethod method = PositionIndexMethod::cie117_table);

// 8 log10(0.25 / Lb * sum of terms); minus infinity when no source counts (CIE 117 reports
// anything under 10 as "< 10"). Lb must be > 0.
double ugr_from_terms(double sum_of_terms, double background_luminance_cd_m2);
double ugr(const std::vector<GlareSource>& sources, const UgrObserver& observer, double background_luminance_cd_m2,
           PositionIndexMethod method = PositionIndexMethod::cie117_table);
// Lb = E_ind / pi from the indirect vertical illuminance at the eye, in lux, that the caller
// computes for the observer (facing its view direction).
double ugr(const std::vector<GlareSource>& sources, const UgrObserver& observer,
           const std::function<double(const UgrObserver&)>& indirect_vertical_illuminance_lx,
           PositionIndexMethod method = PositionIndexMethod::cie117_table);

// The standard's default observers for a rectangular room (EN 12464-1 / CIE 117 practice):
// at the middle of each of the four walls, `wall_offset_m` into the room, eyes at
// floor_z_m + eye_height_m (1.2 m seated, 1.6 m standing), looking straight across the room
// (from the short walls: along its length; from the long walls: across it). Order: the walls
// at min y, max x, max y, min x.
constexpr double kSeatedEyeHeightM = 1.2, kStandingEyeHeightM = 1.6;
std::vector<UgrObserver> default_ugr_observers(const Eigen::Vector2d& room_min_xy_m, const Eigen::Vector2d& room_max_xy_m,
                                               double floor_z_m, double eye_height_m, double wall_offset_m = 0.0);

}  // namespace ilp
