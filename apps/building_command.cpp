// ilp run of a building job (rooms:, docs/building.md): each room through the
// single-room run, its files in rooms/<name>/, the building's result.json from the
// rooms' records, all in one output set (a failure in any room writes nothing).
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <optional>
#include <sstream>

#include "apps/cli_support.h"
#include "apps/run_support.h"
#include "core/base/error.h"
#include "core/cost/cost_model.h"
#include "dist/communicator.h"
#include "job/building.h"
#include "job/plan.h"
#include "job/room_exchange.h"
#include "output/building_record.h"
#include "run/building_ranks.h"
#include "run/split_run.h"
#include "job/config.h"

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

// Room r's files as a rank other than 0 writes them: staged in a private output set
// under the temporary folder, read back (full names under the building's folder, their
// bytes) and the private set removed.
std::vector<std::pair<std::string, std::string>> room_files(const JobConfig& job, std::size_t r, const RoomRun& result) {
  namespace fs = std::filesystem;
  const fs::path private_folder =
      fs::temp_directory_path() / ("ilp-rank-" + std::to_string(::getpid()) + "-room-" + std::to_string(r));
  struct Remove {
    fs::path path;
    ~Remove() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  } remove{private_folder};
  std::vector<std::pair<std::string, std::string>> files;
  OutputSet local((private_folder / "out").string(), building_output_names(job));
  local.set_subfolder(room_folder(job, r));
  stage_room_outputs(local, room_job(job, r), result);
  local.set_subfolder("");
  for (const std::string& name : local.staged_names()) {
    std::ifstream in(local.staging_path(name), std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (!in.is_open()) throw IlpError(name + ": cannot read it back from the rank's staging folder");
    files.emplace_back(name, bytes.str());
  }
  return files;
}

// Stages a file another rank wrote (full name under the building's folder) in `set`.
void stage_received(OutputSet& set, const std::string& name, const std::string& bytes) {
  const std::filesystem::path path = set.staging_path(name);
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw IlpError(set.explained(path.string() + ": cannot write it"));
  set.staged(name);
}

// The building over several ranks (mpirun -np N, docs/cluster.md; run/building_ranks.h):
// rank 0 stages its own rooms' files in the one output set, the others send theirs;
// rank 0 writes the set when every room ran, in room order.
int run_building_distributed(const RunArgs& args, const JobConfig& job, const dist::Communicator& comm) {
  const auto start = Clock::now();
  RunOptions run = run_options(args.threads, args.max_memory, true);
  // Each rank's share of its node's memory, so that the cost model refuses a room that
  // does not fit beside the others' (a scene and its BVH are per rank).
  share_node_memory(run, comm, false);
  const ProgressCallback progress = make_progress(args.quiet);
  const std::string cache = building_cache(args);
  std::optional<OutputSet> set;
  BuildingRun building;
  for (const RoomSetting& room : job.rooms) building.room_names.push_back(room.name);
  building.setup_on_root = [&] { set.emplace(output_directory(job, args.out_dir), building_output_names(job)); };
  building.run_room = [&](std::size_t r) {
    const auto room_start = Clock::now();
    const JobConfig& room = room_job(job, r);
    std::cerr << "room " << r + 1 << " of " << job.rooms.size() << ": " << job.rooms[r].name << " (rank "
              << comm.rank() << " of " << comm.size() << ")\n";
    const RoomRun result = run_room(room, plan_job(room, run), run, progress, cache);
    RoomOutcome outcome;
    outcome.room = r;
    outcome.record = result.record;
    if (set) {
      set->set_subfolder(room_folder(job, r));
      stage_room_outputs(*set, room, result);
      set->set_subfolder("");
    } else {
      outcome.files = room_files(job, r, result);
    }
    outcome.seconds = seconds_since(room_start);
    return outcome;
  };
  building.finish_on_root = [&](const std::vector<const RoomOutcome*>& by_room) {
    std::vector<ResultRecord> records;
    std::vector<std::pair<std::string, double>> timings;
    for (std::size_t r = 0; r < by_room.size(); ++r) {
      for (const auto& [name, bytes] : by_room[r]->files) stage_received(*set, name, bytes);
      records.push_back(by_room[r]->record);
      timings.emplace_back("room " + job.rooms[r].name, by_room[r]->seconds);
    }
    BuildingRecord summary = summarize_building(kProgramVersion, job, records);
    timings.emplace_back("total", seconds_since(start));
    summary.timings_s = timings;
    print_building(std::cout, summary);
    stage_building_json(*set, summary);
    const std::vector<std::string> written = set->commit();
    std::cout << "wrote " << written.size() << " files: " << set->folder() << "/result.json, timings.json and rooms/<name>/ for "
              << job.rooms.size() << " rooms (" << comm.size() << " ranks)\n";
    std::cout << std::fixed << std::setprecision(2) << "peak memory " << peak_memory_gb() << " GB (resident, rank 0)\n";
    return summary.all_met ? 0 : 2;
  };
  return run_rooms_over_ranks(comm, building);
}

}  // namespace

int run_building(const RunArgs& args, const JobConfig& job) {
  const dist::Communicator& comm = dist::Communicator::world();
  if (comm.distributed()) return run_building_distributed(args, job, comm);
  const auto start = Clock::now();
  const RunOptions run = run_options(args.threads, args.max_memory, true);
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
    const RoomRun result = run_room(room, plan_job(room, run), run, progress, cache);
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
