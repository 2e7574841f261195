// SPDX-License-Identifier: GPL-3.0-or-later
// 2D pictures as pixels (render.hpp), the same layers and colours as the SVG writer
// (src/io/write_polygon.cpp). Coverage of lines and discs comes from the exact distance of each
// pixel centre to the shape (a one-pixel ramp), which is enough anti-aliasing for figures and
// keeps the output deterministic.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "constrict/render.hpp"
#include "core/detail/check_points.hpp"

namespace constrict {
namespace {

using Rgb = std::array<std::uint8_t, 3>;

struct Canvas {
  Image& img;
  int cx0, cy0, cx1, cy1;  // the cell, pixels [cx0, cx1) × [cy0, cy1)
  void blend(int x, int y, const Rgb& c, double a) {
    if (x < cx0 || y < cy0 || x >= cx1 || y >= cy1 || a <= 0) return;
    a = std::min(a, 1.0);
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) + static_cast<std::size_t>(x));
    for (std::size_t k = 0; k < 3; ++k)
      img.rgb[i + k] = static_cast<std::uint8_t>(std::lround(img.rgb[i + k] * (1 - a) + c[k] * a));
  }
  // A segment of width w (pixels); dash > 0: on for `dash` pixels, off for dash * 0.75.
  void segment(double ax, double ay, double bx, double by, double w, const Rgb& c, double dash = 0) {
    const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy, len = std::sqrt(len2);
    const double r = 0.5 * w + 0.5;
    const int x0 = static_cast<int>(std::floor(std::min(ax, bx) - r)), x1 = static_cast<int>(std::ceil(std::max(ax, bx) + r));
    const int y0 = static_cast<int>(std::floor(std::min(ay, by) - r)), y1 = static_cast<int>(std::ceil(std::max(ay, by) + r));
    for (int y = std::max(y0, cy0); y <= std::min(y1, cy1 - 1); ++y)
      for (int x = std::max(x0, cx0); x <= std::min(x1, cx1 - 1); ++x) {
        const double px = x + 0.5 - ax, py = y + 0.5 - ay;
        const double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
        if (dash > 0 && std::fmod(t * len, 1.75 * dash) > dash) continue;
        const double d = std::hypot(px - t * dx, py - t * dy);
        blend(x, y, c, 0.5 * w + 0.5 - d);
      }
  }
  // A disc (ring_width == 0) or a ring of that width, radius r.
  void disc(double cx, double cy, double r, const Rgb& c, double ring_width = 0) {
    const double R = r + 0.5 * ring_width + 1;
    for (int y = std::max(cy0, static_cast<int>(std::floor(cy - R))); y <= std::min(cy1 - 1, static_cast<int>(std::ceil(cy + R))); ++y)
      for (int x = std::max(cx0, static_cast<int>(std::floor(cx - R))); x <= std::min(cx1 - 1, static_cast<int>(std::ceil(cx + R))); ++x) {
        const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
        const double a = ring_width > 0 ? 0.5 * ring_width + 0.5 - std::fabs(d - r) : r + 0.5 - d;
        blend(x, y, c, a);
      }
  }
  // Even-odd fill of closed rings (pixel coordinates, a ring each), sampled at pixel centres.
  void fill(const std::vector<std::vector<double>>& xs, const std::vector<std::vector<double>>& ys, const Rgb& c,
            double a) {
    std::vector<double> cut;
    for (int y = cy0; y < cy1; ++y) {
      const double py = y + 0.5;
      cut.clear();
      for (std::size_t r = 0; r < xs.size(); ++r) {
        const std::vector<double>&X = xs[r], &Y = ys[r];
        const std::size_t n = X.size();
        if (n < 3) continue;
        for (std::size_t i = 0; i < n; ++i) {
          const std::size_t j = (i + 1) % n;
          if ((Y[i] <= py) != (Y[j] <= py)) cut.push_back(X[i] + (py - Y[i]) / (Y[j] - Y[i]) * (X[j] - X[i]));
        }
      }
      std::sort(cut.begin(), cut.end());
      for (std::size_t k = 0; k + 1 < cut.size(); k += 2)
        for (int x = std::max(cx0, static_cast<int>(std::ceil(cut[k] - 0.5))); x < std::min(cx1, static_cast<int>(std::ceil(cut[k + 1] - 0.5))); ++x)
          blend(x, y, c, a);
    }
  }
};

}  // namespace

