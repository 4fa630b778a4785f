// The sky vault cut into patches as Radiance cuts it: Tregenza's 145 patches (Tregenza, LRT
// 19(1):13-14, 1987) and Reinhart's MF:n subdivision (144 n² + 1 patches; MF:1 is Tregenza), in
// the order of Radiance's tregenza.cal, reinhart.cal and gendaymtx's rh_init (LBNL-ETA/Radiance,
// src/cal/cal/*.cal, src/gen/gendaymtx.c; followed, not copied). Frame: z up, +y north, +x east;
// azimuths in degrees east of north. Depends on Eigen only; ../shared/DAYLIGHT.md section 2.
#pragma once

#include <iosfwd>
#include <vector>

#include <Eigen/Core>

namespace ilp {

// Radiance numbers its bins with the ground first: bin 0 is every direction below the horizon
// (gendaymtx's matrix row 0, 2π sr), bins 1..N are the sky patches. `SkySubdivision::patches`
// holds the sky only, so patches[i] is Radiance's bin i + 1 (sky matrix row i + 1).
inline constexpr int kGroundBin = 0;

// The largest MF accepted: 64 gives 589,825 patches, far beyond any sky matrix in use.
inline constexpr int kMaxReinhartMf = 64;

struct SkyPatch {
  // Rows are [lo, hi) in altitude; the zenith cap is [90 - α/2, 90].
  double altitude_lo_deg = 0.0, altitude_hi_deg = 0.0;
  // [lo, hi) east of north. A row's first patch is centred due north, so its lo is negative:
  // [-Δ/2, Δ/2) with Δ = 360° / patches in the row. The zenith cap is [0, 360).
  double azimuth_lo_deg = 0.0, azimuth_hi_deg = 0.0;
  // gendaymtx's patch direction (unit): altitude (lo + hi) / 2, azimuth at the patch's centre
  // (Δ j east of north for the row's j-th patch); the zenith cap's is (0, 0, 1).
  Eigen::Vector3d centre_direction = Eigen::Vector3d::UnitZ();
  // Exact: 2π (sin hi - sin lo) / patches in the row; the cap 2π (1 - cos(α/2)).
  double solid_angle_sr = 0.0;
};

struct SkySubdivision {
  int mf = 1;                   // Reinhart's MF (1 = Tregenza)
  double row_width_deg = 12.0;  // α = 90° / (7 mf + 0.5); the zenith cap's half-angle is α/2
  // Index into `patches` of each row's first patch, rows from the horizon up (7 mf rows, then
  // the zenith cap as a row of one), plus a last entry = patches.size().
  std::vector<int> row_start;
  // Sky only, Radiance's order: row by row from the horizon up, each row starting due north and
  // going east (north, east, south, west), the zenith cap last. patches[i] = Radiance bin i + 1.
  std::vector<SkyPatch> patches;
};

// The unit vector at `altitude_deg` above the horizon and `azimuth_deg` east of north:
// (cos alt sin azi, cos alt cos azi, sin alt), gendaymtx's `vector` macro.
Eigen::Vector3d sky_direction(double altitude_deg, double azimuth_deg);

// Tregenza (mf = 1) or Reinhart MF:mf: 144 mf² + 1 patches whose solid angles sum to 2π.
// Radiance accepts any positive MF; 1, 2 (577 patches) and 4 (2305) are the usual ones.
// Throws std::invalid_argument unless 1 <= mf <= kMaxReinhartMf.
SkySubdivision sky_subdivision(int mf);

// The index into `sky.patches` of the patch `direction` (any length > 0) falls in, as
// reinhart.cal's rbin - 1: row floor(alt / α) (the cap from 90 - α/2 up), then the azimuth bin
// floor((azi + Δ/2) / Δ) modulo the row's count (reinhart.cal also sends the 1e-4° just below
// 360° - Δ/2 to the first bin; here they stay in the last). The horizon itself (z = 0) is sky, as
// in Radiance. Throws std::invalid_argument for a zero or non-finite direction or one below the
// horizon (z < 0).
int sky_patch_of(const SkySubdivision& sky, const Eigen::Vector3d& direction);

// Radiance's bin (sky matrix row) of `direction`: kGroundBin (0) below the horizon, else
// sky_patch_of + 1. Throws std::invalid_argument for a zero or non-finite direction.
int radiance_bin_of(const SkySubdivision& sky, const Eigen::Vector3d& direction);

// "altitude [12, 24)° azimuth [-6, 6)° centre (0, 0.951, 0.309) 0.0474 sr"
std::ostream& operator<<(std::ostream& os, const SkyPatch& patch);

}  // namespace ilp
