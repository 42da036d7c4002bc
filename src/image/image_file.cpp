#include "rayform/image/image_file.h"

#include "rayform/base/file_extension.h"
#include "rayform/image/stb_writer.h"

namespace rayform {

ImageFile image_file(const std::string& path) {
  ImageFile f;
  f.path = path;
  f.extension = lower_extension(path);
  const std::string& ext = f.extension;
  f.stb = stb_writes(ext);
  f.bits8 = stb_writes_8bit(ext);
  f.exr = ext == ".exr";
  // The extensions of OpenImageIO's float formats in oiio_plugin_module.cpp
  // (openexr, hdr, tiff, fits, pfm); tests/unit/color_output_test.cpp reads
  // back values above 1 from .exr, .tif and .hdr (rayform reads no FITS, and
  // Debian's OpenImageIO writes no PFM).
  f.floats = ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff" || ext == ".fits" || ext == ".pfm";
  f.alpha = ext == ".png" || ext == ".tga" || ext == ".exr" || ext == ".tif" || ext == ".tiff";
  return f;
}

}  // namespace rayform
