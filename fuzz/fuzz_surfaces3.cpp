// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: reconstruct_surfaces3() with the auto topology (parts, inner shells, handles;
// docs/topology.md §"3D") on small decoded point sets with a decoded gap threshold
// (docs/fuzzing.md). Contract (topology.hpp): the check_points() status for bad input; for valid
// input Ok, or Unsupported when the coordinates cannot be rescaled exactly (as reconstruct3()).
// An Ok complete result is checked here again on the input's own coordinates: the surfaces
// closed, manifold, oriented, without self-intersections, the body's free faces exactly them
// (validate_surfaces3), every point on exactly one surface, the genus the sum of the surfaces'.
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "constrict/mesh.hpp"
#include "constrict/topology.hpp"
#include "fuzz_engine.hpp"

namespace {

using namespace constrict;
using constrict_fuzz::require;

Surfaces3Options decode_options(constrict_fuzz::Bytes& in) {
  const std::uint8_t a = in.u8();
  Surfaces3Options o;
  o.topology = Topology3::Auto;
  const double gaps[] = {kDefaultTopologyGap3, 0.0, 0.5, 1.0, 1.5, 3.0, 6.0, 1e300};
  o.topology_gap = gaps[a & 7];
  if (a & 0x08) o.min_part_points = 4;  // tiny parts of their own
  if (a & 0x10) o.handles = false;
  if (a & 0x20) o.surface.grow = false;  // parts and shells from the constriction
  return o;
}

void check_surfaces(const PointSet& p, const Surfaces3Result& r) {
  if (!r.mesh.complete) return;
  require(r.valid(), "complete Ok result not valid()", r.check);
  const Status v = validate_surfaces3(p, r.mesh.mesh, r.mesh.tets, true);
  require(v.is_ok(), "validate_surfaces3 refuses the result", v.message());
  std::vector<int> count(p.size(), 0);
  int genus = 0;
  for (const Surface3& s : r.surfaces) {
    genus += s.genus;
    for (int v3 : s.points) ++count[static_cast<std::size_t>(v3)];
    require(s.parent >= -1 && s.parent < static_cast<int>(r.surfaces.size()), "parent out of range");
  }
  require(genus == r.genus, "total genus is not the sum of the surfaces'");
  require(std::all_of(count.begin(), count.end(), [](int c) { return c == 1; }),
          "a point is not on exactly one surface");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  constrict_fuzz::Bytes in(data, size);
  const Surfaces3Options options = decode_options(in);
  const constrict_fuzz::Decoded d = constrict_fuzz::decode_points(in, 3);
  constrict_fuzz::print_points(d);
  const PointSet& p = d.points;
  Status checked, st;
  Surfaces3Result r;
  constrict_fuzz::no_throw("reconstruct_surfaces3", [&] {
    checked = check_points(p);
    st = reconstruct_surfaces3(p, options, r);
  });
  if (!constrict_fuzz::engine3_status(p, checked, st)) return 0;
  constrict_fuzz::no_throw("checks", [&] { check_surfaces(p, r); });
  return 0;
}
