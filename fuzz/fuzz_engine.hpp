// SPDX-License-Identifier: GPL-3.0-or-later
// What the engine fuzz targets share (docs/fuzzing.md): a byte reader, a decoder of small point
// sets (at most kMaxPoints) built to hit the documented degenerate cases -- duplicates,
// collinear / coplanar, co-circular / co-spherical, near-degenerate triples, huge, tiny, subnormal
// and mixed magnitudes -- and the check that turns a broken contract into a trap.
//
// Layout of an input: [option bytes of the target][mode][count][mode parameters][point bytes].
// The options come first so that mutating the points keeps the options, and vice versa. A
// missing byte reads as 0, so every input decodes to something.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict_fuzz {

constexpr std::size_t kMaxPoints = 64;  // engine inputs stay small: many executions per second

/// Reports a broken contract and traps (a finding). @p what names the check.
[[noreturn]] inline void fail(const char* what, const std::string& detail = {}) {
  std::fprintf(stderr, "fuzz contract broken: %s%s%s\n", what, detail.empty() ? "" : ": ", detail.c_str());
  __builtin_trap();
}

inline void require(bool ok, const char* what, const std::string& detail = {}) {
  if (!ok) fail(what, detail);
}

inline void require_one_line(const constrict::Status& st) {
  require(st.message().find('\n') == std::string::npos, "message is not one line", st.message());
}

