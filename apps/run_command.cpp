// ilp run, ilp sweep, ilp print: the inverse-lighting job from a YAML file to the
// layout table and the files of the output folder.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <sstream>

#include "apps/cli_support.h"
#include "apps/commands.h"
#include "apps/export_outputs.h"
#include "apps/grid_outputs.h"
#include "apps/plan_outputs.h"
#include "apps/run_support.h"
#include "job/config.h"
#include "job/plan.h"
#include "core/light/luminaire_product.h"
#include "core/cost/cost_model.h"
#include "optimizer/goal_metrics.h"
#include "job/group_runner.h"
#include "job/job_runner.h"
#include "job/result_mapping.h"
#include "job/variant_search.h"
#include "run/room_run.h"
#include "run/split_run.h"
#include "output/atomic_file.h"
#include "output/building_record.h"
#include "dist/communicator.h"
#include "output/colour_map.h"
#include "output/plan_svg.h"
#include "output/ply_writer.h"
#include "output/report_pdf.h"
#include "output/result_record.h"
#include "output/svg_plot.h"

namespace ilp::cli {
namespace {

using Clock = std::chrono::steady_clock;
constexpr const char* kVersion = kProgramVersion;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string cache_folder(const std::string& requested, bool disabled) {
  if (disabled) return {};
  return requested.empty() ? default_cache_dir() : requested;
}

// Prints the operator's build line after the prepared variant's log.
void log_build(const PreparedJob& prepared) {
  if (!prepared.cache_status.empty()) std::cerr << prepared.cache_status << "\n";
  const SampleOperatorStats& st = prepared.model.stats;
  std::cerr << std::fixed << std::setprecision(3)
            << (prepared.loaded_from_cache ? "operator (from the cache) built once in " : "operator built once in ")
            << prepared.model.build_seconds
            << " s (goal rows " << st.goal_seconds << " s, sample rows " << st.sample_row_seconds
            << " s, direct light " << st.direct_seconds << " s, solve " << st.solve_seconds << " s, T "
            << st.response_seconds << " s): " << prepared.model.goal_patches.size() << " goal patches x "
            << prepared.model.grid.size() << " candidates\n";
}

void log_line(const std::string& line) { std::cerr << printable(line, true) << "\n"; }

// The run's reports: progress bars, the run log on stderr, each operator's build line.
RunHooks run_hooks(const ProgressCallback& progress) { return {progress, log_line, log_build}; }

// Every grid of the job with its light: verified where the job was verified (after the
// flux correction), else predicted.
std::vector<GridResult> run_grid_results(const PreparedJob& prepared, const JobConfig& job, const JobOutcome& outcome) {
  const LightingModel& model = prepared.model;
  const Verification& v = outcome.verification;
  const bool verified = v.method != "none";
  const auto patches = static_cast<Eigen::Index>(model.goal_patches.size());
  std::vector<GridResult> out;
  for (std::size_t g = 0; g < model.grids.size(); ++g) {
    const CalcGrid& grid = model.grids[g];
    const Eigen::Index first = model.grid_first_row[g], n = static_cast<Eigen::Index>(grid.points.size());
    GridResult r{&grid, {}};
    r.light.total_initial_lux = verified ? v.point_lux.segment(first - patches, n) : outcome.predicted_lux.segment(first, n);
    r.light.direct_initial_lux =
        verified ? v.point_direct_lux.segment(first - patches, n) : outcome.predicted_direct_lux.segment(first, n);
    r.light.maintenance_factor = outcome.maintenance_factor;
    r.light.target_lux = grid_target_lux(job, grid.name);
    r.light.basis = verified ? "verified, " + v.method : "predicted";
    out.push_back(std::move(r));
  }
  return out;
}

// Verified illuminance per scene patch where known (NaN elsewhere).
Eigen::VectorXd verified_lux_per_patch(const Scene& scene, const JobOutcome& outcome) {
  Eigen::VectorXd lux = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(scene.patches.size()),
                                                  std::numeric_limits<double>::quiet_NaN());
  const Verification& v = outcome.verification;
  for (std::size_t k = 0; k < v.patches.size(); ++k)
    if (v.patches[k] < static_cast<int>(scene.patches.size())) lux[v.patches[k]] = v.lux[static_cast<Eigen::Index>(k)];
  return lux;
}

void write_illuminance_csv(const std::string& path, const PreparedJob& prepared, const JobOutcome& outcome) {
  const Scene& scene = prepared.loaded.scene;
  const std::vector<int>& goals = prepared.model.goal_patches;
  const Eigen::VectorXd verified = verified_lux_per_patch(scene, outcome);
  Eigen::VectorXd verified_direct = Eigen::VectorXd::Constant(verified.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < outcome.verification.patches.size(); ++k)
    if (outcome.verification.patches[k] < static_cast<int>(scene.patches.size()))
      verified_direct[outcome.verification.patches[k]] = outcome.verification.direct_lux[static_cast<Eigen::Index>(k)];
  auto field = [](double v) { return std::isnan(v) ? std::string() : (std::ostringstream() << std::setprecision(9) << v).str(); };
  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(9);
    out << "patch,surface,centroid_x_m,centroid_y_m,centroid_z_m,normal_x,normal_y,normal_z,area_m2,"
           "predicted_direct_lux,predicted_total_lux,verified_direct_lux,verified_total_lux\n";
    for (std::size_t r = 0; r < goals.size(); ++r) {
      const Patch& p = scene.patches[static_cast<std::size_t>(goals[r])];
      const auto row = static_cast<Eigen::Index>(r);
      out << goals[r] << ',' << csv_field(scene.surfaces[static_cast<std::size_t>(p.surface)].name) << ','
          << p.centroid_m.x() << ',' << p.centroid_m.y() << ',' << p.centroid_m.z() << ',' << p.normal.x() << ','
          << p.normal.y() << ',' << p.normal.z() << ',' << p.area_m2 << ',' << outcome.predicted_direct_lux[row] << ','
          << outcome.predicted_lux[row] << ',' << field(verified_direct[goals[r]]) << ',' << field(verified[goals[r]])
          << '\n';
    }
  });
}

