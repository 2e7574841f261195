// SPDX-License-Identifier: GPL-3.0-or-later
// CGAL Delaunay triangulations exported as plain index arrays. This is the only translation unit
// that includes CGAL's triangulation packages (GPL; swappable behind include/constrict/delaunay.hpp).
//
// The insertion is exactly CGAL's range insertion with info (Delaunay_triangulation_2/3::
// insert_with_info: spatial_sort with the fixed-seed BRIO + Hilbert median policy, then hinted
// insertion in that order), so the triangulation and its face order are CGAL's. We sort
// (point, index) pairs instead of CGAL's indices into a point array: spatial_sort only compares
// coordinates, so the permutation is the same, and the sort touches memory sequentially; the
// sort's independent subranges run in parallel (below).
// Vertex info = the insertion rank ("local" id); simplex info = the finite simplex index, -1 for
// infinite ones, so a neighbour is one load (no is_infinite(), no hash map).
#include "constrict/delaunay.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/property_map.h>
#include <CGAL/Hilbert_sort_median_2.h>
#include <CGAL/Hilbert_sort_median_3.h>
#include <CGAL/algorithm.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/spatial_sort.h>
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <unordered_map>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "cgal/detail/delaunay_local.hpp"
#include "core/detail/big_vector.hpp"
#include "core/detail/check_points.hpp"

namespace constrict {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

using Vb2 = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fb2 = CGAL::Triangulation_face_base_with_info_2<int, K>;
using Tds2 = CGAL::Triangulation_data_structure_2<Vb2, Fb2>;
using DT2 = CGAL::Delaunay_triangulation_2<K, Tds2>;

// ---- CGAL's cells given back while they are exported (3D) --------------------------------------
// At 10^6 points CGAL's cells are about 600 bytes per point (72-byte cells, 6-8 per point) and the
// exported tetrahedra with their neighbours 32 bytes per cell: written beside the cells, the two
// made the peak of a whole 3D run. Instead, each finite cell's export record is first written
// into the cell itself (over its four vertex handles, which nothing reads afterwards), then the
// records are copied out in container order and copied cells' pages are given back to the
// system (export_released3; from kReleasedExportFromTets tetrahedra on). The triangulation is
// then destroyed without reading its cells: while t_cells_released is set on this thread, every
// cell reports itself free to CGAL's Compact_container, whose clear() then only deallocates the
// blocks. (The thread-local flag is read only while some thread destroys such a triangulation:
// g_releasing counts them. CGAL's insertion reads the accessor for every cell it creates or
// frees, and in a shared library, the Python module, a thread-local read is a function call.)
thread_local bool t_cells_released = false;
std::atomic<int> g_releasing{0};

template <class Cb>
class ReleasableCell : public Cb {
 public:
  template <class Tds2>
  struct Rebind_TDS {
    using Other = ReleasableCell<typename Cb::template Rebind_TDS<Tds2>::Other>;
  };
  using Cb::Cb;
  // Compact_container's type bits (the low two bits): 2 = FREE.
  void* for_compact_container() const {
    if (g_releasing.load(std::memory_order_relaxed) != 0 && t_cells_released)
      return reinterpret_cast<void*>(std::uintptr_t{2});
    return Cb::for_compact_container();
  }
  void for_compact_container(void* p) { Cb::for_compact_container(p); }
};

using Vb3 = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using Cb3 = ReleasableCell<CGAL::Triangulation_cell_base_with_info_3<int, K, CGAL::Delaunay_triangulation_cell_base_3<K>>>;
using Tds3 = CGAL::Triangulation_data_structure_3<Vb3, Cb3>;
using DT3 = CGAL::Delaunay_triangulation_3<K, Tds3>;

constexpr std::size_t kGrain = 8192;
constexpr std::size_t kAhead = 16;  // prefetch distance (simplices) of the export loops

// parallel_for over [0, n) in chunks of kGrain; small ranges run inline (task dispatch and thread
// wake-up cost more than they save below a few chunks).
template <class F>
void par_for(std::size_t n, const F& f) {
  if (n <= 4 * kGrain) {
    f(tbb::blocked_range<std::size_t>(0, n, kGrain));
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), f);
}

// Exports simplices (K = 3 triangles, 4 tetrahedra) given as handles in output order, with their
// neighbour indices (the handles' info), and optionally the local mesh (vertex ranks, opposite
// vertex, mirror index, ownership of each face). Shared by 2D and 3D.
template <int K, class Handle, class LocalMesh>
void export_simplices(const std::vector<Handle>& hs, std::size_t base, const detail::BigArray<int>* id,
                      std::vector<std::array<int, K>>& simplices, std::vector<std::array<int, K>>& neighbors,
                      LocalMesh& lm, bool local) {
  par_for(hs.size(), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      const std::size_t t = base + c;  // the simplex's index (hs holds simplices base, base + 1, ...)
      // The neighbours are scattered in memory: prefetch them, then their far vertex.
      if (c + 2 * kAhead < r.end())
        for (int k = 0; k < K; ++k) __builtin_prefetch(&*hs[c + 2 * kAhead]->neighbor(k));
      if (c + kAhead < r.end()) {
        const Handle fa = hs[c + kAhead];
        for (int k = 0; k < K; ++k) {
          const Handle g = fa->neighbor(k);
          __builtin_prefetch(&*g->vertex(g->index(fa)));
        }
      }
      const Handle f = hs[c];
      std::array<int, K> sim{}, nb{}, loc{}, opp{};
      unsigned mir = 0;
      for (int i = 0; i < K; ++i) {
        const std::size_t k = static_cast<std::size_t>(i);
        loc[k] = f->vertex(i)->info();
        sim[k] = id ? (*id)[static_cast<std::size_t>(loc[k])] : loc[k];
        const Handle g = f->neighbor(i);
        nb[k] = g->info();
        opp[k] = -1;
        if (nb[k] >= 0) {
          const int j = g->index(f);
          opp[k] = g->vertex(j)->info();
          mir |= static_cast<unsigned>(j) << (2 * i);
        }
      }
      simplices[t] = sim;
      neighbors[t] = nb;
      if (local) {
        lm.simplices[t] = loc;
        lm.opposite[t] = opp;
        lm.mirror[t] = static_cast<unsigned char>(mir);
        unsigned own = 0;
        for (int i = 0; i < K; ++i)
          if (nb[static_cast<std::size_t>(i)] == -1 || static_cast<std::size_t>(nb[static_cast<std::size_t>(i)]) > t)
            own |= 1u << i;
        lm.owned[t] = static_cast<unsigned char>(own);
      }
    }
  });
}


std::string duplicate_message(std::size_t n, std::size_t nv) {
  return "Delaunay: " + std::to_string(n - nv) + " input points coincide with others (remove duplicates first)";
}

// ---- CGAL's spatial_sort (Hilbert median policy, multiscale BRIO), run in parallel ---------
// Same operations as CGAL::spatial_sort<Sequential_tag> on each subrange (the same fixed-seed
// random_shuffle, the same std::nth_element splits, the same recursion), only the four (2D) /
// eight (3D) subranges of a split are sorted concurrently: they are disjoint, so the
// permutation is exactly the sequential one, whatever the number of threads.
constexpr std::ptrdiff_t kParallelSort = std::ptrdiff_t{1} << 15;

