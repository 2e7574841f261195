// SPDX-License-Identifier: GPL-3.0-or-later
// Triangle mesh input (reference meshes for `constrict compare` and `constrict render`): OFF, PLY
// (ascii, binary little/big endian), OBJ and STL (binary and ascii). Polygons with more than three
// vertices are split into a fan. Errors name the file and the 1-based line (binary files: the
// element and its index), like the point reader.
#include <fast_float/fast_float.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "constrict/mesh.hpp"
#include "io/detail/write_util.hpp"

namespace constrict {
namespace {

struct Builder {
  const std::string& name;
  PointSet pts;
  TriMesh3 mesh;
  MeshReadReport rep;

  // Adds polygon `ids` (already 0-based and in range) as a triangle fan.
  void polygon(const std::vector<long long>& ids) {
    ++rep.polygons;
    if (ids.size() > 3) ++rep.split_polygons;
    for (std::size_t k = 1; k + 1 < ids.size(); ++k)
      mesh.triangles.push_back({{static_cast<int>(ids[0]), static_cast<int>(ids[k]), static_cast<int>(ids[k + 1])}});
  }
};

Status at(StatusCode c, const std::string& name, std::size_t line, const std::string& what) {
  return {c, name + ":" + std::to_string(line) + ": " + what};
}

bool to_double(std::string_view t, double& v) {
  const auto r = fast_float::from_chars(t.data(), t.data() + t.size(), v);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}
bool to_ll(std::string_view t, long long& v) {
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

// Splits a text buffer into lines (without '\n', '\r' stripped) and words.
struct Lines {
  std::string_view data;
  std::size_t pos = 0, line = 0;
  bool next(std::string_view& out) {
    if (pos >= data.size()) return false;
    std::size_t e = data.find('\n', pos);
    if (e == std::string_view::npos) e = data.size();
    out = data.substr(pos, e - pos);
    if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
    pos = e + 1;
    ++line;
    return true;
  }
};

void words(std::string_view s, std::vector<std::string_view>& w) {
  w.clear();
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    if (i >= s.size() || s[i] == '#') break;
    std::size_t j = i;
    while (j < s.size() && s[j] != ' ' && s[j] != '\t') ++j;
    w.push_back(s.substr(i, j - i));
    i = j;
  }
}

Status finite_point(Builder& b, const std::array<double, 3>& p, std::size_t line) {
  for (double v : p)
    if (!std::isfinite(v)) return at(StatusCode::NonFinite, b.name, line, "non-finite vertex coordinate");
  b.pts.coords.insert(b.pts.coords.end(), p.begin(), p.end());
  return Status::ok();
}

Status check_ids(Builder& b, std::vector<long long>& ids, std::size_t line) {
  if (ids.size() < 3) return at(StatusCode::ParseError, b.name, line, "a face needs at least 3 vertices");
  const long long n = static_cast<long long>(b.pts.size());
  for (long long v : ids)
    if (v < 0 || v >= n)
      return at(StatusCode::ParseError, b.name, line,
                "vertex index " + std::to_string(v) + " out of range (" + std::to_string(n) + " vertices)");
  return Status::ok();
}

Status parse_off(std::string_view data, Builder& b) {
  Lines L{data};
  std::string_view s;
  std::vector<std::string_view> w;
  // Header keyword (OFF, COFF, NOFF, STOFF...), possibly followed by the counts on the same line.
  std::vector<std::string_view> counts;
  bool keyword = false;
  while (L.next(s)) {
    words(s, w);
    if (w.empty()) continue;
    if (!keyword) {
      if (w[0].size() < 3 || w[0].substr(w[0].size() - 3) != "OFF")
        return at(StatusCode::ParseError, b.name, L.line, "an OFF file starts with 'OFF'");
      keyword = true;
      counts.assign(w.begin() + 1, w.end());
      if (counts.empty()) continue;
    } else {
      counts = w;
    }
    break;
  }
  long long nv = 0, nf = 0;
  if (counts.size() < 2 || !to_ll(counts[0], nv) || !to_ll(counts[1], nf) || nv < 0 || nf < 0)
    return at(StatusCode::ParseError, b.name, L.line, "expected 'vertices faces edges' counts");
  b.pts.coords.reserve(static_cast<std::size_t>(nv) * 3);
  for (long long i = 0; i < nv;) {
    if (!L.next(s)) return at(StatusCode::ParseError, b.name, L.line, "file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    words(s, w);
    if (w.empty()) continue;
    std::array<double, 3> p{};
    if (w.size() < 3) return at(StatusCode::ParseError, b.name, L.line, "a vertex needs 3 coordinates");
    for (int k = 0; k < 3; ++k)
      if (!to_double(w[static_cast<std::size_t>(k)], p[static_cast<std::size_t>(k)]))
        return at(StatusCode::ParseError, b.name, L.line, "malformed number '" + std::string(w[static_cast<std::size_t>(k)]) + "'");
    if (Status st = finite_point(b, p, L.line); !st) return st;
    ++i;
  }
  std::vector<long long> ids;
  for (long long f = 0; f < nf;) {
    if (!L.next(s)) return at(StatusCode::ParseError, b.name, L.line, "file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    words(s, w);
    if (w.empty()) continue;
    long long k = 0;
    if (!to_ll(w[0], k) || k < 0 || static_cast<std::size_t>(k) + 1 > w.size())
      return at(StatusCode::ParseError, b.name, L.line, "malformed face (count, then that many indices)");
    ids.assign(static_cast<std::size_t>(k), 0);
    for (long long j = 0; j < k; ++j)
      if (!to_ll(w[static_cast<std::size_t>(j + 1)], ids[static_cast<std::size_t>(j)]))
        return at(StatusCode::ParseError, b.name, L.line, "malformed vertex index");
    if (Status st = check_ids(b, ids, L.line); !st) return st;
    b.polygon(ids);
    ++f;
  }
  return Status::ok();
}

Status parse_obj(std::string_view data, Builder& b) {
  Lines L{data};
  std::string_view s;
  std::vector<std::string_view> w;
  // Faces may come before all vertices are known (negative indices are relative to the vertices
  // read so far), so indices are resolved and checked per line.
  std::vector<long long> ids;
  while (L.next(s)) {
    words(s, w);
    if (w.empty()) continue;
    if (w[0] == "v") {
      if (w.size() < 4) return at(StatusCode::ParseError, b.name, L.line, "a vertex needs 3 coordinates");
      std::array<double, 3> p{};
      for (int k = 0; k < 3; ++k)
        if (!to_double(w[static_cast<std::size_t>(k + 1)], p[static_cast<std::size_t>(k)]))
          return at(StatusCode::ParseError, b.name, L.line, "malformed number '" + std::string(w[static_cast<std::size_t>(k + 1)]) + "'");
      if (Status st = finite_point(b, p, L.line); !st) return st;
    } else if (w[0] == "f") {
      ids.clear();
      for (std::size_t j = 1; j < w.size(); ++j) {
        std::string_view t = w[j].substr(0, w[j].find('/'));
        long long v = 0;
        if (!to_ll(t, v) || v == 0) return at(StatusCode::ParseError, b.name, L.line, "malformed vertex index");
        ids.push_back(v > 0 ? v - 1 : static_cast<long long>(b.pts.size()) + v);
      }
      if (Status st = check_ids(b, ids, L.line); !st) return st;
      b.polygon(ids);
    }
  }
  return Status::ok();
}

// ---- PLY ----------------------------------------------------------------------------------
enum class PT { I8, U8, I16, U16, I32, U32, F32, F64 };
bool pt_from(std::string_view s, PT& t) {
  static const std::pair<const char*, PT> names[] = {
      {"char", PT::I8},   {"int8", PT::I8},    {"uchar", PT::U8},   {"uint8", PT::U8},  {"short", PT::I16},
      {"int16", PT::I16}, {"ushort", PT::U16}, {"uint16", PT::U16}, {"int", PT::I32},   {"int32", PT::I32},
      {"uint", PT::U32},  {"uint32", PT::U32}, {"float", PT::F32},  {"float32", PT::F32}, {"double", PT::F64},
      {"float64", PT::F64}};
  for (const auto& n : names)
    if (s == n.first) { t = n.second; return true; }
  return false;
}
std::size_t pt_size(PT t) {
  switch (t) {
    case PT::I8: case PT::U8: return 1;
    case PT::I16: case PT::U16: return 2;
    case PT::I32: case PT::U32: case PT::F32: return 4;
    case PT::F64: return 8;
  }
  return 0;
}
struct Prop { std::string name; bool list = false; PT count{}, type{}; };
struct Elem { std::string name; long long n = 0; std::vector<Prop> props; };

template <class T>
T load(const unsigned char* p, bool swap) {
  unsigned char buf[sizeof(T)];
  std::memcpy(buf, p, sizeof(T));
  if (swap) std::reverse(buf, buf + sizeof(T));
  T v;
  std::memcpy(&v, buf, sizeof(T));
  return v;
}
double load_value(const unsigned char* p, PT t, bool swap) {
  switch (t) {
    case PT::I8: return static_cast<double>(static_cast<std::int8_t>(*p));
    case PT::U8: return static_cast<double>(*p);
    case PT::I16: return load<std::int16_t>(p, swap);
    case PT::U16: return load<std::uint16_t>(p, swap);
    case PT::I32: return load<std::int32_t>(p, swap);
    case PT::U32: return load<std::uint32_t>(p, swap);
    case PT::F32: return static_cast<double>(load<float>(p, swap));
    case PT::F64: return load<double>(p, swap);
  }
  return 0;
}

Status parse_ply(std::string_view data, Builder& b) {
  Lines L{data};
  std::string_view s;
  std::vector<std::string_view> w;
  if (!L.next(s) || s != "ply") return at(StatusCode::ParseError, b.name, 1, "a PLY file starts with 'ply'");
  int format = -1;  // 0 ascii, 1 little, 2 big
  std::vector<Elem> elems;
  bool ended = false;
  while (L.next(s)) {
    words(s, w);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") { ended = true; break; }
    if (w[0] == "format" && w.size() >= 2) {
      if (w[1] == "ascii") format = 0;
      else if (w[1] == "binary_little_endian") format = 1;
      else if (w[1] == "binary_big_endian") format = 2;
      else return at(StatusCode::ParseError, b.name, L.line, "unknown PLY format");
    } else if (w[0] == "element" && w.size() == 3) {
      Elem e;
      e.name = std::string(w[1]);
      if (!to_ll(w[2], e.n) || e.n < 0) return at(StatusCode::ParseError, b.name, L.line, "malformed element count");
      elems.push_back(e);
    } else if (w[0] == "property" && !elems.empty()) {
      Prop p;
      bool ok = false;
      if (w.size() == 5 && w[1] == "list") {
        p.list = true;
        ok = pt_from(w[2], p.count) && pt_from(w[3], p.type);
        p.name = std::string(w[4]);
      } else if (w.size() == 3) {
        ok = pt_from(w[1], p.type);
        p.name = std::string(w[2]);
      }
      if (!ok) return at(StatusCode::ParseError, b.name, L.line, "malformed property");
      elems.back().props.push_back(p);
    } else {
      return at(StatusCode::ParseError, b.name, L.line, "unknown PLY header line");
    }
  }
  if (!ended || format < 0) return at(StatusCode::ParseError, b.name, L.line, "PLY header without format or end_header");
  const bool little_host = [] { const std::uint16_t x = 1; unsigned char c; std::memcpy(&c, &x, 1); return c == 1; }();
  const bool swap = (format == 1 && !little_host) || (format == 2 && little_host);
  std::vector<double> vals;
  std::vector<long long> ids;
  std::size_t off = L.pos;
  const auto* base = reinterpret_cast<const unsigned char*>(data.data());
  const auto truncated = [&b](const Elem& e, long long i) {
    return Status{StatusCode::ParseError, b.name + ": PLY " + e.name + " " + std::to_string(i) + ": file truncated"};
  };
  for (const Elem& e : elems) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int ix = -1, iy = -1, iz = -1, iface = -1;
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const std::string& n = e.props[k].name;
      if (n == "x") ix = static_cast<int>(k);
      if (n == "y") iy = static_cast<int>(k);
      if (n == "z") iz = static_cast<int>(k);
      if (e.props[k].list && (n == "vertex_indices" || n == "vertex_index")) iface = static_cast<int>(k);
    }
    if (is_vertex && (ix < 0 || iy < 0 || iz < 0))
      return {StatusCode::ParseError, b.name + ": PLY vertex element needs x, y and z"};
    for (long long i = 0; i < e.n; ++i) {
      std::array<double, 3> p{};
      ids.clear();
      if (format == 0) {
        std::string_view line;
        do {
          if (!L.next(line)) return at(StatusCode::ParseError, b.name, L.line, "file ends inside element '" + e.name + "'");
          words(line, w);
        } while (w.empty());
        std::size_t t = 0;
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const Prop& pr = e.props[k];
          long long cnt = 1;
          if (pr.list) {
            if (t >= w.size() || !to_ll(w[t], cnt) || cnt < 0) return at(StatusCode::ParseError, b.name, L.line, "malformed list count");
            ++t;
          }
          for (long long j = 0; j < cnt; ++j, ++t) {
            double v = 0;
            if (t >= w.size() || !to_double(w[t], v)) return at(StatusCode::ParseError, b.name, L.line, "malformed or missing value");
            if (static_cast<int>(k) == iface) ids.push_back(static_cast<long long>(v));
            if (static_cast<int>(k) == ix) p[0] = v;
            if (static_cast<int>(k) == iy) p[1] = v;
            if (static_cast<int>(k) == iz) p[2] = v;
          }
        }
      } else {
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const Prop& pr = e.props[k];
          long long cnt = 1;
          if (pr.list) {
            if (off + pt_size(pr.count) > data.size()) return truncated(e, i);
            cnt = static_cast<long long>(load_value(base + off, pr.count, swap));
            off += pt_size(pr.count);
            if (cnt < 0) return {StatusCode::ParseError, b.name + ": PLY " + e.name + " " + std::to_string(i) + ": negative list count"};
          }
          const std::size_t sz = pt_size(pr.type);
          if (off + sz * static_cast<std::size_t>(cnt) > data.size()) return truncated(e, i);
          for (long long j = 0; j < cnt; ++j, off += sz) {
            if (static_cast<int>(k) == iface) ids.push_back(static_cast<long long>(load_value(base + off, pr.type, swap)));
            else if (static_cast<int>(k) == ix) p[0] = load_value(base + off, pr.type, swap);
            else if (static_cast<int>(k) == iy) p[1] = load_value(base + off, pr.type, swap);
            else if (static_cast<int>(k) == iz) p[2] = load_value(base + off, pr.type, swap);
          }
        }
      }
      const std::size_t where = format == 0 ? L.line : static_cast<std::size_t>(i);
      if (is_vertex) {
        for (double v : p)
          if (!std::isfinite(v))
            return format == 0 ? at(StatusCode::NonFinite, b.name, where, "non-finite vertex coordinate")
                               : Status{StatusCode::NonFinite, b.name + ": PLY vertex " + std::to_string(i) + ": non-finite coordinate"};
        b.pts.coords.insert(b.pts.coords.end(), p.begin(), p.end());
      } else if (is_face && iface >= 0) {
        Status st = check_ids(b, ids, where);
        if (!st) return format == 0 ? st : Status{st.code(), b.name + ": PLY face " + std::to_string(i) + ": bad vertex list (" + std::to_string(ids.size()) + " indices, " + std::to_string(b.pts.size()) + " vertices)"};
        b.polygon(ids);
      }
    }
  }
  return Status::ok();
}

