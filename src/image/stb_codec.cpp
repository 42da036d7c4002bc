#include "image/stb_codec.h"

#include "image/bmp_writer.h"
#include "image/checked_write.h"
#include "image/quantize.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace rayform {

bool stb_reads(const std::string& ext) {
  return ext == ".bmp" || ext == ".png" || ext == ".tga" || ext == ".jpg" || ext == ".jpeg" || ext == ".hdr" ||
         ext == ".gif" || ext == ".pnm" || ext == ".ppm" || ext == ".pgm" || ext == ".psd";
}

bool stb_writes(const std::string& ext) {
  return ext == ".bmp" || ext == ".png" || ext == ".tga" || ext == ".jpg" || ext == ".jpeg" || ext == ".hdr";
}

namespace {
// Moves stb's w x h x c samples into *image, each divided by `full_scale` (1
// for HDR floats, 255 or 65535 for integers), and frees them. nullptr: stb's
// reason in *error.
template <class Sample>
bool take_stb_samples(Sample* data, int w, int h, int c, float full_scale, Image* image, std::string* error) {
  if (!data) {
    *error = stbi_failure_reason();
    return false;
  }
  *image = Image(w, h, c);
  for (size_t i = 0; i < image->pixels.size(); ++i) image->pixels[i] = float(data[i]) / full_scale;
  stbi_image_free(data);
  return true;
}
}  // namespace

bool stb_read(const std::string& path, Image* image, std::string* error) {
  int w = 0, h = 0, c = 0;
  const char* file = path.c_str();
  if (stbi_is_hdr(file)) {
    float* data = stbi_loadf(file, &w, &h, &c, 0);
    return take_stb_samples(data, w, h, c, 1.f, image, error);
  }
  if (stbi_is_16_bit(file)) {
    stbi_us* data = stbi_load_16(file, &w, &h, &c, 0);
    return take_stb_samples(data, w, h, c, 65535.f, image, error);
  }
  stbi_uc* data = stbi_load(file, &w, &h, &c, 0);
  return take_stb_samples(data, w, h, c, 255.f, image, error);
}

bool stb_read8(const std::string& path, Image8* image, std::string* error) {
  if (stbi_is_hdr(path.c_str()) || stbi_is_16_bit(path.c_str())) return false;
  int w = 0, h = 0, c = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &c, 0);
  if (!data) {
    *error = stbi_failure_reason();
    return false;
  }
  image->width = w;
  image->height = h;
  image->channels = c;
  image->pixels.assign(data, data + size_t(w) * h * c);
  stbi_image_free(data);
  return true;
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
  std::vector<unsigned char> bytes;
  int ok = 0;
  if (ext == ".png") ok = stbi_write_png_to_func(append_bytes, &bytes, w, h, c, q, w * c);
  else if (ext == ".bmp") ok = stbi_write_bmp_to_func(append_bytes, &bytes, w, h, c, q);
  else if (ext == ".tga") ok = stbi_write_tga_to_func(append_bytes, &bytes, w, h, c, q);
  else if (ext == ".jpg" || ext == ".jpeg") ok = stbi_write_jpg_to_func(append_bytes, &bytes, w, h, c, q, 95);
  return write_encoded(path, ok, bytes, error);
}

bool stb_write(const std::string& path, const std::string& ext, const Image& img, std::string* error) {
  if (ext == ".hdr") {
    std::vector<unsigned char> bytes;
    const int ok = stbi_write_hdr_to_func(append_bytes, &bytes, img.width, img.height, img.channels, img.pixels.data());
    return write_encoded(path, ok, bytes, error);
  }
  Image8 q{img.width, img.height, img.channels, std::vector<unsigned char>(img.pixels.size())};
  for (size_t i = 0; i < q.pixels.size(); ++i) q.pixels[i] = quantize_unit(img.pixels[i]);
  return stb_write8(path, ext, q, error);
}

}  // namespace rayform