// The handles of the finite simplices are gathered and exported in chunks of kExportChunk (a list
// of all of them was 8 bytes per simplex at the peak, beside CGAL's triangulation).
constexpr std::size_t kExportChunk = std::size_t{1} << 16;

// Numbers the finite simplices in CGAL's container order (info() = index, -1 for the infinite
// ones, which are also collected in *infinite when given), then exports them (2D and 3D).
// id == nullptr: the simplices are written in local ids (build_delaunay2_ranked).
template <int K, class Handle, class It, class VertexHandle, class LocalMesh>
void export_finite(It first, It last, VertexHandle inf, const detail::BigArray<int>* id,
                   std::vector<std::array<int, K>>& simplices, std::vector<std::array<int, K>>& neighbors,
                   LocalMesh& lm, bool local, std::vector<Handle>* infinite) {
  std::size_t T = 0;
  for (It s = first; s != last; ++s) {
    bool is_infinite = false;
    for (int k = 0; k < K; ++k) is_infinite = is_infinite || s->vertex(k) == inf;
    if (is_infinite) {
      s->info() = -1;
      if (infinite) infinite->push_back(s);
    } else {
      s->info() = static_cast<int>(T++);
    }
  }
  // (A caller may have sized the arrays beforehand, off the critical path; shrinking keeps them.
  // Otherwise their zero-filling, page faults included, runs on both cores.)
  tbb::parallel_invoke([&] { detail::resize_big(simplices, T); }, [&] { detail::resize_big(neighbors, T); });
  if (local) {
    lm.simplices.allocate(T);
    lm.opposite.allocate(T);
    lm.mirror.allocate(T);
    lm.owned.allocate(T);
  }
  std::vector<Handle> hs;
  hs.reserve(std::min(T, kExportChunk));
  std::size_t base = 0;
  for (It s = first; s != last; ++s) {
    if (s->info() < 0) continue;
    hs.push_back(s);
    if (hs.size() == kExportChunk) {
      export_simplices<K>(hs, base, id, simplices, neighbors, lm, local);
      base += hs.size();
      hs.clear();
    }
  }
  export_simplices<K>(hs, base, id, simplices, neighbors, lm, local);
}

// ---- The 3D export that gives CGAL's cells back (see ReleasableCell) ----------------------------
// The record of a finite cell: its tetrahedron (input ids) and its neighbours (finite indices, -1
// on the hull), written over the cell's vertex handles: bytes [32, 64) of CGAL 5's
// Triangulation_ds_cell_base_3 (Cell_handle N[4], then Vertex_handle V[4]). The layout is checked
// on a cell before it is used (record_layout_holds); if it ever differs, export_finite runs.
struct CellRecord {
  std::array<int, 4> tet;
  std::array<int, 4> nb;
};
constexpr std::size_t kRecordOffset = 4 * sizeof(void*);
static_assert(sizeof(DT3::Vertex_handle) == sizeof(void*) && sizeof(DT3::Cell_handle) == sizeof(void*));
static_assert(sizeof(CellRecord) == 4 * sizeof(void*));

unsigned char* cell_bytes(DT3::Cell_handle c) { return reinterpret_cast<unsigned char*>(&*c); }

bool record_layout_holds(DT3::Cell_handle c) {
  const unsigned char* raw = cell_bytes(c);
  for (int k = 0; k < 4; ++k) {
    const DT3::Cell_handle n = c->neighbor(k);
    const DT3::Vertex_handle v = c->vertex(k);
    const std::size_t at = static_cast<std::size_t>(k) * sizeof(void*);
    if (std::memcmp(raw + at, &n, sizeof n) != 0 || std::memcmp(raw + kRecordOffset + at, &v, sizeof v) != 0)
      return false;
  }
  const auto* info = reinterpret_cast<const unsigned char*>(&c->info());
  return info >= raw + kRecordOffset + sizeof(CellRecord) && info + sizeof(int) <= raw + sizeof(*c);
}

// Gives the whole pages within [b, e) back to the system (they read as zeros afterwards).
void give_back(const unsigned char* b, const unsigned char* e) {
#if defined(__linux__)
  static const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const std::uintptr_t lo = (reinterpret_cast<std::uintptr_t>(b) + page - 1) & ~(page - 1);
  const std::uintptr_t hi = reinterpret_cast<std::uintptr_t>(e) & ~(page - 1);
  if (hi > lo) (void)madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_DONTNEED);
#else
  (void)b;
  (void)e;
#endif
}

constexpr std::size_t kCell = sizeof(DT3::Cell);

// CGAL's type bits of the container element at p: 0 a cell in use, 2 a free slot (1 and 3: the
// boundary elements of a block).
std::uintptr_t type_bits(const unsigned char* p) {
  return reinterpret_cast<std::uintptr_t>(reinterpret_cast<const DT3::Cell*>(p)->for_compact_container()) & 3;
}
bool is_used(const unsigned char* p) { return type_bits(p) == 0; }

// Whether the elements of CGAL's container in [from, to) are all free slots of one block: then
// the cells before and after them lie in the same block. A block ends with a boundary element,
// so a walk that leaves the block meets it first.
bool free_slots_between(const unsigned char* from, const unsigned char* to) {
  if (to <= from || static_cast<std::size_t>(to - from) % kCell != 0) return false;
  for (const unsigned char* p = from; p != to; p += kCell)
    if (type_bits(p) != 2) return false;
  return true;
}

// A piece of CGAL's cell container: n elements from `first` (cells in use and free slots, all in
// one block), whose finite cells are numbered from `base` on.
struct Piece {
  unsigned char* first;
  std::size_t n;
  std::size_t base;
  std::size_t finite;
  bool joined;  // the next piece continues this one's run of elements in the same block
};
constexpr std::size_t kPieceElements = 8192;

