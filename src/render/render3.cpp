// SPDX-License-Identifier: GPL-3.0-or-later
// 3D software rasteriser (render.hpp): orthographic views, a per-pixel depth buffer, flat Lambert
// shading, wireframe from the visible triangle's edge distances. The image is cut into bands of
// rows; every band scans the triangles binned to it in index order, so each pixel's winner (nearest
// depth, ties to the lower triangle) does not depend on the thread schedule.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "constrict/predicates.hpp"
#include "constrict/render.hpp"
#include "core/detail/check_points.hpp"

namespace constrict {
namespace {

constexpr int kBand = 16;        // rows per band
constexpr double kPi = 3.14159265358979323846;

struct Vec {
  double x, y, z;
};
Vec sub(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec cross(Vec a, Vec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec scale(Vec a, double s) { return {a.x * s, a.y * s, a.z * s}; }
Vec add(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec unit(Vec a) {
  const double l = std::sqrt(dot(a, a));
  return l > 0 ? scale(a, 1.0 / l) : a;
}

struct Camera {
  Vec dir, right, up;  // dir points from the scene to the viewer
};

Camera camera(const View& v) {
  // (The angles reduced to a turn first, exactly: 6e307 degrees times pi overflowed to inf, a
  // blank picture; within a turn fmod changes nothing.)
  const double az = std::fmod(v.azimuth, 360.0) * kPi / 180, el = std::fmod(v.elevation, 360.0) * kPi / 180;
  Camera c;
  c.dir = {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
  c.right = {-std::sin(az), std::cos(az), 0};
  c.up = cross(c.dir, c.right);
  return c;
}

// A triangle projected to the screen, ready for the bands.
struct Screen {
  double x[3], y[3], z[3];
  double area;               // edge(A, B, C) in pixels² (signed)
  int x0, x1, y0, y1;        // pixel bounding box, clipped to the cell (inclusive)
  std::array<std::uint8_t, 3> color;
};

inline double edge(double ax, double ay, double bx, double by, double px, double py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// Cyclic axis permutation that brings the up axis to z (orientation preserving).
struct UpFrame {
  const PointSet& points;
  int ax, ay, az;
  UpFrame(const PointSet& p, int up_axis) : points(p), ax((up_axis + 1) % 3), ay((up_axis + 2) % 3), az(up_axis) {}
  Vec operator()(std::size_t i) const {
    const double* q = points[i];
    return Vec{q[ax], q[ay], q[az]};
  }
};

// The bounding sphere (box centre, half diagonal) of a set of vertices: one frame for all panels.
struct Sphere {
  Vec centre;
  double radius;
};

// The sheet: cols x rows cells over a W x H image, panel p in cell (p % cols, p / cols).
struct Sheet {
  int cols, rows, W, H;
};

// The pixel columns [x0, x1) and rows [y0, y1) of one sheet cell.
struct Cell {
  int x0, x1, y0, y1;
};

Cell cell_of(const Sheet& g, int p) {
  return {(p % g.cols) * g.W / g.cols, (p % g.cols + 1) * g.W / g.cols, (p / g.cols) * g.H / g.rows,
          (p / g.cols + 1) * g.H / g.rows};
}

// The stages of render_sheet3, in order (defined after it).
Status mark_used(const PointSet& pts, const std::vector<Panel3>& panels, std::vector<char>& used);
Sphere bounding_sphere(const UpFrame& at, const std::vector<char>& used);
void project_panel(const Panel3& pan, const Cell& cell, const UpFrame& at, const Sphere& frame, const RenderOptions3& o,
                   Screen* tris, char* live);
std::vector<std::vector<std::uint32_t>> bin_to_bands(const std::vector<Screen>& tris, const std::vector<char>& live, int nb);
void rasterise_band(const std::vector<Screen>& tris, const std::vector<std::uint32_t>& bin, int by0, int by1, int W,
                    std::vector<double>& depth, std::vector<std::int64_t>& id);
void shade_band(const std::vector<Screen>& tris, const std::vector<std::int64_t>& id, int by0, int by1,
                const RenderOptions3& o, double half, Image& out);
void draw_separators(const Sheet& g, const RenderOptions3& o, Image& out);

// A triangle repeated with the same orientation (the same vertices from the same cyclic start
// up) projects to the same pixels, depth and colour, and the first of them wins every pixel
// (the depth test is strict): the others are not drawn. (A mesh of one face repeated 3·10^5
// times, each covering the picture, took minutes.) Same picture.
void skip_repeats(const TriMesh3& mesh, char* live) {
  const auto& T = mesh.triangles;
  std::vector<std::pair<std::array<int, 3>, std::size_t>> keys;
  keys.reserve(T.size());
  for (std::size_t t = 0; t < T.size(); ++t) {
    if (!live[t]) continue;
    const auto& v = T[t];
    const int k = v[0] <= v[1] && v[0] <= v[2] ? 0 : v[1] <= v[2] ? 1 : 2;  // rotate the smallest first
    keys.push_back({{v[static_cast<std::size_t>(k)], v[static_cast<std::size_t>((k + 1) % 3)], v[static_cast<std::size_t>((k + 2) % 3)]}, t});
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (keys[i].first == keys[i - 1].first) live[keys[i].second] = 0;
}

}  // namespace

Status render_sheet3(const PointSet& points, const std::vector<Panel3>& panels, const RenderOptions3& o, Image& out) {
  if (points.dim != 3) return {StatusCode::InvalidArgument, "render: a 3D picture needs 3D points"};
  if (Status f = detail::check_finite(points, "render"); !f) return f;
  if (panels.empty()) return {StatusCode::InvalidArgument, "render: nothing to draw (no panel)"};
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
    return {StatusCode::InvalidArgument, "render: image size must be in [1, 16384]"};
  if (!(o.ambient >= 0 && o.ambient <= 1) || !(o.edge_width > 0) || o.columns < 0 || o.up_axis < 0 || o.up_axis > 2)
    return {StatusCode::InvalidArgument, "render: ambient in [0, 1], edge width > 0, columns >= 0, up axis 0..2"};
  std::vector<char> used(points.size(), 0);
  if (Status s = mark_used(points, panels, used); !s) return s;
  // Far from 1 in magnitude the normals' cross products overflow or underflow (a blank or flat
  // picture): the picture of the points times 2^-e (e the largest exponent of the vertices drawn;
  // an unused vertex at 1e100 had scaled a unit mesh to 1e-100, blank) is the same.
  if (const int e = max_coordinate_exponent(points, used); e > kRescaleExponent || e < -kRescaleExponent) {
    return render_sheet3(scaled_by_power_of_two(points, -e), panels, o, out);
  }
  const UpFrame at(points, o.up_axis);
  const Sphere frame = bounding_sphere(at, used);

  const int P = static_cast<int>(panels.size());
  const int cols = o.columns > 0 ? std::min(o.columns, P) : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(P))));
  const Sheet sheet{cols, (P + cols - 1) / cols, o.width, o.height};
  const int W = sheet.W, H = sheet.H;

  // Project every panel's triangles; panel p's start at first[p].
  std::vector<Screen> tris;
  std::vector<std::size_t> first(static_cast<std::size_t>(P) + 1, 0);
  for (int p = 0; p < P; ++p) first[static_cast<std::size_t>(p) + 1] = first[static_cast<std::size_t>(p)] + panels[static_cast<std::size_t>(p)].mesh->triangles.size();
  tris.resize(first.back());
  std::vector<char> live(tris.size(), 0);
  for (int p = 0; p < P; ++p) {
    const std::size_t base = first[static_cast<std::size_t>(p)];
    project_panel(panels[static_cast<std::size_t>(p)], cell_of(sheet, p), at, frame, o, tris.data() + base, live.data() + base);
    skip_repeats(*panels[static_cast<std::size_t>(p)].mesh, live.data() + base);
  }

  const int nb = (H + kBand - 1) / kBand;
  const std::vector<std::vector<std::uint32_t>> bins = bin_to_bands(tris, live, nb);
  const std::size_t npix = static_cast<std::size_t>(W) * static_cast<std::size_t>(H);
  out.width = W;
  out.height = H;
  out.rgb.assign(3 * npix, 0);
  const double half = 0.5 * o.edge_width + 0.5;
  // The depth buffer and the winners of one band at a time (a band reads and writes only its own
  // rows): the whole picture's were 16 bytes a pixel, 4.3 GB at 16384 x 16384.
  tbb::parallel_for(tbb::blocked_range<int>(0, nb, 1), [&](const tbb::blocked_range<int>& r) {
    std::vector<double> depth;
    std::vector<std::int64_t> id;
    for (int b = r.begin(); b != r.end(); ++b) {
      const int by0 = b * kBand, by1 = std::min(H, by0 + kBand) - 1;
      const std::size_t cells = static_cast<std::size_t>(by1 - by0 + 1) * static_cast<std::size_t>(W);
      depth.assign(cells, -std::numeric_limits<double>::infinity());
      id.assign(cells, -1);
      rasterise_band(tris, bins[static_cast<std::size_t>(b)], by0, by1, W, depth, id);
      shade_band(tris, id, by0, by1, o, half, out);
    }
  });
  draw_separators(sheet, o, out);
  return Status::ok();
}

namespace {

// Checks every panel (mesh, view, vertex ids, a proper triangle) and marks the vertices its mesh uses.
Status mark_used(const PointSet& pts, const std::vector<Panel3>& panels, std::vector<char>& used) {
  const std::size_t n = pts.size();
  for (const auto& p : panels) {
    if (!p.mesh) return {StatusCode::InvalidArgument, "render: panel without a mesh"};
    if (!std::isfinite(p.view.azimuth) || !std::isfinite(p.view.elevation))
      return {StatusCode::InvalidArgument, "render: non-finite view angle"};
    for (const auto& t : p.mesh->triangles)
      for (int v : t) {
        if (v < 0 || static_cast<std::size_t>(v) >= n)
          return {StatusCode::InvalidArgument, "render: vertex index " + std::to_string(v) + " out of range"};
        used[static_cast<std::size_t>(v)] = 1;
      }
    // A mesh of degenerate triangles only (points on a line, repeated ids) draws nothing: refused,
    // as compare refuses it, rather than a blank picture (exact test, up to the first proper one).
    const auto proper = [&](const std::array<int, 3>& t) {
      return !collinear3(pts[static_cast<std::size_t>(t[0])], pts[static_cast<std::size_t>(t[1])], pts[static_cast<std::size_t>(t[2])]);
    };
    if (!p.mesh->triangles.empty() && std::none_of(p.mesh->triangles.begin(), p.mesh->triangles.end(), proper))
      return {StatusCode::InvalidArgument,
              "render: the mesh has no triangle with a positive area (every one is degenerate): nothing to draw"};
  }
  return Status::ok();
}

Sphere bounding_sphere(const UpFrame& at, const std::vector<char>& used) {
  double lo[3] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[3] = {-lo[0], -lo[1], -lo[2]};
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) {
      const Vec v = at(i);
      const double c[3] = {v.x, v.y, v.z};
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], c[k]);
        hi[k] = std::max(hi[k], c[k]);
      }
    }
  if (lo[0] > hi[0]) lo[0] = lo[1] = lo[2] = hi[0] = hi[1] = hi[2] = 0;  // only empty meshes
  const Vec centre{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  double radius = 0.5 * std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                  (hi[2] - lo[2]) * (hi[2] - lo[2]));
  if (!(radius > 0)) radius = 1;
  return {centre, radius};
}

// Projects the triangles of one panel into its cell (parallel per triangle, results per index):
// tris[t] and live[t] (a visible, non-degenerate triangle) for triangle t of the panel's mesh.
void project_panel(const Panel3& pan, const Cell& cell, const UpFrame& at, const Sphere& frame, const RenderOptions3& o,
                   Screen* tris, char* live) {
  const Camera cam = camera(pan.view);
  const Vec light = unit(add(add(cam.dir, scale(cam.up, 0.6)), scale(cam.right, -0.4)));
  const int cx0 = cell.x0, cx1 = cell.x1, cy0 = cell.y0, cy1 = cell.y1;
  const double s = 0.94 * std::min(cx1 - cx0, cy1 - cy0) / (2 * frame.radius);
  const double mx = 0.5 * (cx0 + cx1), my = 0.5 * (cy0 + cy1);
  const auto& T = pan.mesh->triangles;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, T.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      Screen& sc = tris[t];
      Vec w[3];
      for (int k = 0; k < 3; ++k) {
        w[k] = at(static_cast<std::size_t>(T[t][static_cast<std::size_t>(k)]));
        const Vec d = sub(w[k], frame.centre);
        sc.x[k] = mx + s * dot(d, cam.right);
        sc.y[k] = my - s * dot(d, cam.up);
        sc.z[k] = dot(d, cam.dir);
      }
      const Vec nrm = cross(sub(w[1], w[0]), sub(w[2], w[0]));
      sc.area = edge(sc.x[0], sc.y[0], sc.x[1], sc.y[1], sc.x[2], sc.y[2]);
      if (!(dot(nrm, nrm) > 0) || sc.area == 0 || !std::isfinite(sc.area)) continue;
      const Vec nu = unit(nrm);
      const bool front = dot(nu, cam.dir) > 0;
      const double shade = o.ambient + (1 - o.ambient) * std::fabs(dot(nu, light));
      const auto& c = front ? o.front : o.back;
      for (int k = 0; k < 3; ++k)
        sc.color[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(std::lround(std::min(255.0, c[static_cast<std::size_t>(k)] * shade)));
      sc.x0 = std::max(cx0, static_cast<int>(std::floor(std::min({sc.x[0], sc.x[1], sc.x[2]}) - 0.5)));
      sc.x1 = std::min(cx1 - 1, static_cast<int>(std::ceil(std::max({sc.x[0], sc.x[1], sc.x[2]}) - 0.5)));
      sc.y0 = std::max(cy0, static_cast<int>(std::floor(std::min({sc.y[0], sc.y[1], sc.y[2]}) - 0.5)));
      sc.y1 = std::min(cy1 - 1, static_cast<int>(std::ceil(std::max({sc.y[0], sc.y[1], sc.y[2]}) - 0.5)));
      live[t] = sc.x0 <= sc.x1 && sc.y0 <= sc.y1;
    }
  });
}

