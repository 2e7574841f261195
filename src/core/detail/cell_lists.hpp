// SPDX-License-Identifier: GPL-3.0-or-later
// One id list per grid cell, for the segment grids of the 2D fallback and refinement
// (sparse_segments.hpp, the dense layers in constrict/detail/grid2.hpp and refine2.cpp). Those grids are
// filled once with a whole polygon (10^6 edges) and then changed by a few edges per move. One
// std::vector per cell cost a heap allocation per non-empty cell, and on the uniform 10^6 square
// the filling and freeing were a tenth of the run. Here the first filling is a counting sort into
// one array (build()); later additions go to a chain of nodes per cell, removals take an id out of
// either part. The order of the ids in a list is not part of the interface: every query asks
// whether any registered segment meets a new one, so its answer does not depend on it.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>

#include "constrict/status.hpp"

namespace constrict::detail {

template <class Id> class CellLists {
 public:
  /// No cells.
  void clear() {
    start_.clear();
    len_.clear();
    head_.clear();
    bulk_.clear();
    nodes_.clear();
    free_ = -1;
  }
  /// The number of cells.
  std::size_t size() const { return start_.size(); }
  /// Adds empty cells up to `cells` in all.
  void grow(std::size_t cells) {
    if (cells <= size()) return;
    start_.resize(cells, 0);
    len_.resize(cells, 0);
    head_.resize(cells, -1);
  }
  /// Replaces every list with what visit(emit) registers by calling emit(cell, id); the cells
  /// are those of every index emitted, and at least `cells`. visit is called twice (count, then
  /// place) and must emit the same pairs both times.
  template <class Visit> void build(std::size_t cells, Visit&& visit) {
    clear();
    std::vector<std::size_t> at(cells + 1, 0);
    visit([&](std::size_t c, Id) {
      if (c + 2 > at.size()) at.resize(c + 2, 0);
      ++at[c + 1];
    });
    cells = at.size() - 1;
    grow(cells);
    for (std::size_t c = 0; c < cells; ++c) {
      start_[c] = at[c];
      len_[c] = static_cast<std::uint32_t>(at[c + 1]);
      at[c + 1] += at[c];
    }
    bulk_.resize(at[cells]);
    visit([&](std::size_t c, Id id) { bulk_[at[c]++] = id; });
  }
  /// build() for the ids that visit(k0, k1, emit) emits for items [k0, k1) of count, counted and
  /// placed in kBlocks fixed ranges of items side by side. Every cell emitted must be below
  /// `cells`. The lists are those of build() over the items in order (in each cell, a block's ids
  /// follow the earlier blocks'), whatever the thread count. Below kBlocksFrom items, build().
  template <class Visit>
  void build_in_blocks(std::size_t cells, std::size_t count, Visit&& visit) {
    if (count < kBlocksFrom) return build(cells, [&](auto&& emit) { visit(std::size_t{0}, count, emit); });
    clear();
    grow(cells);
    const auto first = [count](std::size_t b) { return count * b / kBlocks; };
    // Per block and cell: the count, then the position of the block's next id in the cell (32
    // bits: together as much memory as build()'s one array of positions).
    std::array<std::vector<std::uint32_t>, kBlocks> at;
    tbb::parallel_for(std::size_t{0}, kBlocks, [&](std::size_t b) {
      at[b].assign(cells, 0);
      visit(first(b), first(b + 1), [&](std::size_t c, Id) {
        CONSTRICT_CHECK(c < cells, "CellLists::build_in_blocks: a cell beyond the grid");
        ++at[b][c];
      });
    });
    std::size_t total = 0;
    for (std::size_t c = 0; c < cells; ++c) {
      start_[c] = total;
      for (std::size_t b = 0; b < kBlocks; ++b) {
        const std::size_t k = at[b][c];
        at[b][c] = static_cast<std::uint32_t>(total);
        total += k;
      }
      len_[c] = static_cast<std::uint32_t>(total - start_[c]);
    }
    CONSTRICT_CHECK(total <= UINT32_MAX, "CellLists::build_in_blocks: more than 2^32 registrations");
    bulk_.resize(total);
    tbb::parallel_for(std::size_t{0}, kBlocks, [&](std::size_t b) {
      visit(first(b), first(b + 1), [&](std::size_t c, Id id) { bulk_[at[b][c]++] = id; });
    });
  }
  void add(std::size_t c, Id id) {
    int k = free_;
    if (k >= 0) {
      free_ = nodes_[static_cast<std::size_t>(k)].next;
      nodes_[static_cast<std::size_t>(k)] = Node{id, head_[c]};
    } else {
      k = static_cast<int>(nodes_.size());
      nodes_.push_back(Node{id, head_[c]});
    }
    head_[c] = k;
  }
  /// Takes one registration of id out of cell c's list (none if it has none).
  void remove(std::size_t c, Id id) {
    Id* b = bulk_.data() + start_[c];
    for (std::uint32_t k = 0; k < len_[c]; ++k)
      if (b[k] == id) {
        b[k] = b[--len_[c]];
        return;
      }
    for (int* link = &head_[c]; *link >= 0; link = &nodes_[static_cast<std::size_t>(*link)].next) {
      Node& node = nodes_[static_cast<std::size_t>(*link)];
      if (node.id == id) {
        const int k = *link;
        *link = node.next;
        node.next = free_;
        free_ = k;
        return;
      }
    }
  }
  /// Calls f(id) for cell c's ids until f returns true; true if it did.
  template <class F> bool any(std::size_t c, F&& f) const {
    const Id* b = bulk_.data() + start_[c];
    for (std::uint32_t k = 0; k < len_[c]; ++k)
      if (f(b[k])) return true;
    for (int k = head_[c]; k >= 0; k = nodes_[static_cast<std::size_t>(k)].next)
      if (f(nodes_[static_cast<std::size_t>(k)].id)) return true;
    return false;
  }

 private:
  // build_in_blocks: two ranges (one per core of the machines it is made for; a fixed number, so
  // that nothing depends on the thread count), from 2^16 items on.
  static constexpr std::size_t kBlocks = 2, kBlocksFrom = std::size_t{1} << 16;
  struct Node {
    Id id;
    int next;
  };
  std::vector<std::size_t> start_;  // per cell: its built part, bulk_[start_, start_ + len_)
  std::vector<std::uint32_t> len_;
  std::vector<int> head_;           // per cell: its added ids, a chain of nodes_ (-1: none)
  std::vector<Id> bulk_;
  std::vector<Node> nodes_;
  int free_ = -1;                   // chain of removed nodes, reused by add()
};

/// The bulk fills of the segment grids (sparse_segments.hpp, dense_segments.hpp) take their
/// segments as seg(k, a, b, id) for k < count; this calls f(a, b, id) for each.
template <class Id, class Seg, class F> void for_each_segment(std::size_t count, Seg& seg, F&& f) {
  for_each_segment<Id>(0, count, seg, f);
}
/// The same for k in [k0, k1).
template <class Id, class Seg, class F>
void for_each_segment(std::size_t k0, std::size_t k1, Seg& seg, F&& f) {
  for (std::size_t k = k0; k < k1; ++k) {
    const double* a = nullptr;
    const double* b = nullptr;
    Id id{};
    seg(k, a, b, id);
    f(a, b, id);
  }
}

}  // namespace constrict::detail
