// SPDX-License-Identifier: GPL-3.0-or-later
// Point input: text columns (XYZ/CSV/TXT), PLY (ascii and binary), OFF, OBJ and STL vertices,
// GeoJSON points. The file is mapped (or read) into memory once and handed to the format's one
// reader (io/detail/: text_points, ply, off, obj, stl, geojson; the mesh reader uses the same
// ones). LAS/LAZ and E57 are recognised and refused with a conversion hint. Every defect is
// reported as a Status naming the file and the 1-based line (or the 0-based vertex index for
// binary PLY, which has no lines).

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#define CONSTRICT_HAVE_MMAP 1
#else
#define CONSTRICT_HAVE_MMAP 0
#endif

#include "constrict/io.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"
#include "io/detail/geojson.hpp"
#include "io/detail/obj.hpp"
#include "io/detail/off.hpp"
#include "io/detail/ply.hpp"
#include "io/detail/scan.hpp"
#include "io/detail/stl.hpp"
#include "io/detail/text_points.hpp"
#include "io/detail/write_util.hpp"

namespace constrict {
namespace {

using detail::error_at;
using detail::error_in;
using detail::is_space;
using detail::plural;

// ---- OFF / OBJ -------------------------------------------------------------------------------

Status parse_off(std::string_view data, const std::string& name, int forced_dim, PointSet& out) {
  const int dim = forced_dim == 0 ? 3 : forced_dim;
  detail::OffReader off(data, name);
  Status st = off.header(false);
  if (!st || off.empty()) return st;
  st = off.vertices(dim, out.coords);
  if (st) st = off.after_vertices();
  if (st) out.dim = dim;
  return st;
}

Status parse_obj(std::string_view data, const std::string& name, int forced_dim, PointSet& out) {
  const int dim = forced_dim == 0 ? 3 : forced_dim;
  Status st = detail::read_obj(data, name, dim, out.coords, nullptr);
  if (st) out.dim = dim;
  return st;
}

// ---- STL: the distinct corners ---------------------------------------------------------------

Status parse_stl(std::string_view data, const std::string& name, int forced_dim, PointSet& out,
                 std::vector<std::string>& warnings) {
  std::vector<double> xyz;
  std::size_t corners = 0;
  Status st = detail::read_stl(data, name, xyz, nullptr, corners);
  if (!st) return st;
  const std::size_t distinct = xyz.size() / 3;
  out.dim = forced_dim == 0 ? 3 : forced_dim;
  if (out.dim == 3) {
    out.coords = std::move(xyz);
  } else {
    for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) out.coords.insert(out.coords.end(), {xyz[i], xyz[i + 1]});
  }
  if (corners > distinct)
    warnings.push_back(name + ": STL repeats shared vertices in every facet: " +
                       plural(corners, "facet corner") + " read, " + plural(distinct, "distinct point") +
                       " kept (exactly equal corners are one point)");
  return Status::ok();
}

// ---- PLY -------------------------------------------------------------------------------------

// Where x, y, z and the optional attributes sit in the vertex element, as PlyRecordSpec slots:
// coordinates first (0..dim-1), then nx ny nz, then the colour channels.
struct VertexLayout {
  detail::PlyRecordSpec spec;
  int dim = 3;
  int width = 3;           // slots per record
  int normals = -1;        // first slot of nx ny nz, -1: not read
  int colors = -1;         // first slot of the colour channels, -1: not read
  int channels = 0;        // 3 or 4
  double color_scale[4] = {1.0, 1.0, 1.0, 1.0};  // integer colour types: 1 / their maximum
};

// Slots for the properties named in @p names, all scalar; false if one is missing or a list.
bool take_slots(const detail::PlyElement& el, const char* const* names, int n, VertexLayout& l) {
  int at[4] = {-1, -1, -1, -1};
  for (int k = 0; k < n; ++k) {
    at[k] = el.find(names[k]);
    if (at[k] < 0 || el.properties[static_cast<std::size_t>(at[k])].is_list) return false;
  }
  for (int k = 0; k < n; ++k) l.spec.slot[static_cast<std::size_t>(at[k])] = l.width + k;
  l.width += n;
  return true;
}

// Colour channels: uchar 0..255 (and other integer types, by their range), floats as written.
double color_scale(detail::PlyType t) {
  switch (t) {
    case detail::PlyType::UInt16:
      return 1.0 / 65535.0;
    case detail::PlyType::Float32:
    case detail::PlyType::Float64:
      return 1.0;
    default:
      return 1.0 / 255.0;
  }
}

void attribute_layout(const detail::PlyElement& vertex, VertexLayout& l) {
  static const char* const kNormals[3] = {"nx", "ny", "nz"};
  static const char* const kColors[4] = {"red", "green", "blue", "alpha"};
  const int first_normal = l.width;
  if (take_slots(vertex, kNormals, 3, l)) l.normals = first_normal;
  const int first_color = l.width;
  const int channels = vertex.find("alpha") >= 0 ? 4 : 3;
  if (take_slots(vertex, kColors, channels, l)) {
    l.colors = first_color;
    l.channels = channels;
    for (int k = 0; k < channels; ++k)
      l.color_scale[k] = color_scale(vertex.properties[static_cast<std::size_t>(
                                                           vertex.find(kColors[k]))].type);
  }
}

Status vertex_layout(const detail::PlyElement& vertex, const std::string& name, int forced_dim,
                     bool attributes, VertexLayout& layout) {
  static const char* const kAxes[3] = {"x", "y", "z"};
  int prop[3] = {-1, -1, -1};
  for (int k = 0; k < 3; ++k) {
    prop[k] = vertex.find(kAxes[k]);
    if (prop[k] >= 0 && vertex.properties[static_cast<std::size_t>(prop[k])].is_list)
      return error_in(StatusCode::ParseError, name,
                      std::string("PLY vertex property '") + kAxes[k] + "' is a list");
    for (std::size_t j = prop[k] < 0 ? vertex.properties.size() : static_cast<std::size_t>(prop[k]) + 1; j < vertex.properties.size(); ++j)
      if (vertex.properties[j].name == kAxes[k])  // which one is the coordinate? not guessed
        return error_in(StatusCode::ParseError, name,
                        std::string("PLY vertex element has two properties '") + kAxes[k] + "'; rename one");
  }
  if (prop[0] < 0 || prop[1] < 0)
    return error_in(StatusCode::ParseError, name, "PLY vertex element has no x and y properties");
  const bool has_z = prop[2] >= 0;
  if (forced_dim == 3 && !has_z)
    return error_in(StatusCode::ParseError, name,
                    "PLY vertex element has no z property, but dimension 3 was requested");
  layout.dim = forced_dim != 0 ? forced_dim : (has_z ? 3 : 2);
  layout.spec.slot.assign(vertex.properties.size(), -1);
  for (int k = 0; k < layout.dim; ++k) layout.spec.slot[static_cast<std::size_t>(prop[k])] = k;
  layout.spec.n_finite = layout.dim;
  layout.width = layout.dim;
  if (attributes) attribute_layout(vertex, layout);
  return Status::ok();
}

// Splits the vertex table (width slots per record) into coordinates and attributes.
void split_table(const std::vector<double>& table, const VertexLayout& l, PointSet& out,
                 PointAttributes& attributes) {
  const auto width = static_cast<std::size_t>(l.width);
  const std::size_t n = table.size() / width;
  const auto dim = static_cast<std::size_t>(l.dim);
  out.coords.resize(n * dim);
  if (l.normals >= 0) attributes.normals.resize(n * 3);
  if (l.colors >= 0) attributes.colors.resize(n * static_cast<std::size_t>(l.channels));
  attributes.color_channels = l.channels;
  for (std::size_t i = 0; i < n; ++i) {
    const double* row = table.data() + i * width;
    std::copy(row, row + dim, out.coords.begin() + static_cast<std::ptrdiff_t>(i * dim));
    if (l.normals >= 0)
      std::copy(row + l.normals, row + l.normals + 3,
                attributes.normals.begin() + static_cast<std::ptrdiff_t>(i * 3));
    for (int k = 0; k < l.channels; ++k)
      attributes.colors[i * static_cast<std::size_t>(l.channels) + static_cast<std::size_t>(k)] =
          row[l.colors + k] * l.color_scale[k];
  }
}

// The first 'vertex' element; elements before it are skipped, elements after it never read.
Status parse_ply(std::string_view data, const std::string& name, int forced_dim, PointSet& out,
                 PointAttributes* attributes) {
  detail::PlyHeader header;
  Status st = detail::parse_ply_header(data, name, header);
  if (!st) return st;
  detail::PlyBody body(data, name, header);
  for (const detail::PlyElement& el : header.elements) {
    st = body.check_room(el);
    if (!st) return st;
    if (el.name != "vertex") {
      st = body.skip(el);
      if (!st) return st;
      continue;
    }
    VertexLayout layout;
    st = vertex_layout(el, name, forced_dim, attributes != nullptr, layout);
    if (!st) return st;
    out.dim = layout.dim;
    std::vector<double> table;
    st = layout.width == layout.dim ? body.read_table(el, layout.spec, layout.dim, out.coords)
                                    : body.read_table(el, layout.spec, layout.width, table);
    if (!st) return st;
    // A vertex count smaller than the data would drop points silently: the data must end here,
    // or (ascii) the next element's first record must read as one. Later elements are not read.
    const detail::PlyElement* next = &el + 1;
    while (next != header.elements.data() + header.elements.size() && next->count == 0) ++next;
    if (next == header.elements.data() + header.elements.size()) {
      st = body.check_end(el);
    } else if (body.ascii()) {
      detail::PlyElement first = *next;
      first.count = std::min<std::uint64_t>(first.count, 1);
      st = body.check_room(first);
      if (st) st = body.skip(first);
    }
    if (st && layout.width != layout.dim) split_table(table, layout, out, *attributes);
    return st;
  }
  return error_in(StatusCode::ParseError, name, "PLY file has no 'vertex' element");
}

// ---- common ----------------------------------------------------------------------------------

PointFormat format_from_name(const std::string& name) {
  const std::size_t slash = name.find_last_of("/\\");
  const std::size_t dot = name.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return PointFormat::Text;
  std::string ext = name.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "ply") return PointFormat::Ply;
  if (ext == "off") return PointFormat::Off;
  if (ext == "obj") return PointFormat::Obj;
  if (ext == "stl") return PointFormat::Stl;
  if (ext == "geojson" || ext == "json") return PointFormat::GeoJson;
  return PointFormat::Text;
}