// export_finite for the 3D triangulation without the local mesh, in three passes:
//  (1) number the finite cells in container order, and cut the container into pieces;
//  (2) on both cores, write each finite cell's record into it (reading its own vertex handles and
//      its neighbours' numbers);
//  (3) in container order, a group of pieces at a time: copy the records out (on both cores; the
//      number of a cell is its output position) and give the group's pages back, as long as no
//      more bytes were given back than the output holds.
// The peak is then CGAL's triangulation alone instead of it plus 32 bytes per cell. Same arrays,
// same order as export_finite.
void export_released3(DT3& dt, const detail::BigArray<int>& id, Delaunay3& out) {
  const DT3::Vertex_handle inf = dt.infinite_vertex();
  std::vector<Piece> pieces;
  std::size_t T = 0;
  unsigned char* end = nullptr;  // end of the last element met
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
    unsigned char* a = cell_bytes(c);
    const bool same_run = end != nullptr && (a == end || free_slots_between(end, a));
    if (same_run && static_cast<std::size_t>(a - pieces.back().first) / kCell < kPieceElements) {
      pieces.back().n = static_cast<std::size_t>(a - pieces.back().first) / kCell + 1;
    } else {
      if (!pieces.empty()) pieces.back().joined = same_run;
      pieces.push_back({a, 1, T, 0, false});
    }
    end = a + kCell;
    if (c->has_vertex(inf)) {
      c->info() = -1;
    } else {
      c->info() = static_cast<int>(T++);
      ++pieces.back().finite;
    }
  }

  // f(cell, its bytes) for each finite cell of pieces [p0, p1); ahead(cell) for the element
  // kAhead further in the same piece, when it is a cell in use.
  const auto for_cells = [&](std::size_t p0, std::size_t p1, const auto& f, const auto& ahead) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(p0, p1, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t p = r.begin(); p != r.end(); ++p) {
        unsigned char* e = pieces[p].first;
        for (std::size_t k = 0; k < pieces[p].n; ++k, e += kCell) {
          if (k + kAhead < pieces[p].n && is_used(e + kAhead * kCell))
            ahead(*reinterpret_cast<const DT3::Cell*>(e + kAhead * kCell));
          if (is_used(e) && reinterpret_cast<DT3::Cell*>(e)->info() >= 0) f(*reinterpret_cast<DT3::Cell*>(e), e);
        }
      }
    });
  };
  // The records read the cell's vertices and neighbours, which lie anywhere in CGAL's containers:
  // fetched kAhead elements before.
  const auto fetch_around = [](const DT3::Cell& c) {
    for (int k = 0; k < 4; ++k) {
      __builtin_prefetch(&c.vertex(k)->info());
      __builtin_prefetch(&c.neighbor(k)->info());
    }
  };
  for_cells(0, pieces.size(), [&](DT3::Cell& c, unsigned char* bytes) {
    CellRecord rec{};
    for (int k = 0; k < 4; ++k) {
      const auto u = static_cast<std::size_t>(k);
      rec.tet[u] = id[static_cast<std::size_t>(c.vertex(k)->info())];
      rec.nb[u] = c.neighbor(k)->info();
    }
    std::memcpy(bytes + kRecordOffset, &rec, sizeof rec);
  }, fetch_around);

  out.tets.clear();
  out.neighbors.clear();
  tbb::parallel_invoke([&] { detail::reserve_big(out.tets, T); }, [&] { detail::reserve_big(out.neighbors, T); });
  std::size_t given = 0;  // bytes given back
  for (std::size_t p0 = 0; p0 < pieces.size();) {
    std::size_t p1 = p0, m = 0;
    while (p1 < pieces.size() && m < kExportChunk) m += pieces[p1++].finite;
    const std::size_t size = pieces[p1 - 1].base + pieces[p1 - 1].finite;
    tbb::parallel_invoke([&] { out.tets.resize(size); }, [&] { out.neighbors.resize(size); });
    for_cells(p0, p1, [&](DT3::Cell& c, const unsigned char* bytes) {
      CellRecord rec;
      std::memcpy(&rec, bytes + kRecordOffset, sizeof rec);
      const auto t = static_cast<std::size_t>(c.info());
      out.tets[t] = rec.tet;
      out.neighbors[t] = rec.nb;
    }, [](const DT3::Cell&) {});
    // Only as many bytes as the output holds by now are given back: the peak stays the
    // triangulation's, and the rest stays with the heap, which takes the engine's next (small)
    // arrays from it without faulting pages in again.
    if (given < size * sizeof(CellRecord))
      for (std::size_t p = p0; p < p1;) {  // each run of joined pieces at once (whole pages)
        std::size_t q = p;
        while (q + 1 < p1 && pieces[q].joined) ++q;
        given += static_cast<std::size_t>(pieces[q].first + pieces[q].n * kCell - pieces[p].first);
        give_back(pieces[p].first, pieces[q].first + pieces[q].n * kCell);
        p = q + 1;
      }
    p0 = p1;
  }
}

template <class Traits, int x, bool upx, bool upy, class It>
void hilbert2(const CGAL::Hilbert_sort_median_2<Traits, CGAL::Sequential_tag>& hs, const Traits& k, It begin, It end,
              std::ptrdiff_t limit) {
  if (end - begin <= limit) return;
  if (end - begin <= kParallelSort) {
    hs.template recursive_sort<x, upx, upy>(begin, end);
    return;
  }
  constexpr int y = (x + 1) % 2;
  using CGAL::internal::hilbert_split;
  using CGAL::internal::Hilbert_cmp_2;
  It m0 = begin, m1, m3, m4 = end;
  It m2 = hilbert_split(m0, m4, Hilbert_cmp_2<Traits, x, upx>(k));
  tbb::parallel_invoke([&] { m1 = hilbert_split(m0, m2, Hilbert_cmp_2<Traits, y, upy>(k)); },
                       [&] { m3 = hilbert_split(m2, m4, Hilbert_cmp_2<Traits, y, !upy>(k)); });
  tbb::parallel_invoke([&] { hilbert2<Traits, y, upy, upx>(hs, k, m0, m1, limit); },
                       [&] { hilbert2<Traits, x, upx, upy>(hs, k, m1, m2, limit); },
                       [&] { hilbert2<Traits, x, upx, upy>(hs, k, m2, m3, limit); },
                       [&] { hilbert2<Traits, y, !upy, !upx>(hs, k, m3, m4, limit); });
}

template <class Traits, int x, bool upx, bool upy, bool upz, class It>
void hilbert3(const CGAL::Hilbert_sort_median_3<Traits, CGAL::Sequential_tag>& hs, const Traits& k, It begin, It end,
              std::ptrdiff_t limit) {
  if (end - begin <= limit) return;
  if (end - begin <= kParallelSort) {
    hs.template recursive_sort<x, upx, upy, upz>(begin, end);
    return;
  }
  constexpr int y = (x + 1) % 3, z = (x + 2) % 3;
  using CGAL::internal::hilbert_split;
  using CGAL::internal::Hilbert_cmp_3;
  It m0 = begin, m1, m2, m3, m5, m6, m7, m8 = end;
  It m4 = hilbert_split(m0, m8, Hilbert_cmp_3<Traits, x, upx>(k));
  tbb::parallel_invoke(
      [&] {
        m2 = hilbert_split(m0, m4, Hilbert_cmp_3<Traits, y, upy>(k));
        tbb::parallel_invoke([&] { m1 = hilbert_split(m0, m2, Hilbert_cmp_3<Traits, z, upz>(k)); },
                             [&] { m3 = hilbert_split(m2, m4, Hilbert_cmp_3<Traits, z, !upz>(k)); });
      },
      [&] {
        m6 = hilbert_split(m4, m8, Hilbert_cmp_3<Traits, y, !upy>(k));
        tbb::parallel_invoke([&] { m5 = hilbert_split(m4, m6, Hilbert_cmp_3<Traits, z, upz>(k)); },
                             [&] { m7 = hilbert_split(m6, m8, Hilbert_cmp_3<Traits, z, !upz>(k)); });
      });
  tbb::parallel_invoke([&] { hilbert3<Traits, z, upz, upx, upy>(hs, k, m0, m1, limit); },
                       [&] { hilbert3<Traits, y, upy, upz, upx>(hs, k, m1, m2, limit); },
                       [&] { hilbert3<Traits, y, upy, upz, upx>(hs, k, m2, m3, limit); },
                       [&] { hilbert3<Traits, x, upx, !upy, !upz>(hs, k, m3, m4, limit); });
  tbb::parallel_invoke([&] { hilbert3<Traits, x, upx, !upy, !upz>(hs, k, m4, m5, limit); },
                       [&] { hilbert3<Traits, y, !upy, upz, !upx>(hs, k, m5, m6, limit); },
                       [&] { hilbert3<Traits, y, !upy, upz, !upx>(hs, k, m6, m7, limit); },
                       [&] { hilbert3<Traits, z, !upz, !upx, upy>(hs, k, m7, m8, limit); });
}

