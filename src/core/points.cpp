// SPDX-License-Identifier: GPL-3.0-or-later
// Point-set checks: dimension, emptiness, finiteness, duplicates, degenerate (collinear/coplanar)
// position. The reconstruction needs all of them: spec gamma-graph.md §3.8 rejects duplicate
// points, and a Delaunay triangulation of a collinear (2D) or coplanar (3D) set has no faces.
#include "constrict/points.hpp"
#include "core/detail/check_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "constrict/predicates.hpp"
#include "constrict/status.hpp"

namespace constrict {
namespace {

constexpr std::size_t kListedDuplicates = 5;  // pairs named in the Duplicate message

// Strict weak order on doubles: operator< with every NaN above everything else.
bool less_total(double a, double b) noexcept {
  if (std::isnan(a)) return false;
  if (std::isnan(b)) return true;
  return a < b;
}

bool equal_coords(const double* a, const double* b, int dim) noexcept {
  for (int k = 0; k < dim; ++k)
    if (!(a[k] == b[k])) return false;
  return true;
}

// Radix sort entry: the high 32 bits of the key of x, and the point index.
// A 32-bit hash of a point's coordinates, equal for equal points (operator==: -0.0 == 0.0).
std::uint32_t coordinate_hash(const double* p, int dim) noexcept {
  std::uint64_t h = 0x9e3779b97f4a7c15ULL;
  for (int k = 0; k < dim; ++k) {
    const double x = p[k] == 0.0 ? 0.0 : p[k];
    std::uint64_t bits = 0;
    std::memcpy(&bits, &x, sizeof bits);
    h = (h ^ bits) * 0xff51afd7ed558ccdULL;
    h ^= h >> 32;
  }
  return static_cast<std::uint32_t>(h >> 32);
}

struct HighIndex {
  std::uint32_t high;
  std::uint32_t index;
};

// Sorts by `high`, stable: entries arrive in index order, so equal keys stay in index order.
// LSD radix sort with 11-bit digits (3 passes over 8-byte entries, counts that fit in L1); digits
// where all keys agree are skipped. O(N).
void radix_sort(std::vector<HighIndex>& a) {
  constexpr int kBits = 11;
  constexpr int kDigits = (32 + kBits - 1) / kBits;
  constexpr std::size_t kBuckets = std::size_t{1} << kBits;
  constexpr std::uint32_t kMask = kBuckets - 1;
  const std::size_t n = a.size();
  std::vector<std::array<std::size_t, kBuckets>> histogram(kDigits);
  for (auto& h : histogram) h.fill(0);
  for (const HighIndex& e : a)
    for (int d = 0; d < kDigits; ++d) ++histogram[d][(e.high >> (kBits * d)) & kMask];
  std::vector<HighIndex> buffer(n);
  HighIndex* src = a.data();
  HighIndex* dst = buffer.data();
  for (int d = 0; d < kDigits; ++d) {
    std::array<std::size_t, kBuckets>& h = histogram[d];
    const unsigned shift = static_cast<unsigned>(kBits * d);
    if (h[(src[0].high >> shift) & kMask] == n) continue;
    std::size_t sum = 0;
    for (std::size_t& c : h) {
      const std::size_t count = c;
      c = sum;
      sum += count;
    }
    for (std::size_t i = 0; i < n; ++i) dst[h[(src[i].high >> shift) & kMask]++] = src[i];
    std::swap(src, dst);
  }
  if (src != a.data()) std::copy(src, src + n, a.data());
}

std::string plural(std::size_t n, const char* word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

std::string duplicate_message(const std::vector<DuplicatePair>& dups) {
  std::string msg = "points " + std::to_string(dups[0].first) + " and " +
                    std::to_string(dups[0].second) + " are identical";
  const std::size_t listed = std::min(dups.size(), kListedDuplicates);
  for (std::size_t k = 1; k < listed; ++k)
    msg += "; " + std::to_string(dups[k].first) + " and " + std::to_string(dups[k].second);
  if (dups.size() > listed) msg += "; ...";
  msg += " (" + plural(dups.size(), "duplicate point") +
         " in all; use --merge-duplicates to keep the first of each)";
  return msg;
}

// Collinear / coplanar test in O(N) with exact predicates. Each stage looks for the first point
// that extends the current affine frame (a distinct point, then one off the line, then one off the
// plane); a frame point never has to be revisited, so one pass per stage suffices. Duplicates are
// tolerated here (the first two input points may be the only distinct ones).
Status check_affine_span(const PointSet& points) {
  const std::size_t n = points.size();
  const int dim = points.dim;
  const double* a = points[0];
  std::size_t ib = 1;
  while (ib < n && equal_coords(points[ib], a, dim)) ++ib;
  if (ib == n) {
    // Unreachable after the duplicate check, kept for callers passing duplicates.
    return {dim == 2 ? StatusCode::Collinear : StatusCode::Coplanar,
            "all " + plural(n, "point") + " are identical"};
  }
  const double* b = points[ib];
  std::size_t ic = ib + 1;
  if (dim == 2) {
    while (ic < n && orient2(a, b, points[ic]) == 0) ++ic;
    if (ic == n) return {StatusCode::Collinear, "all " + plural(n, "point") + " are collinear"};
    return Status::ok();
  }
  while (ic < n && collinear3(a, b, points[ic])) ++ic;
  if (ic == n) return {StatusCode::Coplanar, "all " + plural(n, "point") + " are collinear (3D)"};
  const double* c = points[ic];
  std::size_t id = ic + 1;
  while (id < n && orient3(a, b, c, points[id]) == 0) ++id;
  if (id == n) {
    // Points of a 2D outline written with a constant coordinate: say how to read them as 2D.
    for (int k = 0; k < 3; ++k) {
      std::size_t i = 1;
      while (i < n && points[i][k] == a[k]) ++i;
      if (i < n) continue;
      static const char* const kHow[3] = {"read y, z as 2D points (--columns 2,3)", "read x, z as 2D points (--columns 1,3)",
                                          "read them as 2D points (--dim 2)"};
      return {StatusCode::Coplanar, "all " + plural(n, "point") + " are coplanar: every " + "xyz"[k] + " is the same; to reconstruct an outline " + kHow[k]};
    }
    return {StatusCode::Coplanar, "all " + plural(n, "point") + " are coplanar; a surface needs points off one plane"};
  }
  return Status::ok();
}

}  // namespace

std::vector<DuplicatePair> find_duplicates(const PointSet& points) {
  std::vector<DuplicatePair> dups;
  if (points.dim < 1) return dups;
  const std::size_t n = points.size();
  const int dim = points.dim;
  if (n < 2) return dups;

  // Identical points are brought together by sorting, and each group sorted lexicographically by
  // coordinates, ties broken by index, so that the first occurrence comes first; the pairs are
  // sorted at the end, so the result does not depend on the sort algorithm. For speed this is done
  // in two steps: a radix sort of compact (32-bit hash of the coordinates, index) pairs, then a
  // comparison sort of each run of equal hashes. Identical points have equal hashes (-0.0 is
  // hashed as 0.0), and distinct points rarely do, so the second step reads few points (an
  // order-preserving key such as the high bits of x groups many distinct points of a sample, and
  // reading them at random cost more than the radix sort).
  const auto lex_less = [&points, dim](std::size_t l, std::size_t r) {
    const double* p = points[l];
    const double* q = points[r];
    for (int k = 0; k < dim; ++k) {
      if (less_total(p[k], q[k])) return true;
      if (less_total(q[k], p[k])) return false;
    }
    return l < r;
  };
  // Pairs every later copy in a lexicographically sorted range with its first occurrence.
  const auto pair_copies = [&](const std::size_t* b, const std::size_t* e, std::vector<DuplicatePair>& out) {
    for (const std::size_t* g = b; g != e;) {
      const std::size_t* g_end = g + 1;
      while (g_end != e && equal_coords(points[*g], points[*g_end], dim)) {
        out.push_back({*g, *g_end});
        ++g_end;
      }
      g = g_end;
    }
  };
  // The pairs of a range sorted by hash (equal hashes in index order), run by run of equal hashes;
  // `run`: scratch of the caller (one per thread).
  const auto pair_runs = [&](const HighIndex* b, const HighIndex* e, std::vector<DuplicatePair>& out,
                             std::vector<std::size_t>& run) {
    for (const HighIndex* r = b; r != e;) {
      const HighIndex* r_end = r + 1;
      while (r_end != e && r_end->high == r->high) ++r_end;
      if (r_end - r == 2) {
        // The common collision: two points, already in index order; no sort needed.
        if (equal_coords(points[r[0].index], points[r[1].index], dim)) out.push_back({r[0].index, r[1].index});
      } else if (r_end - r > 2) {
        run.clear();
        for (const HighIndex* i = r; i != r_end; ++i) run.push_back(i->index);
        std::sort(run.begin(), run.end(), lex_less);
        pair_copies(run.data(), run.data() + run.size(), out);
      }
      r = r_end;
    }
  };

  constexpr std::size_t kRadixMin = 2048;
  constexpr std::size_t kParallelMin = std::size_t{1} << 17;
  if (n < kRadixMin || n > std::numeric_limits<std::uint32_t>::max()) {
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), lex_less);
    pair_copies(order.data(), order.data() + n, dups);
  } else if (n < kParallelMin) {
    std::vector<HighIndex> order(n);
    for (std::size_t i = 0; i < n; ++i)
      order[i] = {coordinate_hash(points[i], dim), static_cast<std::uint32_t>(i)};
    radix_sort(order);
    std::vector<std::size_t> run;
    pair_runs(order.data(), order.data() + n, dups, run);
  } else {
    // On every core: the (hash, index) pairs scattered by the hash's top kTop bits (counts per
    // fixed block, so each bucket holds its pairs in index order), each bucket sorted by (hash,
    // index), a strict total order, and its runs of equal hashes paired; the buckets' pairs are
    // sorted below like the others. The same pairs as the sequential radix sort.
    constexpr int kTop = 11;
    constexpr std::size_t kB = std::size_t{1} << kTop, kBlock = std::size_t{1} << 15;
    const std::size_t nblocks = (n + kBlock - 1) / kBlock;
    std::vector<HighIndex> key(n), order(n);
    std::vector<std::size_t> count(nblocks * kB, 0);
    tbb::parallel_for(std::size_t{0}, nblocks, [&](std::size_t blk) {
      std::size_t* c = &count[blk * kB];
      for (std::size_t i = blk * kBlock, e = std::min(n, i + kBlock); i < e; ++i) {
        key[i] = {coordinate_hash(points[i], dim), static_cast<std::uint32_t>(i)};
        ++c[key[i].high >> (32 - kTop)];
      }
    });
    std::vector<std::size_t> start(kB + 1, 0);
    for (std::size_t b = 0, sum = 0; b < kB; ++b) {  // bucket-major prefix: offsets per (bucket, block)
      start[b] = sum;
      for (std::size_t blk = 0; blk < nblocks; ++blk) {
        const std::size_t c = count[blk * kB + b];
        count[blk * kB + b] = sum;
        sum += c;
      }
    }
    start[kB] = n;
    tbb::parallel_for(std::size_t{0}, nblocks, [&](std::size_t blk) {
      std::size_t* at = &count[blk * kB];
      for (std::size_t i = blk * kBlock, e = std::min(n, i + kBlock); i < e; ++i)
        order[at[key[i].high >> (32 - kTop)]++] = key[i];
    });
    std::vector<HighIndex>().swap(key);
    std::vector<std::vector<DuplicatePair>> found(kB);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kB, 16), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<DuplicatePair> local;
      std::vector<std::size_t> local_run;
      for (std::size_t b = r.begin(); b != r.end(); ++b) {
        HighIndex* lo = order.data() + start[b];
        HighIndex* hi = order.data() + start[b + 1];
        std::sort(lo, hi, [](const HighIndex& x, const HighIndex& y) {
          return x.high != y.high ? x.high < y.high : x.index < y.index;
        });
        pair_runs(lo, hi, local, local_run);
      }
      found[r.begin()] = std::move(local);
    });
    for (auto& f : found) dups.insert(dups.end(), f.begin(), f.end());
  }
  std::sort(dups.begin(), dups.end(), [](const DuplicatePair& l, const DuplicatePair& r) {
    return l.first != r.first ? l.first < r.first : l.second < r.second;
  });
  return dups;
}

