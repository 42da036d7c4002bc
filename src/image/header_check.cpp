#include "rayform/image/header_check.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>

namespace rayform {
namespace {

uint32_t le32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
uint32_t le16(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8; }

// The bytes OpenEXR reads for a value of `type` starting at head[at],
// whatever size the attribute declares: fixed for most types, found by
// parsing for channel lists (names until an empty one, 16 bytes after each)
// and previews (width, height, then RGBA8 pixels); -1 for types read by their
// declared size (string, stringvector, floatvector, unknown types), -2 when
// the value runs past what was read.
int64_t exr_value_bytes(const std::string& type, const uint8_t* head, size_t size, size_t at) {
  static const struct {
    const char* type;
    int bytes;
  } fixed[] = {{"box2i", 16},
               {"box2f", 16},
               {"chromaticities", 32},
               {"compression", 1},
               {"deepImageState", 1},
               {"double", 8},
               {"envmap", 1},
               {"float", 4},
               {"int", 4},
               {"keycode", 28},
               {"lineOrder", 1},
               {"m33f", 36},
               {"m33d", 72},
               {"m44f", 64},
               {"m44d", 128},
               {"rational", 8},
               {"tiledesc", 9},
               {"timecode", 8},
               {"v2i", 8},
               {"v2f", 8},
               {"v2d", 16},
               {"v3i", 12},
               {"v3f", 12},
               {"v3d", 24}};
  for (const auto& f : fixed)
    if (type == f.type) return f.bytes;
  if (type == "chlist") {
    size_t p = at;
    while (true) {
      const void* end = p < size ? std::memchr(head + p, 0, size - p) : nullptr;
      if (!end) return -2;
      const size_t name_bytes = size_t(static_cast<const uint8_t*>(end) - (head + p));
      p += name_bytes + 1;
      if (name_bytes == 0) return int64_t(p - at);
      p += 16;  // pixel type, pLinear, reserved, x and y sampling
    }
  }
  if (type == "preview") {
    if (at + 8 > size) return -2;
    const uint64_t texels = uint64_t(le32(head + at)) * le32(head + at + 4);  // < 2^64
    constexpr uint64_t most = (uint64_t(INT64_MAX) - 8) / 4;  // more never matches a declared int32 anyway
    return texels > most ? INT64_MAX : int64_t(8 + 4 * texels);
  }
  return -1;
}

// OpenEXR: magic, version, then attributes "name\0type\0" int32 size, value;
// an empty name ends the (first part's) header. OpenEXR reads some values by
// their type, not their declared size, and goes on from where the value
// ended: an attribute whose value takes other than the bytes it declares is
// refused, so that the walk here stays where OpenEXR's is.
std::string exr_problem(const uint8_t* head, size_t size, uint64_t file_bytes, const DecodeOptions& options) {
  size_t at = 8;
  while (at < size) {
    auto text = [&](std::string* out) {  // a NUL-terminated string inside head
      const void* end = std::memchr(head + at, 0, size - at);
      if (!end) return false;
      out->assign(reinterpret_cast<const char*>(head + at), static_cast<const uint8_t*>(end) - (head + at));
      at += out->size() + 1;
      return true;
    };
    std::string name, type;
    if (!text(&name)) return "";  // the header goes on past what was read
    if (name.empty()) return "";  // end of the header
    if (!text(&type) || at + 4 > size) return "";
    const uint64_t bytes = le32(head + at);
    at += 4;
    if (int32_t(bytes) < 0 || at + bytes > file_bytes)
      return "EXR attribute '" + name + "' declares " + std::to_string(int32_t(bytes)) + " bytes, more than the " +
             std::to_string(file_bytes) + " bytes of the file";
    const int64_t value_bytes = exr_value_bytes(type, head, size, at);
    if (value_bytes == -2) return "";  // the header goes on past what was read
    if (value_bytes >= 0 && uint64_t(value_bytes) != bytes)
      return "EXR attribute '" + name + "' of type " + type + " declares " + std::to_string(bytes) +
             " bytes but its value takes " +
             (uint64_t(value_bytes) > file_bytes ? "more than the " + std::to_string(file_bytes) + " bytes of the file"
                                                 : std::to_string(value_bytes));
    if (name == "dataWindow" && type == "box2i" && bytes == 16 && at + 16 <= size) {
      const int64_t x0 = int32_t(le32(head + at)), y0 = int32_t(le32(head + at + 4)), x1 = int32_t(le32(head + at + 8)),
                    y1 = int32_t(le32(head + at + 12));
      const uint64_t w = x1 >= x0 ? uint64_t(x1 - x0 + 1) : 0, h = y1 >= y0 ? uint64_t(y1 - y0 + 1) : 0;
      if (exceeds_texel_limit(w, h, options)) return texture_size_message(w, h, 16, options);
    }
    at += bytes;
  }
  return "";
}

}  // namespace

std::string header_problem(const uint8_t* head, size_t size, uint64_t file_bytes, const DecodeOptions& options) {
  if (size >= 8 && std::memcmp(head, "\x76\x2f\x31\x01", 4) == 0) return exr_problem(head, size, file_bytes, options);
  // A BMP reaches here only when our reader does not take it (RLE, paletted,
  // bit fields, odd headers): OpenImageIO 2.4's BMP reader is not safe for
  // such files (a fuzzed one crashed it in read_native_scanline), so none goes there.
  if (size >= 2 && head[0] == 'B' && head[1] == 'M')
    return "BMP other than uncompressed 24- or 32-bit is not read (RLE, paletted and bit-field BMPs are refused)";
  // giflib takes any "GIF" signature (the version is not checked), whatever the extension.
  if (size >= 10 && std::memcmp(head, "GIF", 3) == 0) {
    const uint64_t w = le16(head + 6), h = le16(head + 8);  // the logical screen: giflib's canvas
    if (exceeds_texel_limit(w, h, options)) return texture_size_message(w, h, 4, options);
  }
  return "";
}

const char* const oiio_read_formats = "TGA, HDR, EXR, TIFF, GIF, PNM, PSD";

const char* oiio_reader_for(const uint8_t* head, size_t size, const std::string& path) {
  auto starts = [&](const char* magic, size_t n) { return size >= n && std::memcmp(head, magic, n) == 0; };
  if (starts("\x76\x2f\x31\x01", 4)) return "openexr";
  if (starts("#?", 2)) return "hdr";  // #?RADIANCE, #?RGBE
  if (starts("II*\0", 4) || starts("MM\0*", 4) || starts("II+\0", 4) || starts("MM\0+", 4)) return "tiff";
  if (starts("GIF", 3)) return "gif";
  if (size >= 2 && head[0] == 'P' && head[1] != '\0' && std::strchr("123456fF", head[1])) return "pnm";
  if (starts("8BPS", 4)) return "psd";
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".tga" || ext == ".targa") return "targa";
  return nullptr;
}

}  // namespace rayform
