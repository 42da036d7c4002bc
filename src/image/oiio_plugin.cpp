#include "rayform/image/oiio_plugin.h"

#include "rayform/image/checked_write.h"

#include "rayform/image/oiio_plugin_abi.h"
#include "rayform/base/error.h"
#include "rayform/base/plugin_library.h"

#include <dlfcn.h>

#include <mutex>

namespace rayform {
namespace {

struct Plugin {
  rayform_oiio_can_write_fn can_write = nullptr;
  rayform_oiio_read_fn read = nullptr;
  rayform_oiio_free_fn free = nullptr;
  rayform_oiio_write_fn write = nullptr;
};

const Plugin& plugin() {
  static Plugin p;
  static std::once_flag once;
  static std::string failure;
  std::call_once(once, [] {
    void* h = open_plugin("librayform_oiio.so", "RAYFORM_OIIO_PLUGIN", &failure);
    if (!h) return;
    p.can_write = reinterpret_cast<rayform_oiio_can_write_fn>(dlsym(h, "rayform_oiio_can_write"));
    p.read = reinterpret_cast<rayform_oiio_read_fn>(dlsym(h, "rayform_oiio_read_within"));
    p.free = reinterpret_cast<rayform_oiio_free_fn>(dlsym(h, "rayform_oiio_free"));
    p.write = reinterpret_cast<rayform_oiio_write_fn>(dlsym(h, "rayform_oiio_write"));
    if (p.can_write && p.read && p.free && p.write) return;
    failure = "librayform_oiio.so lacks the rayform_oiio_* functions";
    p = {};
  });
  if (!p.write) throw Error("OpenImageIO plugin unavailable: " + failure);
  return p;
}

}  // namespace

bool oiio_can_write(const std::string& path) { return plugin().can_write(path.c_str()) != 0; }

bool oiio_read(const std::string& path, const char* format, const DecodeOptions& options, DecodedImage* image,
               std::string* error) {
  const Plugin& p = plugin();
  int w = 0, h = 0, c = 0, bits = 0;
  void* data = nullptr;
  char buf[512] = {0};
  // The plugin's buffer and image->bytes, a copy of it, are both held at once.
  MemoryBudget& budget = options.memory ? *options.memory : job_memory();
  const uint64_t left = budget.used() < budget.limit() ? budget.limit() - budget.used() : 0;
  const int r = p.read(path.c_str(), format, options.max_texels, max_texture_side(options), left, &w, &h, &c, &bits,
                       &data, buf, sizeof buf);
  if (r == 2) check_texture_size(path, uint64_t(w), uint64_t(h), bits == 8 ? 4 : 16, options);  // throws
  const uint64_t bytes_read = uint64_t(w) * uint64_t(h) * uint64_t(c) * uint64_t(bits / 8);
  const std::string what = "decoding the " + std::to_string(w) + "x" + std::to_string(h) + " texture";
  if (r == 3) throw Error(path + ": " + budget.problem(2 * bytes_read, what));
  if (r != 1) {
    *error = buf;
    return false;
  }
  MemoryCharge plugin_buffer;
  try {
    plugin_buffer = budget.charge(bytes_read, what);
    image->memory = budget.charge(bytes_read, what);
  } catch (...) {  // (another thread took what was left)
    p.free(data);
    throw;
  }
  image->width = w;
  image->height = h;
  image->channels = c;
  image->bits = bits;
  const uint8_t* bytes = static_cast<const uint8_t*>(data);
  image->bytes.assign(bytes, bytes + size_t(w) * h * c * size_t(bits / 8));
  p.free(data);
  return true;
}

bool oiio_write(const std::string& file_for_format, const std::string& path, const Image& image, std::string* error) {
  char buf[512] = {0};
  if (!plugin().write(file_for_format.c_str(), path.c_str(), image.width, image.height, image.channels,
                      image.pixels.data(), buf, sizeof buf)) {
    *error = buf;
    return false;
  }
  return sync_file(path, error);  // OpenImageIO's own writes are not all checked
}

}  // namespace rayform
