// One operator build split over processes (docs/cluster.md, issue 23). A phase that
// scales with the model is cut into fixed blocks (their size is an option, never the
// number of processes or threads); in round r, share i computes block r x count + i,
// and the blocks' partial sums are added in block order on every path, one process
// included, so the result has the same bits whatever the split. Core never talks to
// MPI: the two exchanges are callbacks (job/ and apps/ wire them to dist/).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace ilp {

struct WorkShare {
  int index = 0;  // this process's share, in [0, count)
  int count = 1;  // shares (processes) the build is split over
  // One round: every share passes its block's partial sum (empty when it has no block
  // this round); share 0 gets every share's, in share order (= block order), the others
  // an empty list. Unset: one process (the list is {mine}).
  std::function<std::vector<std::vector<double>>(std::vector<double> mine)> gather;
  // Share 0's `values` on every share. Unset: one process (values as they are).
  std::function<std::vector<double>(std::vector<double> values)> broadcast;

  bool is_root() const { return index == 0; }
  // The block this share computes in `round`, or >= blocks when it has none.
  std::size_t block_of_round(std::size_t round) const {
    return round * static_cast<std::size_t>(count) + static_cast<std::size_t>(index);
  }
  // Rounds needed for `blocks` blocks.
  std::size_t rounds(std::size_t blocks) const {
    return (blocks + static_cast<std::size_t>(count) - 1) / static_cast<std::size_t>(count);
  }
  // This share's columns of `columns` (the sources of T): [first, second), contiguous,
  // in share order, as even as can be (a share may have none when columns < count).
  std::pair<std::size_t, std::size_t> column_range(std::size_t columns) const {
    const auto n = static_cast<std::size_t>(count), i = static_cast<std::size_t>(index);
    return {columns * i / n, columns * (i + 1) / n};
  }
  bool is_valid(std::string* error) const;
};

// Adds `blocks` (partial sums of one block each, in block order; an empty one adds
// nothing) to `total` one after the other: the one order every path uses. An empty
// `total` takes the first block's values. Throws std::logic_error when sizes differ.
void add_blocks_in_order(std::vector<double>& total, const std::vector<std::vector<double>>& blocks);

// The sum over `blocks` blocks, block b's partial sum given by partial(b), computed by
// the blocks of `share` and reduced in block order (add_blocks_in_order): the same
// bits for every share count. Every share gets the total.
std::vector<double> reduce_blocks(std::size_t blocks, const WorkShare& share,
                                  const std::function<std::vector<double>(std::size_t block)>& partial);

// Every block's values concatenated in block order, on every share: block b's from
// values(b), computed by the share that owns it (rows computed each on its own, such as
// a block of receivers' direct light: no sum, so any split gives the same bits).
std::vector<double> gather_blocks(std::size_t blocks, const WorkShare& share,
                                  const std::function<std::vector<double>(std::size_t block)>& values);

// Every share's `mine` concatenated in share order, on every share (one gather and one
// broadcast; one share: mine as it is). With each share's columns of a column-major
// matrix (column_range), the whole matrix.
std::vector<double> gather_shares(const WorkShare& share, std::vector<double> mine);

// The element-wise maximum over the shares of `mine` (every share passes as many values),
// on every share: a split iteration's stopping test sees every share's columns.
std::vector<double> max_over_shares(const WorkShare& share, std::vector<double> mine);

}  // namespace ilp
