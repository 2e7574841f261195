// SPDX-License-Identifier: GPL-3.0-or-later
// Point-set checks: dimension, emptiness, finiteness, duplicates, degenerate (collinear/coplanar)
// position. The reconstruction needs all of them: spec gamma-graph.md §3.8 rejects duplicate
// points, and a Delaunay triangulation of a collinear (2D) or coplanar (3D) set has no faces.
#include "constrict/points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "constrict/predicates.hpp"
#include "constrict/status.hpp"

namespace constrict {
namespace {

constexpr std::size_t kListedDuplicates = 5;  // pairs named in the Duplicate message

// Maps a double to an unsigned key with the same order as operator< on doubles: -0.0 and 0.0 get
// the same key (they compare equal), every NaN gets the largest key (NaNs are never duplicates,
// see equal_coords, but they must not break the strict weak order of the sort).
std::uint64_t order_key(double x) noexcept {
  if (std::isnan(x)) return ~std::uint64_t{0};
  if (x == 0.0) x = 0.0;
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  constexpr std::uint64_t kSign = std::uint64_t{1} << 63;
  return (bits & kSign) != 0 ? ~bits : (bits | kSign);
}

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

struct KeyIndex {
  std::uint64_t key;
  std::size_t index;
};

// Sorts by (key, index) for entries that arrive in index order: an LSD radix sort is stable, so
// equal keys keep their index order. Digits where all keys agree are skipped (for points in a
// bounding box, often the sign and exponent bits). O(N); std::sort below a size where that pays.
void sort_by_key(std::vector<KeyIndex>& a) {
  const std::size_t n = a.size();
  if (n < 2048) {
    std::sort(a.begin(), a.end(), [](const KeyIndex& l, const KeyIndex& r) {
      return l.key != r.key ? l.key < r.key : l.index < r.index;
    });
    return;
  }
  // 11-bit digits: 6 passes over 64-bit keys, counts small enough to stay in L1.
  constexpr int kBits = 11;
  constexpr int kDigits = (64 + kBits - 1) / kBits;
  constexpr std::size_t kBuckets = std::size_t{1} << kBits;
  constexpr std::uint64_t kMask = kBuckets - 1;
  std::vector<std::array<std::size_t, kBuckets>> histogram(kDigits);
  for (auto& h : histogram) h.fill(0);
  for (const KeyIndex& e : a)
    for (int d = 0; d < kDigits; ++d) ++histogram[d][(e.key >> (kBits * d)) & kMask];
  std::vector<KeyIndex> buffer(n);
  KeyIndex* src = a.data();
  KeyIndex* dst = buffer.data();
  for (int d = 0; d < kDigits; ++d) {
    std::array<std::size_t, kBuckets>& h = histogram[d];
    const unsigned shift = static_cast<unsigned>(kBits * d);
    if (h[(src[0].key >> shift) & kMask] == n) continue;
    std::size_t sum = 0;
    for (std::size_t& c : h) {
      const std::size_t count = c;
      c = sum;
      sum += count;
    }
    for (std::size_t i = 0; i < n; ++i) dst[h[(src[i].key >> shift) & kMask]++] = src[i];
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
  if (id == n) return {StatusCode::Coplanar, "all " + plural(n, "point") + " are coplanar"};
  return Status::ok();
}

}  // namespace

std::vector<DuplicatePair> find_duplicates(const PointSet& points) {
  std::vector<DuplicatePair> dups;
  if (points.dim < 1) return dups;
  const std::size_t n = points.size();
  const int dim = points.dim;
  if (n < 2) return dups;

  // Lexicographic sort of the indices by coordinates, ties broken by index, so the result does not
  // depend on the sort algorithm. Done in two steps for speed: radix-sort compact (key(x), index)
  // pairs, then sort the runs of equal x by the other coordinates. The final order is exactly the
  // lexicographic (x, y, z, index) order.
  std::vector<KeyIndex> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = {order_key(points[i][0]), i};
  sort_by_key(order);
  const auto lex_less = [&points, dim](const KeyIndex& l, const KeyIndex& r) {
    const double* p = points[l.index];
    const double* q = points[r.index];
    for (int k = 1; k < dim; ++k) {
      if (less_total(p[k], q[k])) return true;
      if (less_total(q[k], p[k])) return false;
    }
    return l.index < r.index;
  };

  for (std::size_t run = 0; run < n;) {
    std::size_t run_end = run + 1;
    while (run_end < n && order[run_end].key == order[run].key) ++run_end;
    if (run_end - run > 1) {
      std::sort(order.begin() + static_cast<std::ptrdiff_t>(run),
                order.begin() + static_cast<std::ptrdiff_t>(run_end), lex_less);
      // Within the run, groups of equal points are contiguous and start with their lowest index.
      for (std::size_t g = run; g < run_end;) {
        std::size_t g_end = g + 1;
        const double* first = points[order[g].index];
        while (g_end < run_end && equal_coords(first, points[order[g_end].index], dim)) {
          dups.push_back({order[g].index, order[g_end].index});
          ++g_end;
        }
        g = g_end;
      }
    }
    run = run_end;
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

Status check_points(const PointSet& points, PointCheck* report) {
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

  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < dim; ++k) {
      const double v = points[i][k];
      if (!std::isfinite(v))
        return {StatusCode::NonFinite, "point " + std::to_string(i) +
                                           " has a non-finite coordinate (" +
                                           (std::isnan(v) ? "nan"
                                            : v > 0       ? "inf"
                                                          : "-inf") +
                                           ")"};
    }
  }

  std::vector<DuplicatePair> dups = find_duplicates(points);
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

}  // namespace constrict
