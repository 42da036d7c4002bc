#include "rayform/importers/texture_files.h"

#include "rayform/image/image.h"
#include "rayform/image/image_extent.h"
#include "rayform/base/memory_budget.h"
#include "rayform/base/error.h"
#include "rayform/base/file_extension.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

namespace rayform {
namespace fs = std::filesystem;

std::string texture_base_name(const Texture& t) {
  std::string n = !t.name.empty() ? t.name : (!t.path.empty() ? t.path : std::string("texture"));
  std::replace(n.begin(), n.end(), '\\', '/');
  std::string stem = fs::path(n).stem().string();
  return stem.empty() ? std::string("texture") : stem;
}

std::vector<uint8_t> read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(path + ": cannot read file");
  return bytes;
}

std::vector<uint8_t> read_image_bytes(const std::string& path, std::string* note) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const uint64_t file_bytes = fs::file_size(path, ec);
  if (!in || ec) throw Error(path + ": cannot open file");
  const ImageExtent extent = image_extent(in, file_bytes);
  if (!extent.problem.empty()) throw Error(path + ": cannot copy image: " + extent.problem);
  if (note) *note = trailing_bytes_note(extent);
  // Charged while read: refused when more than is left of the memory limit.
  const MemoryCharge charge = job_memory().charge(extent.bytes, path + ": copying the image file");
  std::vector<uint8_t> bytes(size_t(extent.bytes));
  in.clear();
  in.seekg(0);
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
  if (size_t(in.gcount()) != bytes.size()) throw Error(path + ": cannot read file");
  return bytes;
}

Pixels8 texture_pixels(const Texture& t) {
  Pixels8 p;
  if (!t.pixels.empty()) {
    p.width = t.width;
    p.height = t.height;
    p.channels = t.channels;
    if (p.width <= 0 || p.height <= 0 || p.channels < 1 || p.channels > 4 ||
        t.pixels.size() != size_t(p.width) * size_t(p.height) * size_t(p.channels))
      throw Error("texture '" + t.name + "': inconsistent pixel data");
    p.data = t.pixels;
    return p;
  }
  if (t.path.empty()) throw Error("texture '" + t.name + "': neither pixels nor a file");
  // Decoded as the renderer decodes it (image.h: libpng, libjpeg-turbo,
  // libwebp, our BMP reader, else OpenImageIO), under the default size limit.
  DecodedImage d = read_image_file(t.path);
  // (the pixels made of the decoded samples are charged with them: d.memory is held until they are made)
  p.width = d.width;
  p.height = d.height;
  p.channels = std::min(d.channels, 4);
  p.data.resize(size_t(p.width) * size_t(p.height) * size_t(p.channels));
  const size_t n = size_t(p.width) * size_t(p.height), c = size_t(d.channels);
  if (d.bits == 8 || d.bits == 16) {                          // 16-bit: the high byte
    const size_t step = size_t(d.bits / 8), high = step - 1;  // (little-endian samples)
    for (size_t i = 0; i < n; ++i)
      for (size_t k = 0; k < size_t(p.channels); ++k)
        p.data[i * size_t(p.channels) + k] = d.bytes[(i * c + k) * step + high];
    return p;
  }
  // Float formats (hdr, exr, ...): clamped to [0, 1] and rounded.
  Image img = to_float_image(d);
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < p.channels; ++k)
      p.data[i * size_t(p.channels) + size_t(k)] =
          uint8_t(std::lround(std::clamp(img.pixels[i * c + size_t(k)], 0.f, 1.f) * 255.f));
  return p;
}

namespace {
void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<uint8_t>*>(context);
  const uint8_t* b = static_cast<const uint8_t*>(data);
  out->insert(out->end(), b, b + size);
}
}  // namespace

std::vector<uint8_t> encode_png(const Pixels8& p) {
  std::vector<uint8_t> out;
  if (!stbi_write_png_to_func(append_bytes, &out, p.width, p.height, p.channels, p.data.data(), p.width * p.channels))
    throw Error("cannot encode a PNG image");
  return out;
}

std::vector<uint8_t> encode_bmp(const Pixels8& p) {
  // 24-bit BMP: the course reads no other kind.
  std::vector<uint8_t> rgb(size_t(p.width) * size_t(p.height) * 3);
  for (size_t i = 0, n = size_t(p.width) * size_t(p.height); i < n; ++i)
    for (int k = 0; k < 3; ++k)
      rgb[i * 3 + size_t(k)] = p.data[i * size_t(p.channels) + size_t(p.channels >= 3 ? k : 0)];
  std::vector<uint8_t> out;
  if (!stbi_write_bmp_to_func(append_bytes, &out, p.width, p.height, 3, rgb.data()))
    throw Error("cannot encode a BMP image");
  return out;
}

std::vector<uint8_t> texture_file(const Texture& t, const std::vector<std::string>& wanted, std::string* ext,
                                  std::string* note) {
  if (!t.path.empty()) {
    std::string e = lower_extension(t.path);
    if (!e.empty()) e = e.substr(1);
    if (e == "jpeg") e = "jpg";
    std::error_code ec;
    if (std::find(wanted.begin(), wanted.end(), e) != wanted.end() && fs::is_regular_file(t.path, ec)) {
      *ext = e;
      return read_image_bytes(t.path, note);
    }
  }
  Pixels8 p = texture_pixels(t);
  *ext = wanted.at(0);
  return *ext == "bmp" ? encode_bmp(p) : encode_png(p);
}

}  // namespace rayform
