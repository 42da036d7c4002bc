#include "image/image.h"

#include "scene/error.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

namespace rayform {
namespace fs = std::filesystem;

Image read_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    std::string why = OIIO::geterror();
    throw Error(path + ": cannot read image" + (why.empty() ? "" : ": " + why));
  }
  const OIIO::ImageSpec& spec = in->spec();
  Image img(spec.width, spec.height, spec.nchannels);
  bool ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data());
  if (!ok) throw Error(path + ": cannot decode image: " + in->geterror());
  return img;
}

bool is_writable_image_path(const std::string& path) {
  auto out = OIIO::ImageOutput::create(path);
  return bool(out);
}

void write_image(const std::string& path, const Image& image) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw Error(path + ": cannot write images of this type (unknown extension '" +
                        fs::path(path).extension().string() + "')");
  bool float_format = out->supports("channelformat:float") ||
                      std::string(out->format_name()) == "openexr" || std::string(out->format_name()) == "hdr";
  // Keep the extension last so that plugins which check it are satisfied.
  fs::path target(path);
  std::string tmp_name = ".";  // (built by appends: GCC 12 warns falsely on "." + string)
  tmp_name.append(target.stem().string()).append(".tmp").append(std::to_string(getpid())).append(target.extension().string());
  fs::path tmp = target.parent_path() / tmp_name;
  OIIO::ImageSpec spec(image.width, image.height, image.channels,
                       float_format ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  bool ok = out->open(tmp.string(), spec);
  if (ok) {
    if (float_format) {
      ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
    } else {
      std::vector<unsigned char> q(image.pixels.size());
      for (size_t i = 0; i < q.size(); ++i) {
        float v = image.pixels[i];
        v = std::isnan(v) ? 0.f : std::clamp(v, 0.f, 1.f);
        q[i] = (unsigned char)std::min(255.f, std::floor(v * 255.f));
      }
      ok = out->write_image(OIIO::TypeDesc::UINT8, q.data());
    }
    ok = out->close() && ok;
  }
  if (!ok) {
    std::string why = out->geterror();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw Error(path + ": cannot write image" + (why.empty() ? "" : ": " + why));
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(path + ": cannot write image: " + ec.message());
  }
}

}  // namespace rayform