/// Sequential reader over the input; past the end every read yields zero bytes.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::int8_t i8() { return static_cast<std::int8_t>(u8()); }
  double f64() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= static_cast<std::uint64_t>(u8()) << (8 * i);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  float f32() {
    std::uint32_t bits = 0;
    for (int i = 0; i < 4; ++i) bits |= static_cast<std::uint32_t>(u8()) << (8 * i);
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  bool done() const { return pos_ >= size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// How the point bytes are read (the mode byte, modulo kModes).
enum class Mode : std::uint8_t {
  SmallInt,     ///< coordinates in [-4, 4]: duplicates, collinear/coplanar, co-circular sets
  RawDouble,    ///< 8 raw bytes per coordinate (any magnitude, subnormals; NaN/Inf replaced
                ///< unless the keep-non-finite flag is set)
  ScaledInt,    ///< small integers times one power of two 2^e, e in [-1100, 1016]
  MixedScale,   ///< small integers, each coordinate with its own power of two
  Lattice,      ///< a k^d lattice subset (repeats possible), jittered by 2^-j multiples
  Cospherical,  ///< integer points on the circle x^2+y^2 = 25 / the sphere |x|^2 = 9, plus a few
                ///< inside, translated and scaled by powers of two (exact)
  NearLine,     ///< small integers plus a few ulps: nearly collinear / coplanar triples
  RawFloat,     ///< 4 raw bytes per coordinate (float32 magnitudes)
};
constexpr int kModes = 8;

// The status contract of the 3D engines (reconstruct3, reconstruct_surfaces3): for bad input the
// check_points() status; for valid input Ok, or Unsupported only when no exact power-of-two
// rescaling exists. True when the result is Ok and is to be checked.
inline bool engine3_status(const constrict::PointSet& p, const constrict::Status& checked, const constrict::Status& st) {
  require_one_line(st);
  if (!checked) {
    require(st.code() == checked.code(), "status differs from check_points()", st.message());
    return false;
  }
  if (st.code() == constrict::StatusCode::Unsupported) {
    constrict::PointSet scaled;
    int e = 0;
    require(!constrict::exact_power_of_two_scale(p, scaled, e).is_ok(), "Unsupported although exactly rescalable",
            st.message());
    return false;
  }
  require(st.is_ok(), "valid input refused", st.message());
  return true;
}

namespace detail {

// Exact lattice points on the circle of radius 5 and the sphere of radius 3 (x^2+y^2+z^2 = 9).
inline const std::vector<std::array<int, 3>>& circle_points() {
  static const std::vector<std::array<int, 3>> pts = {
      {5, 0, 0}, {-5, 0, 0}, {0, 5, 0}, {0, -5, 0}, {3, 4, 0},   {-3, 4, 0},
      {3, -4, 0}, {-3, -4, 0}, {4, 3, 0}, {-4, 3, 0}, {4, -3, 0}, {-4, -3, 0}};
  return pts;
}

inline const std::vector<std::array<int, 3>>& sphere_points() {
  static const std::vector<std::array<int, 3>> pts = [] {
    std::vector<std::array<int, 3>> v;
    for (int x = -3; x <= 3; ++x)
      for (int y = -3; y <= 3; ++y)
        for (int z = -3; z <= 3; ++z)
          if (x * x + y * y + z * z == 9) v.push_back({x, y, z});
    return v;  // 30 points: permutations of (±1,±2,±2) and (±3,0,0)
  }();
  return pts;
}

inline double small_int(std::uint8_t b) { return static_cast<double>(static_cast<int>(b % 9) - 4); }

}  // namespace detail

/// The decoded input and what the decoder chose (printed on a finding).
struct Decoded {
  constrict::PointSet points;
  Mode mode = Mode::SmallInt;
  bool has_non_finite = false;
};

/// Decodes a point set of dimension @p dim (2 or 3) from the rest of @p in.
inline Decoded decode_points(Bytes& in, int dim) {
  Decoded d;
  const std::uint8_t mode_byte = in.u8();
  d.mode = static_cast<Mode>(mode_byte % kModes);
  const bool keep_non_finite = (mode_byte & 0x80) != 0;
  const std::size_t n = in.u8() % (kMaxPoints + 1);
  d.points.dim = dim;
  d.points.coords.reserve(n * static_cast<std::size_t>(dim));
  auto push = [&](double v) { d.points.coords.push_back(v); };

  switch (d.mode) {
    case Mode::SmallInt:
      for (std::size_t i = 0; i < n * static_cast<std::size_t>(dim); ++i) push(detail::small_int(in.u8()));
      break;
    case Mode::RawDouble:
    case Mode::RawFloat:
      for (std::size_t i = 0; i < n * static_cast<std::size_t>(dim); ++i) {
        double v = d.mode == Mode::RawDouble ? in.f64() : static_cast<double>(in.f32());
        if (!std::isfinite(v) && !keep_non_finite) v = static_cast<double>(i % 5);
        push(v);
      }
      break;
    case Mode::ScaledInt: {
      const int e = std::clamp(static_cast<int>(in.i8()) * 9, -1100, 1016);
      for (std::size_t i = 0; i < n * static_cast<std::size_t>(dim); ++i)
        push(std::ldexp(detail::small_int(in.u8()), e));
      break;
    }
    case Mode::MixedScale:
      for (std::size_t i = 0; i < n * static_cast<std::size_t>(dim); ++i) {
        const double k = detail::small_int(in.u8());
        push(std::ldexp(k, std::clamp(static_cast<int>(in.i8()) * 9, -1100, 1016)));
      }
      break;
    case Mode::Lattice: {
      const int k = 2 + in.u8() % 3;  // 2..4 per axis
      const int jitter_exp = -(in.u8() % 64);
      const int cells = dim == 2 ? k * k : k * k * k;
      for (std::size_t i = 0; i < n; ++i) {
        int c = in.u8() % cells;
        for (int j = 0; j < dim; ++j) {
          push(static_cast<double>(c % k) + std::ldexp(static_cast<double>(in.i8() % 3), jitter_exp));
          c /= k;
        }
      }
      break;
    }
    case Mode::Cospherical: {
      const auto& table = dim == 2 ? detail::circle_points() : detail::sphere_points();
      std::array<double, 3> offset{};
      for (int j = 0; j < dim; ++j) offset[static_cast<std::size_t>(j)] = detail::small_int(in.u8());
      const int e = static_cast<int>(in.i8()) * 4;  // exact while the integers keep their bits
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t pick = in.u8();
        for (int j = 0; j < dim; ++j) {
          const double c = pick < 240 ? table[pick % table.size()][static_cast<std::size_t>(j)]
                                      : detail::small_int(in.u8()) / 2;  // a point inside
          push(std::ldexp(c + offset[static_cast<std::size_t>(j)], e));
        }
      }
      break;
    }
    case Mode::NearLine:
      for (std::size_t i = 0; i < n; ++i) {
        const double t = detail::small_int(in.u8());
        for (int j = 0; j < dim; ++j) {
          double v = t * static_cast<double>(j + 1);  // on the line x = t (1, 2, 3)
          for (int s = in.i8() % 4; s != 0; s += s > 0 ? -1 : 1)
            v = std::nextafter(v, s > 0 ? HUGE_VAL : -HUGE_VAL);
          push(v);
        }
      }
      break;
  }
  for (double v : d.points.coords) d.has_non_finite = d.has_non_finite || !std::isfinite(v);
  return d;
}

inline const char* mode_name(Mode m) {
  switch (m) {
    case Mode::SmallInt: return "small-int";
    case Mode::RawDouble: return "raw-double";
    case Mode::ScaledInt: return "scaled-int";
    case Mode::MixedScale: return "mixed-scale";
    case Mode::Lattice: return "lattice";
    case Mode::Cospherical: return "cospherical";
    case Mode::NearLine: return "near-line";
    case Mode::RawFloat: return "raw-float";
  }
  return "?";
}

/// The points as a text file the CLI reads (one point a line, shortest round-trip decimals), to
/// turn a finding into a regression file: set CONSTRICT_FUZZ_PRINT=1 when reproducing.
inline void print_points(const Decoded& d) {
  if (std::getenv("CONSTRICT_FUZZ_PRINT") == nullptr) return;
  std::fprintf(stderr, "# mode %s, %zu points\n", mode_name(d.mode), d.points.size());
  for (std::size_t i = 0; i < d.points.size(); ++i) {
    for (int j = 0; j < d.points.dim; ++j) std::fprintf(stderr, "%s%.17g", j ? " " : "", d.points[i][j]);
    std::fprintf(stderr, "\n");
  }
}

/// Runs @p f; an exception escaping the library is a finding (it never throws for bad input).
template <class F>
void no_throw(const char* where, F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    fail(where, std::string("exception: ") + e.what());
  }
}

}  // namespace constrict_fuzz
