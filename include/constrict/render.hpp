// SPDX-License-Identifier: GPL-3.0-or-later
/// @file render.hpp
/// @brief Pictures of results: a software rasteriser for 3D surfaces (z-buffer, flat shading,
/// optional wireframe, several views or stages on one sheet) and for 2D polygons (points, polygon,
/// γ-graph dashed, stuck points, fallback edges), PNG files through libpng. Deterministic: the
/// same input gives the same pixels on any thread count. Details: docs/rendering.md.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "constrict/io.hpp"
#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

/// An 8-bit RGB image, rows top to bottom, 3 bytes per pixel.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< size 3 * width * height
  /// Pixel (x, y), y = 0 at the top. @pre inside the image.
  std::array<std::uint8_t, 3> at(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x));
    return {{rgb[i], rgb[i + 1], rgb[i + 2]}};
  }
};

/// Writes @p image as an 8-bit RGB PNG (libpng, default compression).
/// @return Ok, or WriteFailed (cannot open, libpng error), InvalidArgument (empty image)
Status write_png(const std::string& path, const Image& image);
/// Reads a PNG (any bit depth / colour type, converted to 8-bit RGB; alpha dropped).
/// @return Ok, FileNotFound, ParseError (not a PNG or corrupt)
Status read_png(const std::string& path, Image& image);

/// A viewing direction: the camera looks at the centre from azimuth (degrees, about +z, 0 = from
/// +x) and elevation (degrees above the xy plane). Orthographic projection, z up on the screen
/// (RenderOptions3::up_axis picks another model axis as "z": the axes are permuted cyclically).
struct View {
  double azimuth = 35;
  double elevation = 25;
};

/// One panel of a 3D sheet: a mesh seen from a view.
struct Panel3 {
  const TriMesh3* mesh = nullptr;
  View view;
};

/// Options of render_mesh3() / render_sheet3().
struct RenderOptions3 {
  int width = 1024, height = 1024;  ///< size of the whole image (a sheet is split into cells)
  int columns = 0;                  ///< sheet columns; 0: ceil(sqrt(panels))
  bool wireframe = false;           ///< draw the triangle edges (hidden ones stay hidden)
  double edge_width = 1.0;          ///< wireframe line width in pixels
  int up_axis = 2;                  ///< model axis drawn upwards: 0 x, 1 y, 2 z (views rotate about it)
  double ambient = 0.25;            ///< ambient share of the Lambert shading, in [0, 1]
  std::array<std::uint8_t, 3> front{{158, 184, 217}};   ///< outward side colour
  std::array<std::uint8_t, 3> back{{217, 120, 110}};    ///< inward side (shows orientation errors)
  std::array<std::uint8_t, 3> edge{{35, 45, 60}};       ///< wireframe colour
  std::array<std::uint8_t, 3> background{{255, 255, 255}};
  std::array<std::uint8_t, 3> separator{{200, 200, 200}};  ///< lines between sheet cells
};

/// Renders panels on a sheet (a grid of equal cells, row by row). All panels use one scale: the
/// bounding sphere of every vertex used by any panel fits its cell, so stages of one run compare
/// directly. Hidden-surface removal by a per-pixel depth buffer (nearest surface wins; equal depth:
/// the lower triangle index). Flat shading: ambient + (1 - ambient) · |n · l| with a light from the
/// viewer's upper left; triangles seen from their inner side get the `back` colour.
/// @param[in] points dim 3
/// @param[out] out the picture (width × height)
/// @return Ok, InvalidArgument (not 3D, no panel, null mesh, index out of range, size out of
///         [1, 16384], non-finite view)
/// @note O(F + covered pixels) per panel, parallel over image bands (TBB), deterministic.
Status render_sheet3(const PointSet& points, const std::vector<Panel3>& panels, const RenderOptions3& options, Image& out);

/// Renders one mesh from one or several views (several: a sheet). Empty @p views: one view, the
/// default View (azimuth 35°, elevation 25°).
Status render_mesh3(const PointSet& points, const TriMesh3& mesh, const std::vector<View>& views,
                    const RenderOptions3& options, Image& out);

/// One panel of a 2D sheet: a polygon (may be empty: points only) or a ring set, with optional
/// layers.
struct Panel2 {
  Panel2() = default;
  Panel2(std::vector<int> polygon, const PolygonSvgLayers* with = nullptr)
      : boundary(std::move(polygon)), layers(with) {}
  std::vector<int> boundary;       ///< polygon as input indices (closed implicitly)
  const PolygonSvgLayers* layers = nullptr;  ///< graph dashed, stuck points, fallback edges
  /// Further rings (input indices, closed implicitly), drawn with the boundary: the fill is
  /// even-odd over all of them, so a hole stays empty and an island in it is filled again.
  std::vector<std::vector<int>> rings;
};

/// Options of render_sheet2().
struct RenderOptions2 {
  int width = 1024, height = 1024;  ///< size of the whole image
  int columns = 0;                  ///< sheet columns; 0: ceil(sqrt(panels))
  double line_width = 2.0;          ///< polygon edges, pixels (graph: half)
  double point_radius = 0;          ///< 0: from the point count (as the SVG writer)
};

/// Renders 2D polygons like the SVG writer (paper Figures 4, 5, 8): the polygon filled light and
/// outlined, the γ-graph dashed grey under it, fallback edges orange, points red, stuck points
/// circled purple. Lines and discs are anti-aliased by their exact pixel-centre distance. All
/// panels share one frame (the bounding box of all points).
/// @return Ok, InvalidArgument (not 2D, no panel, index out of range, bad size)
Status render_sheet2(const PointSet& points, const std::vector<Panel2>& panels, const RenderOptions2& options, Image& out);

}  // namespace constrict
