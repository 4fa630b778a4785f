// A persistent cache of the expensive part of a LightingModel (the operator:
// fixed_lux, the candidate columns, sample_size, stats, build_seconds and the
// operator's log lines), so that a second run of a job, or a sweep, skips the build.
//
// A cache file is found by its key, a digest of everything the operator depends
// on, computed from the stage inputs themselves: the scene's (hash_scene_inputs in
// job/job_scene.h: the bytes of the input files and the scene settings) and the
// lighting model's spec (hash_fields(ModelSpec), each options struct hashing its own
// fields next to its definition, core/base/key_hash.h). Not in it: goal targets and
// metrics, the flux range (but for the probe flux under a target error), the
// optimizer, verification, output, sweep or thread count. The file carries the key
// again and a checksum; a file that is missing, stale, corrupt or from another format
// version is reported and not used.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "job/scene_spec.h"
#include "optimizer/lighting_model.h"

namespace ilp {

// Bump whenever the file layout, the key's canonical text or the way the operator
// is computed changes: files of another version are not used (and the key differs).
inline constexpr std::uint32_t kLightingModelCacheVersion = 8;  // 2: duplicate triangles dropped in meshing; 3: luminaire direct light by type; 4: grid points as goal rows; 5: interreflection solved by iteration; 6: the key from the stage inputs (KeyWriter); 7: shadows by the opening's refined grid, patches cut along contact lines; 8: the first reflection summed in blocks of hit patches

// 32 lowercase hex digits: XXH3-128 of lighting_model_key_text. Never throws for a
// missing or unreadable file (it contributes a marker instead).
std::string lighting_model_key(const SceneSpec& scene, const ModelSpec& model);

// The canonical text the key digests: the format version, hash_scene_inputs(scene) and
// hash_fields(model), one field a line (to see which field two keys differ in).
std::string lighting_model_key_text(const SceneSpec& scene, const ModelSpec& model);

// Writes the operator part of `model` to `path`, atomically: to a temporary file
// next to it that is renamed over `path` once complete (a previous file stays as it
// was on failure). Throws IlpError "<path>: cannot write ..." when it cannot.
void save_lighting_model(const std::string& path, const LightingModel& model, const std::string& key);

// Fills the operator part of `model`, which came from lighting_model_geometry for
// the same job, from the file at `path`. Returns std::nullopt when it did, else why
// the file was not used ("no cache file", "written by another format version ...",
// "stale: the key differs ...", "corrupt: ...", "truncated ...", "sizes do not match
// ..."); then `model` is unchanged. Never throws for a bad file.
std::optional<std::string> load_lighting_model(const std::string& path, const std::string& key, LightingModel& model);

}  // namespace ilp
