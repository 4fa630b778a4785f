// Colours for illuminance: the viridis sequential map (perceptually uniform, readable
// in grey scale and with colour-vision deficiencies) and the lux range it spans,
// shared by the SVG plan and the PLY export so that both read the same.
#pragma once

#include <Eigen/Core>
#include <string>

namespace ilp {

// sRGB colour (channels in [0, 1]) of viridis at t: 0 dark violet, 1 yellow; t is
// clamped to [0, 1]. NaN gives mid grey (0.5, 0.5, 0.5), the "no value" colour.
Eigen::Vector3d colour_map(double t);

// "#rrggbb" for an sRGB colour, each channel clamped to [0, 1] (NaN as 0) and rounded.
std::string svg_colour(const Eigen::Vector3d& rgb);

// The lux range the colour map spans.
struct ColourScale {
  double min_lux = 0.0, max_lux = 1.0;

  // Where `lux` falls on the scale, clamped to [0, 1]; NaN stays NaN (see colour_map);
  // 0 for a degenerate scale (max_lux <= min_lux, or a bound not finite).
  double fraction(double lux) const;
};

// From 0 lux to the smallest "nice" number (1, 2, 2.5, 4, 5, 6 or 8 x 10^n) >= the largest
// finite entry, so that legend ticks at quarters read well. NaN and infinite entries
// are ignored; no finite entry above 0 gives [0, 1].
ColourScale colour_scale_for(const Eigen::VectorXd& lux);

// The same up to the `quantile` (in (0, 1]) of the finite entries, each counted with its
// weight (a patch's area): what a whole scene shows, where a few hot patches (a
// luminaire housing right under a panel) would otherwise stretch the scale and paint
// everything else one dark colour. Entries above it take the top colour.
ColourScale colour_scale_for(const Eigen::VectorXd& lux, const Eigen::VectorXd& weights, double quantile);

}  // namespace ilp
