// The scene coloured by illuminance as a PLY mesh, for viewers such as MeshLab,
// Blender or CloudCompare.
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/scene/scene.h"
#include "output/colour_map.h"

namespace ilp {

// Writes the scene as a binary little-endian PLY, written atomically (see
// atomic_file.h):
//  - 3 vertices per patch, not shared, so that colours stay per patch: float x y z
//    (metres, z up) and uchar red green blue;
//  - one face per patch, vertex_indices as a uchar count and int indices, in the
//    patch's vertex order (counter-clockwise seen from the front), with uchar red
//    green blue and the float `lux` of the patch.
// Colours come from colour_map over [scale.min_lux, scale.max_lux]; NaN lux is mid
// grey (128 128 128) and stays NaN in `lux`. The header says
// "comment ilp illuminance, lux from MIN to MAX". Throws std::invalid_argument when
// lux_per_patch does not have one value per patch, IlpError when the file cannot be
// written.
void write_illuminance_ply(const std::string& path, const Scene& scene, const Eigen::VectorXd& lux_per_patch,
                           const ColourScale& scale);

}  // namespace ilp
