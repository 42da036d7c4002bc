// 24-bit uncompressed BMP. The bytes are those
// stb_image_write's stbi_write_bmp gives for a 1- or 3-channel image (the
// BITMAPINFOHEADER with zero resolution and size fields, rows bottom to top,
// BGR, each row padded with zeros to 4 bytes), but the file is assembled row
// by row rather than through a call per pixel: 3 MB in ~2 ms instead of ~11.
#pragma once

#include "rayform/image/image.h"

#include <string>
#include <vector>

namespace rayform {

// The file's bytes. `image` has 1 (grey, written as BGR) or 3 (RGB) channels.
std::vector<unsigned char> encode_bmp24(const Image8& image);

// Writes the bytes of encode_bmp24(image) to `path` (the caller picks the
// temporary name) through a CheckedFile, a block of rows at a time. Returns
// false and sets *error when the file cannot be written.
bool write_bmp24(const std::string& path, const Image8& image, std::string* error);

}  // namespace rayform
