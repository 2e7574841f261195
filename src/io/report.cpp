// SPDX-License-Identifier: GPL-3.0-or-later
// The JSON reports of reconstruct2 / reconstruct3 (report.hpp): one writer for every caller.
#include "constrict/report.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

namespace constrict {
namespace {

// One line of JSON; bytes that are not UTF-8 (a path's) become U+FFFD instead of a type error.
std::string dump(const nlohmann::json& j) { return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace); }

nlohmann::json stages_json(const std::vector<Constrict3Stage>& stages) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& s : stages) a.push_back({{"name", to_string(s.name)}, {"placed", s.placed}, {"removed", s.removed}});
  return a;
}

nlohmann::json variants_json(const std::vector<Constrict3Candidate>& cand) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& c : cand)
    a.push_back({{"size_bias", c.size_bias}, {"label_weight", c.label_weight}, {"surface_area", c.surface_area},
                 {"complete", c.complete}, {"ms", c.ms}});
  return a;
}

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json rings_json(const std::vector<Ring2>& rings) {
  nlohmann::json a = nlohmann::json::array();
  for (const Ring2& r : rings)
    a.push_back({{"role", to_string(r.role)}, {"parent", r.parent}, {"indices", r.indices},
                 {"gap_spacings", finite_or_null(r.gap_spacings)}, {"nearest_ring", r.nearest_ring}});
  return a;
}

}  // namespace

std::string to_json(const Mesh3Result& r, const Constrict3Options& opt) {
  nlohmann::json j;
  j["complete"] = r.complete;
  j["valid"] = r.valid();
  j["method"] = to_string(r.method);
  j["fallback_mode"] = to_string(opt.fallback);
  j["fallback"] = r.cavities > 0 ? nlohmann::json("cavity") : nlohmann::json(nullptr);
  j["locked"] = r.locked;
  j["stuck_points"] = r.stuck_points;
  j["unplaced_points"] = r.unplaced_points;
  j["stages"] = stages_json(r.stages);
  if (!r.handle_changes.empty()) {  // (the auto topology's handle stage; docs/topology.md §3D)
    nlohmann::json h = nlohmann::json::array();
    for (const Handle3Change& c : r.handle_changes)
      h.push_back({{"kind", to_string(c.kind)},
                   {"tetrahedra", c.tetrahedra},
                   {"delta_faces", c.delta_faces},
                   {"bridges_before", c.bridges_before},
                   {"bridges_after", c.bridges_after},
                   {"worst_ratio_before", c.worst_ratio_before},
                   {"worst_ratio_after", c.worst_ratio_after},
                   {"separates_parts", c.separates_parts},
                   {"cavity_tetrahedra", c.cavity_tetrahedra},
                   {"cavity_points", c.cavity_points},
                   {"cavity_width", c.cavity_width},
                   {"loop_spacings", c.loop_spacings},
                   {"pinched", c.pinched}});
    j["handles"] = h;
    j["genus"] = r.genus;
  }
  j["removed_one_face"] = r.removed_one_face;
  j["removed_two_face"] = r.removed_two_face;
  j["cavities"] = r.cavities;
  j["cavity_capped"] = r.cavity_capped;
  j["body_tetrahedra"] = r.tets.size();
  j["non_delaunay_tetrahedra"] = r.non_delaunay_tets;
  j["faces"] = r.mesh.triangles.size();
  j["volume"] = r.volume;
  j["surface_area"] = r.surface_area;
  j["bridges"] = {{"faces", r.bridge_faces}, {"area", r.bridge_area}, {"max_ratio", r.max_bridge_ratio},
                  {"min_ratio", Mesh3Result::kBridgeRatio}};
  // What the options let run, not only what was asked: the flips run on a complete surface of the
  // constriction or the growth (not on a partial one, nor after the skeleton); the growth only with
  // the γ criterion and no stop_after (growth_planned). (Both had named passes that never ran.)
  const bool flips_ran = r.complete && r.method != Method3::VoronoiSkeleton && r.method != Method3::Incomplete;
  const bool grow_ran = opt.growth_planned() && r.method != Method3::VoronoiSkeleton && r.method != Method3::Incomplete;
  j["refine"] = {{"mode", opt.refine == Refine3::None ? "none" : flips_ran ? "flips" : "skipped"},
                 {"added", r.refine_added},
                 {"removed", r.refine_removed},
                 {"capped", r.refine_capped}};
  j["carve"] = {{"removed", r.carved}, {"undone", r.carve_undone}, {"capped", r.carve_capped}};
  j["grow"] = {{"enabled", grow_ran},
               {"tetrahedra", r.grown},
               {"labelled_outside", r.grown_outside},
               {"thin_part_steps", r.grown_crawled},
               {"filled", r.filled},
               {"cavities", r.grow_cavities},
               {"unreached", r.grow_unreached},
               {"pocket_points", r.grow_pocket_points},
               {"pocket_filled", r.grow_pocket_filled},
               {"thin_wall_check", r.grow_checked},
               {"replaced_by_constriction", r.grow_replaced}};
  j["size_bias"] = r.size_bias;
  j["label_weight"] = r.label_weight;
  j["variants"] = variants_json(r.candidates);
  j["timings_ms"] = {{"delaunay_gamma", r.ms_delaunay}, {"constrict", r.ms_constrict}, {"grow", r.ms_grow},
                     {"fill", r.ms_fill},               {"fallback", r.ms_fallback},   {"sculpt", r.ms_sculpt},
                     {"carve", r.ms_carve},             {"refine", r.ms_refine},       {"variants_setup", r.ms_setup},
                     {"variants_total", r.ms_variants}, {"validate", r.ms_validate}};
  return dump(j);
}