// ---- STL: shared vertices are identified by exact coordinates (first occurrence order) -----
int stl_vertex(Builder& b, std::map<std::array<double, 3>, int>& ids, const std::array<double, 3>& p) {
  auto [it, fresh] = ids.emplace(p, static_cast<int>(b.pts.size()));
  if (fresh) b.pts.coords.insert(b.pts.coords.end(), p.begin(), p.end());
  return it->second;
}

Status parse_stl(std::string_view data, Builder& b) {
  std::map<std::array<double, 3>, int> ids;
  const auto* base = reinterpret_cast<const unsigned char*>(data.data());
  const bool little_host = [] { const std::uint16_t x = 1; unsigned char c; std::memcpy(&c, &x, 1); return c == 1; }();
  if (data.size() >= 84) {
    const auto n = load<std::uint32_t>(base + 80, !little_host);
    if (84 + 50ull * n == data.size()) {  // binary
      for (std::uint32_t f = 0; f < n; ++f) {
        std::vector<long long> tri;
        for (int v = 0; v < 3; ++v) {
          std::array<double, 3> p{};
          for (int k = 0; k < 3; ++k)
            p[static_cast<std::size_t>(k)] = static_cast<double>(load<float>(base + 84 + 50ull * f + 12 + 12 * v + 4 * k, !little_host));
          for (double c : p)
            if (!std::isfinite(c)) return {StatusCode::NonFinite, b.name + ": STL triangle " + std::to_string(f) + ": non-finite coordinate"};
          tri.push_back(stl_vertex(b, ids, p));
        }
        b.polygon(tri);
      }
      return Status::ok();
    }
  }
  Lines L{data};
  std::string_view s;
  std::vector<std::string_view> w;
  std::vector<long long> tri;
  bool solid = false;
  while (L.next(s)) {
    words(s, w);
    if (w.empty()) continue;
    if (!solid) {
      if (w[0] != "solid") return at(StatusCode::ParseError, b.name, L.line, "not a binary STL (size mismatch) and not ASCII STL ('solid')");
      solid = true;
    } else if (w[0] == "vertex") {
      std::array<double, 3> p{};
      if (w.size() != 4) return at(StatusCode::ParseError, b.name, L.line, "a vertex needs 3 coordinates");
      for (int k = 0; k < 3; ++k)
        if (!to_double(w[static_cast<std::size_t>(k + 1)], p[static_cast<std::size_t>(k)]))
          return at(StatusCode::ParseError, b.name, L.line, "malformed number");
      for (double c : p)
        if (!std::isfinite(c)) return at(StatusCode::NonFinite, b.name, L.line, "non-finite vertex coordinate");
      tri.push_back(stl_vertex(b, ids, p));
    } else if (w[0] == "endloop") {
      if (tri.size() < 3) return at(StatusCode::ParseError, b.name, L.line, "a facet needs at least 3 vertices");
      b.polygon(tri);
      tri.clear();
    }
  }
  return Status::ok();
}

}  // namespace

Status read_mesh(const std::string& path, PointSet& points, TriMesh3& mesh, MeshReadReport* report) {
  const std::string ext = detail::extension(path);
  if (ext != "off" && ext != "ply" && ext != "obj" && ext != "stl")
    return {StatusCode::ParseError, path + ": unknown mesh format '" + ext + "' (use .off, .ply, .obj or .stl)"};
  std::ifstream f(path, std::ios::binary);
  if (!f) return {StatusCode::FileNotFound, path + ": cannot open: " + std::strerror(errno)};
  std::ostringstream ss;
  ss << f.rdbuf();
  const std::string data = ss.str();
  Builder b{path, {}, {}, {}};
  b.pts.dim = 3;
  Status st;
  if (ext == "off") st = parse_off(data, b);
  else if (ext == "ply") st = parse_ply(data, b);
  else if (ext == "obj") st = parse_obj(data, b);
  else st = parse_stl(data, b);
  if (!st) return st;
  if (b.mesh.triangles.empty()) return {StatusCode::EmptyInput, path + ": no faces"};
  points = std::move(b.pts);
  mesh = std::move(b.mesh);
  if (report) *report = b.rep;
  return Status::ok();
}

}  // namespace constrict
