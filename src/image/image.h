// Float image buffers and their file I/O through OpenImageIO (format chosen by
// the file extension). Row 0 is the top row; channels are interleaved.
#pragma once

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

// Reads any format OpenImageIO knows; 8-bit data map to v / 255 exactly.
// Throws rayform::Error naming the file on failure.
Image read_image(const std::string& path);

// Writes by extension (bmp, png, tga, jpg, exr, hdr, tif, ...). Integer
// formats store floor(clamp(v, 0, 1) * 255) per channel, as the course
// reference quantises; float formats store the values. The image is written to
// a temporary file beside `path` and renamed over it, so a failure never leaves
// a partial file. Throws rayform::Error on failure.
void write_image(const std::string& path, const Image& image);

// True when OpenImageIO can write files with this path's extension.
bool is_writable_image_path(const std::string& path);

}  // namespace rayform
