// SPDX-License-Identifier: GPL-3.0-or-later
// The shared 3D models (../shared/data/3d, README there): every model, in scope or not, gives a
// valid closed genus-0 surface through all points. Prints lock counts, fallback work and the share
// of ground-truth triangles recovered (docs/reconstruction-3d.md). Skips when the data is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "constrict/constrict3.hpp"
#include "constrict/io.hpp"
#include "constrict/mesh.hpp"

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

void run_model(const std::string& name) {
  const std::string xyz = kDir + name + ".xyz";
  if (!exists(xyz)) GTEST_SKIP() << "shared data not found: " << xyz;
  SCOPED_TRACE(name);
  PointSet p;
  ReadOptions ro;
  ro.dim = 3;
  ASSERT_TRUE(read_points(xyz, ro, p).is_ok());
  Mesh3Result r;
  ASSERT_TRUE(reconstruct3(p, {}, r).is_ok());  // validates internally (throws on a bug)
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
  std::size_t hit = 0, total = 0;
  if (exists(kDir + name + "_gt.off"))
    for (auto t : read_gt_faces(kDir + name + "_gt.off")) {
      std::sort(t.begin(), t.end());
      hit += ours.count(t);
      ++total;
    }
  char line[512];
  std::snprintf(line, sizeof line,
                "[ model ] %s: N %zu, locked %d, stuck %zu, cavities %zu/%zu, one-face %zu, two-face %zu, "
                "GT triangles recovered %.1f%%, ms delaunay %.0f constrict %.0f fallback %.0f validate %.0f",
                name.c_str(), p.size(), int(r.locked), r.stuck_points.size(), r.cavities, r.cavity_attempts,
                r.removed_one_face, r.removed_two_face, total ? 100.0 * double(hit) / double(total) : 0.0,
                r.ms_delaunay, r.ms_constrict, r.ms_fallback, r.ms_validate);
  std::cout << line << "\n";
}

// Small and medium models (≈ 1 s in Release together); the 34k-134k models run in the benchmark
// script of docs/reconstruction-3d.md.
TEST(Constrict3Models, KnightSparse) { run_model("knight_sparse"); }
TEST(Constrict3Models, Spot) { run_model("spot"); }
TEST(Constrict3Models, BunnyClosed) { run_model("bunny_closed"); }
TEST(Constrict3Models, Elephant) { run_model("elephant"); }
TEST(Constrict3Models, Fandisk) { run_model("fandisk"); }
TEST(Constrict3Models, RockerArmGenus1OutOfScope) { run_model("rocker_arm_genus1"); }
#ifdef NDEBUG
TEST(Constrict3Models, BunnyScanOpenOutOfAssumption) { run_model("bunny_scan_open"); }
TEST(Constrict3Models, Armadillo) { run_model("armadillo"); }
TEST(Constrict3Models, Horse) { run_model("horse"); }
#endif

}  // namespace
}  // namespace constrict
