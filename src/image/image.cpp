#include "image/image.h"

#include "image/oiio_plugin.h"
#include "image/stb_codec.h"
#include "scene/error.h"
#include "scene/file_extension.h"

#include <filesystem>
#include <unistd.h>

namespace rayform {
namespace fs = std::filesystem;
Image read_image(const std::string& path) {
  if (!fs::exists(path)) throw Error(path + ": cannot read image: no such file");
  Image img;
  std::string error;
  bool ok = stb_reads(lower_extension(path)) ? stb_read(path, &img, &error) : oiio_read(path, &img, &error);
  if (!ok) throw Error(path + ": cannot decode image" + (error.empty() ? "" : ": " + error));
  return img;
}

bool read_image8(const std::string& path, Image8* image) {
  if (!stb_reads(lower_extension(path))) return false;
  if (!fs::exists(path)) throw Error(path + ": cannot read image: no such file");
  std::string error;
  if (stb_read8(path, image, &error)) return true;
  if (!error.empty()) throw Error(path + ": cannot decode image: " + error);
  return false;
}

bool is_writable_image_path(const std::string& path) {
  std::string ext = lower_extension(path);
  if (ext.empty()) return false;
  return stb_writes(ext) || oiio_can_write(path);
}

std::string write_image_temporary(const std::string& path, const Image& image) {
  std::string ext = lower_extension(path);
  bool use_stb = stb_writes(ext);
  if (!use_stb && (ext.empty() || !oiio_can_write(path)))
    throw Error(path + ": cannot write images of this type (unknown extension '" + ext + "')");
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0) throw Error(path + ": cannot write an empty image");
  // Beside the target under a temporary name (extension kept last for the
  // writers that look at it), so that the rename is atomic.
  fs::path target(path);
  std::string tmp_name = ".";  // (built by appends: GCC 12 warns falsely on "." + string)
  tmp_name.append(target.stem().string())
      .append(".tmp")
      .append(std::to_string(getpid()))
      .append(target.extension().string());
  fs::path tmp = target.parent_path() / tmp_name;
  std::string error;
  bool ok = use_stb ? stb_write(tmp.string(), ext, image, &error) : oiio_write(path, tmp.string(), image, &error);
  if (!ok) {
    discard_temporary(tmp.string());
    throw Error(path + ": cannot write image" + (error.empty() ? "" : ": " + error));
  }
  return tmp.string();
}

void commit_temporary(const std::string& temporary, const std::string& path) {
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    discard_temporary(temporary);
    throw Error(path + ": cannot write image: " + ec.message());
  }
}

void discard_temporary(const std::string& temporary) {
  std::error_code ec;
  fs::remove(temporary, ec);
}

void write_image(const std::string& path, const Image& image) {
  commit_temporary(write_image_temporary(path, image), path);
}

}  // namespace rayform
