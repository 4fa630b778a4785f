// ilp run of a building job (rooms:, docs/building.md): each room through the
// single-room run, its files in rooms/<name>/, the building's result.json from the
// rooms' records, all in one output set (a failure in any room writes nothing).
#include <chrono>
#include <iomanip>
#include <iostream>

#include "apps/cli_support.h"
#include "apps/run_support.h"
#include "job/building.h"
#include "output/building_record.h"

namespace ilp::cli {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The building's own files, the rooms folder (replaced as a whole: a room renamed or
// removed leaves no folder behind) and every file each room may write there.
std::vector<std::string> building_output_names(const JobConfig& job) {
  std::vector<std::string> names{"result.json", "timings.json", "rooms"};
  for (std::size_t r = 0; r < job.rooms.size(); ++r)
    for (const std::string& name : run_output_names(room_job(job, r), false))
      names.push_back(room_folder(job, r) + "/" + name);
  return names;
}

std::string building_cache(const RunArgs& args) {
  if (args.no_cache) return {};
  return args.cache_dir.empty() ? default_cache_dir() : args.cache_dir;
}

void stage_building_json(OutputSet& set, const BuildingRecord& building) {
  write_building_json(set.staging_path("result.json"), building);
  set.staged("result.json");
  write_building_timings_json(set.staging_path("timings.json"), building);
  set.staged("timings.json");
}

}  // namespace

int run_building(const RunArgs& args, const JobConfig& job) {
  const auto start = Clock::now();
  const RunOptions run = run_options(args.threads, args.max_memory);
  const ProgressCallback progress = make_progress(args.quiet);
  // Staged from the start, so a folder that cannot take the outputs fails before the work.
  OutputSet set(output_directory(job, args.out_dir), building_output_names(job));
  const std::string cache = building_cache(args);
  std::vector<ResultRecord> records;
  std::vector<std::pair<std::string, double>> timings;
  for (std::size_t r = 0; r < job.rooms.size(); ++r) {
    const auto room_start = Clock::now();
    const JobConfig& room = room_job(job, r);
    std::cerr << "room " << r + 1 << " of " << job.rooms.size() << ": " << job.rooms[r].name << "\n";
    const RoomRun result = run_room(room, run, progress, cache);
    set.set_subfolder(room_folder(job, r));
    stage_room_outputs(set, room, result);
    set.set_subfolder("");
    records.push_back(result.record);
    timings.emplace_back("room " + job.rooms[r].name, seconds_since(room_start));
  }
  BuildingRecord building = summarize_building(kProgramVersion, job, records);
  timings.emplace_back("total", seconds_since(start));
  building.timings_s = timings;
  print_building(std::cout, building);
  stage_building_json(set, building);
  const std::vector<std::string> written = set.commit();
  std::cout << "wrote " << written.size() << " files: " << set.folder() << "/result.json, timings.json and rooms/<name>/ for "
            << job.rooms.size() << " rooms\n";
  std::cout << std::fixed << std::setprecision(2) << "peak memory " << peak_memory_gb() << " GB (resident)\n";
  return building.all_met ? 0 : 2;
}

}  // namespace ilp::cli
