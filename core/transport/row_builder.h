// Building a compressed row-major sparse matrix (SparseRows) row by row on several
// threads: each row is visited twice by the same function, once to count its entries
// and once to write them, so no row is copied or grown. A row is written by one thread
// from its own inputs, so the matrix is the same for any thread count.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/transport/form_factors.h"

namespace ilp {

// visit(r, emit) calls emit(column, value) for row r's entries, columns ascending.
// threads: 0, every core.
template <class Visit>
SparseRows build_rows(Eigen::Index rows, Eigen::Index cols, int threads, const Visit& visit) {
  using Index = SparseRows::StorageIndex;
  std::vector<long long> end(static_cast<std::size_t>(rows) + 1, 0);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  constexpr Eigen::Index kGrain = 2048;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, rows, kGrain), [&](const auto& range) {
      for (Eigen::Index r = range.begin(); r != range.end(); ++r) {
        long long count = 0;
        visit(r, [&count](Index, double) { ++count; });
        end[static_cast<std::size_t>(r) + 1] = count;
      }
    });
  });
  for (std::size_t r = 1; r < end.size(); ++r) end[r] += end[r - 1];
  if (end.back() > std::numeric_limits<Index>::max())
    throw std::length_error("build_rows: " + std::to_string(end.back()) + " non-zeros exceed the sparse index type");
  SparseRows F(rows, cols);
  F.resizeNonZeros(static_cast<Eigen::Index>(end.back()));
  for (std::size_t r = 0; r < end.size(); ++r) F.outerIndexPtr()[r] = static_cast<Index>(end[r]);
  Index* columns = F.innerIndexPtr();
  double* values = F.valuePtr();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, rows, kGrain), [&](const auto& range) {
      for (Eigen::Index r = range.begin(); r != range.end(); ++r) {
        long long at = end[static_cast<std::size_t>(r)];
        visit(r, [&](Index column, double value) {
          columns[at] = column;
          values[at] = value;
          ++at;
        });
      }
    });
  });
  return F;
}

}  // namespace ilp
