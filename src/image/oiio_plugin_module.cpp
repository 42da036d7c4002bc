// librayform_oiio.so: OpenImageIO behind the C interface of oiio_plugin_abi.h.
#include "image/oiio_plugin_abi.h"

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

extern "C" {

__attribute__((visibility("default"))) int rayform_oiio_can_write(const char* path) {
  return OIIO::ImageOutput::create(path) ? 1 : 0;
}

__attribute__((visibility("default"))) int rayform_oiio_read(const char* path, int* width, int* height, int* channels,
                                                             float** pixels, char* error, size_t error_size) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    set_error(error, error_size, OIIO::geterror());
    return 0;
  }
  const OIIO::ImageSpec& spec = in->spec();
  size_t n = size_t(spec.width) * spec.height * spec.nchannels;
  float* data = static_cast<float*>(std::malloc(n * sizeof(float)));
  if (!data || !in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data)) {
    set_error(error, error_size, data ? in->geterror() : "out of memory");
    std::free(data);
    return 0;
  }
  *width = spec.width;
  *height = spec.height;
  *channels = spec.nchannels;
  *pixels = data;
  return 1;
}

__attribute__((visibility("default"))) void rayform_oiio_free(float* pixels) { std::free(pixels); }

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