// LAS/LAZ ("LASF" file signature) and E57 ("ASTM-E57" signature) are binary scanner formats
// this library has no reader for; read as text they gave "no points". Refused by their magic
// bytes whatever the format asked for, and by extension when the format is Auto.
Status refuse_scanner_formats(std::string_view data, const std::string& name, bool by_extension) {
  const std::string ext = by_extension ? detail::extension(name) : std::string();
  const auto starts = [data](const char* magic) {
    return data.size() >= std::strlen(magic) && std::memcmp(data.data(), magic, std::strlen(magic)) == 0;
  };
  if (ext == "las" || ext == "laz" || starts("LASF"))
    return error_in(StatusCode::Unsupported, name,
                    "LAS/LAZ point clouds cannot be read; convert to text or PLY first, e.g. 'pdal "
                    "translate " + name + " points.xyz' or 'las2txt -i " + name + " -parse xyz -o points.xyz'");
  if (ext == "e57" || starts("ASTM-E57"))
    return error_in(StatusCode::Unsupported, name,
                    "E57 scans cannot be read; convert to PLY or text first, e.g. 'pdal translate " +
                        name + " points.ply' (PDAL's E57 reader) or CloudCompare");
  return Status::ok();
}

// One {kept_row, dropped_row} pair per copy merge_duplicates dropped: the rows sorted by their
// coordinates (ties by row), so each run of equal points starts with its first occurrence. The
// comparison is the one of check_points() (-0.0 == 0.0).
std::vector<std::array<std::size_t, 2>> merged_pairs(const PointSet& rows) {
  const auto dim = static_cast<std::size_t>(rows.dim);
  std::vector<std::size_t> order(rows.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto less = [&rows, dim](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(rows[a], rows[a] + dim, rows[b], rows[b] + dim);
  };
  std::stable_sort(order.begin(), order.end(), less);
  std::vector<std::array<std::size_t, 2>> pairs;
  for (std::size_t i = 1, first = order[0]; i < order.size(); ++i) {
    if (less(order[i - 1], order[i])) {
      first = order[i];
    } else {
      pairs.push_back({first, order[i]});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a[1] < b[1]; });
  return pairs;
}

bool is_blank(std::string_view data) {
  return std::all_of(data.begin(), data.end(), [](char c) { return is_space(c) || c == '\n'; });
}

Status cannot_read(const std::string& path, int err) {
  return {StatusCode::FileNotFound,
          path + ": cannot read: " + std::generic_category().message(err)};
}

// The bytes of a file. A regular file is memory-mapped where the platform allows it: for large
// inputs copying the file into a buffer (and faulting that buffer in) costs as much as parsing it.
// Other files (pipes, /proc) and other platforms are read into a string.
class FileContents {
 public:
  FileContents() = default;
  FileContents(const FileContents&) = delete;
  FileContents& operator=(const FileContents&) = delete;
  ~FileContents() {
#if CONSTRICT_HAVE_MMAP
    if (map_ != nullptr) ::munmap(map_, map_size_);
#endif
  }

  std::string_view view() const noexcept {
    if (map_ != nullptr) return {static_cast<const char*>(map_), map_size_};
    return buffer_;
  }

  Status open(const std::string& path) {
#if CONSTRICT_HAVE_MMAP
    int flags = O_RDONLY;
#ifdef O_CLOEXEC
    flags |= O_CLOEXEC;
#endif
    const int fd = ::open(path.c_str(), flags);
    if (fd < 0) return cannot_read(path, errno);
    Status st = read_fd(path, fd);
    ::close(fd);
    return st;
#else
    // fopen() succeeds on a directory on some systems (reading then fails), so catch it first.
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return cannot_read(path, EISDIR);
    errno = 0;
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) return cannot_read(path, errno != 0 ? errno : ENOENT);
    char chunk[1 << 16];
    for (;;) {
      const std::size_t got = std::fread(chunk, 1, sizeof chunk, file);
      buffer_.append(chunk, got);
      if (got < sizeof chunk) break;
    }
    const bool failed = std::ferror(file) != 0;
    const int err = errno;
    std::fclose(file);
    if (failed) return cannot_read(path, err != 0 ? err : EIO);
    return Status::ok();
#endif
  }

 private:
#if CONSTRICT_HAVE_MMAP
  Status read_fd(const std::string& path, int fd) {
    struct stat info {};
    if (::fstat(fd, &info) != 0) return cannot_read(path, errno);
    if (S_ISDIR(info.st_mode)) return cannot_read(path, EISDIR);
    if (S_ISREG(info.st_mode) && info.st_size > 0) {
      int map_flags = MAP_PRIVATE;
#ifdef MAP_POPULATE
      map_flags |= MAP_POPULATE;  // fault the pages in at once, not one by one while parsing
#endif
      const auto size = static_cast<std::size_t>(info.st_size);
      void* m = ::mmap(nullptr, size, PROT_READ, map_flags, fd, 0);
      if (m != MAP_FAILED) {
        map_ = m;
        map_size_ = size;
        return Status::ok();
      }
      buffer_.reserve(size);  // mapping refused (some file systems): read it instead
    }
    // A character device other than a terminal (/dev/zero, /dev/urandom) may never end: reading
    // it grew the buffer without bound. An empty one (/dev/null) reads as an empty file.
    const bool device = S_ISCHR(info.st_mode) && ::isatty(fd) == 0;
    char chunk[1 << 16];
    for (;;) {
      const ssize_t got = ::read(fd, chunk, sizeof chunk);
      if (got < 0) {
        if (errno == EINTR) continue;
        return cannot_read(path, errno);
      }
      if (got == 0) break;
      if (device)
        return {
            StatusCode::FileNotFound,
            path + ": a character device, not a file (its data may never end): read the points from a file or a pipe"};
      buffer_.append(chunk, static_cast<std::size_t>(got));
    }
    return Status::ok();
  }
#endif

  void* map_ = nullptr;
  std::size_t map_size_ = 0;
  std::string buffer_;
};

