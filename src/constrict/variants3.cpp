// SPDX-License-Identifier: GPL-3.0-or-later
// Stage "candidates" of the 3D engine (docs/reconstruction-3d.md §4.5): when the growth does not
// reach every point, one constriction per variant (size bias, label weight) from the same
// Delaunay tetrahedralization (shared, read-only), in parallel; the complete result with the
// smallest surface area wins, ties -> the earlier variant. Each run is independent and
// sequential, so the choice does not depend on the thread count.
#include <memory>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "constrict/detail/constrict3_impl.hpp"

namespace constrict {

Status Constrictor3::run_candidates(const PointSet& points, const Constrict3Options& options, Mesh3Result& result,
                                    Constrict3Visitor* visitor) {
  Constrict3Options o = options;
  o.size_bias = options.variants[0].size_bias;
  o.label_weight = options.variants[0].label_weight;
  if (Status s = init(points, o, nullptr); !s) return s;
  Impl& base = *impl_;
  // The growth first (§4.7) or the hull alone (every point on it): then there is nothing to vary.
  const auto single = [&](bool growth_only, Mesh3Result& r) {
    base.set_visitor(visitor);  // (stage events; the parallel variant runs below report none)
    const Status s = finish_impl(base, r, false, growth_only);
    base.set_visitor(nullptr);
    return s;
  };
  // What a failed growth leaves in the result that replaces it: its unreached points, its bound
  // and its time.
  Mesh3Result failed_growth;
  const auto keep_growth_facts = [&](Mesh3Result& r) {
    r.grow_unreached = failed_growth.grow_unreached;
    r.cavity_capped = r.cavity_capped || failed_growth.cavity_capped;
    r.ms_grow = failed_growth.ms_grow;
  };
  // A complete growth that took many tetrahedra against their labels (a thin wall): kept, and
  // compared with the variants below.
  std::unique_ptr<Mesh3Result> grown;
  if (base.can_grow()) {
    Mesh3Result rg;
    if (Status sg = single(true, rg); !sg) return sg;
    if (rg.method == Method3::Grow) {
      if (options.validate) validate_result(base, rg);
      // (A growth whose handle stage closed a loop or sealed a cavity is kept: the variants give
      // genus 0 and one surface, and the auto topology asked for what the labels show. The
      // share counts the one-face outside steps, as measured: the two-face steps into thin parts
      // (§4.11) are the growth following such a part, not zigzagging across it.)
      const std::size_t against = rg.grown_outside - rg.grown_crawled;
      if (against * Mesh3Result::kThinWallShare < rg.grown || rg.genus != 0 || rg.surfaces != 1) {
        result = std::move(rg);
        return Status::ok();
      }
      rg.grow_checked = true;
      grown = std::make_unique<Mesh3Result>(std::move(rg));
      base.reset_to_hull();
    } else {
      failed_growth.grow_unreached = rg.grow_unreached;
      failed_growth.cavity_capped = rg.cavity_capped;
      failed_growth.ms_grow = rg.ms_grow;
    }
    base.opt.grow = false;  // the variants below start from the hull (reset by the growth stage)
  }
  if (!grown && !base.keys.dg && base.body.n_onb == base.body.n) {
    if (Status sh = single(false, result); !sh) return sh;
    keep_growth_facts(result);
    if (options.validate) validate_result(base, result);
    return Status::ok();
  }
  base.set_visitor(visitor);
  base.stage_event(Stage3::Candidates);
  base.set_visitor(nullptr);
  base.ensure_hull_start();  // shared face terms and bridge ratios, before the copies
  const std::vector<Constrict3Variant>& cand = options.variants;
  const std::size_t k = cand.size();
  std::vector<Mesh3Result> res(k);
  std::vector<std::unique_ptr<Impl>> runs(k);
  std::vector<Status> st(k);
  const auto tv = Clock::now();
  tbb::parallel_for(std::size_t(0), k, [&](std::size_t i) {
    runs[i] = std::make_unique<Impl>(base);
    runs[i]->opt.size_bias = cand[i].size_bias;
    runs[i]->opt.label_weight = cand[i].label_weight;
    runs[i]->constriction().start_heap();
    st[i] = finish_impl(*runs[i], res[i], false);
  });
  std::size_t best = k;
  for (std::size_t i = 0; i < k; ++i) {
    if (!st[i]) return st[i];
    if (best == k || (res[i].complete && !res[best].complete) ||
        (res[i].complete == res[best].complete && res[i].surface_area < res[best].surface_area))
      best = i;
  }
  std::vector<Constrict3Candidate> summary;
  for (std::size_t i = 0; i < k; ++i)
    summary.push_back({cand[i].size_bias, cand[i].label_weight, res[i].surface_area, res[i].complete,
                       res[i].ms_constrict + res[i].ms_fallback + res[i].ms_sculpt + res[i].ms_carve + res[i].ms_refine});
  const double ms_runs = ms_since(tv);
  // The thin-wall check: the growth stays unless a complete variant has a smaller surface (a
  // zigzag between a wall's two sides has about 1.4 times the area; docs/reconstruction-3d.md §4.7).
  if (grown && !(res[best].complete && res[best].surface_area < grown->surface_area)) {
    result = std::move(*grown);
    result.candidates = std::move(summary);
    result.ms_variants = ms_runs;
    return Status::ok();
  }
  result = std::move(res[best]);
  keep_growth_facts(result);
  if (grown) {
    result.grown = grown->grown;
    result.grown_outside = grown->grown_outside;
    result.grown_crawled = grown->grown_crawled;
    result.ms_grow = grown->ms_grow;
    result.grow_checked = result.grow_replaced = true;
  }
  result.candidates = std::move(summary);
  result.ms_variants = ms_runs;
  result.ms_setup = base.ms_setup;
  if (options.validate) validate_result(*runs[best], result);
  return Status::ok();
}

}  // namespace constrict