// What `ilp run` writes its files from.
struct RunProducts {
  const PreparedJob& prepared;
  const JobConfig& job;
  const JobOutcome& outcome;
  const ResultRecord& record;
  const std::vector<GridResult>& grids;
};

// The goal patches' illuminance the pictures show: verified where there is one, else predicted.
Eigen::VectorXd picture_goal_lux(const PreparedJob& prepared, const JobOutcome& outcome) {
  Eigen::VectorXd goal_lux = outcome.predicted_lux.head(static_cast<Eigen::Index>(prepared.model.goal_patches.size()));
  if (outcome.verification.method == "none") return goal_lux;
  const Eigen::VectorXd per_patch = verified_lux_per_patch(prepared.loaded.scene, outcome);
  for (std::size_t r = 0; r < prepared.model.goal_patches.size(); ++r)
    goal_lux[static_cast<Eigen::Index>(r)] = per_patch[prepared.model.goal_patches[r]];
  return goal_lux;
}

void stage_result_json(OutputSet& set, const RunProducts& p) {
  write_result_json(set.staging_path("result.json"), p.record);
  set.staged("result.json");
  write_timings_json(set.staging_path("timings.json"), p.record);
  set.staged("timings.json");
}

void stage_illuminance_csv(OutputSet& set, const RunProducts& p) {
  write_illuminance_csv(set.staging_path("illuminance.csv"), p.prepared, p.outcome);
  set.staged("illuminance.csv");
}

// The plan's view (plan.svg, plan.png and the plan page of report.pdf): apps/plan_outputs
// builds it.
PlanView plan_view(const RunProducts& p) {
  std::vector<std::string> names, grid_files;
  for (const GridResult& g : p.grids) names.push_back(g.grid->name);
  for (const std::string& stem : isolux_file_stems(names)) {
    grid_files.push_back(p.job.output.wants("isolux_png")   ? stem + ".png"
                         : p.job.output.wants("isolux_svg") ? stem + ".svg"
                         : p.job.output.wants("grid_csv")   ? std::string(kGridCsvName)
                                                            : std::string());
  }
  return run_plan_view(
      {p.prepared, p.job, p.outcome, p.record, p.grids, picture_goal_lux(p.prepared, p.outcome), grid_files});
}

