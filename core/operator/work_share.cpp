// The ordered reduction behind a split operator build (core/operator/work_share.h).
#include "core/operator/work_share.h"

#include <algorithm>
#include <stdexcept>

namespace ilp {

bool WorkShare::is_valid(std::string* error) const {
  const bool ok = count >= 1 && index >= 0 && index < count && (count == 1 || (gather && broadcast));
  if (!ok && error)
    *error = "WorkShare: index " + std::to_string(index) + " of " + std::to_string(count) +
             " shares: must be in [0, count), and more than one share needs gather and broadcast";
  return ok;
}

void add_blocks_in_order(std::vector<double>& total, const std::vector<std::vector<double>>& blocks) {
  for (const std::vector<double>& block : blocks) {
    if (block.empty()) continue;
    if (total.empty()) {
      total = block;
      continue;
    }
    if (block.size() != total.size())
      throw std::logic_error("add_blocks_in_order: a block of " + std::to_string(block.size()) +
                             " values, the total has " + std::to_string(total.size()));
    for (std::size_t i = 0; i < total.size(); ++i) total[i] += block[i];
  }
}

std::vector<double> reduce_blocks(std::size_t blocks, const WorkShare& share,
                                  const std::function<std::vector<double>(std::size_t block)>& partial) {
  if (std::string error; !share.is_valid(&error)) throw std::invalid_argument(error);
  std::vector<double> total;
  for (std::size_t round = 0; round < share.rounds(blocks); ++round) {
    const std::size_t block = share.block_of_round(round);
    std::vector<double> mine = block < blocks ? partial(block) : std::vector<double>();
    if (share.count == 1) {
      add_blocks_in_order(total, {std::move(mine)});
      continue;
    }
    // Share 0 adds the round's blocks, which arrive in share order: block order.
    const std::vector<std::vector<double>> round_blocks = share.gather(std::move(mine));
    if (share.is_root()) add_blocks_in_order(total, round_blocks);
  }
  if (share.count > 1) total = share.broadcast(std::move(total));
  return total;
}

std::vector<double> gather_blocks(std::size_t blocks, const WorkShare& share,
                                  const std::function<std::vector<double>(std::size_t block)>& values) {
  if (std::string error; !share.is_valid(&error)) throw std::invalid_argument(error);
  std::vector<double> all;
  for (std::size_t round = 0; round < share.rounds(blocks); ++round) {
    const std::size_t block = share.block_of_round(round);
    std::vector<double> mine = block < blocks ? values(block) : std::vector<double>();
    if (share.count == 1) {
      all.insert(all.end(), mine.begin(), mine.end());
      continue;
    }
    const std::vector<std::vector<double>> round_blocks = share.gather(std::move(mine));
    if (share.is_root())
      for (const std::vector<double>& b : round_blocks) all.insert(all.end(), b.begin(), b.end());
  }
  if (share.count > 1) all = share.broadcast(std::move(all));
  return all;
}

std::vector<double> gather_shares(const WorkShare& share, std::vector<double> mine) {
  if (std::string error; !share.is_valid(&error)) throw std::invalid_argument(error);
  if (share.count == 1) return mine;
  std::vector<double> all;
  const std::vector<std::vector<double>> parts = share.gather(std::move(mine));
  if (share.is_root())
    for (const std::vector<double>& p : parts) all.insert(all.end(), p.begin(), p.end());
  return share.broadcast(std::move(all));
}

std::vector<double> max_over_shares(const WorkShare& share, std::vector<double> mine) {
  if (std::string error; !share.is_valid(&error)) throw std::invalid_argument(error);
  if (share.count == 1) return mine;
  const std::size_t n = mine.size();
  std::vector<double> most;
  const std::vector<std::vector<double>> parts = share.gather(std::move(mine));
  if (share.is_root()) {
    most = parts.at(0);
    for (const std::vector<double>& p : parts) {
      if (p.size() != n) {  // broadcast nothing: every share then stops here alike
        most.clear();
        break;
      }
      for (std::size_t i = 0; i < n; ++i) most[i] = std::max(most[i], p[i]);
    }
  }
  most = share.broadcast(std::move(most));
  if (most.size() != n)
    throw std::logic_error("max_over_shares: " + std::to_string(most.size()) + " values gathered, expected " +
                           std::to_string(n) + " (a share passed another number)");
  return most;
}

}  // namespace ilp
