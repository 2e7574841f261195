// SPDX-License-Identifier: GPL-3.0-or-later
// Sizing of the large arrays of the Delaunay export and the γ loops. A fresh multi-megabyte
// array costs one page fault per 4 KiB page when it is first written (a measurable part of the
// export for 10^6 points); on Linux we ask for transparent huge pages on it first (a hint only:
// no effect when THP is disabled, and no effect on any value), unless huge_pages_enabled() says
// they cost more than they save on this machine.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "constrict/memory.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace constrict::detail {

/// v.reserve(n), with a huge-page hint for the newly allocated storage (nothing is written: the
/// pages count only once the elements are).
template <class T>
void reserve_big(std::vector<T>& v, std::size_t n) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::size_t kHuge = std::size_t{2} << 20;
  if (n * sizeof(T) >= 2 * kHuge && v.capacity() < n && huge_pages_enabled()) {
    v.reserve(n);
    const auto begin = reinterpret_cast<std::uintptr_t>(v.data());
    const std::uintptr_t b = (begin + kHuge - 1) & ~(kHuge - 1);
    const std::uintptr_t e = (begin + n * sizeof(T)) & ~(kHuge - 1);
    if (e > b) (void)madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
  }
#endif
  v.reserve(n);
}

/// v.resize(n), with a huge-page hint for the newly allocated storage.
template <class T>
void resize_big(std::vector<T>& v, std::size_t n) {
  reserve_big(v, n);
  v.resize(n);
}

}  // namespace constrict::detail

namespace constrict::detail {

/// A fixed-size array of trivially constructible T that is NOT zero-filled (each element is
/// written exactly once by a parallel loop, so the first touch of its pages is parallel too),
/// with the same huge-page hint as resize_big.
template <class T>
class BigArray {
 public:
  void allocate(std::size_t n) {
    data_.reset(new T[n]);  // default-initialised: no writes
    size_ = n;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::size_t kHuge = std::size_t{2} << 20;
    if (n * sizeof(T) >= 2 * kHuge && huge_pages_enabled()) {
      const auto begin = reinterpret_cast<std::uintptr_t>(data_.get());
      const std::uintptr_t b = (begin + kHuge - 1) & ~(kHuge - 1);
      const std::uintptr_t e = (begin + n * sizeof(T)) & ~(kHuge - 1);
      if (e > b) (void)madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
    }
#endif
  }
  T& operator[](std::size_t i) noexcept { return data_[i]; }
  const T& operator[](std::size_t i) const noexcept { return data_[i]; }
  T* data() noexcept { return data_.get(); }
  const T* data() const noexcept { return data_.get(); }
  std::size_t size() const noexcept { return size_; }

 private:
  std::unique_ptr<T[]> data_;
  std::size_t size_ = 0;
};

}  // namespace constrict::detail