std::string plan_svg(const RunProducts& p) { return render_plan_svg(p.prepared.loaded.scene, plan_view(p)); }

void stage_plan_file(OutputSet& set, const RunProducts& p, const std::string& name) {
  stage_plan(set, p.prepared.loaded.scene, plan_view(p), name);
}
void stage_plan_svg(OutputSet& set, const RunProducts& p) { stage_plan_file(set, p, "plan.svg"); }
void stage_plan_png(OutputSet& set, const RunProducts& p) { stage_plan_file(set, p, "plan.png"); }

// The PLY's colour scale spans the values it shows (verified where the job was verified:
// every patch after an exact solve), not only the goal patches' (none when every goal
// is on a grid, which gave a 0 .. 1 lx scale), up to their area-weighted 99th
// percentile: the few patches of a housing right under a panel (14,700 lx on the
// classroom, where 99 % of the area is under 570 lx) take the top colour.
constexpr double kPlyScaleQuantile = 0.99;

void stage_scene_ply(OutputSet& set, const RunProducts& p) {
  const Scene& scene = p.prepared.loaded.scene;
  Eigen::VectorXd lux = verified_lux_per_patch(scene, p.outcome);
  if (p.outcome.verification.method == "none")
    for (std::size_t r = 0; r < p.prepared.model.goal_patches.size(); ++r)
      lux[p.prepared.model.goal_patches[r]] = p.outcome.predicted_lux[static_cast<Eigen::Index>(r)];
  Eigen::VectorXd area(lux.size());
  for (std::size_t i = 0; i < scene.patches.size(); ++i) area[static_cast<Eigen::Index>(i)] = scene.patches[i].area_m2;
  write_illuminance_ply(set.staging_path("scene.ply"), scene, lux, colour_scale_for(lux, area, kPlyScaleQuantile));
  set.staged("scene.ply");
}

// The layout found (L1, L2, ... as the report names them) and the luminaires placed in the config.
std::vector<DrawnLuminaire> run_luminaires(const RunProducts& p) {
  std::vector<DrawnLuminaire> out = scene_luminaires(p.prepared.loaded.scene);
  for (std::size_t j = 0; j < p.outcome.luminaires.size(); ++j) {
    const SearchLuminaire& s = outcome_plan(p.prepared, p.outcome, j).search.luminaire;
    out.push_back({outcome_luminaire_name(p.outcome, j), s.product, s.type,
                   {p.outcome.luminaires[j].position_m, s.rotation_deg, s.tilt_deg}});
  }
  return out;
}

void stage_run_grid_csv(OutputSet& set, const RunProducts& p) { stage_grid_csv(set, p.grids); }
void stage_isolux_file(OutputSet& set, const RunProducts& p, const std::string& extension) {
  const std::vector<DrawnLuminaire> luminaires = run_luminaires(p);
  stage_isolux(set, p.grids, luminaires, extension, run_architecture(p.prepared, p.job, luminaires));
}
void stage_isolux_svg(OutputSet& set, const RunProducts& p) { stage_isolux_file(set, p, ".svg"); }
void stage_isolux_png(OutputSet& set, const RunProducts& p) { stage_isolux_file(set, p, ".png"); }

// The chosen variant's product as its data sheet shows it.
ReportProduct report_product(const VariantPlan& plan) {
  const ProductVariant& v = plan.product;
  ReportProduct p;
  p.name = v.product;
  const auto* photometric = dynamic_cast<const PhotometricDistribution*>(v.type.distribution.get());
  p.file = photometric ? std::filesystem::path(v.source).filename().string() : std::string();
  p.photometry = photometric ? &photometric->photometry() : nullptr;
  p.rated_flux_lm = v.rated_flux_lm;
  p.power_w = v.power_w;
  p.dim_min = v.dim_min;
  p.dim_max = v.dim_max;
  p.length_m = v.type.length_m;
  p.width_m = v.type.width_m;
  return p;
}

