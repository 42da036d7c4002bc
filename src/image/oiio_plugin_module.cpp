// librayform_oiio.so: OpenImageIO behind the C interface of oiio_plugin_abi.h.
// Reading checks the header's dimensions against the caller's texel limit
// before any pixel is decoded, and returns 8-bit files as 8-bit samples.
#include "rayform/image/oiio_plugin_abi.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {
void set_error(char* error, size_t size, const std::string& message) {
  if (size == 0) return;
  std::strncpy(error, message.c_str(), size - 1);
  error[size - 1] = '\0';
}
}  // namespace

namespace {
int read_with_oiio(const char* path, const char* format, unsigned long long max_texels, unsigned long long max_side,
                   unsigned long long max_bytes, int* width, int* height, int* channels, int* bits, void** pixels,
                   char* error, size_t error_size) {
  // Alpha as the file stores it: OpenImageIO would premultiply unassociated
  // alpha (TGA, TIFF, ...) by default; textures take it as stb_image gave it.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  // The reader named, not ImageInput::open's: that one tries every reader
  // OpenImageIO has on a file its extension's reader does not take.
  auto in = OIIO::ImageInput::create(format, false, &config);
  if (!in) {
    set_error(error, error_size, OIIO::geterror());
    return 0;
  }
  OIIO::ImageSpec opened;
  if (!in->open(path, opened, config)) {
    set_error(error, error_size, in->geterror());
    return 0;
  }
  const OIIO::ImageSpec& spec = in->spec();
  // The header only has been read: refuse what the caller's limit forbids
  // before allocating or decoding anything.
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1 || spec.nchannels <= 0 || spec.nchannels > 64) {
    set_error(error, error_size,
              "unsupported image layout (" + std::to_string(spec.width) + "x" + std::to_string(spec.height) + "x" +
                  std::to_string(spec.depth) + ", " + std::to_string(spec.nchannels) + " channels)");
    return 0;
  }
  *width = spec.width;
  *height = spec.height;
  *channels = spec.nchannels;
  bool eight = spec.format == OIIO::TypeDesc::UINT8;
  for (const OIIO::TypeDesc& t : spec.channelformats) eight = eight && t == OIIO::TypeDesc::UINT8;
  *bits = eight ? 8 : 32;
  if ((unsigned long long)spec.width > max_side || (unsigned long long)spec.height > max_side ||
      (unsigned long long)spec.width * (unsigned long long)spec.height > max_texels)
    return 2;
  const size_t n = size_t(spec.width) * spec.height * spec.nchannels;
  if ((unsigned long long)n * (eight ? 1 : sizeof(float)) > max_bytes / 2) return 3;
  void* data = std::malloc(n * (eight ? 1 : sizeof(float)));
  const OIIO::TypeDesc type = eight ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
  if (!data || !in->read_image(0, 0, 0, spec.nchannels, type, data)) {
    set_error(error, error_size, data ? in->geterror() : "out of memory");
    std::free(data);
    return 0;
  }
  *pixels = data;
  return 1;
}
}  // namespace

extern "C" {

__attribute__((visibility("default"))) int rayform_oiio_can_write(const char* path) {
  return OIIO::ImageOutput::create(path) ? 1 : 0;
}

// No exception crosses this C boundary: OpenImageIO's readers throw on some
// broken files (a GIF whose frame asks for a vector longer than max_size).
__attribute__((visibility("default"))) int rayform_oiio_read_within(const char* path, const char* format,
                                                                    unsigned long long max_texels,
                                                                    unsigned long long max_side,
                                                                    unsigned long long max_bytes, int* width,
                                                                    int* height, int* channels, int* bits,
                                                                    void** pixels, char* error, size_t error_size) {
  try {
    return read_with_oiio(path, format, max_texels, max_side, max_bytes, width, height, channels, bits, pixels, error,
                          error_size);
  } catch (const std::exception& e) {
    set_error(error, error_size, std::string("OpenImageIO failed: ") + e.what());
  } catch (...) {
    set_error(error, error_size, "OpenImageIO failed");
  }
  return 0;
}

__attribute__((visibility("default"))) void rayform_oiio_free(void* pixels) { std::free(pixels); }

__attribute__((visibility("default"))) int rayform_oiio_write(const char* format_path, const char* path, int width,
                                                              int height, int channels, const float* pixels,
                                                              char* error, size_t error_size) {
  auto out = OIIO::ImageOutput::create(format_path);
  if (!out) {
    set_error(error, error_size, "no writer for this file type");
    return 0;
  }
  std::string format = out->format_name();
  bool float_format = format == "openexr" || format == "hdr" || format == "tiff" || format == "fits" || format == "pfm";
  OIIO::ImageSpec spec(width, height, channels, float_format ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  bool ok = out->open(path, spec);
  if (ok) {
    if (float_format) {
      ok = out->write_image(OIIO::TypeDesc::FLOAT, pixels);
    } else {
      size_t n = size_t(width) * height * channels;
      std::vector<unsigned char> q(n);
      for (size_t i = 0; i < n; ++i) {
        float v = std::isnan(pixels[i]) ? 0.f : std::clamp(pixels[i], 0.f, 1.f);
        q[i] = (unsigned char)std::min(255.f, std::floor(v * 255.f));
      }
      ok = out->write_image(OIIO::TypeDesc::UINT8, q.data());
    }
    ok = out->close() && ok;
  }
  if (!ok) set_error(error, error_size, out->geterror());
  return ok ? 1 : 0;
}

}  // extern "C"
