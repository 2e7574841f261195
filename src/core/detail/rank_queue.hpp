// SPDX-License-Identifier: GPL-3.0-or-later
// A priority queue of distinct integer ranks as a tree of bit words.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace constrict::detail {

/// A set of distinct ranks in [0, n) that pops its smallest (the growth's inside tetrahedra
/// waiting to join, rank 0 the first it takes: src/constrict/grow3.cpp). One bit per rank, and
/// above the bits a tree of 64-bit words, each bit of a word saying that the word below it is not
/// empty: the smallest rank is found from the top in one word per level (four levels for 16
/// million ranks), a push or a pop changes at most one word per level. The growth pops nearly in
/// ascending rank (254 of 4.3 million pushes on the 10^6 star outranked the rank just popped), so
/// the bits it reads come nearly in order, where a binary heap of the waiting tetrahedra (up to
/// 437 000 there) read about twenty entries at random per pop, half of the growth's time
/// (docs/benchmarks.md). A forward scan over the bits alone was as fast on the star, but a volume
/// cloud pushes below the scan hundreds of thousands of times and its rescans grow with the input.
class RankQueue {
 public:
  void reset(std::size_t ranks) {
    level_.clear();
    std::size_t words = std::max<std::size_t>(ranks, 1);
    do {
      words = (words + 63) / 64;
      level_.emplace_back(words, 0);
    } while (words > 1);
    count_ = 0;
  }
  bool empty() const { return count_ == 0; }
  void push(std::uint32_t r) {
    std::size_t i = r;
    for (std::vector<std::uint64_t>& word : level_) {
      const std::uint64_t bit = std::uint64_t{1} << (i & 63);
      i >>= 6;
      const bool had_bits = word[i] != 0;
      word[i] |= bit;
      if (had_bits) break;  // (the levels above know this word already)
    }
    ++count_;
  }
  // The smallest rank in the set (not empty).
  std::uint32_t top() const {
    std::size_t i = 0;
    for (std::size_t k = level_.size(); k-- > 0;) i = i * 64 + static_cast<std::size_t>(__builtin_ctzll(level_[k][i]));
    return static_cast<std::uint32_t>(i);
  }
  std::uint32_t pop() {
    const std::uint32_t r = top();
    std::size_t i = r;
    for (std::vector<std::uint64_t>& word : level_) {
      const std::size_t w = i >> 6;
      word[w] &= ~(std::uint64_t{1} << (i & 63));
      if (word[w] != 0) break;
      i = w;
    }
    --count_;
    return r;
  }

 private:
  std::vector<std::vector<std::uint64_t>> level_;  // [0]: one bit per rank; the last: one word
  std::size_t count_ = 0;
};

}  // namespace constrict::detail