// report.pdf: the record, the plan, each grid's isolux view and the product's data sheet.
void stage_report_pdf(OutputSet& set, const RunProducts& p) {
  ReportInput in;
  in.job = std::filesystem::path(p.job.path).filename().string();
  in.record = &p.record;
  in.plan_svg = plan_svg(p);
  const std::vector<DrawnLuminaire> luminaires = run_luminaires(p);
  for (const GridResult& g : p.grids) in.grids.push_back(isolux_grid_view(*g.grid, g.light, luminaires));
  if (p.outcome.groups.empty()) in.products.push_back(report_product(p.prepared.plan));
  for (const OutcomeGroup& g : p.outcome.groups) in.products.push_back(report_product(g.plan));
  write_report_pdf(set.staging_path("report.pdf"), in);
  set.staged("report.pdf");
}

// The exports' view of the run: the layout's luminaires (as the record has them), then
// those the job placed; the PLY's illuminance and colour scale; the grids' points.
ExportInputs export_inputs(const RunProducts& p) {
  ExportInputs in;
  const Scene& scene = p.prepared.loaded.scene;
  in.scene = &scene;
  for (std::size_t j = 0; j < p.outcome.luminaires.size(); ++j) {
    const VariantPlan& plan = outcome_plan(p.prepared, p.outcome, j);
    const SearchLuminaire& s = plan.search.luminaire;
    ExportLuminaire l{outcome_luminaire_name(p.outcome, j), s.product, s.type,
                      {p.outcome.luminaires[j].position_m, s.rotation_deg, s.tilt_deg},
                      p.outcome.luminaires[j].flux_lm, plan.product.rated_flux_lm,
                      p.outcome.luminaires[j].power_w};
    if (j < p.record.luminaires.size()) l.above_floor_m = p.record.luminaires[j].above_floor_m;
    in.luminaires.push_back(std::move(l));
  }
  const std::optional<double> floor_z = p.prepared.model.floor_z_m;
  for (const SceneLuminaire& sl : scene.luminaires) {
    ExportLuminaire l{scene.surfaces[static_cast<std::size_t>(sl.surface)].name, sl.type.name, sl.type, sl.placement,
                      sl.flux_lm};
    if (floor_z) l.above_floor_m = sl.placement.position_m.z() - *floor_z;
    l.placed_by_job = true;
    in.luminaires.push_back(std::move(l));
  }
  in.lux_per_patch = verified_lux_per_patch(scene, p.outcome);
  if (p.outcome.verification.method == "none")
    for (std::size_t r = 0; r < p.prepared.model.goal_patches.size(); ++r)
      in.lux_per_patch[p.prepared.model.goal_patches[r]] = p.outcome.predicted_lux[static_cast<Eigen::Index>(r)];
  in.scale = colour_scale_for(picture_goal_lux(p.prepared, p.outcome));
  for (const GridResult& g : p.grids) {
    ExportGrid grid{g.grid->name, {}, {}};
    for (const ReceiverPoint& q : g.grid->points) {
      grid.positions_m.push_back(q.position_m);
      grid.normals.push_back(q.normal);
    }
    in.grids.push_back(std::move(grid));
  }
  in.floor_z_m = floor_z ? *floor_z : scene.bounds_m.min().z();
  return in;
}

void stage_run_radiance(OutputSet& set, const RunProducts& p) { stage_radiance(set, export_inputs(p), p.job); }
void stage_run_gltf(OutputSet& set, const RunProducts& p) { stage_gltf(set, export_inputs(p)); }
void stage_run_dxf(OutputSet& set, const RunProducts& p) { stage_dxf(set, export_inputs(p)); }
void stage_run_schedule(OutputSet& set, const RunProducts& p) { stage_schedule(set, export_inputs(p)); }

std::vector<std::string> named(const char* name) { return {name}; }

