// The job file's names for the settings core/ and optimizer/ messages point at
// (core/base/setting.h): each setting's YAML key, as docs/config.md spells it.
#pragma once

#include <string>
#include <string_view>

#include "core/base/setting.h"

namespace ilp {

// The YAML key of `s` (of the grid or goal named `of`).
std::string setting_key(Setting s, std::string_view of = {});

// Registers setting_key as the name of every setting (load_job_config does, and the
// ilp command before any work).
void name_settings_by_key();

}  // namespace ilp
