// An image file to be written, its path parsed once: which writer takes it and
// what its samples hold. A render job parses each output once and hands this
// to every decision and writer (render/color_output.h, image.h).
#pragma once

#include <string>

namespace rayform {

struct ImageFile {
  std::string path;
  std::string extension;  // lower-case, with its dot; "" when none
  bool stb = false;       // written by stb_writer.h (bmp, png, tga, jpg/jpeg, hdr), else by exr_writer.h or OpenImageIO
  bool exr = false;       // OpenEXR, written by exr_writer.h (not OpenImageIO)
  bool bits8 = false;     // 8-bit samples (bmp, png, tga, jpg/jpeg): written from 8-bit pixels too
  bool floats = false;    // float samples, unclamped (exr, hdr, tif/tiff, fits, pfm)
  bool alpha = false;     // written with alpha: png, tga (straight), exr, tif/tiff (premultiplied)
};

// `path` parsed by its extension (no file is touched, no plugin loaded).
ImageFile image_file(const std::string& path);

}  // namespace rayform
