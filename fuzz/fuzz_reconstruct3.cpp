// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: reconstruct3() on small decoded point sets with decoded options
// (docs/fuzzing.md). Contract (constrict3.hpp, issue 20): the check_points() status for bad
// input; for valid input Ok, or Unsupported when the coordinates span too many orders of magnitude
// to rescale exactly. An Ok mesh is always a closed, oriented, genus-0 2-manifold without
// self-intersections, checked here again on the input's own coordinates; when complete, every
// point is a vertex, otherwise the mesh vertices and the unplaced points cover the input.
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "constrict/constrict3.hpp"
#include "constrict/mesh.hpp"
#include "fuzz_engine.hpp"

namespace {

using namespace constrict;
using constrict_fuzz::require;

Constrict3Options decode_options(constrict_fuzz::Bytes& in) {
  const std::uint8_t a = in.u8(), b = in.u8();
  Constrict3Options o;
  const char* const presets[] = {"default", "paper", "fast"};
  require(Constrict3Options::from_preset(presets[a % 3], o).is_ok(), "3D preset refused");
  if (a & 0x04) o.fallback = Fallback3::None;
  const Criterion criteria[] = {Criterion::Gamma, Criterion::MinAreaChange, Criterion::Boissonnat};
  o.criterion = criteria[((a >> 3) & 3) % 3];
  if (a & 0x20) o.grow = !o.grow;
  const Sculpt3 sculpts[] = {Sculpt3::None, Sculpt3::None, Sculpt3::TwoFace, Sculpt3::Bridges};
  o.sculpt = sculpts[b & 3];
  if (b & 0x04) {
    const Refine3 refines[] = {Refine3::None, Refine3::Area, Refine3::Circumradius, Refine3::Alternate};
    o.refine = refines[(b >> 3) & 3];
  }
  if (b & 0x20) o.two_face_key = o.two_face_key == TwoFaceKey::Sum ? TwoFaceKey::Max : TwoFaceKey::Sum;
  if (b & 0x40) o.max_cavity_tets = 8;  // a tight fallback: more locks survive to the end
  return o;
}

void check_mesh(const PointSet& p, const Mesh3Result& r) {
  MeshCheckOptions mo;
  mo.require_all_points = r.complete;
  mo.self_intersections = true;
  MeshCheck c;
  const Status v = validate_mesh3(p, r.mesh, &c, mo);
  require(v.is_ok(), "validate_mesh3 refuses the result", v.message());
  std::vector<int> seen(p.size(), 0);
  for (const auto& t : r.mesh.triangles)
    for (int v3 : t) seen[static_cast<std::size_t>(v3)] = 1;
  if (r.complete) {
    require(r.valid(), "complete Ok result not valid()");
    require(r.unplaced_points.empty(), "complete but unplaced points listed");
    return;
  }
  for (int u : r.unplaced_points) {
    require(u >= 0 && static_cast<std::size_t>(u) < p.size(), "unplaced point out of range");
    require(seen[static_cast<std::size_t>(u)]++ == 0, "unplaced point on the surface or repeated");
  }
  require(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }),
          "surface and unplaced points do not cover the input");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // One thread: one fuzzer uses one core (the variants run in parallel otherwise), and the
  // variant choice does not depend on the thread count (variants3.cpp).
  static tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  constrict_fuzz::Bytes in(data, size);
  const Constrict3Options options = decode_options(in);
  const constrict_fuzz::Decoded d = constrict_fuzz::decode_points(in, 3);
  constrict_fuzz::print_points(d);
  const PointSet& p = d.points;

  Status checked, st;
  Mesh3Result r;
  constrict_fuzz::no_throw("reconstruct3", [&] {
    checked = check_points(p);
    st = reconstruct3(p, options, r);
  });
  if (!constrict_fuzz::engine3_status(p, checked, st)) return 0;
  constrict_fuzz::no_throw("checks", [&] { check_mesh(p, r); });
  return 0;
}
