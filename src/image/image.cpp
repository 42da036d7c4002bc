#include "rayform/image/image.h"

#include "rayform/image/exr_writer.h"
#include "rayform/image/header_check.h"
#include "rayform/image/image_extent.h"
#include "rayform/image/image_file.h"
#include "rayform/image/interrupt_cleanup.h"
#include "rayform/image/oiio_plugin.h"
#include "rayform/image/replace_file.h"
#include "rayform/image/stb_writer.h"
#include "rayform/base/error.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

namespace rayform {
namespace fs = std::filesystem;
namespace {
// Enough for every header decodes_in_memory looks at (a BMP's is the longest).
constexpr size_t sniff_bytes = 256;
// How much of a file OpenImageIO will read is checked first (header_check.h).
constexpr size_t header_bytes = 64 * 1024;
}  // namespace

DecodedImage read_image_file(const std::string& path, const DecodeOptions& options) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in)
    throw Error(path + (fs::exists(path, ec) ? ": cannot open image file" : ": cannot read image: no such file"));
  std::vector<uint8_t> bytes(sniff_bytes);
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
  bytes.resize(size_t(in.gcount()));
  if (decodes_in_memory(bytes.data(), bytes.size())) {
    // Up to the image's end (image_extent.h), not what follows it; charged
    // while it is decoded.
    std::error_code size_error;
    const uint64_t file_bytes = fs::file_size(path, size_error);
    MemoryCharge file_memory;
    std::string note;
    if (bytes.size() == sniff_bytes && !size_error) {
      const ImageExtent extent = image_extent(in, file_bytes);
      if (!extent.problem.empty()) throw Error(path + ": cannot decode image: " + extent.problem);
      note = trailing_bytes_note(extent);
      MemoryBudget& budget = options.memory ? *options.memory : job_memory();
      budget.credit_input(extent.bytes);
      file_memory = budget.charge(extent.bytes, path + ": reading the file");
      bytes.resize(size_t(extent.bytes));
      in.clear();
      in.seekg(0);
      in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
      if (size_t(in.gcount()) != bytes.size()) throw Error(path + ": cannot read image file");
    } else if (bytes.size() == sniff_bytes) {  // (not a regular file: read to its end)
      bytes.insert(bytes.end(), std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    if (in.bad()) throw Error(path + ": cannot read image file");
    DecodedImage d = decode_image_memory(bytes.data(), bytes.size(), path, options);
    d.note = std::move(note);
    return d;
  }
  // Every other format rayform reads (tga, hdr, exr, tif, gif, pnm, psd):
  // OpenImageIO's reader for it, once the headers it trusts too far are
  // checked (header_check.h).
  const char* format = nullptr;
  {
    if (bytes.size() == sniff_bytes) {  // more to read
      bytes.resize(header_bytes);
      in.read(reinterpret_cast<char*>(bytes.data()) + sniff_bytes, std::streamsize(header_bytes - sniff_bytes));
      bytes.resize(sniff_bytes + size_t(in.gcount()));
    }
    std::error_code ec;
    const uint64_t file_bytes = fs::file_size(path, ec);
    if (std::string problem = header_problem(bytes.data(), bytes.size(), ec ? bytes.size() : file_bytes, options);
        !problem.empty())
      throw Error(path + ": " + (problem.rfind("texture is", 0) == 0 ? "" : "cannot decode image: ") + problem);
    format = oiio_reader_for(bytes.data(), bytes.size(), path);
    if (!format)
      throw Error(path + ": cannot decode image: not a format rayform reads (PNG, JPEG, WebP, BMP, " +
                  oiio_read_formats + ")");
  }
  DecodedImage img;
  std::string error;
  if (!oiio_read(path, format, options, &img, &error))
    throw Error(path + ": cannot decode image" + (error.empty() ? "" : ": " + error));
  return img;
}

Image to_float_image(const DecodedImage& d) {
  Image img(d.width, d.height, d.channels);
  const size_t n = img.pixels.size();
  if (d.bits == 8) {
    for (size_t i = 0; i < n; ++i) img.pixels[i] = float(d.bytes[i]) / 255.f;
  } else if (d.bits == 16) {
    for (size_t i = 0; i < n; ++i) {
      uint16_t v;
      std::memcpy(&v, &d.bytes[2 * i], 2);
      img.pixels[i] = float(v) / 65535.f;
    }
  } else {
    std::memcpy(img.pixels.data(), d.bytes.data(), n * sizeof(float));
  }
  return img;
}

Image read_image(const std::string& path, const DecodeOptions& options) {
  return to_float_image(read_image_file(path, options));
}

bool is_writable_image_path(const std::string& path) { return is_writable(image_file(path)); }

bool is_writable(const ImageFile& file) {
  if (file.extension.empty()) return false;
  return file.stb || file.exr || oiio_can_write(file.path);
}

namespace {
// Beside the target under a temporary name (extension kept last for the
// writers that look at it), so that the rename is atomic.
std::string temporary_path(const std::string& path) {
  fs::path target(path);
  std::string tmp_name = ".";  // (built by appends: GCC 12 warns falsely on "." + string)
  tmp_name.append(target.stem().string())
      .append(".tmp")
      .append(std::to_string(getpid()))
      .append(target.extension().string());
  return (target.parent_path() / tmp_name).string();
}

// Runs `write(temporary)` for a width x height x channels image; on failure
// removes the temporary and throws.
template <class WriteFn>
std::string write_temporary(const std::string& path, int width, int height, int channels, WriteFn&& write) {
  if (width <= 0 || height <= 0 || channels <= 0) throw Error(path + ": cannot write an empty image");
  const std::string tmp = temporary_path(path);
  track_temporary(tmp);  // removed if the run is interrupted before commit or discard
  std::string error;
  if (!write(tmp, &error)) {
    discard_temporary(tmp);
    throw Error(path + ": cannot write image" + (error.empty() ? "" : ": " + error));
  }
  return tmp;
}
}  // namespace

std::string write_image_temporary(const ImageFile& file, const Image& image) {
  const std::string& path = file.path;
  if (!is_writable(file))
    throw Error(path + ": cannot write images of this type (unknown extension '" + file.extension + "')");
  return write_temporary(path, image.width, image.height, image.channels,
                         [&](const std::string& tmp, std::string* error) {
                           if (file.stb) return stb_write(tmp, file.extension, image, error);
                           return file.exr ? write_exr(tmp, image, error) : oiio_write(path, tmp, image, error);
                         });
}

std::string write_image_temporary(const std::string& path, const Image& image) {
  return write_image_temporary(image_file(path), image);
}

bool is_alpha_image_path(const std::string& path) { return image_file(path).alpha; }

bool is_8bit_image_path(const std::string& path) { return image_file(path).bits8; }

bool is_float_image_path(const std::string& path) { return image_file(path).floats; }

std::string write_image8_temporary(const ImageFile& file, const Image8& image) {
  if (!file.bits8) throw Error(file.path + ": not an 8-bit image type (bmp, png, tga, jpg)");
  return write_temporary(
      file.path, image.width, image.height, image.channels,
      [&](const std::string& tmp, std::string* error) { return stb_write8(tmp, file.extension, image, error); });
}

std::string write_image8_temporary(const std::string& path, const Image8& image) {
  return write_image8_temporary(image_file(path), image);
}

void commit_temporary(const std::string& temporary, const std::string& path) {
  std::error_code ec;
  replace_file(temporary, path, ec);
  if (ec) {
    discard_temporary(temporary);
    throw Error(path + ": cannot write image: " + ec.message());
  }
  untrack_temporary(temporary);
}

void discard_temporary(const std::string& temporary) {
  std::error_code ec;
  fs::remove(temporary, ec);
  untrack_temporary(temporary);
}

void write_image(const std::string& path, const Image& image) {
  commit_temporary(write_image_temporary(path, image), path);
}

}  // namespace rayform
