// SPDX-License-Identifier: GPL-3.0-or-later
// A max-heap of four children per node whose sibling groups fill one cache line each.
#pragma once

#include <cstddef>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>

#include "constrict/status.hpp"

namespace constrict::detail {

/// A priority queue with the interface of std::priority_queue (push, top, pop, empty, size):
/// `top()` is an element that no other element `less`-exceeds. Under a strict weak order the
/// sequence of pops is the one of any other heap, except among equivalent elements; the 2D
/// constriction's entries are equivalent only when they are two versions of one triangle, of
/// which at most one is live (TriEntry in src/constrict/detail/engine2.hpp,
/// Constrictor2::Impl::step_untimed in constrict2.cpp), so its removals do not depend on the heap
/// kind. The order must be a strict weak order (no NaN keys).
///
/// Why four children: a pop of a binary heap of the constriction's 10^5-10^6 entries walks about
/// twenty levels, each a cache miss below the top levels. Here a pop walks half as many levels,
/// and the four children of a node lie in one 64-byte line when an element is 16 bytes (node k is
/// stored at slot k + 3 of a 64-byte aligned array, so its children 4k+1..4k+4 sit at slots
/// 4k+4..4k+7). Other element sizes work the same way, only without that alignment gain. The pop
/// is bottom-up, as libstdc++'s: a first version that compared the moved element at every level
/// (four comparisons per level against the binary heap's one) was 10-20 % slower than
/// std::priority_queue on the 10^6 inputs; this one is 5-15 % faster (docs/benchmarks.md).
template <class T, class Less>
class QuadHeap {
  static_assert(std::is_trivially_copyable_v<T>, "QuadHeap keeps plain entries in raw storage");

 public:
  explicit QuadHeap(Less less = Less{}) : less_(std::move(less)) {}
  QuadHeap(const QuadHeap&) = delete;
  QuadHeap& operator=(const QuadHeap&) = delete;
  QuadHeap(QuadHeap&& o) noexcept { swap(o); }
  QuadHeap& operator=(QuadHeap&& o) noexcept {
    swap(o);
    return *this;
  }
  ~QuadHeap() { release(); }

  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  const T& top() const {
    CONSTRICT_ASSERT(size_ > 0, "QuadHeap::top on an empty heap");
    return at(0);
  }

  void push(T v) {  // (by value: v may be one of the heap's own elements, which grow() moves)
    if (size_ == capacity_) grow();
    rise(size_++, v);
  }

  void pop() {
    CONSTRICT_ASSERT(size_ > 0, "QuadHeap::pop on an empty heap");
    const std::size_t n = --size_;
    if (n == 0) return;
    // Bottom-up: the hole goes down along the larger children to a leaf, then the last element
    // rises from there (it came from the bottom, so it rarely rises far): one comparison per
    // child, none against the moved element on the way down.
    std::size_t k = 0;
    for (;;) {
      const std::size_t first = 4 * k + 1;
      if (first >= n) break;
      std::size_t best = first;
      if (first + 4 <= n) {
        const std::size_t b01 = less_(at(first), at(first + 1)) ? first + 1 : first;
        const std::size_t b23 = less_(at(first + 2), at(first + 3)) ? first + 3 : first + 2;
        best = less_(at(b01), at(b23)) ? b23 : b01;
      } else {
        for (std::size_t c = first + 1; c < n; ++c)
          if (less_(at(best), at(c))) best = c;
      }
      at(k) = at(best);
      k = best;
    }
    rise(k, at(n));
  }

 private:
  // Node 0 at slot kShift: the children 4k+1..4k+4 of node k then start at slot 4k+4, a multiple
  // of four slots, which is one 64-byte line for 16-byte elements.
  static constexpr std::size_t kShift = 3;
  static constexpr std::align_val_t kAlign{64};
  static constexpr std::size_t kFirstSlots = 1024;  // slots of the first allocation (16 KiB at 16 bytes)

  T& at(std::size_t k) { return data_[k + kShift]; }
  const T& at(std::size_t k) const { return data_[k + kShift]; }

  // Puts v into the hole at node k after moving down the ancestors it outranks. (Inlined into
  // push and pop: as a call, the 10^6 square's constriction took 10-15 % longer.)
  __attribute__((always_inline)) void rise(std::size_t k, const T v) {
    while (k > 0) {
      const std::size_t parent = (k - 1) / 4;
      if (!less_(at(parent), v)) break;
      at(k) = at(parent);
      k = parent;
    }
    at(k) = v;
  }

  void grow() {
    // Capacities kFirstSlots - kShift, then doubling the slots: the allocations are powers of two.
    const std::size_t cap = capacity_ == 0 ? kFirstSlots - kShift : 2 * capacity_ + kShift;
    T* d = static_cast<T*>(::operator new(sizeof(T) * (cap + kShift), kAlign));
    if (size_ > 0) std::memcpy(static_cast<void*>(d + kShift), data_ + kShift, sizeof(T) * size_);
    release();
    data_ = d;
    capacity_ = cap;
  }
  void release() {
    if (data_) ::operator delete(data_, kAlign);
    data_ = nullptr;
    capacity_ = 0;
  }
  void swap(QuadHeap& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
    std::swap(less_, o.less_);
  }

  T* data_ = nullptr;
  std::size_t size_ = 0, capacity_ = 0;
  Less less_{};
};

/// A priority queue of two QuadHeaps (the same interface): a push that outranks the main heap's
/// top goes to a second, *hot* heap, and the hot heap is popped first. Invariant: every hot element
/// outranks every main element (a push goes to main only when main's top is not below it, so
/// main's top never rises), so top() is the greatest element and the pops are those of one heap
/// under the same order. Main is empty only when hot is too: a push goes to hot only over a
/// non-empty main, and main is popped only when hot is empty.
///
/// Why: in the 2D constriction a removal exposes its neighbours, and half of the curve's pushes
/// (30 % of the noisy curve's, 73 % of the square's at 10^6 points) outrank every entry waiting;
/// they are popped within a few steps. In a heap of 3-1 935 entries (the largest hot heaps seen
/// there) their push and pop stay in cache instead of walking the 10^5-10^6-entry heap
/// (docs/benchmarks.md, twenty-second session).
template <class T, class Less>
class TwoTierHeap {
 public:
  explicit TwoTierHeap(Less less = Less{}) : main_(less), hot_(less), less_(std::move(less)) {}

  bool empty() const { return main_.empty() && hot_.empty(); }
  std::size_t size() const { return main_.size() + hot_.size(); }
  const T& top() const { return hot_.empty() ? main_.top() : hot_.top(); }
  /// The entries in the hot heap (for measurements and tests).
  std::size_t hot_size() const { return hot_.size(); }

  void push(T v) {
    if (!main_.empty() && less_(main_.top(), v))
      hot_.push(v);
    else
      main_.push(v);
  }
  void pop() {
    if (!hot_.empty())
      hot_.pop();
    else
      main_.pop();
    CONSTRICT_ASSERT(!main_.empty() || hot_.empty(), "TwoTierHeap: a hot entry over an empty main heap");
  }

 private:
  QuadHeap<T, Less> main_, hot_;
  Less less_;
};

}  // namespace constrict::detail
