// The exact reference: radiosity B = E + R F B solved by Gauss-Seidel over the full
// form-factor matrix (all n rows), then illuminance H = F B per patch. This is the
// yardstick the sample-based inverse is measured against; it is meant for scenes
// up to about 20K patches (F is sparse: at most rays_per_patch entries a row).
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/transport/form_factors.h"
#include "core/scene/scene.h"

namespace ilp {

struct RadiosityOptions {
  double relative_residual = 1e-8;  // stop when ||E - (I - R F) B|| / ||E|| is below this
  int max_iterations = 100'000;     // Gauss-Seidel sweeps; more is a NumericalError
  int threads = 0;                  // the colour channels solved at once (0: all cores); never changes B

  bool is_valid(std::string* error) const;
};

struct RadiositySolution {
  Eigen::MatrixXd radiosity_lm_per_m2;    // #patches by #channels
  Eigen::MatrixXd illuminance_lux;        // #patches by #channels, incident H = F B
  Eigen::VectorXd total_lux;              // #patches, photometric (luminance-weighted) incident illuminance
  Eigen::VectorXd direct_lux;             // #patches, F E: light straight from the emitters
  int iterations = 0;                     // Gauss-Seidel sweeps
  double relative_residual = 0.0;         // achieved, measured on the returned B
  double seconds = 0.0;
};

// Photometric value of a per-channel quantity: the channel itself for gray scenes,
// the luminance-weighted sum for RGB.
double photometric(const Eigen::Ref<const Eigen::RowVectorXd>& channels);

// F: #patches by #patches (all rows, row i = patch i). Throws NumericalError when
// the iteration does not reach the tolerance or anything becomes non-finite, and
// std::invalid_argument on shape mismatch or bad options.
// `initial`, when given (#patches by #channels): the sweeps start from it instead of E (a
// solve of nearly the same rows: fewer sweeps to the same residual).
RadiositySolution solve_radiosity(const Scene& scene, const SparseRows& F, const RadiosityOptions& options,
                                  const Eigen::MatrixXd* initial = nullptr);

}  // namespace ilp