// CGAL's Multiscale_sort: the first `ratio` part recursively, then the rest.
template <class It, class Sort>
void multiscale(It begin, It end, std::ptrdiff_t threshold, double ratio, const Sort& sort) {
  It middle = begin;
  if (end - begin >= threshold) {
    middle = begin + static_cast<std::ptrdiff_t>(static_cast<double>(end - begin) * ratio);
    multiscale(begin, middle, threshold, ratio, sort);
  }
  sort(middle, end);
}

// Spatially sorted (point, input index) pairs, in the order of CGAL's insert_with_info:
// spatial_sort's random_shuffle is applied to an index array (same swaps, less memory), then
// the pairs are gathered in that order.
// With @p subset: those points only (pairs carry their index in @p points), in the order the
// same sort gives the subset as a point set of its own.
template <int D, class Point>
std::vector<std::pair<Point, int>> sorted_input(const PointSet& points, const std::vector<int>* subset = nullptr) {
  const std::size_t n = subset ? subset->size() : points.size();
  std::vector<int> perm;
  detail::resize_big(perm, n);
  for (std::size_t i = 0; i < n; ++i) perm[i] = subset ? (*subset)[i] : static_cast<int>(i);
  {
    boost::rand48 random;
    boost::random_number_generator<boost::rand48, std::ptrdiff_t> rng(random);
    CGAL::cpp98::random_shuffle(perm.begin(), perm.end(), rng);
  }
  std::vector<std::pair<Point, int>> items;
  detail::resize_big(items, n);
  par_for(n, [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const double* p = points[static_cast<std::size_t>(perm[k])];
      if constexpr (D == 2) items[k] = {Point(p[0], p[1]), perm[k]};
      else items[k] = {Point(p[0], p[1], p[2]), perm[k]};
    }
  });
  using Pmap = CGAL::First_of_pair_property_map<std::pair<Point, int>>;
  using It = typename std::vector<std::pair<Point, int>>::iterator;
  if constexpr (D == 2) {
    using Traits = CGAL::Spatial_sort_traits_adapter_2<K, Pmap>;
    const Traits k{Pmap(), K()};
    const CGAL::Hilbert_sort_median_2<Traits, CGAL::Sequential_tag> hs(k, 4);
    multiscale(items.begin(), items.end(), 16, 0.25,
               [&](It b, It e) { hilbert2<Traits, 0, false, false>(hs, k, b, e, 4); });
  } else {
    using Traits = CGAL::Spatial_sort_traits_adapter_3<K, Pmap>;
    const Traits k{Pmap(), K()};
    const CGAL::Hilbert_sort_median_3<Traits, CGAL::Sequential_tag> hs(k, 8);
    multiscale(items.begin(), items.end(), 64, 0.125,
               [&](It b, It e) { hilbert3<Traits, 0, false, false, false>(hs, k, b, e, 8); });
  }
  return items;
}

template <int D, class Point>
void fill_local(const std::vector<std::pair<Point, int>>& items, detail::LocalMesh<D>& local, bool coords) {
  const std::size_t n = items.size();
  local.id.allocate(n);
  if (coords) local.coords.allocate(D * n);
  par_for(n, [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      local.id[k] = items[k].second;
      if (coords)
        for (int c = 0; c < D; ++c) local.coords[D * k + static_cast<std::size_t>(c)] = items[k].first[c];
    }
  });
}

// The first of the points p(0), ..., p(n - 1) off the line through p(0) and the first point that
// differs from it (exact), or n when they are all on one line.
template <class At>
std::size_t first_off_line(std::size_t n, const At& p) {
  std::size_t b = 1;
  while (b < n && p(b) == p(0)) ++b;
  for (std::size_t k = b + 1; k < n; ++k)
    if (CGAL::orientation(p(0), p(b), p(k)) != CGAL::COLLINEAR) return k;
  return n;
}

// CGAL's hinted insertion of p(0), ..., p(n - 1) in this order; vertex info = info0 + the index.
// While every point so far lies on one line, CGAL's triangulation has dimension 1 and locates each
// new point by a walk along that line: when the first points in this order are collinear and the
// first point off their line comes late (199 999 points on a line and one off it: 36 s, against
// 0.1 s at 10^5 where it came early), that is quadratic. So when the first three are collinear,
// the first point off their line is inserted first; otherwise the order is the given one.
template <class At>
void insert_in_order(DT2& dt, std::size_t n, const At& p, int info0) {
  const std::size_t first =
      n > 3 && CGAL::orientation(p(0), p(1), p(2)) == CGAL::COLLINEAR ? first_off_line(n, p) : n;
  DT2::Face_handle hint;
  const auto insert = [&](std::size_t k) {
    const DT2::Vertex_handle v = dt.insert(p(k), hint);
    if (v != DT2::Vertex_handle()) {
      v->info() = info0 + static_cast<int>(k);
      hint = v->face();
    }
  };
  if (first < n) insert(first);
  for (std::size_t k = 0; k < n; ++k)
    if (k != first) insert(k);
}

// CGAL's hinted insertion in the spatially sorted order; vertex info = the insertion rank.
void insert_sorted(DT2& dt, const std::vector<std::pair<K::Point_2, int>>& items) {
  insert_in_order(dt, items.size(), [&](std::size_t k) { return items[k].first; }, 0);
}

