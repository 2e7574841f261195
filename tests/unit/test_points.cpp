// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of check_points(), find_duplicates() and merge_duplicates(): hand cases, the order of
// the checks, and find_duplicates against brute force on random inputs with many repeats.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "constrict/points.hpp"
#include "constrict/predicates.hpp"
#include "constrict/status.hpp"

namespace constrict {
namespace {

::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

PointSet make(int dim, std::vector<double> coords) {
  PointSet p;
  p.dim = dim;
  p.coords = std::move(coords);
  return p;
}

bool operator==(const DuplicatePair& a, const DuplicatePair& b) {
  return a.first == b.first && a.second == b.second;
}

std::vector<DuplicatePair> brute_force_duplicates(const PointSet& p) {
  std::vector<DuplicatePair> out;
  const auto equal = [&p](std::size_t i, std::size_t j) {
    for (int k = 0; k < p.dim; ++k)
      if (!(p[i][k] == p[j][k])) return false;
    return true;
  };
  // Pairs ordered by (first, second): for each first occurrence, its later copies.
  for (std::size_t i = 0; i < p.size(); ++i) {
    bool is_first = true;
    for (std::size_t h = 0; h < i && is_first; ++h)
      if (equal(h, i)) is_first = false;
    if (!is_first) continue;
    for (std::size_t j = i + 1; j < p.size(); ++j)
      if (equal(i, j)) out.push_back({i, j});
  }
  return out;
}

// ---- check_points ----------------------------------------------------------------------------

TEST(Status, NumberTextIsTheShortestRoundTrip) {
  // (Messages used std::to_string: "-1.000000", and 1e-10 as "0.000000".)
  EXPECT_EQ(number_text(-1), "-1");
  EXPECT_EQ(number_text(1e-10), "1e-10");
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(number_text(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(std::stod(number_text(2.0 / 3)), 2.0 / 3);
}

TEST(PointsCheck, AcceptsTriangleAndTetrahedron) {
  EXPECT_TRUE(check_points(make(2, {0, 0, 1, 0, 0, 1})));
  EXPECT_TRUE(check_points(make(3, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1})));
}

TEST(PointsCheck, InvalidDimension) {
  for (int dim : {0, 1, 4, -2}) {
    Status st = check_points(make(dim, {0, 0, 0, 0}));
    EXPECT_EQ(st.code(), StatusCode::InvalidArgument) << dim;
    EXPECT_TRUE(Contains(st.message(), "got " + std::to_string(dim)));
  }
  Status st = check_points(make(3, {0, 0, 0, 1}));
  EXPECT_EQ(st.code(), StatusCode::InvalidArgument);
}

TEST(PointsCheck, Empty) {
  EXPECT_EQ(check_points(make(2, {})).code(), StatusCode::EmptyInput);
  EXPECT_EQ(check_points(make(3, {})).code(), StatusCode::EmptyInput);
}

TEST(PointsCheck, NonFiniteNamesPoint) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  Status st = check_points(make(2, {0, 0, 1, 0, 0, nan, 1, 1}));
  EXPECT_EQ(st.code(), StatusCode::NonFinite);
  EXPECT_TRUE(Contains(st.message(), "point 2 has a non-finite coordinate (nan)"));
  st = check_points(make(3, {0, 0, 0, -inf, 0, 0}));
  EXPECT_EQ(st.code(), StatusCode::NonFinite);
  EXPECT_TRUE(Contains(st.message(), "point 1 has a non-finite coordinate (-inf)"));
}

TEST(PointsCheck, OrderNonFiniteBeforeDuplicateBeforeTooFewBeforeCollinear) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Duplicate, too few and non-finite at once: NonFinite wins.
  EXPECT_EQ(check_points(make(2, {0, 0, 0, 0, nan, 1})).code(), StatusCode::NonFinite);
  // Duplicate and too few: Duplicate wins.
  EXPECT_EQ(check_points(make(2, {0, 0, 0, 0})).code(), StatusCode::Duplicate);
  // Duplicate and collinear: Duplicate wins.
  EXPECT_EQ(check_points(make(2, {0, 0, 1, 1, 2, 2, 1, 1})).code(), StatusCode::Duplicate);
  // Too few and collinear: TooFewPoints wins.
  EXPECT_EQ(check_points(make(3, {0, 0, 0, 1, 1, 1, 2, 2, 2})).code(), StatusCode::TooFewPoints);
}

TEST(PointsCheck, DuplicateMessageAndReport) {
  PointCheck report;
  PointSet p = make(2, {5, 5, 1, 0, 0, 1, 5, 5, 1, 0, 7, 7, 5, 5});
  Status st = check_points(p, &report);
  EXPECT_EQ(st.code(), StatusCode::Duplicate);
  EXPECT_EQ(st.message(),
            "points 0 and 3 are identical; 0 and 6; 1 and 4 (3 duplicate points in all; use "
            "--merge-duplicates to keep the first of each)");
  ASSERT_EQ(report.duplicates.size(), 3u);
  EXPECT_TRUE(report.duplicates[0] == (DuplicatePair{0, 3}));
  EXPECT_TRUE(report.duplicates[1] == (DuplicatePair{0, 6}));
  EXPECT_TRUE(report.duplicates[2] == (DuplicatePair{1, 4}));
  // A clean set clears a reused report.
  EXPECT_TRUE(check_points(make(2, {0, 0, 1, 0, 0, 1}), &report));
  EXPECT_TRUE(report.duplicates.empty());
}

TEST(PointsCheck, DuplicateMessageSingular) {
  Status st = check_points(make(2, {0, 0, 1, 0, 0, 1, 1, 0}));
  EXPECT_EQ(st.message(),
            "points 1 and 3 are identical (1 duplicate point in all; use --merge-duplicates to "
            "keep the first of each)");
}

TEST(PointsCheck, TooFewStatesCountAndMinimum) {
  Status st = check_points(make(2, {0, 0, 1, 0}));
  EXPECT_EQ(st.code(), StatusCode::TooFewPoints);
  EXPECT_EQ(st.message(), "only 2 points; at least 3 are needed in 2D");
  st = check_points(make(3, {0, 0, 0}));
  EXPECT_EQ(st.code(), StatusCode::TooFewPoints);
  EXPECT_EQ(st.message(), "only 1 point; at least 4 are needed in 3D");
  st = check_points(make(3, {0, 0, 0, 1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(st.code(), StatusCode::TooFewPoints);
  EXPECT_TRUE(Contains(st.message(), "only 3 points; at least 4"));
}

TEST(PointsCheck, Collinear2D) {
  Status st = check_points(make(2, {0, 0, 3, 3, 1, 1, -2, -2, 0.5, 0.5}));
  EXPECT_EQ(st.code(), StatusCode::Collinear);
  EXPECT_EQ(st.message(), "all 5 points are collinear");
  // Nearly collinear is not collinear: the exact predicate sees the 2^-50 offset.
  EXPECT_TRUE(check_points(make(2, {0, 0, 1, 1, 2, 2 + std::ldexp(1.0, -50), 3, 3})));
  // The only point off the line is the last one.
  std::vector<double> c;
  for (int i = 0; i < 100; ++i) {
    c.push_back(i);
    c.push_back(2.0 * i + 1.0);
  }
  EXPECT_EQ(check_points(make(2, c)).code(), StatusCode::Collinear);
  c.push_back(5);
  c.push_back(0);
  EXPECT_TRUE(check_points(make(2, c)));
}

TEST(PointsCheck, Coplanar3D) {
  Status st = check_points(make(3, {0, 0, 2, 1, 0, 2, 0, 1, 2, 3, 4, 2, -1, 7, 2}));
  EXPECT_EQ(st.code(), StatusCode::Coplanar);
  EXPECT_EQ(st.message(), "all 5 points are coplanar: every z is the same; to reconstruct an outline read them as 2D points (--dim 2)");
  // Tilted plane x + y + z = 1 with points that are collinear at the start.
  std::vector<double> c = {1, 0, 0, 0, 1, 0, 0.5, 0.5, 0, 0, 0, 1, 0.25, 0.25, 0.5};
  EXPECT_EQ(check_points(make(3, c)).code(), StatusCode::Coplanar);
  EXPECT_EQ(check_points(make(3, c)).message(), "all 5 points are coplanar; a surface needs points off one plane");
  c.insert(c.end(), {1, 1, 1});
  EXPECT_TRUE(check_points(make(3, c)));
}

TEST(PointsCheck, Collinear3DIsCoplanarWithCollinearMessage) {
  Status st = check_points(make(3, {0, 0, 0, 1, 2, 3, 2, 4, 6, -1, -2, -3}));
  EXPECT_EQ(st.code(), StatusCode::Coplanar);
  EXPECT_EQ(st.message(), "all 4 points are collinear (3D)");
}

// ---- find_duplicates / merge_duplicates --------------------------------------------------------

TEST(PointsDuplicates, NoneInDistinctSet) {
  EXPECT_TRUE(find_duplicates(make(2, {0, 0, 0, 1, 1, 0, 1, 1})).empty());
  EXPECT_TRUE(find_duplicates(make(3, {})).empty());
  EXPECT_TRUE(find_duplicates(make(3, {1, 2, 3})).empty());
}

TEST(PointsDuplicates, EqualInSomeCoordinatesOnly) {
  // Same x (or x and y) is not a duplicate.
  EXPECT_TRUE(find_duplicates(make(3, {1, 2, 3, 1, 2, 4, 1, 5, 3, 0, 2, 3})).empty());
}

TEST(PointsDuplicates, CopiesPairedWithFirstOccurrence) {
  const auto d = find_duplicates(make(2, {4, 4, 1, 1, 4, 4, 1, 1, 4, 4, 2, 2}));
  ASSERT_EQ(d.size(), 3u);
  EXPECT_TRUE(d[0] == (DuplicatePair{0, 2}));
  EXPECT_TRUE(d[1] == (DuplicatePair{0, 4}));
  EXPECT_TRUE(d[2] == (DuplicatePair{1, 3}));
}

TEST(PointsDuplicates, SignedZeroAndNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto d = find_duplicates(make(2, {0.0, 1.0, -0.0, 1.0, nan, 0.0, nan, 0.0}));
  ASSERT_EQ(d.size(), 1u);  // NaN never equals anything, -0 == 0
  EXPECT_TRUE(d[0] == (DuplicatePair{0, 1}));
}

TEST(PointsDuplicates, MatchesBruteForceOnRandomRepeats) {
  const std::uint64_t seed = 7;
  std::mt19937_64 rng(seed);
  for (int round = 0; round < 50; ++round) {
    const int dim = 2 + round % 2;
    const int n = 1 + static_cast<int>(rng() % 200);
    // Few distinct values per coordinate: many exact repeats and many equal-x runs.
    std::uniform_int_distribution<int> value(-3, 3);
    std::vector<double> c;
    for (int i = 0; i < n * dim; ++i) c.push_back(0.5 * value(rng));
    const PointSet p = make(dim, c);
    const auto got = find_duplicates(p);
    const auto want = brute_force_duplicates(p);
    ASSERT_EQ(got.size(), want.size()) << "seed " << seed << " round " << round;
    for (std::size_t k = 0; k < got.size(); ++k)
      ASSERT_TRUE(got[k] == want[k]) << "seed " << seed << " round " << round << " pair " << k;

    // merge_duplicates keeps exactly the first occurrences, in input order.
    std::vector<std::size_t> kept;
    const PointSet merged = merge_duplicates(p, &kept);
    ASSERT_EQ(merged.size(), p.size() - want.size());
    ASSERT_EQ(kept.size(), merged.size());
    for (std::size_t i = 0; i < kept.size(); ++i) {
      if (i > 0) {
        EXPECT_LT(kept[i - 1], kept[i]);
      }
      for (int k = 0; k < dim; ++k) EXPECT_EQ(merged[i][k], p[kept[i]][k]);
    }
    EXPECT_TRUE(find_duplicates(merged).empty());
  }
}

TEST(PointsDuplicates, MatchesReferenceOnLargeInputs) {
  // Large enough for the radix sort path (3*10^4) and the parallel one (3*10^5); both signs, -0.0
  // and 0.0, equal x, exact repeats.
  const std::uint64_t seed = 99;
  std::mt19937_64 rng(seed);
  for (const auto& [dim, n] : {std::pair<int, std::size_t>{2, 30000}, {3, 30000}, {2, 300000}, {3, 300000}}) {
    std::vector<double> c;
    std::uniform_int_distribution<int> pick(0, 9);
    std::uniform_real_distribution<double> any(-1e6, 1e6);
    for (std::size_t i = 0; i < n; ++i) {
      const int r = pick(rng);
      if (r < 3 && i > 0) {  // copy an earlier point
        const std::size_t j = static_cast<std::size_t>(rng() % i);
        for (int k = 0; k < dim; ++k) c.push_back(c[j * static_cast<std::size_t>(dim) + k]);
      } else if (r < 5) {
        // Few x values whose bit patterns differ only in the sign and exponent bytes (the radix
        // sort must order those too), a small integer grid for y, z.
        const double xs[6] = {0.0, -0.0, 1.0, 2.0, 4.0, -2.0};
        c.push_back(xs[rng() % 6]);
        for (int k = 1; k < dim; ++k)
          c.push_back(static_cast<double>(static_cast<int>(rng() % 5)) - 2);
      } else {
        for (int k = 0; k < dim; ++k) c.push_back(any(rng));
      }
    }
    const PointSet p = make(dim, c);
    // Reference: the first index of every distinct point, in a std::map (-0.0 == 0.0 there too).
    std::map<std::vector<double>, std::size_t> first;
    std::vector<DuplicatePair> want;
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<double> key(p[i], p[i] + dim);
      auto [it, inserted] = first.emplace(key, i);
      if (!inserted) want.push_back({it->second, i});
    }
    std::sort(want.begin(), want.end(), [](const DuplicatePair& l, const DuplicatePair& r) {
      return l.first != r.first ? l.first < r.first : l.second < r.second;
    });
    const auto got = find_duplicates(p);
    ASSERT_FALSE(want.empty());
    ASSERT_EQ(got.size(), want.size()) << "seed " << seed << " dim " << dim << " n " << n;
    for (std::size_t k = 0; k < got.size(); ++k)
      ASSERT_TRUE(got[k] == want[k]) << "seed " << seed << " dim " << dim << " n " << n << " pair " << k;
  }
}

TEST(PointsDuplicates, MergeWithoutIndexOutput) {
  const PointSet merged = merge_duplicates(make(2, {1, 1, 2, 2, 1, 1}), nullptr);
  EXPECT_EQ(merged.dim, 2);
  EXPECT_EQ(merged.coords, (std::vector<double>{1, 1, 2, 2}));
}

TEST(PointsDuplicates, MergeNothingIsIdentity) {
  std::vector<std::size_t> kept = {99};
  const PointSet p = make(3, {0, 0, 0, 1, 0, 0});
  const PointSet merged = merge_duplicates(p, &kept);
  EXPECT_EQ(merged.coords, p.coords);
  EXPECT_EQ(kept, (std::vector<std::size_t>{0, 1}));
}

// collinear3 (a filtered projection test, then CGAL's exact one) against the definition: the
// cross product of b - a and c - a is zero, computed exactly in 128-bit integers. Integer
// coordinates below 2^40 (the double products round: the filter must see it), scaled by powers of
// two (exact; the filter's range changes); half of the triples collinear by construction, many
// with an axis-parallel line (projections degenerate) and many nearly collinear (one unit off).
TEST(Predicates, Collinear3IsTheExactCrossProductTest) {
  const unsigned seed = 20261203;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::int64_t> coord(-(std::int64_t{1} << 39), std::int64_t{1} << 39), small(-8, 8),
      pick(0, 5);
  int collinear = 0;
  for (int it = 0; it < 60000; ++it) {
    std::int64_t a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = coord(rng);
      b[k] = coord(rng);
    }
    const int kind = static_cast<int>(pick(rng));
    if (kind >= 2) {  // c on the line ab (b - a small for kinds 4, 5: maybe axis-parallel), maybe one off
      if (kind >= 4)
        for (int k = 0; k < 3; ++k) b[k] = a[k] + (kind == 5 && k > 0 ? 0 : small(rng));
      else
        for (int k = 0; k < 3; ++k) b[k] = a[k] + coord(rng) / 64;
      const std::int64_t t = small(rng);
      for (int k = 0; k < 3; ++k) c[k] = a[k] + t * (b[k] - a[k]);
      if (kind == 4) c[it % 3] += 1;
    } else {
      for (int k = 0; k < 3; ++k) c[k] = coord(rng);
    }
    __extension__ typedef __int128 I;  // (GCC and Clang)
    const I u[3] = {I{b[0]} - a[0], I{b[1]} - a[1], I{b[2]} - a[2]},
            v[3] = {I{c[0]} - a[0], I{c[1]} - a[1], I{c[2]} - a[2]};
    const bool want =
        u[1] * v[2] - u[2] * v[1] == 0 && u[2] * v[0] - u[0] * v[2] == 0 && u[0] * v[1] - u[1] * v[0] == 0;
    collinear += want;
    const int e = static_cast<int>(it % 7) * 150 - 450;  // 2^-450 .. 2^450
    double pa[3], pb[3], pc[3];
    for (int k = 0; k < 3; ++k) {
      pa[k] = std::ldexp(static_cast<double>(a[k]), e);
      pb[k] = std::ldexp(static_cast<double>(b[k]), e);
      pc[k] = std::ldexp(static_cast<double>(c[k]), e);
    }
    ASSERT_EQ(collinear3(pa, pb, pc), want) << "seed " << seed << ", triple " << it;
  }
  EXPECT_GT(collinear, 15000);  // both answers are tested often
}

}  // namespace
}  // namespace constrict