// Attributes of the points kept by merge_duplicates (kept[i]: file index of point i).
void keep_attributes(const std::vector<std::size_t>& kept, PointAttributes& a) {
  const auto select = [&kept](std::vector<double>& values, std::size_t width) {
    if (values.empty()) return;
    std::vector<double> out(kept.size() * width);
    for (std::size_t i = 0; i < kept.size(); ++i)
      std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(kept[i] * width), width,
                  out.begin() + static_cast<std::ptrdiff_t>(i * width));
    values = std::move(out);
  };
  select(a.normals, 3);
  select(a.colors, static_cast<std::size_t>(a.color_channels));
}

}  // namespace

Status read_points_from_buffer(std::string_view data, const std::string& name, PointFormat format,
                               const ReadOptions& options, PointSet& out, ReadReport* report) {
  if (report != nullptr) *report = ReadReport{};
  if (options.dim != 0 && options.dim != 2 && options.dim != 3)
    return error_in(
        StatusCode::InvalidArgument, name,
        "dimension must be 0 (from the data), 2 or 3, got " + std::to_string(options.dim));
  if (format == PointFormat::Auto) format = options.format;
  Status st = refuse_scanner_formats(data, name, format == PointFormat::Auto);
  if (!st) return st;
  if (format == PointFormat::Auto) format = format_from_name(name);
  if (!options.columns.empty() && format != PointFormat::Text)
    return error_in(StatusCode::InvalidArgument, name,
                    "columns can be chosen only for text input (XYZ/CSV/TXT), this is read as " +
                        std::string(to_string(format)));
  if (is_blank(data)) return error_in(StatusCode::EmptyInput, name, "empty file");
  // PLY and OFF headers are lines ended by LF (or CRLF); a file with CR-only line ends (classic
  // Mac) read as one line and gave a misleading message.
  if ((format == PointFormat::Ply || format == PointFormat::Off) && data.find('\n') == std::string_view::npos &&
      data.find('\r') != std::string_view::npos)
    return error_in(StatusCode::ParseError, name, "the lines end in CR only (classic Mac); convert the line ends to LF");

  PointSet points;
  points.dim = options.dim == 0 ? 3 : options.dim;
  PointAttributes attributes;
  std::vector<std::string> warnings;
  switch (format) {
    case PointFormat::Auto:
    case PointFormat::Text:
      st = detail::read_text_points(data, name, options.dim, options.columns, points);
      break;
    case PointFormat::Ply:
      st = parse_ply(data, name, options.dim, points, report != nullptr ? &attributes : nullptr);
      break;
    case PointFormat::Off:
      st = parse_off(data, name, options.dim, points);
      break;
    case PointFormat::Obj:
      st = parse_obj(data, name, options.dim, points);
      break;
    case PointFormat::Stl:
      st = parse_stl(data, name, options.dim, points, warnings);
      break;
    case PointFormat::GeoJson:
      st = detail::read_geojson_points(data, name, options.dim, points);
      break;
  }
  if (!st) return st;
  const std::size_t n_read = points.size();
  if (report != nullptr) {
    report->points_read = n_read;
    report->format = format;
  }
  if (n_read == 0) return error_in(StatusCode::EmptyInput, name, "no points");

  std::vector<std::size_t> kept;
  std::vector<std::array<std::size_t, 2>> pairs;
  if (options.merge_duplicates) {
    PointSet merged = merge_duplicates(points, &kept);
    if (merged.size() == n_read) {
      kept.clear();
    } else {
      if (report != nullptr) pairs = merged_pairs(points);
      points = std::move(merged);
    }
  }
  const std::size_t n_merged = n_read - points.size();

  if (options.check) {
    st = check_points(points);
    if (!st) return error_in(st.code(), name, degenerate_message_for(format, st.message()));
  }

  if (report != nullptr) {
    report->merged_duplicates = n_merged;
    report->warnings = std::move(warnings);
    if (n_merged > 0) {
      keep_attributes(kept, attributes);
      report->original_index = std::move(kept);
      report->merged = std::move(pairs);
      report->warnings.push_back(name + ": merged " + plural(n_merged, "duplicate point") +
                                 " (kept the first occurrence of each; output indices are file rows)");
    } else {
      report->original_index.resize(n_read);
      std::iota(report->original_index.begin(), report->original_index.end(), std::size_t{0});
    }
    report->attributes = std::move(attributes);
  }
  out = std::move(points);
  return Status::ok();
}

