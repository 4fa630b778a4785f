#include "output/output_formats.h"

namespace ilp {
namespace {

constexpr OutputFormat kFormats[] = {
    {"json", true, false, false, false, false, "result.json and timings.json"},
    {"csv", true, false, true, false, false, "illuminance.csv: every goal patch, predicted and verified"},
    {"svg", true, false, false, false, false, "plan.svg: the installation plan"},
    {"ply", true, false, true, false, false, "scene.ply coloured by illuminance"},
    {"grid_csv", true, true, false, false, false, "grid.csv: every calculation grid's points"},
    {"isolux_svg", true, true, false, false, false, "isolux_<grid>.svg per grid"},
    {"isolux_png", true, true, false, true, false, "isolux_<grid>.png per grid"},
    {"plan_png", true, false, false, true, true, "plan.png: plan.svg rendered"},
    {"pdf", false, false, false, true, true, "report.pdf for the client"},
    {"radiance", false, false, false, false, false, "a Radiance scene of the verified layout"},
    {"gltf", false, false, false, false, false, "scene.glb coloured by illuminance"},
    {"dxf", false, false, false, false, false, "plan.dxf on layers"},
    {"schedule", false, false, false, false, false, "schedule.csv: the luminaire schedule"},
};

}  // namespace

std::span<const OutputFormat> output_formats() { return kFormats; }

const OutputFormat* find_output_format(std::string_view key) {
  for (const OutputFormat& f : kFormats)
    if (f.key == key) return &f;
  return nullptr;
}

std::vector<std::string> default_output_formats() {
  std::vector<std::string> out;
  for (const OutputFormat& f : kFormats)
    if (f.by_default) out.emplace_back(f.key);
  return out;
}

std::string output_format_keys() {
  std::string out;
  for (const OutputFormat& f : kFormats) out += (out.empty() ? "" : ", ") + std::string(f.key);
  return out;
}

}  // namespace ilp
