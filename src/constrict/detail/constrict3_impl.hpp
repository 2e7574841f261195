// SPDX-License-Identifier: GPL-3.0-or-later
// Constrictor3::Impl: the state of one 3D run (docs/architecture.md) — the body, the read-only
// key inputs shared by the variant runs, and each stage's own small state — and the pipeline's
// stage steps (constrict3.cpp) and the variant selection (variants3.cpp).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>

#include "constrict/constrict3.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/detail/stages3.hpp"

namespace constrict {

using Clock = std::chrono::steady_clock;
inline double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Constrictor3::Impl {
  // Below every key: pop whatever is best.
  static constexpr double kAnyKey = -1e300;

  // Inputs.
  const PointSet* input = nullptr;  // the caller's points (the validation reads them)
  // Engine id k is input point (*order)[k] (canonical_order: the coordinates decide, not the
  // file order); work = the points in that order, times 2^-scale_exp.
  std::shared_ptr<const std::vector<int>> order;
  std::shared_ptr<const PointSet> work;
  int scale_exp = 0;
  Constrict3Options opt;
  // Events carry input ids: the stages report to id_map, which maps and passes them on.
  struct IdMapVisitor final : Constrict3Visitor {
    Constrict3Visitor* inner = nullptr;
    const std::vector<int>* order = nullptr;
    void on_event(const Constrict3Event& e) override;
  };
  IdMapVisitor id_map;
  Constrict3Visitor* visitor = nullptr;  // &id_map, or null without a caller's visitor
  void set_visitor(Constrict3Visitor* v);
  std::vector<int> input_ids(std::vector<int> ids) const;  // mapped and ascending
  std::array<int, 4> input_ids(std::array<int, 4> t) const;
  TriMesh3 input_ids(TriMesh3 m) const;

  // A tetrahedralization given by the caller (detail::reconstruct3_sharing), used once by
  // build_tetrahedralization when it would build the same one.
  std::shared_ptr<Delaunay3> shared_dt;
  // The parts of the auto topology's gap rule per engine id (reconstruct3_sharing), or null: the
  // handle stage may then seal cavities that separate parts.
  std::shared_ptr<const std::vector<int>> part_of;
  // The tetrahedra renumbered by their smallest vertex (core/detail/tet_order.hpp: from
  // kOrderTetsFrom tetrahedra on, also those the auto topology shares).
  bool tets_ordered = false;
  bool order_is_identity() const {
    for (std::size_t k = 0; k < order->size(); ++k)
      if ((*order)[k] != static_cast<int>(k)) return false;
    return true;
  }

  // State.
  detail::Body3 body;                 // tetrahedra, adjacency, body, surface points
  detail::Keys3 keys;                 // labels, γ face terms, bridge ratios (shared, read-only)
  detail::Constriction3State hull;    // heap and removal counts of the constriction
  detail::CavityState3 cavity;        // the lock fallback's cavities
  detail::Tets nbr_delaunay;          // adjacency before the growth's cavities (for a reset)
  detail::Growth3Stats growth;
  std::shared_ptr<const detail::GrowthPrep3> growth_prep;  // made beside the labels, used once by the growth
  detail::Carve3Stats carve;
  detail::Carve3Stats handles_closed, handles_opened;
  detail::Flips3Stats flips;
  std::size_t filled = 0, removed_sculpt = 0, n_hull = 0;
  bool fill_capped = false;  // the fill stopped at its work bound (carve3.cpp)
  double ms_delaunay = 0, ms_setup = 0;
  bool ready = false;
  bool need_size = false;   // size bias or bridge sculpting: spacing and bridge ratios
  bool hull_ready = false;  // the constriction's keys and initial heap are made
  bool stepped = false;     // the state has left the start (growth or constriction)
  bool grew = false;        // the growth reached every point

  // The options ask for the growth (decided before the tetrahedralization: init builds the DT
  // alone then); it runs when the labels exist and some point is inside the hull (else the hull
  // itself is the answer).
  bool grow_planned() const { return opt.growth_planned(); }
  bool can_grow() const { return grow_planned() && keys.labels && n_hull < body.n; }
  detail::HullConstriction3 constriction() { return {body, hull, keys, opt, visitor}; }

  Status build_tetrahedralization();
  // The state of init(): the whole tetrahedralization, the hull points on the surface.
  void reset_to_hull();
  // The constriction from the hull needs the face terms, the spacing / bridge ratios (size bias)
  // and its initial heap; they are made on first use, so a growth that reaches every point does
  // not pay for them.
  void ensure_hull_start();
  bool step();
  void stage_event(Stage3 stage) const;

  enum class Growth { NotRun, Grown, Failed };
  Growth grow_stage(Mesh3Result& r);
  void constriction_stage(Mesh3Result& r);
  void lock_fallback_stage(Mesh3Result& r);
  void carve_stage(Mesh3Result& r);
  void handles_stage(Mesh3Result& r);
  void sculpt_stage(Mesh3Result& r);
  void refine_stage(Mesh3Result& r);
  void bridge_stage(Mesh3Result& r);
  void collect(Mesh3Result& r) const;
  void measure_bridges(const TriMesh3& surface, Mesh3Result& r) const;
};

}  // namespace constrict
