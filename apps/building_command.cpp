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
#include "job/room_exchange.h"
#include "output/building_record.h"
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

// The building over several ranks (mpirun -np N, docs/cluster.md): room r runs on rank
// room_rank(r, N); each rank sends rank 0 its rooms' records, times and files (or its
// first failure); rank 0 writes the one output set when every room ran, in room order,
// so the files are the single-process run's bytes. Every rank takes part in the one
// gather and the one broadcast of the exit code whatever fails, so a failure anywhere
// ends every rank with exit 1, rank 0 printing the failure of the lowest room.
int run_building_distributed(const RunArgs& args, const JobConfig& job, const dist::Communicator& comm) {
  const auto start = Clock::now();
  RunOptions run = run_options(args.threads, args.max_memory, true);
  // The ranks on one node share its memory: without --max-memory each may use its share
  // of what the node has, so the cost model refuses a room that does not fit beside the
  // others' (a scene and its BVH are per rank; docs/cluster.md).
  if (!run.max_memory_bytes && comm.node_size() > 1) {
    if (const std::optional<double> node = memory_budget_bytes(std::nullopt)) {
      run.max_memory_bytes = *node / comm.node_size();
      if (comm.is_root())
        std::cerr << "memory per rank: " << format_bytes(*run.max_memory_bytes) << " (what this node has, over its "
                  << comm.node_size() << " ranks; --max-memory sets it per rank)\n";
    }
  }
  const ProgressCallback progress = make_progress(args.quiet);
  const std::string cache = building_cache(args);
  std::optional<OutputSet> set;
  RankReport mine;
  try {
    if (comm.is_root()) set.emplace(output_directory(job, args.out_dir), building_output_names(job));
  } catch (...) {
    mine.failure = RoomFailure{0, dist::failure_message(std::current_exception())};
  }
  for (std::size_t r = 0; r < job.rooms.size() && !mine.failure; ++r) {
    if (room_rank(r, comm.size()) != comm.rank()) continue;
    try {
      const auto room_start = Clock::now();
      const JobConfig& room = room_job(job, r);
      std::cerr << "room " << r + 1 << " of " << job.rooms.size() << ": " << job.rooms[r].name << " (rank "
                << comm.rank() << " of " << comm.size() << ")\n";
      const RoomRun result = run_room(room, run, progress, cache);
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
      mine.rooms.push_back(std::move(outcome));
    } catch (...) {
      mine.failure = RoomFailure{r, dist::failure_message(std::current_exception())};
    }
  }
  std::string my_report;
  if (!comm.is_root()) {
    try {
      my_report = encode_rank_report(mine);
    } catch (...) {
      RankReport failed;
      failed.failure = RoomFailure{mine.rooms.empty() ? 0 : mine.rooms.front().room,
                                   dist::failure_message(std::current_exception())};
      my_report = encode_rank_report(failed);
    }
  }
  const std::vector<std::string> reports = comm.gather(my_report);
  if (!comm.is_root()) {
    const std::string code = comm.broadcast(std::string());
    if (code != "0" && code != "2") throw dist::FailedElsewhere();
    return std::stoi(code);
  }
  int code = 1;
  std::exception_ptr failure;
  try {
    std::vector<RankReport> all{std::move(mine)};
    std::size_t received = 0;
    for (std::size_t k = 1; k < reports.size(); ++k) {
      received += reports[k].size();
      all.push_back(decode_rank_report(reports[k]));
    }
    std::cerr << "gathered " << received << " bytes of rooms' results from " << reports.size() - 1 << " ranks\n";
    const RoomFailure* first = nullptr;
    for (const RankReport& report : all)
      if (report.failure && (first == nullptr || report.failure->room < first->room)) first = &*report.failure;
    if (first != nullptr) throw std::runtime_error(first->message);
    std::vector<const RoomOutcome*> by_room(job.rooms.size(), nullptr);
    for (const RankReport& report : all)
      for (const RoomOutcome& o : report.rooms)
        if (o.room < by_room.size()) by_room[o.room] = &o;
    std::vector<ResultRecord> records;
    std::vector<std::pair<std::string, double>> timings;
    for (std::size_t r = 0; r < by_room.size(); ++r) {
      if (by_room[r] == nullptr) throw std::runtime_error("room " + job.rooms[r].name + ": no rank sent its result");
      for (const auto& [name, bytes] : by_room[r]->files) stage_received(*set, name, bytes);
      records.push_back(by_room[r]->record);
      timings.emplace_back("room " + job.rooms[r].name, by_room[r]->seconds);
    }
    BuildingRecord building = summarize_building(kProgramVersion, job, records);
    timings.emplace_back("total", seconds_since(start));
    building.timings_s = timings;
    print_building(std::cout, building);
    stage_building_json(*set, building);
    const std::vector<std::string> written = set->commit();
    std::cout << "wrote " << written.size() << " files: " << set->folder() << "/result.json, timings.json and rooms/<name>/ for "
              << job.rooms.size() << " rooms (" << comm.size() << " ranks)\n";
    std::cout << std::fixed << std::setprecision(2) << "peak memory " << peak_memory_gb() << " GB (resident, rank 0)\n";
    code = building.all_met ? 0 : 2;
  } catch (...) {
    failure = std::current_exception();
  }
  comm.broadcast(std::to_string(failure ? 1 : code));
  if (failure) std::rethrow_exception(failure);
  return code;
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
