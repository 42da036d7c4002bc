#include "image/stb_writer.h"

#include "image/bmp_writer.h"
#include "image/quantize.h"

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

bool stb_write8(const std::string& path, const std::string& ext, const Image8& img, std::string* error) {
  const int w = img.width, h = img.height, c = img.channels;
  const unsigned char* q = img.pixels.data();
  if (ext == ".bmp" && (c == 1 || c == 3)) return write_bmp24(path, img, error);  // stb's bytes, faster
  int ok = 0;
  if (ext == ".png") ok = stbi_write_png(path.c_str(), w, h, c, q, w * c);
  else if (ext == ".bmp") ok = stbi_write_bmp(path.c_str(), w, h, c, q);
  else if (ext == ".tga") ok = stbi_write_tga(path.c_str(), w, h, c, q);
  else if (ext == ".jpg" || ext == ".jpeg") ok = stbi_write_jpg(path.c_str(), w, h, c, q, 95);
  if (!ok) *error = "cannot write the file (folder missing or not writable?)";
  return ok != 0;
}

bool stb_write(const std::string& path, const std::string& ext, const Image& img, std::string* error) {
  if (ext == ".hdr") {
    if (stbi_write_hdr(path.c_str(), img.width, img.height, img.channels, img.pixels.data())) return true;
    *error = "cannot write the file (folder missing or not writable?)";
    return false;
  }
  Image8 q{img.width, img.height, img.channels, std::vector<unsigned char>(img.pixels.size())};
  for (size_t i = 0; i < q.pixels.size(); ++i) q.pixels[i] = quantize_unit(img.pixels[i]);
  return stb_write8(path, ext, q, error);
}

}  // namespace rayform