// One output format of `ilp run`: its key in output.formats (output/output_formats.h),
// every file it may write for the job (the set owns them all, so a format left out
// removes the previous run's file) and its writer.
struct RunOutput {
  std::string_view key;
  std::function<std::vector<std::string>(const JobConfig&)> names;
  void (*write)(OutputSet&, const RunProducts&);
};

// Every format's writer, in the registry's order; a format of the registry without a
// writer here is a programming error, caught on the first run (and by the tests).
const std::vector<RunOutput>& run_outputs() {
  static const std::vector<RunOutput> outputs = [] {
    const std::vector<RunOutput> writers{
        {"json", [](const JobConfig&) { return std::vector<std::string>{"result.json", "timings.json"}; },
         stage_result_json},
        {"csv", [](const JobConfig&) { return named("illuminance.csv"); }, stage_illuminance_csv},
        {"svg", [](const JobConfig&) { return named("plan.svg"); }, stage_plan_svg},
        {"ply", [](const JobConfig&) { return named("scene.ply"); }, stage_scene_ply},
        {"grid_csv", grid_csv_names, stage_run_grid_csv},
        {"isolux_svg", [](const JobConfig& j) { return isolux_names(j, ".svg"); }, stage_isolux_svg},
        {"isolux_png", [](const JobConfig& j) { return isolux_names(j, ".png"); }, stage_isolux_png},
        {"plan_png", [](const JobConfig&) { return named("plan.png"); }, stage_plan_png},
        {"pdf", [](const JobConfig&) { return named("report.pdf"); }, stage_report_pdf},
        {"radiance", radiance_output_names, stage_run_radiance},
        {"gltf", [](const JobConfig&) { return named(kGltfName); }, stage_run_gltf},
        {"dxf", [](const JobConfig&) { return named(kDxfName); }, stage_run_dxf},
        {"schedule", [](const JobConfig&) { return named(kScheduleName); }, stage_run_schedule},
    };
    std::vector<RunOutput> ordered;
    for (const OutputFormat& f : output_formats()) {
      const auto w = std::find_if(writers.begin(), writers.end(), [&](const RunOutput& o) { return o.key == f.key; });
      if (w == writers.end()) throw std::logic_error("ilp run: output format '" + std::string(f.key) + "' has no writer");
      ordered.push_back(*w);
    }
    if (ordered.size() != writers.size()) throw std::logic_error("ilp run: a writer of no output format");
    return ordered;
  }();
  return outputs;
}

}  // namespace

// Every file `ilp run` may write for the job (all formats), or those output.formats selects.
std::vector<std::string> run_output_names(const JobConfig& job, bool selected_only) {
  std::vector<std::string> out;
  for (const RunOutput& o : run_outputs())
    if (!selected_only || job.output.wants(o.key))
      for (const std::string& name : o.names(job)) out.push_back(name);
  return out;
}

namespace {

// The formats output.formats selects, staged in the set (OutputSet): once committed, the
// folder holds the previous run's files or these, never a mix.
void stage_outputs(OutputSet& set, const RunProducts& products) {
  std::vector<const RunOutput*> chosen;
  for (const RunOutput& o : run_outputs()) {
    if (!products.job.output.wants(o.key)) continue;
    // Without a layout there is no light: result.json and the plan say why.
    const bool light_needed = o.write != stage_result_json && o.write != stage_plan_svg && o.write != stage_plan_png;
    if (!products.record.no_layout.empty() && light_needed) continue;
    chosen.push_back(&o);
  }
  // The files are independent (the pictures take most of the time): written at once on
  // the job's threads; the first failure in the list's order is the one reported.
  std::vector<std::exception_ptr> failed(chosen.size());
  const int threads = products.prepared.plan.model.threads;
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  set.begin_batch();
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, chosen.size(), [&](std::size_t k) {
      try {
        chosen[k]->write(set, products);
      } catch (const IlpError& e) {  // named by the output folder, not the staging folder
        failed[k] = std::make_exception_ptr(IlpError(set.explained(e.what())));
      } catch (...) {
        failed[k] = std::current_exception();
      }
    });
  });
  set.end_batch();
  for (const std::exception_ptr& f : failed)
    if (f) std::rethrow_exception(f);
}

