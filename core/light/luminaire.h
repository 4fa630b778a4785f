// A luminaire: what it is (its type: the model, the luminous opening and how its
// light leaves it) and where it is (position, rotation about the vertical axis, tilt).
// Everything that places, lights, draws or caches a luminaire goes through this
// header: the scene adds its opening as patches (add_luminaire in core/scene/scene.h),
// the direct light asks it for its intensity (core/transport/direct_light.h), the candidate
// grid for its footprint, the operator cache for its key.
//
// Frames. A luminaire's own frame has z up, the opening's centre at the origin, the
// C0-C180 axis of a photometric file along +x (length_m: the opening's extent along x,
// the file's length or width as photometric_opening decides) and C90-C270 along +y
// (width_m); it hangs facing down (gamma 0 = nadir = -z). The placement first tilts
// that frame about its own y axis (the C90-C270 axis) so that its nadir swings toward
// its +x (C0), by tilt_deg in [0, 90] (90: facing horizontally along C0), then turns it
// counter-clockwise about the scene's z axis by rotation_deg, seen from above. So a
// luminaire aims (its nadir points) at (cos r sin t, sin r sin t, -cos t) in the scene.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace ilp {

class KeyWriter;  // core/base/key_hash.h

// How the light leaves the opening, per lumen of the luminaire's output.
class IntensityDistribution {
 public:
  virtual ~IntensityDistribution() = default;
  // Intensity toward a unit direction in the luminaire's frame, cd per lm emitted.
  virtual double cd_per_lm(const Eigen::Vector3d& direction_local) const = 0;
  // Text that identifies the distribution exactly (for the operator cache key).
  virtual std::string key() const = 0;
};

// I = cos(gamma) / pi per lm below the horizontal, 0 above: an ideal diffuser facing down.
class LambertianDistribution final : public IntensityDistribution {
 public:
  double cd_per_lm(const Eigen::Vector3d& direction_local) const override;
  std::string key() const override { return "lambertian"; }
};

enum class OutlineShape { rectangle, disc };

struct LuminaireType {
  std::string name = "square_lambertian";  // the product (or model) name shown in reports
  OutlineShape shape = OutlineShape::rectangle;
  double length_m = 0.6;  // along local x; a disc's diameter
  double width_m = 0.6;   // along local y; a disc's diameter
  // The distribution; a Lambertian opening (the square panel) when it is a LambertianDistribution:
  // its unoccluded direct light is then Lambert's closed form over the opening.
  std::shared_ptr<const IntensityDistribution> distribution = std::make_shared<LambertianDistribution>();
  bool lambertian() const;

  double opening_area_m2() const;
  // Outline of the opening, counter-clockwise seen from above, in the luminaire's frame
  // (z = 0): 4 corners, or a 24-gon for a disc (area kept equal to the disc's).
  std::vector<Eigen::Vector3d> outline_local() const;
  // Half extents along the scene's x and y of the outline turned by rotation_deg and
  // tilted by tilt_deg (luminaire_rotation), projected on the plan.
  Eigen::Vector2d half_footprint_m(double rotation_deg, double tilt_deg = 0.0) const;
  // Exact text of everything that shapes the light (for the operator cache key).
  std::string key() const;

  // The shipped test model: a square Lambertian panel of side size_m.
  static LuminaireType square_lambertian(double size_m);
};

// The operator cache's key (core/base/key_hash.h): every field, the distribution by
// its key().
void hash_fields(KeyWriter& k, const LuminaireType& t);

struct LuminairePlacement {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // centre of the opening, scene frame
  double rotation_deg = 0.0;                             // about +z, counter-clockwise seen from above
  double tilt_deg = 0.0;  // aim: [0, 90], about the local y axis, the nadir toward local +x (C0)
};

// The operator cache's key (core/base/key_hash.h): every field.
void hash_fields(KeyWriter& k, const LuminairePlacement& p);

// Rotation of the luminaire's frame into the scene's: Rz(rotation_deg) Ry(-tilt_deg), so
// local -z (the nadir) goes to (cos r sin t, sin r sin t, -cos t) and local +y (the tilt
// axis) to (-sin r, cos r, 0). Throws std::invalid_argument for a tilt outside [0, 90] or
// a non-finite angle.
Eigen::Matrix3d luminaire_rotation(double rotation_deg, double tilt_deg = 0.0);
Eigen::Matrix3d luminaire_rotation(const LuminairePlacement& at);

// The opening's outline in the scene frame.
std::vector<Eigen::Vector3d> luminaire_outline_m(const LuminaireType& type, const LuminairePlacement& at);

}  // namespace ilp
