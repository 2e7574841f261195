// SPDX-License-Identifier: GPL-3.0-or-later
// The PLY reader shared by read_points() and read_mesh() (contract: io/detail/ply.hpp).
#include "io/detail/ply.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "io/detail/scan.hpp"

namespace constrict {
namespace detail {
namespace {

// Largest magnitude of a kept list item (face index): every integer up to 2^53 is exact in a double,
// so an item of any PLY type converts to int64 without rounding or overflow.
constexpr double kMaxListItem = 9007199254740992.0;  // 2^53
// Most values kept per record: x y z, nx ny nz, red green blue alpha.
constexpr std::size_t kMaxSlots = 10;

// The PLY type names, each type's usual one first.
const struct {
  const char* name;
  PlyType type;
} kTypes[] = {{"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
              {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
              {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
              {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
              {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
              {"float64", PlyType::Float64}};

bool ply_type_from_name(std::string_view s, PlyType& t) {
  for (const auto& k : kTypes) {
    if (s == k.name) {
      t = k.type;
      return true;
    }
  }
  return false;
}

bool host_is_little_endian() noexcept {
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

template <typename T>
T load(const char* p, bool swap) noexcept {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (swap) std::reverse(bytes, bytes + sizeof(T));
  T v;
  std::memcpy(&v, bytes, sizeof(T));
  return v;
}

double load_double(const char* p, PlyType t, bool swap) noexcept {
  switch (t) {
    case PlyType::Int8:
      return load<std::int8_t>(p, swap);
    case PlyType::UInt8:
      return load<std::uint8_t>(p, swap);
    case PlyType::Int16:
      return load<std::int16_t>(p, swap);
    case PlyType::UInt16:
      return load<std::uint16_t>(p, swap);
    case PlyType::Int32:
      return load<std::int32_t>(p, swap);
    case PlyType::UInt32:
      return load<std::uint32_t>(p, swap);
    case PlyType::Float32:
      return static_cast<double>(load<float>(p, swap));
    case PlyType::Float64:
      return load<double>(p, swap);
  }
  return 0.0;
}

// List length; false if negative. @pre t is an integer type (checked in the header).
bool load_count(const char* p, PlyType t, bool swap, std::uint64_t& n) noexcept {
  const double v = load_double(p, t, swap);  // exact: every integer type fits in a double
  if (!(v >= 0.0)) return false;
  n = static_cast<std::uint64_t>(v);
  return true;
}

// A kept list item as an integer: integral and |v| <= 2^53, or false (no UB float->int casts).
bool to_index(double v, std::int64_t& out) noexcept {
  if (!(std::fabs(v) <= kMaxListItem) || std::trunc(v) != v) return false;
  out = static_cast<std::int64_t>(v);
  return true;
}

std::vector<std::string_view> split_words(const char* b, const char* e) {
  std::vector<std::string_view> words;
  const char* p = b;
  while (p < e) {
    while (p < e && is_space(*p)) ++p;
    const char* w = p;
    while (p < e && !is_space(*p)) ++p;
    if (p > w) words.emplace_back(w, static_cast<std::size_t>(p - w));
  }
  return words;
}

std::string quote_word(std::string_view w) { return quote(w.data(), w.data() + w.size()); }

// One 'property' line into the last element.
Status add_property(const std::vector<std::string_view>& w, PlyElement& el,
                    const std::string& name, std::size_t line) {
  const auto bad = [&](const std::string& what) {
    return error_at(StatusCode::ParseError, name, line, what);
  };
  PlyProperty prop;
  if (w.size() == 5 && w[1] == "list") {
    prop.is_list = true;
    if (!ply_type_from_name(w[2], prop.count_type) || !ply_is_integer(prop.count_type))
      return bad("PLY list count type must be an integer type, found " + quote_word(w[2]));
    if (!ply_type_from_name(w[3], prop.type)) return bad("unknown PLY type " + quote_word(w[3]));
    prop.name = std::string(w[4]);
    el.has_list = true;
    el.min_size += ply_size(prop.count_type);
  } else if (w.size() == 3) {
    if (!ply_type_from_name(w[1], prop.type)) return bad("unknown PLY type " + quote_word(w[1]));
    prop.name = std::string(w[2]);
    el.fixed_size += ply_size(prop.type);
    el.min_size += ply_size(prop.type);
  } else {
    return bad("malformed PLY property line");
  }
  el.properties.push_back(std::move(prop));
  return Status::ok();
}

// Whether an ASCII value fits its declared integer type (an integer in range); float and double
// take any finite value (writers often print more digits than a float holds).
bool fits_ply_type(double v, PlyType t) noexcept {
  double lo = 0, hi = 0;
  switch (t) {
    case PlyType::Int8: lo = -128, hi = 127; break;
    case PlyType::UInt8: lo = 0, hi = 255; break;
    case PlyType::Int16: lo = -32768, hi = 32767; break;
    case PlyType::UInt16: lo = 0, hi = 65535; break;
    case PlyType::Int32: lo = -2147483648.0, hi = 2147483647.0; break;
    case PlyType::UInt32: lo = 0, hi = 4294967295.0; break;
    case PlyType::Float32:
    case PlyType::Float64:
      return true;
  }
  return v >= lo && v <= hi && v == std::floor(v);
}

// The type's name as the PLY header spells it (its first spelling in kTypes).
const char* ply_type_name(PlyType t) noexcept {
  for (const auto& k : kTypes)
    if (k.type == t) return k.name;
  return "?";
}

}  // namespace

int PlyElement::find(std::string_view n) const noexcept {
  for (std::size_t k = 0; k < properties.size(); ++k)
    if (properties[k].name == n) return static_cast<int>(k);
  return -1;
}

std::size_t ply_size(PlyType t) noexcept {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 0;
}

bool ply_is_integer(PlyType t) noexcept { return t != PlyType::Float32 && t != PlyType::Float64; }

Status parse_ply_header(std::string_view data, const std::string& name, PlyHeader& h) {
  LineReader lines(data);
  const char* b = nullptr;
  const char* e = nullptr;
  if (!lines.next(b, e, false) || split_words(b, e) != std::vector<std::string_view>{"ply"})
    return error_at(StatusCode::ParseError, name, 1, "not a PLY file (first line must be 'ply')");
  bool have_format = false;
  for (;;) {
    if (!lines.next(b, e, false))
      return error_in(StatusCode::ParseError, name, "PLY header has no 'end_header' line");
    const std::size_t line = lines.line();
    const std::vector<std::string_view> w = split_words(b, e);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    const auto bad = [&](const std::string& what) {
      return error_at(StatusCode::ParseError, name, line, what);
    };
    if (w[0] == "end_header") break;
    if (w[0] == "format") {
      if (w.size() < 2) return bad("PLY 'format' line without a format");
      if (w[1] == "ascii") {
        h.encoding = PlyEncoding::Ascii;
      } else if (w[1] == "binary_little_endian") {
        h.encoding = PlyEncoding::BinaryLittleEndian;
      } else if (w[1] == "binary_big_endian") {
        h.encoding = PlyEncoding::BinaryBigEndian;
      } else {
        return bad("unknown PLY format " + quote_word(w[1]));
      }
      have_format = true;
    } else if (w[0] == "element") {
      PlyElement el;
      if (w.size() != 3 || !parse_count(w[2].data(), w[2].data() + w[2].size(), el.count)) {
        // (digits that do not fit a count: a count too large, not a malformed line)
        const bool digits = w.size() == 3 && !w[2].empty() &&
                            std::all_of(w[2].begin(), w[2].end(), [](char ch) { return ch >= '0' && ch <= '9'; });
        return bad(digits ? "PLY element " + quote_word(w[1]) + ": count " + std::string(w[2]) + " is too large"
                          : "malformed PLY element line (expected 'element NAME COUNT')");
      }
      el.name = std::string(w[1]);
      el.header_line = line;
      h.elements.push_back(std::move(el));
    } else if (w[0] == "property") {
      if (h.elements.empty()) return bad("PLY property before any element");
      Status st = add_property(w, h.elements.back(), name, line);
      if (!st) return st;
    } else {
      return bad("unknown PLY header keyword " + quote_word(w[0]));
    }
  }
  if (!have_format)
    return error_in(StatusCode::ParseError, name, "PLY header has no 'format' line");
  h.body_offset = static_cast<std::size_t>(lines.position() - data.data());
  h.body_line = lines.line() + 1;
  return Status::ok();
}

// ---- body ------------------------------------------------------------------------------------

PlyBody::PlyBody(std::string_view data, const std::string& name, const PlyHeader& header)
    : name_(name),
      p_(data.data() + header.body_offset),
      end_(data.data() + data.size()),
      ascii_(header.encoding == PlyEncoding::Ascii),
      swap_((header.encoding == PlyEncoding::BinaryLittleEndian) != host_is_little_endian()),
      line_(ascii_ ? header.body_line : 0) {}

Status PlyBody::check_room(const PlyElement& el) const {
  const std::uint64_t left = bytes_left();
  if (!ascii_ && el.min_size > 0) {
    // Binary: every record takes at least min_size bytes.
    if (el.count <= left / el.min_size) return Status::ok();
    return error_in(StatusCode::ParseError, name_,
                    "PLY data ends inside element '" + el.name + "' (" + el.name + " " +
                        std::to_string(left / el.min_size) + " of " + std::to_string(el.count) +
                        "): the count on header line " + std::to_string(el.header_line) +
                        " needs at least " + std::to_string(el.min_size) + " bytes per record, " +
                        "only " + std::to_string(left) + " bytes are left; correct the count");
  }
  // Ascii: every value is at least one character. An element without properties holds nothing;
  // its count is still bounded by the bytes left, so a lie of 10^16 empty records is refused.
  const std::uint64_t per_record = std::max<std::uint64_t>(el.properties.size(), 1);
  if (el.count <= left / per_record) return Status::ok();
  const std::string what =
      el.properties.empty()
          ? "has no properties"
          : "has " + plural(el.properties.size(), "value") + " per record";
  return error_at(StatusCode::ParseError, name_, el.header_line,
                  "PLY element '" + el.name + "' announces " + std::to_string(el.count) +
                      " records and " + what + ", more than the " + std::to_string(left) +
                      " bytes left in the file can hold; correct the count");
}

Status PlyBody::check_end(const PlyElement& last) {
  const std::string announced = "the header announces " + std::to_string(last.count) + " records of element '" +
                                last.name + "' (line " + std::to_string(last.header_line) + ")";
  if (ascii_) {
    const char* b = nullptr;
    const char* e = nullptr;
    if (!next_token(b, e)) return Status::ok();
    return error_at(StatusCode::ParseError, name_, line_,
                    "PLY data goes on after its last element: " + announced + ", then " +
                        quote(b, std::min(e, b + 40)) + " follows; correct the count");
  }
  if (bytes_left() < std::max<std::uint64_t>(last.min_size, 1)) return Status::ok();
  return error_in(StatusCode::ParseError, name_,
                  "PLY data goes on after its last element: " + announced + ", then " +
                      std::to_string(bytes_left()) + " bytes follow; correct the count");
}

Status PlyBody::truncated(const PlyElement& el, std::uint64_t i) const {
  return error_in(StatusCode::ParseError, name_,
                  "PLY data ends inside element '" + el.name + "' (" + el.name + " " +
                      std::to_string(i) + " of " + std::to_string(el.count) + ")");
}

Status PlyBody::skip(const PlyElement& el) {
  if (el.properties.empty()) return Status::ok();  // empty records: nothing to read
  if (!ascii_ && !el.has_list) {
    p_ += el.count * el.fixed_size;  // check_room() made sure it fits
    return Status::ok();
  }
  const PlyRecordSpec none{std::vector<int>(el.properties.size(), -1), 0, -1};
  for (std::uint64_t i = 0; i < el.count; ++i) {
    Status st = read_record(el, i, none, nullptr, nullptr);
    if (!st) return st;
  }
  return Status::ok();
}

Status PlyBody::read_table(const PlyElement& el, const PlyRecordSpec& spec, int n_slots,
                           std::vector<double>& table) {
  const auto width = static_cast<std::size_t>(n_slots);
  CONSTRICT_CHECK(width <= kMaxSlots, "more PLY slots than a record row holds");
  if (!ascii_ && !el.has_list) return read_fixed_binary(el, spec, n_slots, table);
  // Never trust the count for an allocation: at most one record per value-sized piece left.
  const std::uint64_t per_record = ascii_ ? 2 * std::max<std::size_t>(el.properties.size(), 1)
                                          : std::max<std::size_t>(el.min_size, 1);
  table.reserve(table.size() +
                static_cast<std::size_t>(std::min(el.count, bytes_left() / per_record)) * width);
  double row[kMaxSlots] = {};
  for (std::uint64_t i = 0; i < el.count; ++i) {
    Status st = ascii_ ? read_record_ascii(el, i, spec, row, nullptr)
                       : read_record_binary(el, i, spec, row, nullptr);
    if (!st) return st;
    table.insert(table.end(), row, row + width);
  }
  return Status::ok();
}

Status PlyBody::read_record(const PlyElement& el, std::uint64_t i, const PlyRecordSpec& spec,
                            double* values, std::vector<std::int64_t>* list) {
  if (list != nullptr) list->clear();
  return ascii_ ? read_record_ascii(el, i, spec, values, list)
                : read_record_binary(el, i, spec, values, list);
}

Status PlyBody::read_record_ascii(const PlyElement& el, std::uint64_t i,
                                  const PlyRecordSpec& spec, double* values,
                                  std::vector<std::int64_t>* list) {
  const char* b = nullptr;
  const char* e = nullptr;
  for (std::size_t k = 0; k < el.properties.size(); ++k) {
    if (!next_token(b, e)) return truncated(el, i);
    const int slot = spec.slot[k];
    if (!el.properties[k].is_list) {
      if (slot < 0) continue;  // skipped values are not parsed
      // A malformed number is an error in any kept value; a non-finite one only in coordinates.
      double& v = values[slot];
      if (parse_double(b, e, v) && (slot >= spec.n_finite || std::isfinite(v))) {
        if (fits_ply_type(v, el.properties[k].type)) continue;
        return error_at(StatusCode::ParseError, name_, line_,
                        "PLY " + el.name + " " + std::to_string(i) + ": " + el.properties[k].name + " = " + quote(b, e) +
                            " does not fit its declared type " + ply_type_name(el.properties[k].type) +
                            " (fix the value or the header's property type)");
      }
      Status st = parse_coordinate(Span{b, e}, name_, line_, v);
      if (st.code() != StatusCode::NonFinite) return st;
      return {st.code(), st.message() + " (" + el.name + " " + std::to_string(i) + ")"};
    }
    std::uint64_t n = 0;
    if (!parse_count(b, e, n))
      return error_at(StatusCode::ParseError, name_, line_,
                      "malformed PLY list length " + quote(b, e));
    const bool keep = list != nullptr && static_cast<int>(k) == spec.list;
    for (std::uint64_t j = 0; j < n; ++j) {
      if (!next_token(b, e)) return truncated(el, i);
      if (!keep) continue;
      double v = 0.0;
      std::int64_t id = 0;
      if (!parse_double(b, e, v) || !to_index(v, id))
        return error_at(StatusCode::ParseError, name_, line_,
                        "PLY list '" + el.properties[k].name + "': " + quote(b, e) +
                            " is not an integer index");
      list->push_back(id);
    }
  }
  return Status::ok();
}

Status PlyBody::read_record_binary(const PlyElement& el, std::uint64_t i,
                                   const PlyRecordSpec& spec, double* values,
                                   std::vector<std::int64_t>* list) {
  for (std::size_t k = 0; k < el.properties.size(); ++k) {
    const PlyProperty& prop = el.properties[k];
    const std::size_t size = ply_size(prop.type);
    if (!prop.is_list) {
      if (bytes_left() < size) return truncated(el, i);
      const int slot = spec.slot[k];
      if (slot >= 0) {
        const double v = load_double(p_, prop.type, swap_);
        if (slot < spec.n_finite && !std::isfinite(v))
          return error_in(StatusCode::NonFinite, name_,
                          "PLY " + el.name + " " + std::to_string(i) +
                              ": non-finite coordinate (" +
                              (std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf") + ")");
        values[slot] = v;
      }
      p_ += size;
      continue;
    }
    const std::size_t count_size = ply_size(prop.count_type);
    std::uint64_t n = 0;
    if (bytes_left() < count_size) return truncated(el, i);
    if (!load_count(p_, prop.count_type, swap_, n))
      return error_in(StatusCode::ParseError, name_,
                      "PLY list with a negative length in element '" + el.name + "' (" + el.name +
                          " " + std::to_string(i) + ")");
    p_ += count_size;
    if (n > bytes_left() / size) return truncated(el, i);
    if (list != nullptr && static_cast<int>(k) == spec.list) {
      for (std::uint64_t j = 0; j < n; ++j, p_ += size) {
        std::int64_t id = 0;
        if (!to_index(load_double(p_, prop.type, swap_), id))
          return error_in(StatusCode::ParseError, name_,
                          "PLY " + el.name + " " + std::to_string(i) + ": list '" + prop.name +
                              "' item " + std::to_string(j) + " is not an integer index");
        list->push_back(id);
      }
    } else {
      p_ += n * size;
    }
  }
  return Status::ok();
}

// Fixed record size: check_room() checked the whole block, so read it with a stride.
Status PlyBody::read_fixed_binary(const PlyElement& el, const PlyRecordSpec& spec, int n_slots,
                                  std::vector<double>& table) {
  struct Column {
    std::size_t offset;
    PlyType type;
    int slot;
  };
  std::vector<Column> columns;
  std::size_t offset = 0;
  for (std::size_t k = 0; k < el.properties.size(); ++k) {
    if (spec.slot[k] >= 0) columns.push_back({offset, el.properties[k].type, spec.slot[k]});
    offset += ply_size(el.properties[k].type);
  }
  const std::size_t stride = el.fixed_size;
  const auto width = static_cast<std::size_t>(n_slots);
  const std::size_t first = table.size();
  table.resize(first + static_cast<std::size_t>(el.count) * width, 0.0);
  double* row = table.data() + first;
  for (std::uint64_t i = 0; i < el.count; ++i, p_ += stride, row += width) {
    for (const Column& c : columns) {
      const double v = load_double(p_ + c.offset, c.type, swap_);
      if (c.slot < spec.n_finite && !std::isfinite(v)) {
        table.resize(first);
        return error_in(StatusCode::NonFinite, name_,
                        "PLY " + el.name + " " + std::to_string(i) + ": non-finite coordinate (" +
                            (std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf") + ")");
      }
      row[c.slot] = v;
    }
  }
  return Status::ok();
}

}  // namespace detail
}  // namespace constrict