// An outcome without a layout (every count screened out): the record says why, and only
// result.json and the plan are written (write_outputs).
void record_no_layout(ResultRecord& record) {
  record.no_layout = "no luminaire count was searched (none can reach an average target at full output, or none "
                     "could draw less than a layout already found)";
  if (!record.attempts.empty())
    record.no_layout += "; " + std::to_string(record.attempts.back().luminaires) + " luminaires: " +
                        record.attempts.back().global_stop;
  std::erase_if(record.files,
                [](const std::string& f) {
                  return f != "result.json" && f != "timings.json" && f != "plan.svg" && f != "plan.png";
                });
}

// Parses "KEY=V1,V2,..." into a sweep.
SweepSetting parse_set(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw ConfigError("--set " + text + ": expected KEY=V1,V2,... (e.g. goals.desks.average_lux=300,500,750)");
  SweepSetting sweep;
  sweep.key = text.substr(0, eq);
  std::stringstream values(text.substr(eq + 1));
  for (std::string item; std::getline(values, item, ',');) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(v))
      throw ConfigError("--set " + sweep.key + ": '" + item + "' is not a number");
    sweep.values.push_back(v);
  }
  return sweep;
}

}  // namespace

std::string default_cache_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (std::filesystem::path(xdg) / "ilp").string();
  if (const char* home = std::getenv("HOME"); home && *home)
    return (std::filesystem::path(home) / ".cache" / "ilp").string();
  return ".ilp-cache";
}

RoomRun run_room(const JobConfig& job, const JobPlan& plan, const RunOptions& run, const ProgressCallback& progress,
                 const std::string& cache, std::vector<PreparedJob> prebuilt, double prebuilt_seconds) {
  RoomRun out;
  out.run = run_plan(plan, run, run_hooks(progress), cache, std::move(prebuilt), prebuilt_seconds);
  const PreparedJob& prepared = out.prepared();
  const JobOutcome& outcome = out.run.chosen.outcome;
  // No layout (every count screened out): nothing lit to report per grid.
  const bool no_layout = outcome.search.beaten;
  if (!no_layout) out.grids = run_grid_results(prepared, job, outcome);
  std::vector<GridRecord> grid_records;
  for (const GridResult& g : out.grids) grid_records.push_back(grid_record(g, outcome.verification.method != "none"));
  out.record = make_record(kVersion, prepared, job, outcome, grid_records, out.run.timings);
  out.record.bill_of_materials = bill_of_materials(prepared.plan, outcome);
  out.record.variants = out.run.chosen.records;
  out.record.files = run_output_names(job, true);
  if (no_layout) record_no_layout(out.record);
  return out;
}

void stage_room_outputs(OutputSet& set, const JobConfig& job, const RoomRun& room) {
  stage_outputs(set, {room.prepared(), job, room.run.chosen.outcome, room.record, room.grids});
}

int run_single_room(const RunArgs& args, const JobConfig& job, const RunOptions& run, const JobPlan& plan,
                    std::vector<PreparedJob> prepared = {}, double prepared_seconds = 0.0);

namespace {

// Under mpirun, a single-room job without luminaire groups: its operator builds split
// over the ranks (run/split_run.h), then rank 0 searches and verifies alone.
int run_split_room(const RunArgs& args, const JobConfig& job, const dist::Communicator& comm) {
  RunOptions run = run_options(args.threads, args.max_memory, true);
  share_node_memory(run, comm, true);
  JobPlan plan;  // a job that cannot be planned is one message (rank 0's), every rank exit 1
  dist::on_every_rank(comm, [&] { plan = plan_job(job, run); });
  const auto build_start = Clock::now();
  std::vector<PreparedJob> prepared =
      prepare_split(plan, run, comm, run_hooks(make_progress(args.quiet)), cache_folder(args.cache_dir, args.no_cache));
  print_peak_memory_per_rank(comm, "after the operator build", peak_memory_gb());
  const double build_seconds = seconds_since(build_start);
  const int code = dist::on_root_only(comm, [&] {
    return run_single_room(args, job, run_options(args.threads, args.max_memory, true), plan, std::move(prepared),
                           build_seconds);
  });
  print_peak_memory_per_rank(comm, "at the end", peak_memory_gb());
  return code;
}

// Under mpirun, a single-room job with luminaire groups runs on rank 0 alone (its
// groups' operators are not split over the ranks): a note says so.
void note_root_alone(const dist::Communicator& comm) {
  if (comm.is_root())
    std::cerr << "note: this job runs on rank 0 alone, the other " << comm.size() - 1
              << " ranks wait (luminaire groups are not spread over ranks; a building's rooms are, and a "
                 "single room's operator build without groups)\n";
}

}  // namespace

