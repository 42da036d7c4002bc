// Float and 8-bit image buffers and their file I/O: reading through
// image_decode.h (or OpenImageIO), writing through stb_image_write, our BMP,
// PNG and EXR writers or OpenImageIO (format chosen by the file extension). Row 0 is the
// top row; channels are interleaved.
#pragma once

#include "rayform/image/image_decode.h"
#include "rayform/image/image_file.h"

#include <string>
#include <vector>

namespace rayform {

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;  // width * height * channels, row-major from the top

  Image() = default;
  Image(int w, int h, int c, float fill = 0.f) : width(w), height(h), channels(c), pixels(size_t(w) * h * c, fill) {}
  bool empty() const { return pixels.empty(); }
  float* at(int x, int y) { return pixels.data() + (size_t(y) * width + x) * channels; }
  const float* at(int x, int y) const { return pixels.data() + (size_t(y) * width + x) * channels; }
};

// Image8: 8-bit pixels as stored in a file (row 0 = top, interleaved channels).
struct Image8 {
  int width = 0, height = 0, channels = 0;
  std::vector<unsigned char> pixels;
};

// Reads an image file with its samples as stored (8-bit, 16-bit or float):
// PNG, JPEG, WebP and uncompressed BMP in memory, every other format through
// OpenImageIO (image_decode.h). The header's dimensions are checked against
// options.max_texels before any pixel is decoded. Throws rayform::Error naming
// the file when it is missing, too large or cannot be decoded.
DecodedImage read_image_file(const std::string& path, const DecodeOptions& options = {});

// The same as floats: 8-bit as v / 255, 16-bit as v / 65535, float as stored.
Image read_image(const std::string& path, const DecodeOptions& options = {});
Image to_float_image(const DecodedImage& decoded);

// Writes by extension (bmp, png, tga, jpg, exr, hdr, tif, ...). Integer
// formats store floor(clamp(v, 0, 1) * 255) per channel, as the course
// reference quantises; float formats store the values. The image is written to
// a temporary file beside `path` and renamed over it, so a failure never leaves
// a partial file. Throws rayform::Error on failure.
void write_image(const std::string& path, const Image& image);

// The two halves of write_image, for several outputs that must appear
// together or not at all: write each to its temporary file first (throws,
// leaving nothing behind), then rename them all. discard_temporary removes a
// temporary that will not be committed.
// The forms that take an ImageFile (image_file.h) use its parse of the path.
std::string write_image_temporary(const std::string& path, const Image& image);
std::string write_image_temporary(const ImageFile& file, const Image& image);
// The same for 8-bit pixels, stored as they are, to a file whose samples are
// 8-bit (ImageFile::bits8: bmp, png, tga, jpg).
std::string write_image8_temporary(const std::string& path, const Image8& image);
std::string write_image8_temporary(const ImageFile& file, const Image8& image);
bool is_8bit_image_path(const std::string& path);
// True when files with this path's extension hold float samples, unclamped:
// exr, hdr, tif/tiff, fits, pfm (the formats OpenImageIO's writer is asked
// for floats, and stb's .hdr). Every other writable format stores 8-bit values.
bool is_float_image_path(const std::string& path);
void commit_temporary(const std::string& temporary, const std::string& path);
void discard_temporary(const std::string& temporary);

// Whether rayform writes files with this path's extension with an alpha
// channel: png and tga (straight alpha), exr and tif/tiff (premultiplied).
bool is_alpha_image_path(const std::string& path);

// True when rayform writes files with this path's extension: stb, or
// OpenImageIO (asked through its plugin, opened for it).
bool is_writable_image_path(const std::string& path);
bool is_writable(const ImageFile& file);

}  // namespace rayform
