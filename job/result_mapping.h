// From a job's outcome to the result record the outputs are written from
// (output/result_record.h): the layout, each goal's line in maintained values, the
// bill of materials, how it was verified.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "job/job_runner.h"
#include "output/result_record.h"

namespace ilp {

struct EnergySettings;  // job/config.h

// Product x count, watts each and in all (empty when the outcome has no layout).
std::vector<BillLine> bill_of_materials(const VariantPlan& plan, const JobOutcome& outcome);

// The room of the scene: the extent of its surfaces (luminaires left out), each
// surface's area, mean reflectance and height range above floor_z_m (the scene's z
// when unknown); `mesh_path` is recorded by its file name only.
RoomRecord room_record(const Scene& scene, std::optional<double> floor_z_m, const std::string& mesh_path);

// Annual energy and LENI (core/energy/leni.h) of `power_w` over `area_m2` with the
// job's energy settings; F_C from the maintenance factor when constant_illuminance is
// set. Nothing when the area is not > 0.
std::optional<EnergyRecord> energy_record(const EnergySettings& settings, double power_w, double area_m2,
                                          double maintenance_factor);
// The verdict's lines of an outcome: each goal (maintained values, judged against
// `goals`' targets) and each constraint.
struct VerdictLines {
  std::vector<VerdictLine> goals, constraints;
  bool all_met() const;  // every line met
};
VerdictLines verdict_lines(const JobGoals& goals, const JobOutcome& outcome);

// A variant's record: its summary line, and its lines when it was searched.
VariantRecord variant_record(const PreparedJob& prepared, const JobGoals& goals, const JobOutcome& outcome,
                             const std::string& summary, bool chosen);

// The record of the chosen variant's outcome, goals judged against `job`'s targets,
// with the grids' records and the run's phase timings.
ResultRecord make_record(const std::string& program_version, const PreparedJob& prepared, const JobConfig& job,
                         const JobOutcome& outcome, const std::vector<GridRecord>& grids,
                         const std::vector<std::pair<std::string, double>>& timings);

}  // namespace ilp