bool room_met(const RoomRun& room) { return room.record.all_met && room.record.no_layout.empty(); }

int run_job(const RunArgs& args) {
  const dist::Communicator& comm = dist::Communicator::world();
  if (comm.distributed()) {
    // Every rank reads the job; a bad file is one message (rank 0's), every rank exit 1.
    JobConfig job;
    dist::on_every_rank(comm, [&] { job = load_job_config(args.config); });
    if (!job.rooms.empty()) return run_building(args, job);
    if (job.groups.empty()) return run_split_room(args, job, comm);
    // A single-room job with luminaire groups: rank 0 alone (docs/cluster.md).
    note_root_alone(comm);
    return dist::on_root_only(comm, [&] {
      const RunOptions run = run_options(args.threads, args.max_memory, true);
      return run_single_room(args, job, run, plan_job(job, run));
    });
  }
  const JobConfig job = load_job_config(args.config);
  if (!job.rooms.empty()) return run_building(args, job);
  const RunOptions run = run_options(args.threads, args.max_memory, true);
  return run_single_room(args, job, run, plan_job(job, run));
}

int run_single_room(const RunArgs& args, const JobConfig& job, const RunOptions& run, const JobPlan& plan,
                    std::vector<PreparedJob> prepared, double prepared_seconds) {
  const ProgressCallback progress = make_progress(args.quiet);
  // Staged from the start, so a folder that cannot take the outputs fails before the work.
  OutputSet set(output_directory(job, args.out_dir), run_output_names(job, false));
  const RoomRun room = run_room(job, plan, run, progress, cache_folder(args.cache_dir, args.no_cache),
                                std::move(prepared), prepared_seconds);
  print_result(std::cout, room.record);
  stage_room_outputs(set, job, room);
  for (const std::string& file : set.commit()) std::cout << "wrote " << file << "\n";
  std::cout << std::fixed << std::setprecision(2) << "peak memory " << peak_memory_gb() << " GB (resident)\n";
  return room_met(room) ? 0 : 2;
}

