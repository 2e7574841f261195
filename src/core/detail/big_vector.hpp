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
#include <utility>
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
  void swap(BigArray& o) noexcept {
    data_.swap(o.data_);
    std::swap(size_, o.size_);
  }

 private:
  std::unique_ptr<T[]> data_;
  std::size_t size_ = 0;
};

/// A fixed-size array of trivially copyable T (zero-filled) whose storage comes from the system and
/// goes back to it when the array is destroyed (mmap / munmap on POSIX systems). For temporaries
/// made after a large structure was freed: malloc serves them from that structure's free chunks,
/// and what is freed there stays counted in the process's memory until reused (the 10^6 star's
/// peak rose 16 MB from two such 30 MB arrays).
template <class T>
class OsArray {
 public:
  OsArray() = default;
  explicit OsArray(std::size_t n) : size_(n) {
    if (n == 0) return;
#if defined(__linux__)
    void* p = mmap(nullptr, n * sizeof(T), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p != MAP_FAILED) {
      data_ = static_cast<T*>(p);
      mapped_ = true;
#if defined(MADV_HUGEPAGE)
      if (n * sizeof(T) >= (std::size_t{4} << 20) && huge_pages_enabled()) (void)madvise(p, n * sizeof(T), MADV_HUGEPAGE);
#endif
      return;
    }
#endif
    data_ = new T[n]();
  }
  OsArray(const OsArray&) = delete;
  OsArray& operator=(const OsArray&) = delete;
  ~OsArray() {
#if defined(__linux__)
    if (mapped_) {
      (void)munmap(data_, size_ * sizeof(T));
      return;
    }
#endif
    delete[] data_;
  }
  T& operator[](std::size_t i) noexcept { return data_[i]; }
  const T& operator[](std::size_t i) const noexcept { return data_[i]; }
  T* data() noexcept { return data_; }
  std::size_t size() const noexcept { return size_; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
  bool mapped_ = false;
};

}  // namespace constrict::detail
