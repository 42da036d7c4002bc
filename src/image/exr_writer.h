// OpenEXR writing of float images, in parallel: a single-part scanline file
// of 32-bit float channels with ZIP compression (blocks of 16 rows, each
// byte-split, delta-predicted and deflated by libdeflate as its own zlib
// stream), the layout and header OpenImageIO wrote before (channels Y; R, G;
// R, G, B; R, G, B, A; capDate; the windows of the image). oneTBB compresses
// the blocks, within the thread bound in force (base/thread_limit.h); the
// bytes do not depend on the thread count.
#pragma once

#include "rayform/image/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rayform {

struct ExrOptions {
  int level = 2;             // libdeflate's compression level, 1 to 12 (2: the least CPU time, docs/performance.md)
  std::string capture_date;  // capDate, "YYYY:MM:DD HH:MM:SS"; empty: the local time now
};

// The EXR file's bytes for `image` (width and height > 0, 1 to 4 channels),
// the samples' bits as they are (negative, infinite and NaN values included).
// Throws rayform::Error for an image it cannot hold.
std::vector<uint8_t> encode_exr(const Image& image, const ExrOptions& options = {});

// encode_exr, written to `path` through write_file_checked (checked_write.h).
bool write_exr(const std::string& path, const Image& image, std::string* error);

}  // namespace rayform
