// Rendering an SVG document to a PNG file (librsvg + cairo; the only file that uses
// them). Fonts come from fontconfig (DejaVu Sans for the writers' "sans-serif").
#pragma once

#include <string>

namespace ilp {

// Renders `svg` (a standalone document with width and height in px) on white at
// `scale` PNG pixels per SVG px, and writes it to `path_png` atomically: the PNG is
// round(width x scale) by round(height x scale) pixels, 8-bit RGBA. Throws IlpError
// "<path>: ..." when the SVG cannot be parsed or has no size, the image would exceed
// 16384 pixels a side, scale is not in (0, 16], or the file cannot be written.
void write_png_from_svg(const std::string& path_png, const std::string& svg, double scale = 1.0);

}  // namespace ilp
