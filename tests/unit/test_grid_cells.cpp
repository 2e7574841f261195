// SPDX-License-Identifier: GPL-3.0-or-later
// for_cells_of_hull (core/detail/grid_cells.hpp): the strip of cells a segment or triangle is
// looked up in must hold the cell of every point of the closed shape, as cell_of() files it.
// Brute force: random shapes (long thin ones included) on grids at several scales and offsets,
// points sampled inside them and on their edges, each point's cell must have been visited.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <algorithm>
#include <array>
#include <cstdio>
#include <random>
#include <vector>

#include <map>
#include <set>
#include <utility>

#include "constrict/gamma_graph.hpp"
#include "constrict/predicates.hpp"
#include "constrict/detail/apex_lens2.hpp"
#include "constrict/detail/segments2.hpp"
#include "core/detail/cell_lists.hpp"
#include "core/detail/cell_table.hpp"
#include "core/detail/dense_segments.hpp"
#include "core/detail/long_segments.hpp"
#include "core/detail/grid_cells.hpp"
#include "core/detail/sparse_segments.hpp"

namespace constrict {
namespace {

struct Case {
  detail::GridFrame frame;
  double hi_x, hi_y;
};

Case make_grid(double lo_x, double lo_y, double span, int cells) {
  Case c;
  const double half = 0.5 * (lo_x + span) - 0.5 * lo_x;
  const double hcs = half / cells;
  c.frame = detail::GridFrame{lo_x, lo_y, std::max({std::fabs(lo_x), std::fabs(lo_y), std::fabs(lo_x + span), std::fabs(lo_y + span)}), hcs,
                              detail::cell_count(half, hcs, 4096), detail::cell_count(half, hcs, 4096)};
  c.hi_x = lo_x + span;
  c.hi_y = lo_y + span;
  return c;
}

// Every sampled point of the shape (convex combinations, edges, vertices) lies in a visited cell;
// returns the number of cells visited.
std::size_t check_shape(const Case& c, const std::vector<std::array<double, 2>>& v, std::mt19937_64& rng, unsigned seed) {
  const int m = static_cast<int>(v.size());
  const double* ptr[detail::kMaxHullVertices] = {};
  for (int k = 0; k < m; ++k) ptr[k] = v[static_cast<std::size_t>(k)].data();
  std::vector<char> seen(static_cast<std::size_t>(c.frame.nx) * static_cast<std::size_t>(c.frame.ny), 0);
  std::size_t visited = 0;
  const auto at = [&](int i, int j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(c.frame.nx) + static_cast<std::size_t>(i); };
  detail::for_cells_of_hull(c.frame, ptr, m, [&](int i, int j) {
    ASSERT_TRUE(i >= 0 && i < c.frame.nx && j >= 0 && j < c.frame.ny) << "seed " << seed;
    visited += !seen[at(i, j)];
    seen[at(i, j)] = 1;
  });
  std::uniform_real_distribution<double> u(0, 1);
  for (int s = 0; s < 400; ++s) {
    // A convex combination: of all vertices, of two consecutive ones (an edge) or one vertex.
    double w[detail::kMaxHullVertices] = {};
    const std::size_t k0 = rng() % static_cast<unsigned>(m);
    if (s % 17 == 0) {
      w[k0] = 1;
    } else if (s % 4 == 0) {
      w[k0] = u(rng);
      w[(k0 + 1) % static_cast<std::size_t>(m)] = u(rng);
    } else {
      for (int k = 0; k < m; ++k) w[k] = u(rng) * u(rng);
    }
    double sum = 0;
    for (int k = 0; k < m; ++k) sum += w[k];
    if (!(sum > 0)) continue;
    double p[2] = {0, 0};
    for (int k = 0; k < m; ++k)
      for (int d = 0; d < 2; ++d) p[d] += w[k] / sum * v[static_cast<std::size_t>(k)][static_cast<std::size_t>(d)];
    bool outside = false;  // rounded outside the closed polygon
    for (int k = 0; m >= 3 && k < m; ++k) {
      const double* e0 = ptr[k];
      const double* e1 = ptr[(k + 1) % m];
      const double* other = ptr[(k + 2) % m];
      outside = outside || orient2(e0, e1, p) * orient2(e0, e1, other) < 0;
    }
    if (outside) continue;
    // (The grids hold points of their box only; shapes may reach beyond it.)
    if (p[0] < c.frame.lo_x || p[0] > c.hi_x || p[1] < c.frame.lo_y || p[1] > c.hi_y) continue;
    if (m == 2 && orient2(ptr[0], ptr[1], p) != 0) continue;  // not exactly on the segment
    const int i = c.frame.cx(p[0]), j = c.frame.cy(p[1]);
    EXPECT_TRUE(seen[at(i, j)]) << "seed " << seed << ": point (" << p[0] << ", " << p[1] << ") in cell (" << i << ", " << j
                                << ") not visited";
  }
  return visited;
}

TEST(GridCells, HullStripHoldsEveryPointsCell) {
  const unsigned seed = 20261202;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const std::vector<std::array<double, 3>> grids = {{0, 0, 1}, {-3.5, 2.25, 7}, {1e6, -1e6, 1e-3}, {-1e-9, 1e-9, 3e-10}};
  std::size_t strip = 0;
  for (const auto& gspec : grids)
    for (const int cells : {1, 7, 64, 1000}) {
      const Case c = make_grid(gspec[0], gspec[1], gspec[2], cells);
      const auto in_box = [&] {
        return std::array<double, 2>{c.frame.lo_x + u(rng) * (c.hi_x - c.frame.lo_x), c.frame.lo_y + u(rng) * (c.hi_y - c.frame.lo_y)};
      };
      for (int t = 0; t < 60; ++t) {
        std::vector<std::array<double, 2>> v = {in_box(), in_box(), in_box()};
        if (t % 3 == 1) {  // long and thin: the third vertex next to the first
          v[2] = {v[0][0] + 1e-3 * (v[1][0] - v[0][0]) + 1e-4 * (c.hi_x - c.frame.lo_x), v[0][1] + 1e-3 * (v[1][1] - v[0][1])};
          v[2][0] = std::min(v[2][0], c.hi_x);
        }
        if (t % 5 == 2) v[1][1] = v[0][1];  // a horizontal edge
        if (t % 7 == 3) v[1][0] = v[0][0];  // a vertical edge
        strip += check_shape(c, v, rng, seed);
        v.pop_back();
        check_shape(c, v, rng, seed);
        // A convex polygon of 4 .. kMaxHullVertices vertices: a regular one, squashed and turned.
        const int m = 4 + t % (detail::kMaxHullVertices - 3);
        const auto centre = in_box();
        const double r = u(rng) * (c.hi_x - c.frame.lo_x), squash = t % 2 ? 1e-3 : u(rng), turn = 6.283185307179586 * u(rng);
        v.clear();
        for (int k = 0; k < m; ++k) {
          const double phi = 6.283185307179586 * k / m, x = r * std::cos(phi), y = squash * r * std::sin(phi);
          v.push_back({centre[0] + x * std::cos(turn) - y * std::sin(turn), centre[1] + x * std::sin(turn) + y * std::cos(turn)});
        }
        check_shape(c, v, rng, seed);
      }
    }
  EXPECT_GT(strip, 0u);
}

// A long thin triangle across a fine grid reads a strip, not its bounding box.
TEST(GridCells, ThinTriangleReadsAStrip) {
  const Case c = make_grid(0, 0, 1, 1000);
  const double a[2] = {0.001, 0.002}, b[2] = {0.998, 0.997}, d[2] = {0.0015, 0.003};
  const double* v[3] = {a, b, d};
  std::size_t cells = 0;
  detail::for_cells_of_hull(c.frame, v, 3, [&](int, int) { ++cells; });
  EXPECT_LT(cells, 10000u);  // the bounding box has about 10^6
  EXPECT_GT(cells, 990u);    // at least the diagonal
}

// SparseSegments against brute force: random short and long segments (many meeting at shared
// end points, some collinear overlaps) added and removed at random; every query must report every
// registered segment that meets it (closed segments, exact), and nothing removed.
// The same random check for both segment grids (sparse: fine cells; dense: area-sized ones).
template <class Grid, class Reset> void find_every_meeting_segment(unsigned seed, Reset&& reset) {
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (const double span : {1.0, 3e-7, 4e5}) {
    const double lo = -0.3 * span;
    std::vector<std::array<double, 2>> pts;
    for (int k = 0; k < 400; ++k) pts.push_back({lo + span * u(rng), lo + span * u(rng)});
    pts.push_back({lo, lo});
    pts.push_back({lo + span, lo + span});
    Grid grid;
    reset(grid, lo, span);
    std::vector<std::array<int, 2>> segs;
    std::vector<char> live;
    const auto random_segment = [&]() -> std::array<int, 2> {
      const int a = static_cast<int>(rng() % pts.size());
      if (rng() % 4 == 0) return {a, static_cast<int>(rng() % pts.size())};  // long
      int best = -1;  // short: a near point
      for (int t = 0; t < 8; ++t) {
        const int b = static_cast<int>(rng() % pts.size());
        if (b != a && (best < 0 || std::hypot(pts[b][0] - pts[a][0], pts[b][1] - pts[a][1]) <
                                       std::hypot(pts[best][0] - pts[a][0], pts[best][1] - pts[a][1])))
          best = b;
      }
      return {a, best};
    };
    // A first batch at once (add_all: the counting sort), then single changes.
    for (int k = 0; k < 300; ++k) {
      const auto [a, b] = random_segment();
      if (a == b) continue;
      segs.push_back({a, b});
      live.push_back(1);
    }
    grid.add_all(segs.size(), [&](std::size_t k, const double*& a, const double*& b, int& id) {
      a = pts[segs[k][0]].data();
      b = pts[segs[k][1]].data();
      id = static_cast<int>(k);
    });
    for (int step = 0; step < 3000; ++step) {
      const auto [a, b] = random_segment();
      if (a == b) continue;
      if (step % 3 != 2 || segs.empty()) {
        segs.push_back({a, b});
        live.push_back(1);
        grid.add(pts[a].data(), pts[b].data(), static_cast<int>(segs.size() - 1));
      } else {
        const std::size_t k = rng() % segs.size();
        if (!live[k]) continue;
        live[k] = 0;
        grid.remove(pts[segs[k][0]].data(), pts[segs[k][1]].data(), static_cast<int>(k));
      }
      // A query segment: every live segment meeting it must be reported, no dead one.
      const auto [qa, qb] = random_segment();
      if (qa == qb) continue;
      std::vector<char> seen(segs.size(), 0);
      grid.any(pts[qa].data(), pts[qb].data(), [&](int id) {
        EXPECT_TRUE(live[static_cast<std::size_t>(id)]) << "seed " << seed << ": removed segment " << id << " reported";
        seen[static_cast<std::size_t>(id)] = 1;
        return false;
      });
      for (std::size_t k = 0; k < segs.size(); ++k)
        if (live[k] && !seen[k] &&
            detail::closed_segments_meet(pts[qa].data(), pts[qb].data(), pts[segs[k][0]].data(), pts[segs[k][1]].data()))
          ADD_FAILURE() << "seed " << seed << " span " << span << " step " << step << ": segment " << k << " meets the query but was not reported";
    }
  }
}

TEST(GridCells, SparseSegmentsFindEveryMeetingSegment) {
  find_every_meeting_segment<detail::SparseSegments<int>>(7, [](auto& grid, double lo, double span) {
    const double half_cell = std::max(span / 500, detail::SparseSegments<int>::min_half_cell(span / 2, span / 2, 2 * std::fabs(lo) + span));
    grid.reset(lo, lo, lo + span, lo + span, half_cell);
  });
}

TEST(GridCells, DenseSegmentsFindEveryMeetingSegment) {
  find_every_meeting_segment<detail::DenseSegments<int>>(8, [](auto& grid, double lo, double span) {
    const double half_cell = span / 40;  // about the spacing of the 400 points
    const int cells = detail::cell_count(span / 2, half_cell, 1 << 20);
    grid.reset(detail::GridFrame{lo, lo, 2 * std::fabs(lo) + span, half_cell, cells, cells});
  });
}

// The long segments' levels (long_segments.hpp; longer than kLongCells cells of either grid): on
// cells of 1/4000 of the box random long segments of every length (many sharing end points, some
// collinear overlaps), queries short and long, segments removed at random. Every live segment that
// meets a query must be reported, none removed, and none twice: each is registered in several
// cells of its level and reported only from one.
template <class Grid, class Reset>
void report_long_segments_once(unsigned seed0, Reset&& reset) {
  const double half_cell = 1.0 / 8000;
  for (const unsigned seed : {seed0, seed0 + 1}) {
    std::printf("seed %u\n", seed);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<std::array<double, 2>> pts;
    for (int k = 0; k < 300; ++k) pts.push_back({u(rng), u(rng)});
    for (int k = 0; k < 40; ++k) pts.push_back({0.25 + 0.01 * k, 0.5});  // collinear runs
    Grid grid;
    reset(grid, half_cell);
    std::vector<std::array<int, 2>> segs;
    std::vector<char> live;
    std::size_t reported = 0, meeting = 0;
    for (int step = 0; step < 4000; ++step) {
      const int a = static_cast<int>(rng() % pts.size()), b = static_cast<int>(rng() % pts.size());
      const double len = std::max(std::fabs(pts[a][0] - pts[b][0]), std::fabs(pts[a][1] - pts[b][1]));
      if (a == b || len <= 32 * 2 * half_cell) continue;  // long ones only
      if (step % 4 != 3 || segs.empty()) {
        segs.push_back({a, b});
        live.push_back(1);
        grid.add(pts[a].data(), pts[b].data(), static_cast<int>(segs.size() - 1));
      } else {
        const std::size_t k = rng() % segs.size();
        if (live[k]) grid.remove(pts[segs[k][0]].data(), pts[segs[k][1]].data(), static_cast<int>(k));
        live[k] = 0;
      }
      // The query: from a random point to a near one or to any other.
      const int qa = static_cast<int>(rng() % pts.size());
      const double q1[2] = {pts[qa][0] + (rng() % 2 ? 1e-3 : 0.3) * (u(rng) - 0.5), pts[qa][1] + 1e-3 * (u(rng) - 0.5)};
      const double* q0 = pts[qa].data();
      std::vector<int> seen(segs.size(), 0);
      grid.any(q0, q1, [&](int id) {
        EXPECT_TRUE(live[static_cast<std::size_t>(id)]) << "seed " << seed << ": removed segment " << id << " reported";
        ++seen[static_cast<std::size_t>(id)];
        ++reported;
        return false;
      });
      for (std::size_t k = 0; k < segs.size(); ++k) {
        EXPECT_LE(seen[k], 1) << "seed " << seed << " step " << step << ": segment " << k << " reported twice";
        const bool meets = detail::closed_segments_meet(q0, q1, pts[segs[k][0]].data(), pts[segs[k][1]].data());
        meeting += live[k] && meets;
        if (live[k] && meets && !seen[k])
          ADD_FAILURE() << "seed " << seed << " step " << step << ": segment " << k
                        << " meets the query but was not reported";
      }
    }
    std::printf("  %zu segments, %zu reports, %zu of them meeting\n", segs.size(), reported, meeting);
    EXPECT_GT(meeting, 100u);
  }
}

TEST(GridCells, SparseSegmentsReportLongSegmentsOnce) {
  report_long_segments_once<detail::SparseSegments<int>>(11, [](auto& grid, double h) { grid.reset(0, 0, 1, 1, h); });
}

TEST(GridCells, DenseSegmentsReportLongSegmentsOnce) {
  report_long_segments_once<detail::DenseSegments<int>>(21, [](auto& grid, double h) {
    grid.reset(detail::GridFrame{0, 0, 1, h, detail::cell_count(0.5, h, 1 << 20), detail::cell_count(0.5, h, 1 << 20)});
  });
}

// LongSegments on a box of subnormal size with a first cell edge of 0 (min_half_cell gives 0
// there): the levels end at once (one cell takes everything) instead of growing a cell of edge 0
// forever, and a query still finds the segments it meets.
TEST(GridCells, LongSegmentsWithACellEdgeOfZero) {
  detail::LongSegments<int> l;
  l.reset(0, 0, 5e-321, 5e-321, 1e-320, 0.0);
  const double a[2] = {0, 0}, b[2] = {1e-320, 1e-320}, c[2] = {0, 1e-320}, d[2] = {1e-320, 0};
  const double e[2] = {0, 2e-321}, f[2] = {2e-321, 0};
  l.add(a, b, 1);
  l.add(e, f, 2);  // parallel to the query, its box meets the query's
  std::vector<int> seen;
  l.any(c, d, [&](int id) {
    seen.push_back(id);
    return false;
  });
  EXPECT_EQ(seen, (std::vector<int>{1}));
  l.remove(a, b, 1);
  EXPECT_EQ(l.size(), 1u);
}

// A long query on a grid of cells near the 2^-28 floor: its strip would be 2^28 rows; the query
// reads the stored cells instead and still finds the short segment it crosses and the long one.
TEST(GridCells, SparseSegmentsLongQueryOnFineCells) {
  detail::SparseSegments<int> grid;
  const double half_cell = detail::SparseSegments<int>::min_half_cell(0.5, 0.5, 1);
  grid.reset(0, 0, 1, 1, half_cell);
  const double a[2] = {0.5, 0.5}, b[2] = {0.5 + 4 * half_cell, 0.5}, c[2] = {0, 0.9}, d[2] = {1, 0.9};
  grid.add(a, b, 1);  // short, across the query
  grid.add(c, d, 2);  // long, across the query
  const double q0[2] = {0.5 + 2 * half_cell, 0}, q1[2] = {0.5 + 2 * half_cell, 1};
  std::vector<int> seen;
  grid.any(q0, q1, [&](int id) {
    seen.push_back(id);
    return false;
  });
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  EXPECT_EQ(seen, (std::vector<int>{1, 2}));
}

// CellLists against a multiset per cell: a built part (counting sort) and random additions and
// removals on top, several registrations of one id in one cell included; every query must report
// exactly the registered ids, and a removal must take out exactly one.
TEST(GridCells, CellListsMatchAMultiset) {
  const unsigned seed = 5;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  const std::size_t cells = 97;
  std::vector<std::pair<std::size_t, int>> first;
  for (int k = 0; k < 2000; ++k) first.push_back({rng() % cells, static_cast<int>(rng() % 300)});
  detail::CellLists<int> lists;
  lists.build(cells / 2, [&](auto&& emit) {  // fewer cells asked for than emitted: it grows
    for (const auto& [c, id] : first) emit(c, id);
  });
  ASSERT_EQ(lists.size(), 1 + std::max_element(first.begin(), first.end())->first);
  lists.grow(cells);
  std::vector<std::multiset<int>> ref(cells);
  for (const auto& [c, id] : first) ref[c].insert(id);
  const auto check = [&](int step) {
    for (std::size_t c = 0; c < cells; ++c) {
      std::multiset<int> got;
      lists.any(c, [&](int id) {
        got.insert(id);
        return false;
      });
      ASSERT_EQ(got, ref[c]) << "seed " << seed << " step " << step << " cell " << c;
    }
  };
  check(-1);
  for (int step = 0; step < 20000; ++step) {
    const std::size_t c = rng() % cells;
    const int id = static_cast<int>(rng() % 300);
    if (rng() % 2) {
      lists.add(c, id);
      ref[c].insert(id);
    } else {
      lists.remove(c, id);
      if (const auto it = ref[c].find(id); it != ref[c].end()) ref[c].erase(it);
    }
    if (step % 997 == 0) check(step);
  }
  check(20000);
  // any() stops at the first true.
  int calls = 0;
  for (std::size_t c = 0; c < cells; ++c)
    if (!ref[c].empty()) {
      EXPECT_TRUE(lists.any(c, [&](int) { return ++calls > 0; }));
      EXPECT_EQ(calls, 1);
      break;
    }
}

// CellLists::build_in_blocks (two ranges of items side by side, from 2^16 items on) gives the
// lists of build() in the same order, cell by cell, on any thread count; 0 to 3 cells per item,
// runs of one cell and scattered ones.
TEST(GridCells, CellListsInBlocksAreTheSequentialLists) {
  const unsigned seed = 17;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  const std::size_t cells = 5003;
  for (const std::size_t count : {std::size_t{1000}, std::size_t{65536}, std::size_t{200001}}) {
    std::vector<std::vector<std::size_t>> item_cells(count);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t m = rng() % 4, c0 = k % 7 == 0 ? rng() % cells : (k / 40) % cells;
      for (std::size_t j = 0; j < m; ++j) item_cells[k].push_back((c0 + j * (rng() % 3)) % cells);
    }
    const auto visit = [&](std::size_t k0, std::size_t k1, auto&& emit) {
      for (std::size_t k = k0; k < k1; ++k)
        for (const std::size_t c : item_cells[k]) emit(c, static_cast<int>(k));
    };
    const auto lists_of = [&](const detail::CellLists<int>& l) {
      std::vector<std::vector<int>> out(cells);
      for (std::size_t c = 0; c < cells; ++c)
        l.any(c, [&](int id) {
          out[c].push_back(id);
          return false;
        });
      return out;
    };
    detail::CellLists<int> seq, blocks, one;
    seq.build(cells, [&](auto&& emit) { visit(0, count, emit); });
    blocks.build_in_blocks(cells, count, visit);
    {
      tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
      one.build_in_blocks(cells, count, visit);
    }
    const auto want = lists_of(seq);
    EXPECT_EQ(blocks.size(), cells);
    EXPECT_TRUE(lists_of(blocks) == want) << "seed " << seed << ", " << count << " items";
    EXPECT_TRUE(lists_of(one) == want) << "seed " << seed << ", " << count << " items, one thread";
  }
}

// CellTable against std::map: cells along curves and scattered ones (growth, collisions), far
// apart and near the ends of the int range; slots are dense and in first-insertion order.
TEST(GridCells, CellTableMatchesAMap) {
  const unsigned seed = 11;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  detail::CellTable table;
  table.clear();
  std::map<std::pair<int, int>, int> ref;
  for (int step = 0; step < 200000; ++step) {
    int i, j;
    switch (rng() % 3) {
      case 0: {  // along a curve: neighbours of the last cells
        const double t = static_cast<double>(step) * 1e-3;
        i = static_cast<int>(1000 * std::cos(t)) + static_cast<int>(rng() % 3);
        j = static_cast<int>(1000 * std::sin(t)) + static_cast<int>(rng() % 3);
        break;
      }
      case 1:  // one column: the same i, many j (a poor hash clusters these)
        i = 7;
        j = static_cast<int>(rng() % 50000);
        break;
      default:  // anywhere, up to the ends of the range
        i = static_cast<int>(rng() % 2147483647u);
        j = static_cast<int>(rng() % 2147483647u);
    }
    if (rng() % 2) {
      const auto it = ref.find({i, j});
      ASSERT_EQ(table.find(i, j), it == ref.end() ? -1 : it->second) << "seed " << seed << " step " << step;
    } else {
      const auto [it, added] = ref.emplace(std::make_pair(i, j), static_cast<int>(ref.size()));
      ASSERT_EQ(table.insert(i, j), it->second) << "seed " << seed << " step " << step << (added ? " (new)" : "");
      ASSERT_EQ(table.size(), ref.size());
    }
  }
  for (const auto& [cell, slot] : ref) ASSERT_EQ(table.find(cell.first, cell.second), slot);
}

// Is p in the closed convex polygon q[0 .. m) (either orientation), up to tol of cross product?
bool in_convex(const double (*q)[2], int m, const double* p, double tol) {
  int pos = 0, neg = 0;
  for (int e = 0; e < m; ++e) {
    const double* s0 = q[e];
    const double* s1 = q[(e + 1) % m];
    const double cross = (s1[0] - s0[0]) * (p[1] - s0[1]) - (s1[1] - s0[1]) * (p[0] - s0[0]);
    pos += cross > tol;
    neg += cross < -tol;
  }
  return pos == 0 || neg == 0;
}

// ApexLens2 against the definition: for random segments (lengths over many magnitudes, at
// offsets far from the origin) and points, every point whose apex value lies below t must pass
// may_hold and lie in the cover polygon of its side (orientation tests against its edges, up to
// the one-cell widening of the grid queries: far below here), also when the cover is cut at a
// lower height h and the point lies below it; points just inside the arc are the hard cases, so a
// third of them are placed near it. It must also be tight enough to matter: most points well
// outside the arc are rejected, and the cover holds few points that may_hold rejects.
TEST(GridCells, ApexLensHoldsEveryPointBelowTheThreshold) {
  const unsigned seed = 12;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::size_t below = 0, rejected_far = 0, far = 0, in_cover = 0, in_cover_held = 0;
  for (int round = 0; round < 4000; ++round) {
    const double scale = std::ldexp(1.0, static_cast<int>(rng() % 40) - 20), offset = (rng() % 2) ? 1e3 * scale : 0;
    const double a[2] = {offset + scale * u(rng), offset + scale * u(rng)};
    const double b[2] = {offset + scale * u(rng), offset + scale * u(rng)};
    if (a[0] == b[0] && a[1] == b[1]) continue;
    const double t = -u(rng) * (rng() % 8 == 0 ? 1e-6 : 1.0);  // some thresholds near 0
    const detail::ApexLens2 lens(a, b, t);
    const double len = lens.length(), mx = 0.5 * (a[0] + b[0]), my = 0.5 * (a[1] + b[1]);
    const double ux = (b[0] - a[0]) / len, uy = (b[1] - a[1]) / len;
    for (int k = 0; k < 50; ++k) {
      double p[2];
      if (k % 3 == 0) {  // near the arc: on the circle of the threshold angle, jittered
        const double alpha = std::asin(std::min(1.0, 1.0 + t)), r = 0.5 * len / std::sin(alpha), c = 0.5 * len / std::tan(alpha);
        const double side = (rng() % 2) ? 1 : -1, phi = (u(rng) - 0.5) * 2 * alpha;
        const double x = r * std::sin(phi), w = r * std::cos(phi) - c, jitter = 1 + (u(rng) - 0.5) * 1e-7;
        p[0] = mx + x * ux - side * w * jitter * uy;
        p[1] = my + x * uy + side * w * jitter * ux;
      } else {
        p[0] = mx + (u(rng) - 0.5) * 1.5 * len;
        p[1] = my + (u(rng) - 0.5) * 1.5 * len;
      }
      const int o = orient2(a, b, p);
      if (o == 0) continue;
      const double side = o;
      const double g = apex_gamma2(a, b, p);
      if (g < t) {
        ++below;
        ASSERT_TRUE(lens.may_hold(p, side, lens.height())) << "seed " << seed << " round " << round << " point " << k;
        double q[detail::ApexLens2::kMaxCover][2];
        int m = 0;
        lens.cover(side, lens.height(), q, m);
        ASSERT_GE(m, 3);
        ASSERT_TRUE(in_convex(q, m, p, 1e-9 * len * len)) << "seed " << seed << " round " << round << " point " << k;
        // Cut lower, where the point still lies below the cut.
        const double w = std::fabs((p[0] - a[0]) * -uy + (p[1] - a[1]) * ux);
        const double h = w + u(rng) * (lens.height() - w);
        lens.cover(side, h, q, m);
        ASSERT_TRUE(lens.may_hold(p, side, h));
        ASSERT_TRUE(in_convex(q, m, p, 1e-9 * len * len)) << "seed " << seed << " round " << round << " point " << k << " cut";
      } else if (g > t + 0.05 && k % 3 != 0) {
        ++far;
        rejected_far += !lens.may_hold(p, side, lens.height());
      }
      // Tightness: of the points in the cover, few are rejected by may_hold.
      double q[detail::ApexLens2::kMaxCover][2];
      int m = 0;
      lens.cover(side, lens.height(), q, m);
      if (in_convex(q, m, p, 0)) {
        ++in_cover;
        in_cover_held += lens.may_hold(p, side, lens.height());
      }
    }
  }
  std::printf("[ GridCells ] %zu points below the threshold held; %zu of %zu well above it rejected; %zu of %zu in the cover held\n",
              below, rejected_far, far, in_cover_held, in_cover);
  EXPECT_GT(below, 10000u);
  EXPECT_GT(rejected_far, far * 9 / 10);
  EXPECT_GT(in_cover_held, in_cover * 9 / 10);
}

}  // namespace
}  // namespace constrict