std::string degenerate_message_for(PointFormat format, const std::string& message) {
  const std::string key = " (--columns ";
  const auto at = message.find(key);
  if (format == PointFormat::Text || format == PointFormat::Auto || at == std::string::npos || message.back() != ')')
    return message;
  const std::string cols = message.substr(at + key.size(), message.size() - 1 - at - key.size());
  return message.substr(0, at) + ": write them to a text file and read that with --columns " + cols + " (" +
         to_string(format) + " input has no columns)";
}

const char* to_string(PointFormat format) noexcept {
  switch (format) {
    case PointFormat::Auto:
      return "auto";
    case PointFormat::Text:
      return "text";
    case PointFormat::Ply:
      return "ply";
    case PointFormat::Off:
      return "off";
    case PointFormat::Obj:
      return "obj";
    case PointFormat::Stl:
      return "stl";
    case PointFormat::GeoJson:
      return "geojson";
  }
  return "auto";
}

Status point_format_from_name(const std::string& name, PointFormat& out) {
  for (PointFormat f : {PointFormat::Auto, PointFormat::Text, PointFormat::Ply, PointFormat::Off,
                        PointFormat::Obj, PointFormat::Stl, PointFormat::GeoJson})
    if (name == to_string(f)) {
      out = f;
      return Status::ok();
    }
  return {StatusCode::InvalidArgument,
          "unknown input format '" + name + "' (use auto, text, ply, off, obj, stl or geojson)"};
}

