// The lighting model's spec in the operator cache's key (core/base/key_hash.h): each
// struct's fields next to a count of them, so that a field added to the struct stops
// the build here until it is hashed or said to be left out.
#include "core/base/key_hash.h"
#include "optimizer/lighting_model.h"

namespace ilp {

static_assert(field_count<WallMountSpec>() == 4, "WallMountSpec changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const WallMountSpec& w) {
  k.field("facing", w.facing).field("height_m", w.height_m);  // not the FileLocs
}

static_assert(field_count<CandidateSpec>() == 19, "CandidateSpec changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const CandidateSpec& c) {
  k.field("mounting_surface", c.mounting_surface).field("type", c.type).field("rotation_deg", c.rotation_deg);
  k.field("tilt_deg", c.tilt_deg);
  k.field("spacing_m", c.spacing_m).field("wall_distance_m", c.wall_distance_m);
  k.field("ceiling_module_m", c.ceiling_module_m).field("mount_offset_m", c.mount_offset_m);
  k.field("zone_m", c.zone_m).field("zone_margin_m", c.zone_margin_m);
  k.field("suspended_height_m", c.suspended_height_m).field("wall", c.wall).field("floor_surface", c.floor_surface);
  // Not the FileLocs: where the values were written.
}

static_assert(field_count<ObserverSpec>() == 4, "ObserverSpec changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const ObserverSpec& o) {
  k.field("xy_m", o.xy_m).field("eye_height_m", o.eye_height_m).field("view", o.view);
  // Not the FileLoc.
}

static_assert(field_count<GoalAreaSpec>() == 8, "GoalAreaSpec changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const GoalAreaSpec& a) {
  k.field("name", a.name).field("surfaces", a.surfaces).field("facing", a.facing).field("grid", a.grid);
  // The area's kind and where its points go (cylinders at eye height, observers' eyes):
  // they are goal rows of the operator. Not the FileLoc.
  k.field("kind", a.kind).field("eye_height_m", a.eye_height_m).field("observers", a.observers);
}

static_assert(field_count<ModelSpec>() == 8, "ModelSpec changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const ModelSpec& m) {
  k.field("candidates", m.candidates).field("areas", m.areas).field("grids", m.grids);
  k.field("operator_options", m.operator_options).field("sample_size", m.sample_size);
  k.field("reflected_stride", m.reflected_stride);
  // A sample size chosen for a target error is judged with every candidate at the
  // probe flux (compute_lighting_operator): only then does it shape the operator.
  if (m.sample_size.target_error) k.field("probe_flux_lm", m.probe_flux_lm);
  // Not threads: the same model for any thread count.
}

}  // namespace ilp