PointSet merge_duplicates(const PointSet& points, std::vector<std::size_t>* kept_index) {
  const std::size_t n = points.size();
  const std::vector<DuplicatePair> dups = find_duplicates(points);
  std::vector<char> drop(n, 0);
  for (const DuplicatePair& d : dups) drop[d.second] = 1;

  PointSet merged;
  merged.dim = points.dim;
  merged.coords.reserve(points.coords.size() -
                        dups.size() * static_cast<std::size_t>(std::max(points.dim, 0)));
  if (kept_index != nullptr) {
    kept_index->clear();
    kept_index->reserve(n - dups.size());
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (drop[i] != 0) continue;
    merged.coords.insert(merged.coords.end(), points[i], points[i] + points.dim);
    if (kept_index != nullptr) kept_index->push_back(i);
  }
  return merged;
}

namespace {
const char* non_finite_name(double v) { return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf"; }

// Message naming the point of the first non-finite coordinate, or empty when all are finite.
std::string non_finite_message(const PointSet& points) {
  const std::size_t dim = points.dim > 0 ? static_cast<std::size_t>(points.dim) : 1;
  for (std::size_t k = 0; k < points.coords.size(); ++k) {
    const double v = points.coords[k];
    if (!std::isfinite(v))
      return "point " + std::to_string(k / dim) + " has a non-finite coordinate (" + non_finite_name(v) + ")";
  }
  return {};
}

Status check_points_impl(const PointSet& points, PointCheck* report, bool duplicates) {
  if (report != nullptr) report->duplicates.clear();
  const int dim = points.dim;
  if (dim != 2 && dim != 3)
    return {StatusCode::InvalidArgument,
            "point dimension must be 2 or 3, got " + std::to_string(dim)};
  if (points.coords.size() % static_cast<std::size_t>(dim) != 0)
    return {StatusCode::InvalidArgument,
            "coordinate count " + std::to_string(points.coords.size()) +
                " is not a multiple of the dimension " + std::to_string(dim)};
  const std::size_t n = points.size();
  if (n == 0) return {StatusCode::EmptyInput, "no points"};

  if (std::string msg = non_finite_message(points); !msg.empty()) return {StatusCode::NonFinite, std::move(msg)};

  std::vector<DuplicatePair> dups;
  if (duplicates) dups = find_duplicates(points);
  if (!dups.empty()) {
    std::string msg = duplicate_message(dups);
    if (report != nullptr) report->duplicates = std::move(dups);
    return {StatusCode::Duplicate, std::move(msg)};
  }

  const std::size_t min_points = dim == 2 ? 3 : 4;
  if (n < min_points)
    return {StatusCode::TooFewPoints, "only " + plural(n, "point") + "; at least " +
                                          std::to_string(min_points) + " are needed in " +
                                          std::to_string(dim) + "D"};

  return check_affine_span(points);
}
}  // namespace

Status check_points(const PointSet& points, PointCheck* report) {
  return check_points_impl(points, report, true);
}

namespace detail {
Status check_finite(const PointSet& points, const char* who) {
  std::string msg = non_finite_message(points);
  if (msg.empty()) return Status::ok();
  return {StatusCode::NonFinite, std::string(who) + ": " + msg};
}

Status check_points_deferred(const PointSet& points) {
  Status st = check_points_impl(points, nullptr, false);
  // Too few or collinear/coplanar: a duplicate check first, so that the status is check_points'
  // (duplicates are reported before the other defects).
  if (!st && (st.code() == StatusCode::TooFewPoints || st.code() == StatusCode::Collinear ||
              st.code() == StatusCode::Coplanar))
    return check_points(points);
  return st;
}
}  // namespace detail

}  // namespace constrict
