// SPDX-License-Identifier: GPL-3.0-or-later
// The cells of a sparse uniform grid (sparse_segments.hpp, the 2D fallback's point grid in
// constrict/detail/grid2.hpp): an open-addressing table (linear probing) from a cell (i, j) to a
// dense slot number 0, 1, 2, ... in the order the cells were first added. Only non-empty cells are stored, so
// a grid fine enough for the spacing along a curve costs memory for the cells the curve crosses,
// not for the plane's area.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace constrict::detail {

class CellTable {
 public:
  /// Empty, with room for about `expected` cells before the first growth.
  void clear(std::size_t expected = 0) {
    std::size_t cap = std::size_t{1} << 12;
    while (cap < 2 * expected) cap *= 2;
    entries_.assign(cap, Entry{});
    size_ = 0;
    set_shift();
  }
  std::size_t size() const { return size_; }
  /// The slot of cell (i, j), -1 if it was never added.
  int find(int i, int j) const {
    const std::uint64_t k = key(i, j);
    for (std::size_t h = home(i, j);; h = (h + 1) & (entries_.size() - 1)) {
      if (entries_[h].key == k) return entries_[h].slot;
      if (entries_[h].key == kEmpty) return -1;
    }
  }
  /// The slot of cell (i, j), added (as slot size() - 1) if new.
  int insert(int i, int j) {
    const std::uint64_t k = key(i, j);
    std::size_t h = home(i, j);
    for (;; h = (h + 1) & (entries_.size() - 1)) {
      if (entries_[h].key == k) return entries_[h].slot;
      if (entries_[h].key == kEmpty) break;
    }
    if (2 * (size_ + 1) > entries_.size()) {
      grow();
      return insert(i, j);
    }
    entries_[h] = Entry{k, static_cast<int>(size_++)};
    return entries_[h].slot;
  }
  /// Calls f(i, j) for every cell added (in no particular order).
  template <class F>
  void for_each(F&& f) const {
    for (const Entry& e : entries_)
      if (e.key != kEmpty) f(static_cast<int>(e.key & 0xffffffffu), static_cast<int>(e.key >> 32));
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // no cell has it (i, j < 2^31)
  struct Entry {
    std::uint64_t key = kEmpty;
    int slot = -1;
  };
  static std::uint64_t key(int i, int j) {
    return static_cast<std::uint64_t>(static_cast<std::uint32_t>(j)) << 32 | static_cast<std::uint32_t>(i);
  }
  // The first entry to probe: the 2 x 2 block of the cell picks an aligned group of 4 entries (one
  // cache line) by Fibonacci hashing (the top bits of the product, where every bit of i and j
  // counts), the cell its place in it. Queries read neighbouring cells (strips, rings), which then
  // share cache lines: 2-6 % off the noisy 1e6 curve's fallback and refinement.
  std::size_t home(int i, int j) const {
    const std::uint64_t block = key(static_cast<int>(static_cast<std::uint32_t>(i) >> 1), static_cast<int>(static_cast<std::uint32_t>(j) >> 1));
    return (static_cast<std::size_t>((block * 0x9E3779B97F4A7C15ull) >> shift_) & ~std::size_t{3}) |
           (static_cast<std::size_t>(i) & 1u) | (static_cast<std::size_t>(j) & 1u) << 1;
  }
  void set_shift() {
    shift_ = 64;
    for (std::size_t c = entries_.size(); c > 1; c >>= 1) --shift_;
  }
  void grow() {
    std::vector<Entry> old;
    old.swap(entries_);
    entries_.assign(2 * old.size(), Entry{});
    set_shift();
    for (const Entry& e : old) {
      if (e.key == kEmpty) continue;
      std::size_t h = home(static_cast<int>(e.key & 0xffffffffu), static_cast<int>(e.key >> 32));
      while (entries_[h].key != kEmpty) h = (h + 1) & (entries_.size() - 1);
      entries_[h] = e;
    }
  }
  std::vector<Entry> entries_;  // kEmpty key: free
  std::size_t size_ = 0;
  int shift_ = 52;  // 64 - log2(table size)
};

}  // namespace constrict::detail
