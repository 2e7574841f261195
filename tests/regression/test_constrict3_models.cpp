// SPDX-License-Identifier: GPL-3.0-or-later
// The shared 3D models (../shared/data/3d, README there): every model, in scope or not, gives a
// valid closed genus-0 surface through all points. Prints lock counts, fallback work and the share
// of ground-truth triangles recovered (docs/reconstruction-3d.md). Skips when the data is absent.
#include <gtest/gtest.h>

#include <cstdlib>

#include <algorithm>
#include <cmath>
#include <array>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "constrict/compare.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/io.hpp"
#include "constrict/mesh.hpp"
#include "constrict/validate.hpp"
#include "unit/test_fixtures.hpp"

namespace constrict {
namespace {

const std::string kDir = std::string(CONSTRICT_SHARED_DIR) + "/data/3d/";

bool exists(const std::string& path) {
  std::ifstream f(path);
  return f.good();
}

// Faces of the ground-truth OFF (its vertex i is input point i).
std::vector<std::array<int, 3>> read_gt_faces(const std::string& path) {
  std::ifstream f(path);
  std::string head;
  f >> head;
  long long nv = 0, nf = 0, ne = 0;
  f >> nv >> nf >> ne;
  for (long long i = 0; i < nv; ++i) {
    double x, y, z;
    f >> x >> y >> z;
  }
  std::vector<std::array<int, 3>> faces;
  for (long long i = 0; i < nf; ++i) {
    int k = 0;
    std::array<int, 3> t{};
    f >> k >> t[0] >> t[1] >> t[2];
    if (k == 3) faces.push_back(t);
  }
  return faces;
}

struct Row {
  std::size_t n = 0, stuck = 0, added = 0, removed = 0;
  bool locked = false, complete = false;
  double recovered = 0, area_ratio = 0, volume_ratio = 0;
  double ms_delaunay = 0, ms_constrict = 0, ms_fallback = 0, ms_refine = 0, ms_validate = 0;
};

// Runs one model, checks validity, compares with the ground truth (exact vertex triples, area,
// volume). Returns false when the data is absent.
bool evaluate(const std::string& name, const Constrict3Options& options, Row& row) {
  const std::string xyz = kDir + name + ".xyz";
  if (!exists(xyz)) return false;
  SCOPED_TRACE(name);
  PointSet p;
  ReadOptions ro;
  ro.dim = 3;
  EXPECT_TRUE(read_points(xyz, ro, p).is_ok());
  Mesh3Result r;
  EXPECT_TRUE(reconstruct3(p, options, r).is_ok());  // validates internally (throws on a bug)
  EXPECT_TRUE(r.complete) << r.unplaced_points.size() << " points unplaced";
  MeshCheck mc;
  EXPECT_TRUE(validate_mesh3(p, r.mesh, &mc).is_ok()) << mc.reason;
  EXPECT_EQ(mc.genus, 0);
  EXPECT_EQ(r.mesh.triangles.size(), 2 * p.size() - 4);
  std::set<std::array<int, 3>> ours;
  for (auto t : r.mesh.triangles) {
    std::sort(t.begin(), t.end());
    ours.insert(t);
  }
  std::size_t hit = 0;
  TriMesh3 gt;
  if (exists(kDir + name + "_gt.off"))
    for (auto t : read_gt_faces(kDir + name + "_gt.off")) {
      gt.triangles.push_back(t);
      std::sort(t.begin(), t.end());
      hit += ours.count(t);
    }
  row = Row{};
  row.n = p.size();
  row.locked = r.locked;
  row.complete = r.complete;
  row.stuck = r.stuck_points.size();
  row.added = r.refine_added;
  row.removed = r.refine_removed;
  if (!gt.triangles.empty()) {
    row.recovered = 100.0 * double(hit) / double(gt.triangles.size());
    row.area_ratio = r.surface_area / mesh_area(p, gt);
    row.volume_ratio = r.volume / std::abs(mesh_volume(p, gt));
  }
  row.ms_delaunay = r.ms_delaunay;
  row.ms_constrict = r.ms_constrict;
  row.ms_fallback = r.ms_fallback;
  row.ms_refine = r.ms_refine;
  row.ms_validate = r.ms_validate;
  return true;
}

std::string format_row(const std::string& name, const std::string& config, const Row& w) {
  char line[512];
  std::snprintf(line, sizeof line,
                "| %s | %s | %zu | %s | %zu | %.1f %% | %.2f | %.3f | %zu/%zu | %.0f | %.0f | %.0f | %.0f | %.0f |",
                name.c_str(), config.c_str(), w.n, w.locked ? "yes" : "no", w.stuck, w.recovered, w.area_ratio,
                w.volume_ratio, w.added, w.removed, w.ms_delaunay, w.ms_constrict, w.ms_fallback, w.ms_refine,
                w.ms_validate);
  return line;
}

// Default options; `floor`: minimum share of GT triangles recovered (measured, minus a margin).
void run_model(const std::string& name, double floor) {
  Row w;
  if (!evaluate(name, {}, w)) GTEST_SKIP() << "shared data not found: " << name;
  std::cout << "[ model ] " << format_row(name, "default", w) << "\n";
  EXPECT_GE(w.recovered, floor) << name << ": GT recovery regressed";
}

// The carve pass (docs/reconstruction-3d.md §4.6) removes the bridges the constriction leaves on
// these models: it keeps some removals, the surface stays valid through every point, and the
// area drops against the same run without the pass (measured: elephant 1.05 -> 1.00 x GT,
// bunny 1.02 -> 1.00, spot 1.00 -> 1.00 with Hausdorff 1.0 % -> 0.45 %).
TEST(Constrict3Models, CarveRemovesBridges) {
  for (const char* name : {"elephant", "bunny_closed", "spot"}) {
    SCOPED_TRACE(name);
    const std::string xyz = kDir + name + ".xyz";
    if (!exists(xyz)) GTEST_SKIP() << "shared data not found: " << name;
    PointSet p;
    ReadOptions ro;
    ro.dim = 3;
    ASSERT_TRUE(read_points(xyz, ro, p).is_ok());
    Constrict3Options on, off;
    on.grow = off.grow = false;  // the carve follows the constriction from the hull
    off.carve_confidence = 2;
    Mesh3Result a, b;
    ASSERT_TRUE(reconstruct3(p, on, a).is_ok());
    ASSERT_TRUE(reconstruct3(p, off, b).is_ok());
    EXPECT_GT(a.carved, 0u);
    EXPECT_EQ(b.carved, 0u);
    EXPECT_EQ(b.ms_carve, 0.0);
    MeshCheck mc;
    EXPECT_TRUE(validate_mesh3(p, a.mesh, &mc).is_ok()) << mc.reason;
    EXPECT_EQ(mc.genus, 0);
    EXPECT_EQ(a.mesh.triangles.size(), 2 * p.size() - 4);
    EXPECT_LT(a.surface_area, b.surface_area);
    std::cout << "[ carve ] " << name << ": kept " << a.carved << ", undone " << a.carve_undone << ", area "
              << b.surface_area << " -> " << a.surface_area << "\n";
  }
}

// The comparison table of docs/reconstruction-3d.md: every option combination on every model.
// Run with --gtest_also_run_disabled_tests --gtest_filter='*Constrict3Eval*'.
TEST(Constrict3Eval, DISABLED_Table) {
  struct Config {
    const char* name;
    TwoFaceKey key;
    Refine3 refine;
    Sculpt3 sculpt = Sculpt3::None;
    double bridge_ratio = 0;
    double size_bias = 0;
    double label_weight = 0;
  };
  const Config configs[] = {{"sum", TwoFaceKey::Sum, Refine3::None},
                            {"max", TwoFaceKey::Max, Refine3::None},
                            {"sum+area", TwoFaceKey::Sum, Refine3::Area},
                            {"max+area", TwoFaceKey::Max, Refine3::Area},
                            {"sum+circ", TwoFaceKey::Sum, Refine3::Circumradius},
                            {"max+circ", TwoFaceKey::Max, Refine3::Circumradius},
                            {"sum+alt", TwoFaceKey::Sum, Refine3::Alternate},
                            {"max+alt", TwoFaceKey::Max, Refine3::Alternate},
                            {"max+br3+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::Bridges, 3},
                            {"max+br4+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::Bridges, 4},
                            {"max+br6+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::Bridges, 6},
                            {"max+br10+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::Bridges, 10},
                            {"max+sb0.25+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 0.25},
                            {"max+sb0.5+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 0.5},
                            {"max+sb1+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 1},
                            {"max+sb2+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 2},
                            {"max+sb0.5", TwoFaceKey::Max, Refine3::None, Sculpt3::None, 0, 0.5},
                            {"max+sb1", TwoFaceKey::Max, Refine3::None, Sculpt3::None, 0, 1},
                            {"auto", TwoFaceKey::Max, Refine3::Alternate},
                            {"max+sb0.25+lw1+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 0.25, 1},
                            {"max+sb1+lw1+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 1, 1},
                            {"max+sb0+lw1+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 0, 1},
                            {"max+sb2+lw1+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 2, 1},
                            {"max+sb1+lw2+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 1, 2},
                            {"max+sb0.5+lw1+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 0.5, 1},
                            {"max+sb3+lw0+alt", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 3, 0},
                            {"auto+lw0.5", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 0, 0.5},
                            {"auto+lw1", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 0, 1},
                            {"auto+lw2", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 0, 2},
                            {"auto+lw4", TwoFaceKey::Max, Refine3::Alternate, Sculpt3::None, 0, 0, 4}};
  // CONSTRICT_EVAL_CONFIGS=name,name,... restricts the table to those configurations.
  const char* only = std::getenv("CONSTRICT_EVAL_CONFIGS");
  const std::string filter = only ? "," + std::string(only) + "," : "";
  std::cout << "| model | config | N | locked | stuck | GT recovered | area/GT | volume/GT | refine added/removed"
               " | ms Delaunay+γ | ms constrict | ms fallback | ms refine | ms validate |\n";
  for (const char* name : {"knight_sparse", "spot", "bunny_closed", "elephant", "fandisk", "armadillo", "horse"})
    for (const auto& c : configs) {
      if (!filter.empty() && filter.find("," + std::string(c.name) + ",") == std::string::npos) continue;
      Constrict3Options o;
      o.two_face_key = c.key;
      o.refine = c.refine;
      o.sculpt = c.sculpt;
      if (c.bridge_ratio > 0) o.bridge_ratio = c.bridge_ratio;
      o.size_bias = c.size_bias;
      o.variants.clear();
      if (std::string(c.name).rfind("auto", 0) == 0) o = Constrict3Options{};
      o.label_weight = c.label_weight;
      Row w;
      if (evaluate(name, o, w)) std::cout << format_row(name, c.name, w) << std::endl;
    }
}

// Small and medium models (≈ 1 s in Release together); the 34k-134k models run in the benchmark
// script of docs/reconstruction-3d.md.
TEST(Constrict3Models, KnightSparse) { run_model("knight_sparse", 57.5); }
TEST(Constrict3Models, Spot) { run_model("spot", 89.5); }
TEST(Constrict3Models, BunnyClosed) { run_model("bunny_closed", 69.5); }
TEST(Constrict3Models, Elephant) { run_model("elephant", 83.5); }
TEST(Constrict3Models, Fandisk) { run_model("fandisk", 84.5); }
TEST(Constrict3Models, RockerArmGenus1OutOfScope) { run_model("rocker_arm_genus1", 86.5); }
#ifdef NDEBUG
TEST(Constrict3Models, BunnyScanOpenOutOfAssumption) { run_model("bunny_scan_open", 90.5); }
TEST(Constrict3Models, Armadillo) { run_model("armadillo", 83.5); }
// 134k points, ≈ 3 s: run on demand (--gtest_also_run_disabled_tests).
TEST(Constrict3Models, DISABLED_Igea) { run_model("igea", 88.5); }
TEST(Constrict3Models, Horse) { run_model("horse", 90.5); }

// Random halves of the models (each point kept with probability 1/2, splitmix64 of its index and
// the seed): parts come within a few spacings of each other (ears, legs), which made the growth
// reach points across the gaps and leave pockets the fill could not take (issue 17,
// docs/reconstruction-3d.md §4.9). Hausdorff distance to the full ground truth ÷ its diagonal, %.
double half_hausdorff(const std::string& name, std::uint64_t seed) {
  const std::string xyz = kDir + name + ".xyz";
  if (!exists(xyz) || !exists(kDir + name + "_gt.off")) return -1;
  PointSet all, half;
  ReadOptions ro;
  ro.dim = 3;
  EXPECT_TRUE(read_points(xyz, ro, all).is_ok());
  half.dim = 3;
  std::uint64_t s = seed;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (test::splitmix64(s) >> 63) half.coords.insert(half.coords.end(), all[i], all[i] + 3);
  TriMesh3 gt;
  for (auto t : read_gt_faces(kDir + name + "_gt.off")) gt.triangles.push_back(t);
  Mesh3Result r;
  EXPECT_TRUE(reconstruct3(half, {}, r).is_ok());
  EXPECT_TRUE(r.complete);
  MeshCheck mc;
  EXPECT_TRUE(validate_mesh3(half, r.mesh, &mc).is_ok()) << mc.reason;
  EXPECT_EQ(mc.genus, 0);
  MeshDistance d;
  EXPECT_TRUE(compare_meshes3(half, r.mesh, all, gt, d).is_ok());
  std::cout << "[ half ] " << name << " seed " << seed << ": " << half.size() << " points, Hausdorff "
            << 100 * d.relative_hausdorff << " %, bridge faces " << r.bridge_faces << "\n";
  return 100 * d.relative_hausdorff;
}

TEST(Constrict3Models, RandomHalvesHaveNoBridges) {
  struct Case {
    const char* name;
    std::uint64_t seed;
    double bound;  // % of the diagonal
  };
  // Measured: bunny_closed seed 2 7.36 / 2.32, horse seed 3 1.86 / 1.56, armadillo seed 1 0.52 / 0.52
  // (before / after the size-first growth order and the fill's local repair).
  const Case cases[] = {{"bunny_closed", 2, 4.0}, {"horse", 3, 1.7}, {"armadillo", 1, 0.8}};
  for (const Case& c : cases) {
    const double h = half_hausdorff(c.name, c.seed);
    if (h < 0) GTEST_SKIP() << "shared data not found: " << c.name;
    EXPECT_LT(h, c.bound) << c.name << " seed " << c.seed;
  }
}

// Growth from the inside (docs/reconstruction-3d.md §4.7) against the constriction from the hull
// on the horse, whose legs the constriction joins by bridges: the growth reaches every point,
// and its Hausdorff distance to the ground truth (relative to the bounding-box diagonal) is far
// below the constriction's (measured 0.54 % against 13.9 %).
TEST(Constrict3Models, GrowthRemovesTheHorseBridges) {
  const std::string xyz = kDir + "horse.xyz";
  if (!exists(xyz) || !exists(kDir + "horse_gt.off")) GTEST_SKIP() << "shared data not found: horse";
  PointSet p;
  ReadOptions ro;
  ro.dim = 3;
  ASSERT_TRUE(read_points(xyz, ro, p).is_ok());
  TriMesh3 gt;
  for (auto t : read_gt_faces(kDir + "horse_gt.off")) gt.triangles.push_back(t);
  Constrict3Options grow, hull;
  hull.grow = false;
  hull.variants = {{1.0, 1.0}};
  Mesh3Result a, b;
  ASSERT_TRUE(reconstruct3(p, grow, a).is_ok());
  ASSERT_TRUE(reconstruct3(p, hull, b).is_ok());
  EXPECT_STREQ(to_string(a.method), "grow");
  EXPECT_TRUE(a.complete);
  EXPECT_GT(a.grown, 0u);
  EXPECT_EQ(b.grown, 0u);
  MeshDistance da, db;
  ASSERT_TRUE(compare_meshes3(p, a.mesh, p, gt, da).is_ok());
  ASSERT_TRUE(compare_meshes3(p, b.mesh, p, gt, db).is_ok());
  std::cout << "[ grow ] horse: Hausdorff " << 100 * da.relative_hausdorff << " % (hull: "
            << 100 * db.relative_hausdorff << " %), area " << a.surface_area << " (hull: " << b.surface_area << ")\n";
  EXPECT_LT(da.relative_hausdorff, 0.01);
  EXPECT_GT(db.relative_hausdorff, 0.05);
  EXPECT_LT(a.surface_area, 0.6 * b.surface_area);
}
#endif

}  // namespace
}  // namespace constrict
