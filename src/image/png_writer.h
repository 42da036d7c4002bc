// PNG writing of 8-bit images (grey, grey + alpha, RGB, RGBA), in parallel:
// the rows are Paeth-filtered and cut into strips of whole rows, each strip
// deflated on its own (zlib, run-length matches, ending with a sync flush on
// a byte boundary, as pigz does) into one IDAT chunk; the strips' raw deflate
// streams, concatenated, are the file's one zlib stream, whose Adler-32 is
// combined from the strips'. The strips do not depend on the thread count, so
// neither do the bytes. oneTBB runs the strips, within the thread bound in
// force (base/thread_limit.h).
#pragma once

#include "rayform/image/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rayform {

struct PngOptions {
  // Rows per strip; 0: about 256 KiB of filtered bytes per strip (at least one row).
  int strip_rows = 0;
};

// The PNG file's bytes for `image` (width and height > 0, 1 to 4 channels).
// Throws rayform::Error for an image PNG cannot hold or zlib refuses.
std::vector<uint8_t> encode_png(const Image8& image, const PngOptions& options = {});

// encode_png, written to `path` through write_file_checked (checked_write.h).
bool write_png(const std::string& path, const Image8& image, std::string* error);

}  // namespace rayform