// ---- 2D on both cores: two halves triangulated side by side, then joined -----------------------
// The points are split at the median x (L: x <= m, R: x > m) and the Delaunay triangulations of
// the two halves are built concurrently. A triangle of DT(L) whose closed circumdisk misses R's
// bounding box holds no point of R, so it is a triangle of the Delaunay triangulation of all
// points: it is *certified* (so is a hull edge of L whose outer closed half-plane misses R's box:
// a hull edge of all points). The test is a sound interval computation (CGAL's Interval_nt in the
// upward rounding mode) or an exact orientation; a triangle it cannot decide is not certified.
// The whole triangulation is the certified triangles of both halves plus the Delaunay triangles of
// S, the vertices of the uncertified faces: at a point all of whose faces are certified, its star
// is the certified one, so every other triangle has its three vertices in S and is a triangle of
// DT(S). The region the certified triangles leave is tiled by the triangles of DT(S) that a flood
// fill reaches from the certified region's boundary edges without crossing one. Every edge is then
// locally Delaunay (a certified triangle's open disk is empty of both halves). The join is checked
// (each boundary edge met exactly once from the other side, the count 2n - 2 - h of a
// triangulation with h hull edges, the neighbours symmetric); if the check fails, or a half has
// no area, the sequential insertion runs instead. So does a curve-like input: on a curve the
// circumdisks of the interior and exterior triangles reach across the split and S holds a third
// of the points (measured on the bench's five-petal curve), so the halves are first tried on a
// sample (every kSplitStride-th point) and the split is made only when the sample's S is small.
// The split does not depend on the thread count, so neither does the result; its triangles are
// those of the sequential triangulation wherever the Delaunay triangulation is unique, and only
// their order and the vertex ranks differ.
constexpr std::size_t kSplitFrom2 = std::size_t{1} << 17;
constexpr std::size_t kSplitStride = 64;
constexpr double kSplitMaxSampleShare = 0.08;

using IV = CGAL::Interval_nt<false>;

struct Box2 {
  double xmin, ymin, xmax, ymax;
};

Box2 box_of(const std::vector<std::pair<K::Point_2, int>>& items) {
  Box2 b{items[0].first.x(), items[0].first.y(), items[0].first.x(), items[0].first.y()};
  for (const auto& it : items) {
    b.xmin = std::min(b.xmin, it.first.x());
    b.xmax = std::max(b.xmax, it.first.x());
    b.ymin = std::min(b.ymin, it.first.y());
    b.ymax = std::max(b.ymax, it.first.y());
  }
  return b;
}

// The closed circumdisk of the counter-clockwise triangle abc misses the box. Needs the upward
// rounding mode (CGAL::Protect_FPU_rounding); false when the intervals cannot tell.
bool disk_misses_box(const K::Point_2& a, const K::Point_2& b, const K::Point_2& c, const Box2& o) {
  const IV bx = IV(b.x()) - a.x(), by = IV(b.y()) - a.y(), cx = IV(c.x()) - a.x(), cy = IV(c.y()) - a.y();
  const IV d = (bx * cy - by * cx) * 2;
  if (!(d.inf() > 0)) return false;
  const IV b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const IV ux = (cy * b2 - by * c2) / d, uy = (bx * c2 - cx * b2) / d;
  const IV r2 = ux * ux + uy * uy;
  const IV ox = ux + a.x(), oy = uy + a.y();
  const double lx = std::max({0.0, (IV(o.xmin) - ox).inf(), (ox - o.xmax).inf()});
  const double ly = std::max({0.0, (IV(o.ymin) - oy).inf(), (oy - o.ymax).inf()});
  const IV dist2 = IV(lx) * lx + IV(ly) * ly;
  return dist2.inf() > r2.sup();
}

// The outer closed half-plane of the hull edge p -> q (the infinite vertex on its left) misses
// the box: every corner strictly on its right (exact orientation).
bool halfplane_misses_box(const K::Point_2& p, const K::Point_2& q, const Box2& o) {
  for (int k = 0; k < 4; ++k) {
    const K::Point_2 c((k & 1) ? o.xmax : o.xmin, (k & 2) ? o.ymax : o.ymin);
    if (CGAL::orientation(p, q, c) != CGAL::RIGHT_TURN) return false;
  }
  return true;
}

// Face info in the halves: >= 0 a certified triangle (its output index once numbered), kHull a
// certified infinite face (a hull edge of all points), kOpen an uncertified face.
constexpr int kHull = -1, kOpen = -2;

struct Half2 {
  DT2 dt;
  Box2 box{};
  std::vector<DT2::Face_handle> open;  // the uncertified faces, container order
  std::size_t n_cert = 0;              // certified triangles
  std::size_t n_hull = 0;              // certified hull edges whose triangle is certified
};

// Inserts the points of ranks [first, first + count) (coordinates in @p ranked) in rank order,
// with hints; vertex info = the rank.
void insert_ranked(DT2& dt, const PointSet& ranked, std::size_t first, std::size_t count) {
  insert_in_order(
      dt, count, [&](std::size_t k) { return K::Point_2(ranked.coords[2 * (first + k)], ranked.coords[2 * (first + k) + 1]); },
      static_cast<int>(first));
}

// Do the points @p ids span an area (three of them not on one line; exact)?
bool has_area(const PointSet& points, const std::vector<int>& ids) {
  const auto p = [&](std::size_t k) {
    const double* c = points[static_cast<std::size_t>(ids[k])];
    return K::Point_2(c[0], c[1]);
  };
  return first_off_line(ids.size(), p) < ids.size();
}

// The halves of @p subset (indices into @p points, ascending) at the median x: each sorted in
// CGAL's spatial order and written to @p ranked / @p id (L's ranks first), then both triangulated
// side by side (vertex info = rank). False when a half is empty or has no area; @p duplicates when
// a half has coinciding points.
bool build_halves(const PointSet& points, const std::vector<int>& subset, Half2& l, Half2& r, PointSet& ranked,
                  std::vector<int>& id, bool& duplicates) {
  const std::size_t m = subset.size();
  std::vector<double> xs(m);
  for (std::size_t i = 0; i < m; ++i) xs[i] = points[static_cast<std::size_t>(subset[i])][0];
  std::nth_element(xs.begin(), xs.begin() + static_cast<std::ptrdiff_t>(m / 2), xs.end());
  const double mx = xs[m / 2];
  std::vector<double>().swap(xs);
  std::vector<int> left, right;
  left.reserve(m / 2 + 1);
  right.reserve(m / 2 + 1);
  for (const int i : subset) (points[static_cast<std::size_t>(i)][0] <= mx ? left : right).push_back(i);
  if (left.size() < 3 || right.size() < 3) return false;
  // A half on one line would be triangulated in dimension 1, where CGAL locates each point by a
  // walk along the line: quadratic (199 999 collinear points and one off the line took 39 s here,
  // 124 ms at 10^5 without the split). Such a half has no area: the sequential insertion runs.
  bool flat[2] = {false, false};
  tbb::parallel_invoke([&] { flat[0] = !has_area(points, left); }, [&] { flat[1] = !has_area(points, right); });
  if (flat[0] || flat[1]) return false;
  const std::size_t nl = left.size();
  ranked.dim = 2;
  detail::resize_big(ranked.coords, 2 * m);
  detail::resize_big(id, m);
  const auto rank_half = [&](const std::vector<int>& half, std::size_t first, Box2& box) {
    const auto items = sorted_input<2, K::Point_2>(points, &half);
    box = box_of(items);
    for (std::size_t k = 0; k < items.size(); ++k) {
      ranked.coords[2 * (first + k)] = items[k].first.x();
      ranked.coords[2 * (first + k) + 1] = items[k].first.y();
      id[first + k] = items[k].second;
    }
  };
  tbb::parallel_invoke([&] { rank_half(left, 0, l.box); }, [&] { rank_half(right, nl, r.box); });
  std::vector<int>().swap(left);
  std::vector<int>().swap(right);
  tbb::parallel_invoke([&] { insert_ranked(l.dt, ranked, 0, nl); }, [&] { insert_ranked(r.dt, ranked, nl, m - nl); });
  duplicates = l.dt.number_of_vertices() + r.dt.number_of_vertices() != m;
  return !duplicates && l.dt.dimension() == 2 && r.dt.dimension() == 2;
}

