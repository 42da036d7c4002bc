// Textures as files for the writers: the texture's own file when the format
// takes it, else its pixels encoded as PNG or BMP; names for those files.
#pragma once

#include "rayform/scene/scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rayform {

// A texture's name for files: the stem of its name (or file), '\\' read as a
// separator (".\\wal67ar_small.jpg" -> "wal67ar_small").
std::string texture_base_name(const Texture& texture);

// Decoded 8-bit pixels, row 0 at the top.
struct Pixels8 {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> data;
};

// The texture's pixels: Texture::pixels, or its file decoded by read_image_file
// (image.h; 16-bit samples keep their high byte, float ones are clamped and
// rounded). Throws rayform::Error.
Pixels8 texture_pixels(const Texture& texture);

// The texture as a file of one of the `wanted` formats (lower-case extensions
// without the dot: "png", "jpg", "bmp"): its own file's bytes when that file
// has one of them (no re-encoding), else its pixels encoded as wanted[0]
// (png or bmp; bmp drops alpha). `ext` receives the extension used.
// A file's bytes are read up to the image's end (image_extent.h: a PNG's
// IEND, a JPEG's EOI, ...), charged to job_memory(); `note`, when given,
// receives "" or what after that end was left out.
std::vector<uint8_t> texture_file(const Texture& texture, const std::vector<std::string>& wanted, std::string* ext,
                                  std::string* note = nullptr);

// PNG / BMP encoding of 8-bit pixels (BMP: 3 channels, alpha dropped).
std::vector<uint8_t> encode_png(const Pixels8& p);
std::vector<uint8_t> encode_bmp(const Pixels8& p);

// A whole file's bytes. Throws rayform::Error naming the file.
std::vector<uint8_t> read_file_bytes(const std::string& path);
// An image file's bytes up to the image's end (image_extent.h); `note` as texture_file's.
std::vector<uint8_t> read_image_bytes(const std::string& path, std::string* note = nullptr);

}  // namespace rayform