// The live triangles of each band of kBand rows, in index order.
std::vector<std::vector<std::uint32_t>> bin_to_bands(const std::vector<Screen>& tris, const std::vector<char>& live, int nb) {
  std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(nb));
  for (std::size_t t = 0; t < tris.size(); ++t)
    if (live[t])
      for (int b = tris[t].y0 / kBand; b <= tris[t].y1 / kBand; ++b) bins[static_cast<std::size_t>(b)].push_back(static_cast<std::uint32_t>(t));
  return bins;
}

// Depth test of the band's triangles over rows by0..by1: the nearest triangle of each pixel
// (ties to the lower index) in id, its depth in depth (the band's rows only: pixel (x, y) at
// (y - by0) · W + x).
void rasterise_band(const std::vector<Screen>& tris, const std::vector<std::uint32_t>& bin, int by0, int by1, int W,
                    std::vector<double>& depth, std::vector<std::int64_t>& id) {
  for (std::uint32_t t : bin) {
    const Screen& sc = tris[t];
    const double inv = 1.0 / sc.area;
    for (int y = std::max(by0, sc.y0); y <= std::min(by1, sc.y1); ++y) {
      const double py = y + 0.5;
      for (int x = sc.x0; x <= sc.x1; ++x) {
        const double px = x + 0.5;
        const double l0 = edge(sc.x[1], sc.y[1], sc.x[2], sc.y[2], px, py) * inv;
        const double l1 = edge(sc.x[2], sc.y[2], sc.x[0], sc.y[0], px, py) * inv;
        const double l2 = edge(sc.x[0], sc.y[0], sc.x[1], sc.y[1], px, py) * inv;
        if (l0 < 0 || l1 < 0 || l2 < 0) continue;
        const double z = l0 * sc.z[0] + l1 * sc.z[1] + l2 * sc.z[2];
        const std::size_t i = static_cast<std::size_t>(y - by0) * static_cast<std::size_t>(W) + static_cast<std::size_t>(x);
        if (z > depth[i]) {
          depth[i] = z;
          id[i] = t;
        }
      }
    }
  }
}