// Runs f(handle) on every face of @p dt in container order, in chunks of kExportChunk handles
// processed on both cores (a list of all of them would be 8 bytes per face at the peak).
// With @p upwards, each range runs in the upward rounding mode.
template <class F>
void for_faces_chunked(DT2& dt, bool upwards, const F& f) {
  std::vector<DT2::Face_handle> hs;
  hs.reserve(kExportChunk);
  const auto run = [&] {
    par_for(hs.size(), [&](const tbb::blocked_range<std::size_t>& r) {
      if (upwards) {
        CGAL::Protect_FPU_rounding<true> up;
        for (std::size_t i = r.begin(); i != r.end(); ++i) f(hs[i]);
      } else {
        for (std::size_t i = r.begin(); i != r.end(); ++i) f(hs[i]);
      }
    });
    hs.clear();
  };
  for (auto it = dt.all_faces_begin(); it != dt.all_faces_end(); ++it) {
    hs.push_back(it);
    if (hs.size() == kExportChunk) run();
  }
  run();
}

// Certifies the faces of one half against the other half's box (face info, n_cert, n_hull, the
// open faces) and marks the vertices of the uncertified ones in @p in_s (by rank).
void certify_half(Half2& h, const Box2& other, unsigned char* in_s) {
  const DT2::Vertex_handle inf = h.dt.infinite_vertex();
  std::atomic<std::size_t> n_cert{0};
  for_faces_chunked(h.dt, true, [&](DT2::Face_handle f) {
    const int k = f->has_vertex(inf) ? f->index(inf) : -1;
    bool ok = false;
    if (k >= 0) {
      // (CGAL's static filters assume rounding to nearest: the range runs upwards for the
      // intervals, the few hull edges go back to nearest for the exact orientations.)
      const CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);
      ok = halfplane_misses_box(f->vertex(DT2::ccw(k))->point(), f->vertex(DT2::cw(k))->point(), other);
    } else {
      ok = disk_misses_box(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point(), other);
    }
    if (ok) {
      f->info() = k >= 0 ? kHull : 0;
      if (k < 0) n_cert.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    f->info() = kOpen;
    for (int j = 0; j < 3; ++j)
      if (j != k) __atomic_store_n(&in_s[static_cast<std::size_t>(f->vertex(j)->info())], 1, __ATOMIC_RELAXED);
  });
  h.n_cert = n_cert;
  DT2::Face_circulator f = h.dt.incident_faces(inf), end = f;
  do {
    if (f->info() == kHull && f->neighbor(f->index(inf))->info() >= 0) ++h.n_hull;
  } while (++f != end);
}

// The directed edge a -> b as one word (core/detail/edge_key.hpp's key is undirected; the join
// needs the direction, which tells the two sides of an edge apart).
std::uint64_t directed_edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// The share of a sample's points (every kSplitStride-th) that the split would leave to DT(S).
double split_sample_share(const PointSet& points) {
  std::vector<int> sample;
  for (std::size_t i = 0; i < points.size(); i += kSplitStride) sample.push_back(static_cast<int>(i));
  Half2 l, r;
  PointSet ranked;
  std::vector<int> id;
  bool dup = false;
  if (!build_halves(points, sample, l, r, ranked, id, dup)) return 1;
  std::vector<unsigned char> in_s(sample.size(), 0);
  certify_half(l, r.box, in_s.data());
  certify_half(r, l.box, in_s.data());
  return static_cast<double>(std::count(in_s.begin(), in_s.end(), 1)) / static_cast<double>(sample.size());
}

}  // namespace

