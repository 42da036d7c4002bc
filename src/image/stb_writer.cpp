#include "rayform/image/stb_writer.h"

#include "rayform/image/bmp_writer.h"
#include "rayform/image/checked_write.h"
#include "rayform/image/png_writer.h"
#include "rayform/image/quantize.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace rayform {

bool stb_writes(const std::string& ext) {
  return ext == ".bmp" || ext == ".png" || ext == ".tga" || ext == ".jpg" || ext == ".jpeg" || ext == ".hdr";
}

bool stb_writes_8bit(const std::string& ext) {
  return ext == ".bmp" || ext == ".png" || ext == ".tga" || ext == ".jpg" || ext == ".jpeg";
}

namespace {
// stb encodes into memory (its file writers do not check fwrite); the bytes
// then go through write_file_checked.
void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
}
bool write_encoded(const std::string& path, int encoded, const std::vector<unsigned char>& bytes, std::string* error) {
  if (!encoded) {
    *error = "cannot encode the image";
    return false;
  }
  return write_file_checked(path, bytes.data(), bytes.size(), error);
}
}  // namespace

bool stb_write8(const std::string& path, const std::string& ext, const Image8& img, std::string* error) {
  const int w = img.width, h = img.height, c = img.channels;
  const unsigned char* q = img.pixels.data();
  if (ext == ".bmp" && (c == 1 || c == 3)) return write_bmp24(path, img, error);  // stb's bytes, faster
  if (ext == ".png") return write_png(path, img, error);                          // in parallel, faster
  std::vector<unsigned char> bytes;
  int ok = 0;
  if (ext == ".bmp") ok = stbi_write_bmp_to_func(append_bytes, &bytes, w, h, c, q);
  else if (ext == ".tga") ok = stbi_write_tga_to_func(append_bytes, &bytes, w, h, c, q);
  else if (ext == ".jpg" || ext == ".jpeg") ok = stbi_write_jpg_to_func(append_bytes, &bytes, w, h, c, q, 95);
  return write_encoded(path, ok, bytes, error);
}

bool stb_write(const std::string& path, const std::string& ext, const Image& img, std::string* error) {
  if (ext == ".hdr") {
    // Radiance RGBE holds no negative values (stb writes -0.1 as 1.906):
    // they are written as 0.
    const float* data = img.pixels.data();
    std::vector<float> non_negative;
    if (std::any_of(img.pixels.begin(), img.pixels.end(), [](float v) { return !(v >= 0.f); })) {
      non_negative.resize(img.pixels.size());
      for (size_t i = 0; i < non_negative.size(); ++i) non_negative[i] = img.pixels[i] >= 0.f ? img.pixels[i] : 0.f;
      data = non_negative.data();
    }
    std::vector<unsigned char> bytes;
    const int ok = stbi_write_hdr_to_func(append_bytes, &bytes, img.width, img.height, img.channels, data);
    return write_encoded(path, ok, bytes, error);
  }
  Image8 q{img.width, img.height, img.channels, std::vector<unsigned char>(img.pixels.size())};
  for (size_t i = 0; i < q.pixels.size(); ++i) q.pixels[i] = quantize_unit(img.pixels[i]);
  return stb_write8(path, ext, q, error);
}

}  // namespace rayform
