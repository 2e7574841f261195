// SPDX-License-Identifier: GPL-3.0-or-later
// PNG files through libpng (Debian libpng-dev). libpng reports errors by longjmp; nothing with a
// destructor lives between setjmp and the libpng calls, and the row pointers are set up first.
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <cerrno>
#include <string>
#include <vector>

#include "constrict/render.hpp"

namespace constrict {
namespace {

struct File {
  std::FILE* f = nullptr;
  ~File() {
    if (f) std::fclose(f);
  }
};

}  // namespace

Status write_png(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != 3u * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    return {StatusCode::InvalidArgument, path + ": empty or inconsistent image"};
  File file;
  file.f = std::fopen(path.c_str(), "wb");
  if (!file.f) return {StatusCode::WriteFailed, path + ": cannot open for writing: " + std::strerror(errno)};
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y)
    rows[static_cast<std::size_t>(y)] =
        const_cast<png_bytep>(image.rgb.data() + 3u * static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width));
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return {StatusCode::WriteFailed, path + ": libpng initialisation failed"};
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return {StatusCode::WriteFailed, path + ": libpng could not write the image"};
  }
  png_init_io(png, file.f);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_rows(png, info, rows.data());
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(file.f) != 0) return {StatusCode::WriteFailed, path + ": write failed: " + std::strerror(errno)};
  return Status::ok();
}

Status read_png(const std::string& path, Image& image) {
  File file;
  file.f = std::fopen(path.c_str(), "rb");
  if (!file.f) return {StatusCode::FileNotFound, path + ": cannot open: " + std::strerror(errno)};
  unsigned char sig[8];
  if (std::fread(sig, 1, 8, file.f) != 8 || png_sig_cmp(sig, 0, 8) != 0)
    return {StatusCode::ParseError, path + ": not a PNG file"};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return {StatusCode::ParseError, path + ": libpng initialisation failed"};
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return {StatusCode::ParseError, path + ": corrupt PNG"};
  }
  png_init_io(png, file.f);
  png_set_sig_bytes(png, 8);
  png_read_png(png, info,
               PNG_TRANSFORM_STRIP_16 | PNG_TRANSFORM_PACKING | PNG_TRANSFORM_EXPAND | PNG_TRANSFORM_STRIP_ALPHA |
                   PNG_TRANSFORM_GRAY_TO_RGB,
               nullptr);
  const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  const png_bytepp rows = png_get_rows(png, info);
  Image out;
  out.width = static_cast<int>(w);
  out.height = static_cast<int>(h);
  out.rgb.resize(3u * w * h);
  for (png_uint_32 y = 0; y < h; ++y) std::memcpy(out.rgb.data() + 3u * w * y, rows[y], 3u * w);
  png_destroy_read_struct(&png, &info, nullptr);
  image = std::move(out);
  return Status::ok();
}

}  // namespace constrict