std::string to_json(const Polygon2Result& r, const Constrict2Options& opt) {
  nlohmann::json j;
  const bool used_fallback = r.method != "gamma" && r.method != "locked" && r.method != "stopped";
  j["complete"] = r.complete;
  j["valid"] = r.valid();
  j["validation"] = {{"simple", r.check.simple}, {"counter_clockwise", r.check.ccw},
                     {"all_points_once", r.check.all_points}, {"reason", r.check.reason}};
  j["method"] = r.method;
  j["fallback_mode"] = to_string(opt.fallback);
  j["fallback"] = used_fallback ? nlohmann::json(r.method) : nlohmann::json(nullptr);
  j["locked"] = r.locked_at_gamma0;
  j["stuck_points"] = r.stuck_points;
  nlohmann::json stages = nlohmann::json::array();
  for (const auto& s : r.stages) {
    nlohmann::json st = {{"name", s.name}, {"placed", s.placed}};
    if (s.candidates > 0) st["candidates"] = s.candidates;
    stages.push_back(std::move(st));
  }
  j["stages"] = stages;
  j["removed_simplices"] = r.removed_simplices;
  j["fallback_insertions"] = r.fallback_insertions;
  j["fallback_edges"] = r.fallback_edges.size();
  j["area"] = r.area;
  j["perimeter"] = r.perimeter;
  // (The local search runs on a complete polygon of the constriction, not after the skeleton.)
  const bool search_ran = r.complete && r.method != "voronoi-skeleton" && r.method != "incomplete";
  j["refine"] = {{"mode", opt.refine == Refine2::None ? "none" : search_ran ? "local-search" : "skipped"},
                 {"moves", r.refine_moves},
                 {"budget_hit", r.refine_budget_hit},
                 {"perimeter_before", r.perimeter_before_refine}};
  j["timings_ms"] = {{"delaunay", r.ms_delaunay}, {"gamma", 0.0},        {"constrict", r.ms_constrict},
                     {"fallback", r.ms_fallback}, {"refine", r.ms_refine}, {"validate", r.ms_validate}};
  return dump(j);
}

std::string to_json(const Rings2Result& r, const Rings2Options& opt) {
  nlohmann::json j;
  if (r.from_polygon) {
    j = nlohmann::json::parse(to_json(r.polygon, opt.polygon));
  } else {
    j["complete"] = r.complete();
    j["valid"] = r.valid();
    j["method"] = "rings";
    j["area"] = r.area;
    j["perimeter"] = r.perimeter;
    j["timings_ms"] = {{"validate", r.ms_validate}};
  }
  j["validation"]["rings_disjoint"] = r.check.simple;
  j["validation"]["rings_oriented"] = r.check.oriented;
  j["validation"]["rings_nested"] = r.check.nested;
  if (!r.from_polygon) j["validation"]["reason"] = r.check.reason;
  j["timings_ms"]["topology"] = r.ms_infer;
  j["rings"] = rings_json(r.rings);
  nlohmann::json t = {{"mode", to_string(r.topology)}, {"gap_threshold", opt.topology_gap}, {"inferred", nullptr}};
  if (r.inferred_run) {
    const RingsInference& in = r.inferred;
    t["inferred"] = {{"decision", to_string(in.decision)},
                     {"rings", in.rings.size()},
                     {"shells", in.shells()},
                     {"holes", in.holes()},
                     {"parts", in.parts},
                     {"parts_polygon", in.parts_polygon},
                     {"thin_parts_joined", in.thin_parts_joined},
                     {"joins_undone", in.joins_undone},
                     {"crossings_joined", in.crossings_joined},
                     {"rings_from_walk", in.rings_from_walk},
                     {"open_parts", in.open_parts},
                     {"bad_degree_points", in.bad_degree_points},
                     {"split_gap_spacings", in.split_gap_spacings},
                     {"min_gap_spacings", finite_or_null(in.min_gap_spacings)},
                     {"reason", in.check.reason},
                     {"ring_list", r.from_polygon && in.rings.size() > 1 ? rings_json(in.rings) : nlohmann::json(nullptr)}};
  }
  j["topology"] = t;
  return dump(j);
}

}  // namespace constrict
