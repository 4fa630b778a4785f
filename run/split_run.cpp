#include "run/split_run.h"

#include <cstring>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include "core/cost/cost_model.h"
#include "job/variant_search.h"

namespace ilp {
namespace {

std::string to_bytes(const std::vector<double>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
}

std::vector<double> from_bytes(const std::string& bytes) {
  std::vector<double> values(bytes.size() / sizeof(double));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(double));
  return values;
}

}  // namespace

WorkShare operator_share(const dist::Communicator& comm) {
  WorkShare share;
  share.index = comm.rank();
  share.count = comm.size();
  share.gather = [&comm](std::vector<double> mine) {
    std::vector<std::vector<double>> out;
    dist::agree(comm, {true, to_bytes(mine)}, [&out](std::vector<std::string> all) {
      for (const std::string& bytes : all) out.push_back(from_bytes(bytes));
      return std::string();
    });
    return out;
  };
  share.broadcast = [&comm](std::vector<double> values) {
    return from_bytes(dist::agree(comm, {true, comm.is_root() ? to_bytes(values) : std::string()},
                                  [](std::vector<std::string> all) { return std::move(all[0]); }));
  };
  return share;
}

void share_node_memory(RunOptions& run, const dist::Communicator& comm, bool same_on_every_rank) {
  if (run.max_memory_bytes || comm.node_size() <= 1) return;
  std::optional<double> node;
  if (same_on_every_rank) {
    std::string figure;
    if (comm.is_root())
      if (const std::optional<double> bytes = memory_budget_bytes(std::nullopt)) figure = std::to_string(*bytes);
    figure = comm.broadcast(figure);
    if (!figure.empty()) node = std::stod(figure);
  } else {
    node = memory_budget_bytes(std::nullopt);
  }
  if (!node) return;
  run.max_memory_bytes = *node / comm.node_size();
  if (comm.is_root())
    std::cerr << "memory per rank: " << format_bytes(*run.max_memory_bytes) << " (what this node has, over its "
              << comm.node_size() << " ranks; --max-memory sets it per rank)\n";
}

std::vector<PreparedJob> prepare_split(const JobPlan& plan, RunOptions run, const dist::Communicator& comm,
                                       const RunHooks& root_hooks, const std::string& cache_dir) {
  run.operator_share = operator_share(comm);
  // The share reaches the operator through each variant's model spec.
  JobPlan split = plan;
  for (VariantPlan& v : split.variants) v.model.operator_options.share = run.operator_share;
  if (comm.is_root())
    std::cerr << "operator build split over " << comm.size()
              << " ranks (scene, BVH and rows on every rank, the sources' columns of the direct light at the "
                 "sample and hit patches and of the k x k solve split); the search and verification then run on "
                 "rank 0\n";
  std::vector<PreparedJob> prepared;
  dist::in_agreed_steps(comm, [&] {
    if (comm.is_root())
      prepared = prepare_variants(split, run, root_hooks.progress, cache_dir, root_hooks.log, root_hooks.prepared_log);
    else prepared = prepare_variants(split, run, {}, cache_dir, {});
  });
  if (!comm.is_root()) prepared.clear();  // rank 0 alone searches: the others hold nothing more
  return prepared;
}

void print_peak_memory_per_rank(const dist::Communicator& comm, const std::string& when, double peak_gb) {
  std::ostringstream mine;
  mine << std::fixed << std::setprecision(2) << peak_gb;
  const std::vector<std::string> all = comm.gather(mine.str());
  if (!comm.is_root()) return;
  std::cout << "peak memory per rank " << when << ":";
  for (std::size_t r = 0; r < all.size(); ++r) std::cout << (r == 0 ? " " : ", ") << r << ": " << all[r] << " GB";
  std::cout << "\n" << std::flush;
}

}  // namespace ilp
