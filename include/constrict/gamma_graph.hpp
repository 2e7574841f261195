// SPDX-License-Identifier: GPL-3.0-or-later
/// @file gamma_graph.hpp
/// @brief γ-values of simplices and the γ-neighborhood graph family (Veltkamp 1992; seed paper §3;
/// ../shared/spec/gamma-graph.md §1-§2, §4). Conventions are in docs/gamma-graph.md.
///
/// A *face* is a candidate simplex of k points (an edge in 2D, a triangle in 3D), stored with its
/// vertex ids sorted ascending. Its two *side values* γ_a, γ_b are the largest γ for which the
/// cap on that side is empty (spec §2.1): side a is the positive side,
///   2D, face (i,j):   points p with orient2(x_i, x_j, p) > 0 (left of i->j),
///   3D, face (i,j,k): points p with orient3(x_i, x_j, x_k, p) > 0.
/// A side with no point has value 1. A face is *blocked* when a point lies in the open segment
/// (2D) / open circumdisc (3D); a blocked face is in no graph. The filtration value
/// Δ = the side value of larger magnitude (ties: the larger) gives γ([-1,1],[β,1]) = {Δ ≥ β}.
/// Signs of all values are decided with exact predicates; magnitudes are doubles.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "constrict/delaunay.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

/// Flags of a face (bit set).
enum FaceFlag : std::uint8_t {
  kFaceDelaunay = 1,  ///< face of the computed Delaunay triangulation
  kFaceHull = 2,      ///< convex hull facet (one side empty)
  kFaceBlocked = 4,   ///< a point lies in the open segment / circumdisc
  kFaceCospherical = 8,  ///< added by the co-circular / co-spherical completion (not a DT face)
};

/// A list of faces with their γ-values (structure of arrays).
struct GammaFaces {
  int dim = 2;                       ///< 2: faces are edges (2 ids); 3: triangles (3 ids)
  std::vector<int> vertices;         ///< dim ids per face, ascending
  std::vector<double> gamma_a;       ///< side value, positive side
  std::vector<double> gamma_b;       ///< side value, negative side
  std::vector<double> delta;         ///< filtration value Δ
  std::vector<std::uint8_t> flags;   ///< FaceFlag bits

  std::size_t size() const noexcept { return gamma_a.size(); }
  /// Vertex id @p j (0 <= j < dim) of face @p f.
  int vertex(std::size_t f, int j) const noexcept { return vertices[static_cast<std::size_t>(dim) * f + static_cast<std::size_t>(j)]; }
  void clear() { vertices.clear(); gamma_a.clear(); gamma_b.clear(); delta.clear(); flags.clear(); }
  void reserve(std::size_t n);
  /// Appends a face. @p ids must hold dim ascending ids.
  void push_back(const int* ids, double ga, double gb, std::uint8_t flag);
};

/// Δ of a face from its side values (spec §2.2): the larger-magnitude value, ties -> the max.
double filtration_value(double gamma_a, double gamma_b) noexcept;

/// Apex value γ(ab; p) in 2D (spec §2.1): sign((a-p).(b-p)) * (1 - sin∠apb). Sign exact.
/// @pre p not on the line ab.
double apex_gamma2(const double* a, const double* b, const double* p) noexcept;

/// Apex value γ(abc; p) in 3D: sign(|p-c|^2 - r^2) * (1 - r/R), r = circumradius of abc,
/// R = circumradius of abcp. Sign exact. @pre p not in the plane abc; abc not collinear.
double apex_gamma3(const double* a, const double* b, const double* c, const double* p) noexcept;

/// The Delaunay triangulation with the γ-values of all its faces.
/// faces = the faces of γ([-1,1],[0,1]): every DT face, plus (degenerate input) every further
/// k-subset of points on a common empty circle/sphere (spec §1.4, §3.8; docs/gamma-graph.md).
/// simplex_face[t][i] = index in faces of the face of simplex t opposite its vertex i.
struct DelaunayGamma2 {
  Delaunay2 dt;
  GammaFaces faces;
  std::vector<std::array<int, 3>> simplex_face;
};
struct DelaunayGamma3 {
  Delaunay3 dt;
  GammaFaces faces;
  std::vector<std::array<int, 4>> simplex_face;
};