Status render_sheet2(const PointSet& points, const std::vector<Panel2>& panels, const RenderOptions2& o, Image& out) {
  if (points.dim != 2) return {StatusCode::InvalidArgument, "render: a 2D picture needs 2D points"};
  if (Status f = detail::check_finite(points, "render"); !f) return f;
  if (panels.empty()) return {StatusCode::InvalidArgument, "render: nothing to draw (no panel)"};
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
    return {StatusCode::InvalidArgument, "render: image size must be in [1, 16384]"};
  if (!(o.line_width > 0) || !(o.point_radius >= 0) || o.columns < 0)
    return {StatusCode::InvalidArgument, "render: line width > 0, point radius >= 0, columns >= 0"};
  const std::size_t n = points.size();
  const auto bad = [n](int i) { return i < 0 || static_cast<std::size_t>(i) >= n; };
  for (const auto& p : panels) {
    for (int i : p.boundary)
      if (bad(i)) return {StatusCode::InvalidArgument, "render: polygon index " + std::to_string(i) + " out of range"};
    for (const auto& ring : p.rings)
      for (int i : ring)
        if (bad(i)) return {StatusCode::InvalidArgument, "render: ring index " + std::to_string(i) + " out of range"};
    if (p.layers) {
      for (int i : p.layers->highlight_points)
        if (bad(i)) return {StatusCode::InvalidArgument, "render: point index " + std::to_string(i) + " out of range"};
      for (const auto& e : p.layers->highlight_edges)
        if (bad(e[0]) || bad(e[1])) return {StatusCode::InvalidArgument, "render: edge index out of range"};
      if (p.layers->graph && p.layers->graph->dim == 2)
        for (std::size_t f = 0; f < p.layers->graph->size(); ++f)
          if (bad(p.layers->graph->vertex(f, 0)) || bad(p.layers->graph->vertex(f, 1)))
            return {StatusCode::InvalidArgument, "render: graph index out of range"};
    }
  }
  double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()}, hi[2] = {-lo[0], -lo[1]};
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], points[i][k]);
      hi[k] = std::max(hi[k], points[i][k]);
    }
  if (n == 0) lo[0] = lo[1] = hi[0] = hi[1] = 0;
  // Half the extent, and the centre from halves: finite for data spanning more than the largest
  // double (it gave a blank picture), bit for bit the plain values below that.
  const double half_ext = std::max({0.5 * hi[0] - 0.5 * lo[0], 0.5 * hi[1] - 0.5 * lo[1], 0.5e-300});
  const double mid[2] = {0.5 * lo[0] + 0.5 * hi[0], 0.5 * lo[1] + 0.5 * hi[1]};

  const int P = static_cast<int>(panels.size());
  const int cols = o.columns > 0 ? std::min(o.columns, P) : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(P))));
  const int rows = (P + cols - 1) / cols;
  out.width = o.width;
  out.height = o.height;
  out.rgb.assign(3u * static_cast<std::size_t>(o.width) * static_cast<std::size_t>(o.height), 255);
  const Rgb kFill{{220, 232, 245}}, kGraph{{138, 138, 138}}, kPoly{{31, 78, 140}}, kFallback{{230, 126, 34}},
      kPoint{{192, 57, 43}}, kStuck{{142, 68, 173}}, kSep{{200, 200, 200}};
  for (int p = 0; p < P; ++p) {
    const Panel2& pan = panels[static_cast<std::size_t>(p)];
    Canvas cv{out, (p % cols) * o.width / cols, (p / cols) * o.height / rows, (p % cols + 1) * o.width / cols,
              (p / cols + 1) * o.height / rows};
    const int cw = cv.cx1 - cv.cx0, ch = cv.cy1 - cv.cy0;
    const double margin = std::max(4.0, 0.03 * std::min(cw, ch));
    const double s = 0.5 * std::max(1e-300, std::min(cw - 2 * margin, ch - 2 * margin)) / half_ext;
    const double ox = cv.cx0 + 0.5 * cw - s * mid[0], oy = cv.cy0 + 0.5 * ch + s * mid[1];
    const auto X = [&](std::size_t i) { return ox + s * points[i][0]; };
    const auto Y = [&](std::size_t i) { return oy - s * points[i][1]; };
    const double unit = std::min(cw, ch) / 800.0;  // the SVG writer draws on an 800-pixel canvas
    std::vector<std::vector<double>> xs, ys;       // the boundary, then the further rings
    const auto add_ring = [&](const std::vector<int>& ring) {
      xs.emplace_back();
      ys.emplace_back();
      for (int i : ring) {
        xs.back().push_back(X(static_cast<std::size_t>(i)));
        ys.back().push_back(Y(static_cast<std::size_t>(i)));
      }
    };
    add_ring(pan.boundary);
    for (const auto& ring : pan.rings) add_ring(ring);
    cv.fill(xs, ys, kFill, 0.6);
    if (pan.layers && pan.layers->graph && pan.layers->graph->dim == 2) {
      const GammaFaces& g = *pan.layers->graph;
      for (std::size_t f = 0; f < g.size(); ++f) {
        const auto a = static_cast<std::size_t>(g.vertex(f, 0)), b = static_cast<std::size_t>(g.vertex(f, 1));
        cv.segment(X(a), Y(a), X(b), Y(b), std::max(0.7, 0.7 * unit), kGraph, std::max(3.0, 4 * unit));
      }
    }
    const double lw = o.line_width * std::max(1.0, unit);
    for (std::size_t r = 0; r < xs.size(); ++r)
      for (std::size_t k = 0; k < xs[r].size() && xs[r].size() >= 2; ++k) {
        const std::size_t j = (k + 1) % xs[r].size();
        cv.segment(xs[r][k], ys[r][k], xs[r][j], ys[r][j], lw, kPoly);
      }
    if (pan.layers)
      for (const auto& e : pan.layers->highlight_edges) {
        const auto a = static_cast<std::size_t>(e[0]), b = static_cast<std::size_t>(e[1]);
        cv.segment(X(a), Y(a), X(b), Y(b), 1.5 * lw, kFallback);
      }
    const double r = o.point_radius > 0 ? o.point_radius
                                        : std::max(1.5, unit * std::clamp(400.0 / std::sqrt(static_cast<double>(n) + 1.0), 0.5, 4.0));
    for (std::size_t i = 0; i < n; ++i) cv.disc(X(i), Y(i), r, kPoint);
    if (pan.layers)
      for (int i : pan.layers->highlight_points)
        cv.disc(X(static_cast<std::size_t>(i)), Y(static_cast<std::size_t>(i)), 2.5 * r + 2 * std::max(1.0, unit), kStuck,
                1.5 * std::max(1.0, unit));
  }
  Canvas all{out, 0, 0, o.width, o.height};
  for (int c = 1; c < cols; ++c)
    for (int y = 0; y < o.height; ++y) all.blend(c * o.width / cols, y, kSep, 1);
  for (int r = 1; r < rows; ++r)
    for (int x = 0; x < o.width; ++x) all.blend(x, r * o.height / rows, kSep, 1);
  return Status::ok();
}

}  // namespace constrict