int run_sweep(const SweepArgs& args) {
  const auto start = Clock::now();
  const JobConfig job = load_job_config(args.config);
  if (!job.groups.empty())
    throw ConfigError(job.path + ": luminaires.groups: ilp sweep searches one luminaire group; run the job with ilp run");
  if (!job.rooms.empty())
    throw ConfigError(job.path + ": rooms: ilp sweep runs single-room jobs; run the building with ilp run");
  const RunOptions run = run_options(args.threads, args.max_memory, true);
  const JobPlan plan = plan_job(job, run);
  SweepSetting sweep;
  if (!args.set.empty()) {
    sweep = parse_set(args.set);
    JobGoals probe = plan.goals;
    for (double v : sweep.values) set_goal_target(probe, sweep.key, v);  // bad keys and values fail before any work
  } else if (job.sweep) {
    sweep = *job.sweep;
  } else {
    throw ConfigError(job.path + ": nothing to sweep: add a sweep block (sweep: {key: goals.NAME.average_lux, values: "
                                 "[...]}) or pass --set KEY=V1,V2,...");
  }
  const ProgressCallback progress = make_progress(args.quiet);
  OutputSet set(output_directory(job, args.out_dir), {"sweep.csv", "sweep.svg"});
  const std::vector<PreparedJob> prepared = prepare_variants(plan, run, progress, cache_folder(args.cache_dir, args.no_cache),
                                                             log_line, log_build);

  std::ostringstream csv;
  csv << std::setprecision(9) << csv_field(sweep.key)
      << ",luminaires,power_w,power_density_w_per_m2,feasible,all_met,flux_correction,evaluations,search_s,verification_s";
  // Targets are maintained values (as the job states them); the search and verification
  // work on initial ones (new luminaires): each column says which (a U0 ratio is both).
  for (const GoalSetting& g : job.goals) {
    const std::string label = "goals." + g.name + "." + std::string(goal_key(g.metric));
    for (const char* column : {".target_maintained", ".predicted_initial", ".predicted_maintained", ".verified_initial",
                               ".verified_maintained", ".met"})
      csv << "," << csv_field(label + column);
  }
  csv << "\n";
  std::vector<double> xs, powers;
  std::cout << std::left << std::setw(28) << sweep.key << std::right << std::setw(12) << "luminaires" << std::setw(11)
            << "power W" << std::setw(10) << "W/m²" << "  goals\n";
  for (std::size_t i = 0; i < sweep.values.size(); ++i) {
    std::cerr << "sweep point " << i + 1 << " of " << sweep.values.size() << ": " << sweep.key << " = "
              << sweep.values[i] << "\n";
    JobGoals point = plan.goals;  // the plan's goals, this point's target set
    set_goal_target(point, sweep.key, sweep.values[i]);
    const JobOutcome outcome = solve_variants(prepared, point, progress, log_line).outcome;
    csv << sweep.values[i] << ',' << outcome.luminaires.size() << ',' << outcome.power_w << ','
        << outcome.power_density_w_per_m2 << ',' << outcome.feasible << ',' << outcome.all_met << ','
        << outcome.flux_correction << ',' << outcome.search.evaluations << ',' << outcome.search.seconds << ','
        << outcome.verify_seconds;
    for (std::size_t k = 0; k < outcome.goals.size(); ++k) {
      const GoalOutcome& g = outcome.goals[k];
      const double mf = metric_rule(g.predicted.metric).lux ? outcome.maintenance_factor : 1.0;
      csv << ',' << point.lines[k].target << ',' << g.predicted.value << ',' << g.predicted.value * mf << ',';
      if (g.verified) csv << g.verified->value << ',' << g.verified->value * mf;
      else csv << ',';
      csv << ',' << g.met;
    }
    csv << "\n";
    std::cout << std::defaultfloat << std::setprecision(6) << std::left << std::setw(28) << sweep.values[i] << std::right << std::setw(12) << outcome.luminaires.size()
              << std::setw(11) << std::fixed << std::setprecision(1) << outcome.power_w << std::setw(10)
              << std::setprecision(2) << outcome.power_density_w_per_m2 << "  "
              << (outcome.all_met ? "all met" : outcome.feasible ? "missed on verification" : "infeasible") << "\n";
    if (outcome.all_met) {
      xs.push_back(sweep.values[i]);
      powers.push_back(outcome.power_w);
    }
  }
  set.write("sweep.csv", [&](std::ostream& out) { out << csv.str(); });
  const std::string plot = render_svg_plot(
      {.title = "Power against " + sweep.key, .x_label = sweep.key, .y_label = "electric power (W)"},
      {PlotSeries{"layouts meeting every goal", xs, powers}});
  set.write("sweep.svg", [&](std::ostream& out) { out << plot; });
  const std::vector<std::string> written = set.commit();
  std::cout << "operator built once for " << sweep.values.size() << " points; total " << std::fixed
            << std::setprecision(2) << seconds_since(start) << " s\n";
  for (const std::string& file : written) std::cout << "wrote " << file << "\n";
  return 0;
}

int run_print(const PrintArgs& args) {
  if (is_building_json(args.result)) print_building(std::cout, read_building_json(args.result));
  else print_result(std::cout, read_result_json(args.result));
  return 0;
}

}  // namespace ilp::cli