/// Builds the DT and computes (γ_a, γ_b, Δ) of every face in O(1) each (spec §2.3), then adds the
/// co-circular completion. @pre check_points(points) is Ok and points.dim == 2.
/// @note O(N log N) expected (2D); the completion costs O(m^2) per co-circular cluster of m points.
Status delaunay_gamma2(const PointSet& points, DelaunayGamma2& out);
/// 3D version; the completion adds all non-collinear triples of each co-spherical cluster.
/// With complete_degenerate = false the completion is skipped: faces holds the DT faces only
/// (what the constriction reads, through simplex_face). Its cost is cubic in the size of a
/// co-spherical cluster, so a sphere sampled exactly needs this (docs/reconstruction-3d.md §2).
Status delaunay_gamma3(const PointSet& points, DelaunayGamma3& out, bool complete_degenerate = true);

/// Parameters of a graph of the family.
struct GraphSpec {
  enum class Kind { Fixed, Interval };
  Kind kind = Kind::Interval;
  double g0 = -1, g1 = 1;                  ///< Fixed: γ(g0, g1), any pair in [-1,1]^2 (cap form)
  double a0 = -1, a1 = 1, b0 = 0, b1 = 1;  ///< Interval: γ([a0,a1],[b0,b1]) (magnitude-ordered)

  static GraphSpec fixed(double g0, double g1);
  static GraphSpec interval(double a0, double a1, double b0, double b1);
  /// Parses a preset: hull, delaunay, gabriel, beta-circle=B (B >= 1), beta-lune=B (0 < B <= 1),
  /// complete, void. @return InvalidArgument with a one-line reason on a bad name or value.
  static Status from_preset(std::string_view preset, GraphSpec& out);
  /// Checks the ranges (all values finite, in [-1,1], intervals non-empty).
  Status validate() const;
  /// Human readable, e.g. "gamma(0,0)" or "gamma([-1,1],[0,1])".
  std::string describe() const;
  /// Smallest side value a member face can have; when >= 0 the graph is a subgraph of the
  /// Delaunay graph γ([-1,1],[0,1]) and is computed from the DT alone.
  double min_side_value() const noexcept;
  /// True iff the graph is a subgraph of γ([-1,1],[0,1]) (Delaunay route).
  bool delaunay_subgraph() const noexcept;
};

/// Membership of a face with side values (ga, gb) in the graph (cap criterion, spec §1.3, §2.2).
bool in_graph(const GraphSpec& spec, double gamma_a, double gamma_b, bool blocked) noexcept;

/// Counters and timings of build_gamma_graph().
struct GraphStats {
  std::size_t delaunay_faces = 0;   ///< faces of γ([-1,1],[0,1]) examined
  std::size_t extra_candidates = 0; ///< non-Delaunay candidates tested (γ < 0 graphs)
  std::size_t faces = 0;            ///< faces in the result
  double ms_delaunay = 0, ms_gamma = 0, ms_extra = 0;
};

/// Builds any graph of the family. Graphs with delaunay_subgraph() are filtered from the DT
/// faces in O(N log N) (2D); the others add the non-Delaunay faces whose lens
/// C+(m) ∪ C-(m) ∪ D (m = min_side_value()) is empty, found with a k-d tree (docs/gamma-graph.md
/// states the complexity).
/// @param[out] out the member faces with their exact side values, sorted by vertex ids
Status build_gamma_graph(const PointSet& points, const GraphSpec& spec, GammaFaces& out,
                         GraphStats* stats = nullptr);

/// Reference oracle (spec §4.1): side values of every k-subset of points, by scanning all
/// points. O(N^(k+1)); meant for tests and small inputs (refuses N > 400 in 2D, N > 80 in 3D
/// with Unsupported). Collinear triples in 3D are skipped.
/// @param[out] out all faces (blocked ones flagged), sorted by vertex ids
Status brute_force_gamma_faces(const PointSet& points, GammaFaces& out);

/// Side values of one face by scanning all points (O(N)); @p ids has points.dim entries.
/// @param[out] blocked set when a point lies in the open segment / circumdisc
void side_values_scan(const PointSet& points, const int* ids, double& gamma_a, double& gamma_b,
                      bool& blocked);

}  // namespace constrict
