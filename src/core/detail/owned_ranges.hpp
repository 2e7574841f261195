// SPDX-License-Identifier: GPL-3.0-or-later
// Parallel passes whose tasks each own a range of ids: every task reads all items and writes only
// the counters and slots of its own ids, with plain (not atomic) writes. The validators and the
// tetrahedron order place millions of scattered items this way; shared atomic counters took four
// times as long (every locked add waited for the scattered writes before it; docs/benchmarks.md,
// fourteenth session). Each id's items are handled in item order by one task, so the result does
// not depend on the number of tasks.
#pragma once

#include <algorithm>
#include <cstddef>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace constrict::detail {

// Calls pass(lo, hi) for a partition of [0, ids) into at most max_tasks ranges (and no more than
// the threads), in parallel; @p items is the number of items each task reads (small passes run as
// one task).
template <class Pass>
void for_owned_ranges(std::size_t ids, std::size_t items, const Pass& pass, std::size_t max_tasks = 8) {
  constexpr std::size_t kItemsPerTask = std::size_t{1} << 14;
  const std::size_t threads = static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency()));
  const std::size_t P = std::max<std::size_t>(1, std::min({max_tasks, threads, items / kItemsPerTask + 1}));
  tbb::parallel_for(std::size_t{0}, P, [&](std::size_t k) { pass(ids * k / P, ids * (k + 1) / P); });
}

}  // namespace constrict::detail
