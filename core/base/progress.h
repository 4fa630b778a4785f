// Progress reporting for long phases. Library code calls it; only programs print.
#pragma once

#include <cstddef>
#include <functional>
#include <string_view>

namespace ilp {

// Called with the phase name, units done and units in total; may be empty.
using ProgressCallback = std::function<void(std::string_view phase, std::size_t done, std::size_t total)>;

}  // namespace ilp