Status parse_columns(const std::string& text, ColumnSelection& out) {
  const auto bad = [&text](const std::string& what) {
    return Status{StatusCode::InvalidArgument, "--columns '" + text + "': " + what};
  };
  ColumnSelection c;
  std::size_t pos = 0;
  for (;;) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    std::string item = text.substr(pos, comma - pos);
    while (!item.empty() && is_space(item.back())) item.pop_back();
    item.erase(0, std::min(item.size(), item.find_first_not_of(" \t")));
    if (item.empty()) return bad("empty entry; give 2 or 3 column numbers or header names, e.g. 2,3,4 or x,y,z");
    std::size_t number = 0;
    const auto r = std::from_chars(item.data(), item.data() + item.size(), number);
    if (r.ec == std::errc() && r.ptr == item.data() + item.size()) {
      if (number == 0) return bad("column numbers are 1-based (the first column is 1)");
      c.numbers.push_back(number);
    } else if (r.ec == std::errc::result_out_of_range && r.ptr == item.data() + item.size()) {
      return bad("column number " + item + " is too large");
    } else {
      c.names.push_back(item);
    }
    if (comma == text.size()) break;
    pos = comma + 1;
  }
  if (!c.numbers.empty() && !c.names.empty())
    return bad("mix of column numbers and names; give either numbers (2,3,4) or names (x,y,z)");
  const std::size_t n = c.numbers.size() + c.names.size();
  if (n != 2 && n != 3) return bad("expected 2 or 3 columns (x,y or x,y,z), got " + std::to_string(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (c.numbers.empty() ? c.names[i] == c.names[j] : c.numbers[i] == c.numbers[j])
        return bad("a column is given twice");
  out = std::move(c);
  return Status::ok();
}

PointSet file_row_points(const PointSet& points, const ReadReport& report) {
  if (report.merged.empty()) return points;
  const auto dim = static_cast<std::size_t>(points.dim);
  PointSet rows;
  rows.dim = points.dim;
  rows.coords.resize(report.points_read * dim);
  for (std::size_t i = 0; i < points.size(); ++i)
    std::copy_n(points[i], dim, rows.coords.begin() + static_cast<std::ptrdiff_t>(report.original_index[i] * dim));
  for (const auto& [kept, dropped] : report.merged)
    std::copy_n(rows.coords.begin() + static_cast<std::ptrdiff_t>(kept * dim), dim,
                rows.coords.begin() + static_cast<std::ptrdiff_t>(dropped * dim));
  return rows;
}

PointAttributes file_row_attributes(const ReadReport& report) {
  PointAttributes a = report.attributes;
  if (report.merged.empty()) return a;
  const auto spread = [&report](std::vector<double>& values, std::size_t width) {
    if (values.empty()) return;
    std::vector<double> rows(report.points_read * width);
    for (std::size_t i = 0; i < report.original_index.size(); ++i)
      std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(i * width), width,
                  rows.begin() + static_cast<std::ptrdiff_t>(report.original_index[i] * width));
    for (const auto& [kept, dropped] : report.merged)
      std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(kept * width), width,
                  rows.begin() + static_cast<std::ptrdiff_t>(dropped * width));
    values = std::move(rows);
  };
  spread(a.normals, 3);
  spread(a.colors, static_cast<std::size_t>(a.color_channels));
  return a;
}

Status read_points(const std::string& path, const ReadOptions& options, PointSet& out,
                   ReadReport* report) {
  if (report != nullptr) *report = ReadReport{};
  FileContents contents;
  // "-": standard input (text, or the format named by ReadOptions::format), as Unix tools read it.
  Status st = contents.open(path == "-" ? std::string("/dev/stdin") : path);
  if (!st) return st;
  return read_points_from_buffer(contents.view(), path == "-" ? std::string("standard input") : path, options.format,
                                 options, out, report);
}

}  // namespace constrict