namespace detail {

bool build_delaunay2_split(const PointSet& points, Delaunay2& out, PointSet& ranked, std::vector<int>& id,
                           Status& status, bool sample_first) {
  const std::size_t n = points.size();
  if (points.dim != 2 || n < 8) return false;
  if (sample_first && split_sample_share(points) > kSplitMaxSampleShare) return false;
  Half2 hl, hr;
  {
    std::vector<int> all(n);
    for (std::size_t i = 0; i < n; ++i) all[i] = static_cast<int>(i);
    bool dup = false;
    const bool ok = build_halves(points, all, hl, hr, ranked, id, dup);
    if (dup) {
      status = {StatusCode::Duplicate, duplicate_message(n, hl.dt.number_of_vertices() + hr.dt.number_of_vertices())};
      return true;
    }
    if (!ok) return false;
  }
  std::vector<unsigned char> in_s(n, 0);
  tbb::parallel_invoke([&] { certify_half(hl, hr.box, in_s.data()); }, [&] { certify_half(hr, hl.box, in_s.data()); });
  if (hl.n_cert + hr.n_cert == 0) return false;

  // DT(S), the vertices of the uncertified faces, with their ranks.
  std::vector<std::pair<K::Point_2, int>> is;
  for (std::size_t k = 0; k < n; ++k)
    if (in_s[k]) is.push_back({K::Point_2(ranked.coords[2 * k], ranked.coords[2 * k + 1]), static_cast<int>(k)});
  std::vector<unsigned char>().swap(in_s);
  {
    using Pmap = CGAL::First_of_pair_property_map<std::pair<K::Point_2, int>>;
    CGAL::spatial_sort(is.begin(), is.end(), CGAL::Spatial_sort_traits_adapter_2<K, Pmap>(Pmap(), K()));
  }
  DT2 ds;
  insert_sorted(ds, is);
  for (auto v = ds.finite_vertices_begin(); v != ds.finite_vertices_end(); ++v)
    v->info() = is[static_cast<std::size_t>(v->info())].second;
  if (ds.dimension() < 2) return false;

  // Output indices of the certified triangles: L's, then R's, in container order.
  int next = 0;
  for (Half2* h : {&hl, &hr})
    for (auto f = h->dt.all_faces_begin(); f != h->dt.all_faces_end(); ++f) {
      if (f->info() >= 0)
        f->info() = next++;
      else if (f->info() == kOpen)
        h->open.push_back(f);
    }
  const std::size_t n_cert = static_cast<std::size_t>(next);

  // The certified region's boundary: each edge of a certified triangle whose neighbour is open,
  // keyed as the tile beyond it sees it (the reversed direction), valued 3 * triangle + slot.
  std::unordered_map<std::uint64_t, int> boundary;
  for (Half2* h : {&hl, &hr})
    for (const DT2::Face_handle g : h->open) {
      for (int j = 0; j < 3; ++j) {
        const DT2::Face_handle f = g->neighbor(j);
        if (f->info() < 0) continue;
        const int s = f->index(g);
        boundary.emplace(directed_edge_key(f->vertex(DT2::cw(s))->info(), f->vertex(DT2::ccw(s))->info()), 3 * f->info() + s);
      }
    }

  // The tiles: DT(S)'s finite faces reached from the boundary without crossing it.
  std::vector<DT2::Face_handle> sf;
  for (auto f = ds.all_faces_begin(); f != ds.all_faces_end(); ++f) {
    f->info() = ds.is_infinite(f) ? -1 : static_cast<int>(sf.size());
    if (!ds.is_infinite(f)) sf.push_back(f);
  }
  const auto key_of = [](DT2::Face_handle f, int j) {
    return directed_edge_key(f->vertex(DT2::ccw(j))->info(), f->vertex(DT2::cw(j))->info());
  };
  std::vector<int> tile(sf.size(), -1);
  std::vector<std::size_t> stack;
  for (std::size_t t = 0; t < sf.size(); ++t)
    for (int j = 0; j < 3 && tile[t] < 0; ++j)
      if (boundary.count(key_of(sf[t], j))) {
        tile[t] = 0;
        stack.push_back(t);
      }
  while (!stack.empty()) {
    const std::size_t t = stack.back();
    stack.pop_back();
    for (int j = 0; j < 3; ++j) {
      if (boundary.count(key_of(sf[t], j))) continue;
      const int g = sf[t]->neighbor(j)->info();
      if (g >= 0 && tile[static_cast<std::size_t>(g)] < 0) {
        tile[static_cast<std::size_t>(g)] = 0;
        stack.push_back(static_cast<std::size_t>(g));
      }
    }
  }
  std::size_t n_tiles = 0;
  for (int& t : tile)
    if (t == 0) t = static_cast<int>(n_cert + n_tiles++);

  // The check of the join: every boundary edge met once, from a tile or from beyond DT(S)'s hull
  // (a hull edge the box test could not tell), and the count of a triangulation.
  std::size_t met = 0, hull = hl.n_hull + hr.n_hull;
  for (auto f = ds.all_faces_begin(); f != ds.all_faces_end(); ++f)
    if (ds.is_infinite(f) && boundary.count(key_of(f, f->index(ds.infinite_vertex())))) {
      ++met;
      ++hull;
    }
  for (std::size_t t = 0; t < sf.size(); ++t) {
    if (tile[t] < 0) continue;
    for (int j = 0; j < 3; ++j) {
      if (boundary.count(key_of(sf[t], j)))
        ++met;
      else if (sf[t]->neighbor(j)->info() < 0)
        ++hull;
    }
  }
  const std::size_t T = n_cert + n_tiles;
  if (met != boundary.size() || T + 2 + hull != 2 * n) return false;

  // The export: certified triangles (an open neighbour is a tile or the hull, set from the tile's
  // side), then the tiles.
  out.n_vertices = n;
  tbb::parallel_invoke([&] { detail::resize_big(out.triangles, T); }, [&] { detail::resize_big(out.neighbors, T); });
  for (Half2* h : {&hl, &hr})
    for_faces_chunked(h->dt, false, [&](DT2::Face_handle f) {
      const int t = f->info();
      if (t < 0) return;
      std::array<int, 3> tri{}, nb{};
      for (int k = 0; k < 3; ++k) {
        tri[static_cast<std::size_t>(k)] = f->vertex(k)->info();
        nb[static_cast<std::size_t>(k)] = std::max(f->neighbor(k)->info(), -1);
      }
      out.triangles[static_cast<std::size_t>(t)] = tri;
      out.neighbors[static_cast<std::size_t>(t)] = nb;
    });
  for (std::size_t t = 0; t < sf.size(); ++t) {
    if (tile[t] < 0) continue;
    const std::size_t o = static_cast<std::size_t>(tile[t]);
    for (int k = 0; k < 3; ++k) {
      out.triangles[o][static_cast<std::size_t>(k)] = sf[t]->vertex(k)->info();
      int nb = -1;
      if (const auto b = boundary.find(key_of(sf[t], k)); b != boundary.end()) {
        nb = b->second / 3;
        out.neighbors[static_cast<std::size_t>(nb)][static_cast<std::size_t>(b->second % 3)] = static_cast<int>(o);
      } else if (const int g = sf[t]->neighbor(k)->info(); g >= 0) {
        nb = tile[static_cast<std::size_t>(g)];
      }
      out.neighbors[o][static_cast<std::size_t>(k)] = nb;
    }
  }
  // The tiles' neighbours name them back (a last guard of the join; between certified triangles
  // they are CGAL's own).
  bool symmetric = true;
  for (std::size_t t = 0; t < sf.size() && symmetric; ++t) {
    if (tile[t] < 0) continue;
    const int o = tile[t];
    for (const int g : out.neighbors[static_cast<std::size_t>(o)]) {
      if (g < 0) continue;
      const auto& back = out.neighbors[static_cast<std::size_t>(g)];
      symmetric = symmetric && (back[0] == o || back[1] == o || back[2] == o);
    }
  }
  if (!symmetric) return false;
  status = Status::ok();
  return true;
}

Status build_delaunay2_local(const PointSet& points, Delaunay2& out, LocalMesh<2>* local) {
  if (points.dim != 2) return {StatusCode::InvalidArgument, "build_delaunay2: points are not 2D"};
  const std::size_t n = points.size();
  auto items = sorted_input<2, K::Point_2>(points);
  DT2 dt;
  insert_sorted(dt, items);
  if (dt.number_of_vertices() != n) return {StatusCode::Duplicate, duplicate_message(n, dt.number_of_vertices())};
  if (dt.dimension() < 2) return {StatusCode::Collinear, "Delaunay: all points are collinear"};

  detail::LocalMesh<2> local_own;
  detail::LocalMesh<2>& lm = local ? *local : local_own;
  fill_local<2>(items, lm, local != nullptr);
  std::vector<std::pair<K::Point_2, int>>().swap(items);  // lower peak memory during the export
  const detail::BigArray<int>& id = lm.id;

  // Finite faces in CGAL's finite_faces order (= all faces, infinite ones skipped).
  out.n_vertices = n;
  export_finite<3, DT2::Face_handle>(dt.all_faces_begin(), dt.all_faces_end(), dt.infinite_vertex(), &id,
                                     out.triangles, out.neighbors, lm, local != nullptr, nullptr);
  return Status::ok();
}

Status build_delaunay2_ranked(const PointSet& points, Delaunay2& out, PointSet& ranked, std::vector<int>& id) {
  if (points.dim != 2) return {StatusCode::InvalidArgument, "build_delaunay2: points are not 2D"};
  const std::size_t n = points.size();
  if (n >= kSplitFrom2) {
    Status st;
    if (build_delaunay2_split(points, out, ranked, id, st, true)) return st;
  }
  auto items = sorted_input<2, K::Point_2>(points);
  // CGAL's insertion is sequential: the second core meanwhile writes the ranked points.
  tbb::task_group side;
  side.run([&] {
    ranked.dim = 2;
    detail::resize_big(ranked.coords, 2 * n);
    detail::resize_big(id, n);
    for (std::size_t k = 0; k < n; ++k) {
      ranked.coords[2 * k] = items[k].first.x();
      ranked.coords[2 * k + 1] = items[k].first.y();
      id[k] = items[k].second;
    }
  });
  DT2 dt;
  insert_sorted(dt, items);
  side.wait();
  std::vector<std::pair<K::Point_2, int>>().swap(items);  // lower peak memory during the export
  // The output arrays (at their upper bound 2n; the export shrinks them) only now, after the
  // sorted input is gone (24 bytes per point less at the peak), zero-filled on both cores.
  tbb::parallel_invoke([&] { detail::resize_big(out.triangles, 2 * n); }, [&] { detail::resize_big(out.neighbors, 2 * n); });
  if (dt.number_of_vertices() != n) return {StatusCode::Duplicate, duplicate_message(n, dt.number_of_vertices())};
  if (dt.dimension() < 2) return {StatusCode::Collinear, "Delaunay: all points are collinear"};
  detail::LocalMesh<2> unused;
  out.n_vertices = n;
  export_finite<3, DT2::Face_handle>(dt.all_faces_begin(), dt.all_faces_end(), dt.infinite_vertex(), nullptr,
                                     out.triangles, out.neighbors, unused, false, nullptr);
  return Status::ok();
}

bool released_export3_available() {
  DT3 dt;
  for (int k = 0; k < 5; ++k) dt.insert(K::Point_3(k == 1, k == 2, k == 3 ? 1 : k == 4 ? 2 : 0));
  return dt.dimension() == 3 && record_layout_holds(dt.finite_cells_begin());
}

// Points along curves in space (two skew lines, a circle and its axis) have a Delaunay
// tetrahedralization of quadratic size: 25 million tetrahedra for 10 000 points, minutes and tens of
// GB (a surface sample has 4.5-8 per point). The insertion stops with Unsupported once the
// triangulation holds more than kMaxCellsPerPoint3 cells per inserted point and kMaxCellsFloor3 in
// all (about 0.8 GB; 1 500 + 1 500 points of a circle and its axis, 2.25 million, still run).
constexpr std::size_t kMaxCellsPerPoint3 = 32, kMaxCellsFloor3 = std::size_t{1} << 22;
static Status too_many_cells3(std::size_t cells, std::size_t inserted, std::size_t n) {
  return {StatusCode::Unsupported,
          "3D Delaunay: " + std::to_string(cells) + " tetrahedra after " + std::to_string(inserted) + " of " +
              std::to_string(n) + " points, quadratically many: the points lie along curves or lines in space, not on "
              "a surface; sample the surface itself"};
}

Status build_delaunay3_local(const PointSet& points, Delaunay3& out, LocalMesh<3>* local, std::size_t release_from) {
  if (points.dim != 3) return {StatusCode::InvalidArgument, "build_delaunay3: points are not 3D"};
  const std::size_t n = points.size();
  auto items = sorted_input<3, K::Point_3>(points);
  // Declared before dt, so that dt is destroyed while a released export's flag is still set.
  struct ReleaseGuard {
    void arm() {
      g_releasing.fetch_add(1, std::memory_order_relaxed);
      t_cells_released = true;
    }
    ~ReleaseGuard() {
      if (!t_cells_released) return;
      t_cells_released = false;
      g_releasing.fetch_sub(1, std::memory_order_relaxed);
    }
  } release_guard;
  DT3 dt;
  {
    DT3::Vertex_handle hint;
    int rank = 0;
    for (const auto& it : items) {
      hint = dt.insert(it.first, hint);
      if (hint != DT3::Vertex_handle()) hint->info() = rank;
      ++rank;
      if ((rank & 1023) == 0 && dt.number_of_cells() > std::max(kMaxCellsFloor3, kMaxCellsPerPoint3 * static_cast<std::size_t>(rank)))
        return too_many_cells3(dt.number_of_cells(), static_cast<std::size_t>(rank), n);
    }
  }
  if (dt.number_of_cells() > std::max(kMaxCellsFloor3, kMaxCellsPerPoint3 * n)) return too_many_cells3(dt.number_of_cells(), n, n);
  if (dt.number_of_vertices() != n) return {StatusCode::Duplicate, duplicate_message(n, dt.number_of_vertices())};
  if (dt.dimension() < 3) return {StatusCode::Coplanar, "Delaunay: all points are coplanar"};

  detail::LocalMesh<3> local_own;
  detail::LocalMesh<3>& lm = local ? *local : local_own;
  fill_local<3>(items, lm, local != nullptr);
  std::vector<std::pair<K::Point_3, int>>().swap(items);  // lower peak memory during the export
  const detail::BigArray<int>& id = lm.id;

  if (!local && dt.number_of_cells() >= release_from && record_layout_holds(dt.infinite_vertex()->cell())) {
    out.n_vertices = n;
    export_released3(dt, id, out);
    release_guard.arm();  // dt's cells are (partly) given back: destroy it without reading them
    return Status::ok();
  }

  // Finite cells in CGAL's finite_cells order (= all cells, infinite ones skipped).
  const DT3::Vertex_handle inf = dt.infinite_vertex();
  std::vector<DT3::Cell_handle> inf_cells;
  if (local) inf_cells.reserve(dt.number_of_cells() - dt.number_of_finite_cells());
  out.n_vertices = n;
  export_finite<4, DT3::Cell_handle>(dt.all_cells_begin(), dt.all_cells_end(), inf, &id,
                                     out.tets, out.neighbors, lm, local != nullptr, local ? &inf_cells : nullptr);
  if (local) {
    // Hull facets and their adjacency, from the infinite cells (one per hull facet; two hull
    // facets share an edge iff their infinite cells are neighbours across a face through the
    // infinite vertex).
    const std::size_t H = inf_cells.size();
    lm.hull.resize(H);
    par_for(H, [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t h = r.begin(); h != r.end(); ++h) {
        const DT3::Cell_handle ic = inf_cells[h];
        const int ki = ic->index(inf);
        const DT3::Cell_handle fc = ic->neighbor(ki);
        detail::HullFace& hf = lm.hull[h];
        hf.t = fc->info();
        hf.i = fc->index(ic);
        int k = 0;
        for (int m = 0; m < 4; ++m) {
          if (m == ki) continue;
          const DT3::Cell_handle ic2 = ic->neighbor(m);
          const DT3::Cell_handle fc2 = ic2->neighbor(ic2->index(inf));
          hf.adj_t[k] = fc2->info();
          hf.adj_i[k] = fc2->index(ic2);
          hf.far[k] = ic2->vertex(ic2->index(ic))->info();
          ++k;
        }
      }
    });
  }
  return Status::ok();
}

}  // namespace detail

Status build_delaunay2(const PointSet& points, Delaunay2& out) {
  if (Status f = detail::check_finite(points, "build_delaunay2"); !f) return f;
  return detail::build_delaunay2_local(points, out, nullptr);
}

Status build_delaunay3(const PointSet& points, Delaunay3& out) {
  if (Status f = detail::check_finite(points, "build_delaunay3"); !f) return f;
  return detail::build_delaunay3_local(points, out, nullptr);
}

}  // namespace constrict
