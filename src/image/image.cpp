#include "image/image.h"

#include "image/oiio_plugin.h"
#include "image/stb_codec.h"
#include "scene/error.h"

#include <algorithm>
#include <filesystem>
#include <unistd.h>

namespace rayform {
namespace fs = std::filesystem;
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

Image read_image(const std::string& path) {
  if (!fs::exists(path)) throw Error(path + ": cannot read image: no such file");
  Image img;
  std::string error;
  bool ok = stb_reads(lower_extension(path)) ? stb_read(path, &img, &error) : oiio_read(path, &img, &error);
  if (!ok) throw Error(path + ": cannot decode image" + (error.empty() ? "" : ": " + error));
  return img;
}

bool is_writable_image_path(const std::string& path) {
  std::string ext = lower_extension(path);
  if (ext.empty()) return false;
  return stb_writes(ext) || oiio_can_write(path);
}

void write_image(const std::string& path, const Image& image) {
  std::string ext = lower_extension(path);
  bool use_stb = stb_writes(ext);
  if (!use_stb && (ext.empty() || !oiio_can_write(path)))
    throw Error(path + ": cannot write images of this type (unknown extension '" + ext + "')");
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0) throw Error(path + ": cannot write an empty image");
  // Written beside the target under a temporary name (extension kept last for
  // the writers that look at it), then renamed over it: a failed run never
  // leaves a partial file.
  fs::path target(path);
  std::string tmp_name = ".";  // (built by appends: GCC 12 warns falsely on "." + string)
  tmp_name.append(target.stem().string()).append(".tmp").append(std::to_string(getpid())).append(target.extension().string());
  fs::path tmp = target.parent_path() / tmp_name;
  std::string error;
  bool ok = use_stb ? stb_write(tmp.string(), ext, image, &error) : oiio_write(path, tmp.string(), image, &error);
  std::error_code ec;
  if (ok) {
    fs::rename(tmp, target, ec);
    if (ec) error = ec.message();
  }
  if (!ok || ec) {
    fs::remove(tmp, ec);
    throw Error(path + ": cannot write image" + (error.empty() ? "" : ": " + error));
  }
}

}  // namespace rayform
