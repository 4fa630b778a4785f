// The goal rows of the areas that are not patches or grid points (optimizer/goal_spec.h,
// AreaKind): a grid's points lifted to eye height as cylinders, and observers' eyes; and
// the glare terms of the candidates and fixed luminaires at each observer. Used by
// lighting_model_geometry.
#pragma once

#include <optional>
#include <vector>

#include "core/glare/ugr.h"
#include "core/transport/ray_caster.h"
#include "optimizer/lighting_model.h"

namespace ilp {

// The cylinder receivers of a grid's points at height z_m: per point kCylinderPlanes
// vertical receivers, then one facing up.
std::vector<ReceiverPoint> cylinder_receivers(const CalcGrid& grid, double z_m);

// A glare area's observers: its own (each checked: inside the room, not inside a solid),
// or the standard's four at the floor's plan box. Throws ConfigError at the observer's
// (or the goal's) location.
std::vector<UgrObserver> area_observers(const Scene& job_scene, const RayCaster& caster, const GoalAreaSpec& area,
                                        std::optional<double> floor_z_m, const std::string& floor_surface);

// The receiver at an observer's eye: facing along the line of sight.
ReceiverPoint eye_receiver(const UgrObserver& observer);

// model.candidate_glare_per_lm2 and model.fixed_glare for model.observers.
void compute_glare_terms(LightingModel& model, const Scene& job_scene, const CandidateSpec& spec);

}  // namespace ilp