// The wireframe blend of a pixel centre (px, py) of triangle sc: coverage of the nearest edge
// line, for lines of half width `half` (in pixels, antialiasing included).
double edge_alpha(const Screen& sc, double px, double py, double half) {
  double dmin = std::numeric_limits<double>::max();
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, bb = (k + 2) % 3;
    const double len = std::hypot(sc.x[bb] - sc.x[a], sc.y[bb] - sc.y[a]);
    if (len > 0) dmin = std::min(dmin, std::fabs(edge(sc.x[a], sc.y[a], sc.x[bb], sc.y[bb], px, py)) / len);
  }
  return std::clamp(half - dmin, 0.0, 1.0);
}

// Colours rows by0..by1 from the band's winners in id (as rasterise_band() indexes them): flat
// shade, wireframe blend, or background.
void shade_band(const std::vector<Screen>& tris, const std::vector<std::int64_t>& id, int by0, int by1,
                const RenderOptions3& o, double half, Image& out) {
  const int W = out.width;
  for (int y = by0; y <= by1; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(W) + static_cast<std::size_t>(x);
      const std::int64_t winner = id[static_cast<std::size_t>(y - by0) * static_cast<std::size_t>(W) + static_cast<std::size_t>(x)];
      std::array<std::uint8_t, 3> c = o.background;
      if (winner >= 0) {
        const Screen& sc = tris[static_cast<std::size_t>(winner)];
        c = sc.color;
        if (o.wireframe) {
          const double alpha = edge_alpha(sc, x + 0.5, y + 0.5, half);
          for (int k = 0; k < 3; ++k) {
            const auto u = static_cast<std::size_t>(k);
            c[u] = static_cast<std::uint8_t>(std::lround(c[u] * (1 - alpha) + o.edge[u] * alpha));
          }
        }
      }
      out.rgb[3 * i] = c[0];
      out.rgb[3 * i + 1] = c[1];
      out.rgb[3 * i + 2] = c[2];
    }
}

// The lines between sheet cells.
void draw_separators(const Sheet& g, const RenderOptions3& o, Image& out) {
  const int W = g.W, H = g.H;
  const auto put = [&](int x, int y) {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(W) + static_cast<std::size_t>(x));
    for (int k = 0; k < 3; ++k) out.rgb[i + static_cast<std::size_t>(k)] = o.separator[static_cast<std::size_t>(k)];
  };
  for (int c = 1; c < g.cols; ++c)
    for (int y = 0; y < H; ++y) put(c * W / g.cols, y);
  for (int r = 1; r < g.rows; ++r)
    for (int x = 0; x < W; ++x) put(x, r * H / g.rows);
}

}  // namespace

Status render_mesh3(const PointSet& points, const TriMesh3& mesh, const std::vector<View>& views,
                    const RenderOptions3& options, Image& out) {
  std::vector<Panel3> panels;
  if (views.empty()) panels.push_back({&mesh, View{}});
  for (const View& v : views) panels.push_back({&mesh, v});
  return render_sheet3(points, panels, options, out);
}

}  // namespace constrict
