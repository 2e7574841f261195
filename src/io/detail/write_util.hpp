// SPDX-License-Identifier: GPL-3.0-or-later
// Small helpers shared by the writers: exact shortest decimals (std::to_chars), whole-file writes
// with one-line errors, extensions, XML/JSON escaping, and an SVG frame (y axis up).
#pragma once

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>

#include "constrict/points.hpp"
#include "constrict/status.hpp"
#include "core/detail/check_points.hpp"

namespace constrict {
namespace detail {

inline void put_double(std::string& s, double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}
inline void put_int(std::string& s, long long v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}

/// InvalidArgument naming @p path and the first point with a coordinate that is not finite (the
/// project's check_finite): a writer would put "nan" or "inf" into the file (points built by hand,
/// through the library or Python; read input is checked). Ok when every coordinate is finite.
inline Status check_finite_coordinates(const std::string& path, const PointSet& points) {
  if (Status f = check_finite(points, path.c_str()); !f)
    return {StatusCode::InvalidArgument, f.message() + "; nothing written"};
  return Status::ok();
}

/// Lower-case extension without the dot ("" if none).
inline std::string extension(const std::string& path) {
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

inline Status write_file(const std::string& path, const std::string& data) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return {StatusCode::WriteFailed, path + ": cannot open for writing: " + std::strerror(errno)};
  const std::size_t w = std::fwrite(data.data(), 1, data.size(), f);
  const int c = std::fclose(f);
  if (w != data.size() || c != 0) {
    const std::string why = std::strerror(errno);
    // A partial file (disk full, file size limit) is taken back, not left looking like a result;
    // a device (/dev/full) or pipe is not a file to remove.
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec)) std::filesystem::remove(path, ec);
    return {StatusCode::WriteFailed, path + ": write failed: " + why};
  }
  return Status::ok();
}

inline std::string json_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') { o += '\\'; o += c; }
    else if (static_cast<unsigned char>(c) < 0x20) o += ' ';
    else o += c;
  }
  return o;
}

// Text for an XML document: the markup characters escaped, and what XML 1.0 cannot hold (control
// characters, bytes that are not UTF-8: a file name's) as U+FFFD, so that the SVG stays
// well-formed whatever the input's path.
inline std::string xml_escape(const std::string& s) {
  static const char kReplacement[] = "\xEF\xBF\xBD";
  std::string o;
  const auto byte = [&s](std::size_t i) { return static_cast<unsigned char>(s[i]); };
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char c = byte(i);
    if (c < 0x80) {
      switch (c) {
        case '<': o += "&lt;"; break;
        case '>': o += "&gt;"; break;
        case '&': o += "&amp;"; break;
        case '"': o += "&quot;"; break;
        default:
          o += (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f ? kReplacement
                                                                              : std::string(1, static_cast<char>(c));
      }
      ++i;
      continue;
    }
    // A UTF-8 sequence: its length from the lead byte, then continuation bytes (overlong forms
    // and surrogates refused as well).
    const std::size_t len = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
    bool ok = len != 0 && i + len <= s.size();
    for (std::size_t k = 1; ok && k < len; ++k) ok = (byte(i + k) & 0xC0) == 0x80;
    if (ok && len == 3) ok = !(c == 0xE0 && byte(i + 1) < 0xA0) && !(c == 0xED && byte(i + 1) >= 0xA0);
    if (ok && len == 4) ok = !(c == 0xF0 && byte(i + 1) < 0x90) && !(c == 0xF4 && byte(i + 1) >= 0x90);
    if (ok) {
      o.append(s, i, len);
      i += len;
    } else {
      o += kReplacement;
      ++i;
    }
  }
  return o;
}

/// Maps 2D data coordinates into an SVG canvas of at most `size` pixels, y axis up.
struct SvgFrame {
  double lo[2] = {0, 0}, scale = 1, W = 0, H = 0, margin = 20;
  explicit SvgFrame(const PointSet& pts, double size = 800.0) {
    lo[0] = lo[1] = std::numeric_limits<double>::max();
    double hi[2] = {-lo[0], -lo[1]};
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], pts[i][k]);
        hi[k] = std::max(hi[k], pts[i][k]);
      }
    // Half extents and half differences: a span beyond the largest double (points near ±1e308)
    // stays finite (it gave NaN coordinates), and below it every value is bit for bit that of the
    // plain span (halving and doubling are exact).
    const double hw = std::max(0.5 * hi[0] - 0.5 * lo[0], 0.5e-300), hh = std::max(0.5 * hi[1] - 0.5 * lo[1], 0.5e-300);
    scale = 0.5 * (size - 2 * margin) / std::max(hw, hh);
    W = hw * (2 * scale) + 2 * margin;
    H = hh * (2 * scale) + 2 * margin;
  }
  double x(double v) const { return margin + (0.5 * v - 0.5 * lo[0]) * (2 * scale); }
  double y(double v) const { return H - margin - (0.5 * v - 0.5 * lo[1]) * (2 * scale); }
  /// XML header, <svg> with size and viewBox, title, white background.
  std::string open(const std::string& title) const {
    std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"";
    put_double(s, W);
    s += "\" height=\"";
    put_double(s, H);
    s += "\" viewBox=\"0 0 ";
    put_double(s, W);
    s += ' ';
    put_double(s, H);
    s += "\">\n<title>" + xml_escape(title) + "</title>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    return s;
  }
  /// Point radius that keeps dense sets readable.
  static double point_radius(std::size_t n) {
    return std::clamp(400.0 / std::sqrt(static_cast<double>(n) + 1.0), 0.5, 4.0);
  }
  void line(std::string& s, const double* a, const double* b) const {
    s += "<line x1=\"";
    put_double(s, x(a[0]));
    s += "\" y1=\"";
    put_double(s, y(a[1]));
    s += "\" x2=\"";
    put_double(s, x(b[0]));
    s += "\" y2=\"";
    put_double(s, y(b[1]));
    s += "\"/>\n";
  }
  void circle(std::string& s, const double* p, double r) const {
    s += "<circle cx=\"";
    put_double(s, x(p[0]));
    s += "\" cy=\"";
    put_double(s, y(p[1]));
    s += "\" r=\"";
    put_double(s, r);
    s += "\"/>\n";
  }
};

}  // namespace detail
}  // namespace constrict
