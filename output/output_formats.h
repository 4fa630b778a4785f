// The output formats a job may list (output.formats), in the order they are written: the
// one registry the job file's loader (the keys it takes, the defaults), the cost model
// (what they cost) and `ilp run`'s writers (apps/run_command.cpp: one writer per key,
// checked against this list) share.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ilp {

struct OutputFormat {
  std::string_view key;   // in output.formats: json, csv, svg, ...
  bool by_default;        // written when output.formats is not given
  bool needs_grids;       // one file per calculation grid (or grid.csv): listing it needs a grids section
  bool per_patch;         // a file of every patch (its cost grows with the scene)
  bool rendered;          // a PNG or PDF render
  bool renders_plan;      // renders the plan (its outline's triangles)
  std::string_view what;  // for messages and docs
};

std::span<const OutputFormat> output_formats();
// The format of this key, or nullptr.
const OutputFormat* find_output_format(std::string_view key);
// The keys written by default, in registry order.
std::vector<std::string> default_output_formats();
// "json, csv, svg, ...": every key, in registry order.
std::string output_format_keys();

}  // namespace ilp
