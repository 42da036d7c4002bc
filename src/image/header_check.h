// Headers that OpenImageIO's readers trust too far, checked by us before the
// file is handed to them: an OpenEXR attribute whose declared size runs past
// the end of the file (OpenEXR allocates it first: a 54-byte file asked for
// 1.9 GB), the declared sizes of EXR images (dataWindow) and GIF canvases
// (the logical screen, which giflib allocates at open) against the texel
// limit; and every BMP our own reader does not take is refused (OpenImageIO
// 2.4's BMP reader allocated a 69-byte file's rows first and crashed on
// another). And which of OpenImageIO's readers may read a file at all: one
// chosen from the file's signature, never OpenImageIO's own guess (given a
// file it cannot place, OpenImageIO tries every reader it has: its RLA reader
// aborted on a fuzzed ".tif").
#pragma once

#include "rayform/image/image_decode.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace rayform {

// What is wrong with the file whose first `size` bytes are `head` and whose
// whole length is `file_bytes`; "" when nothing is found. A header longer than
// `head` is checked as far as `head` goes. Messages as image_decode.h's:
// "texture is WxH (...), more than the limit of N texels (...)", or what the
// header claims, e.g. "EXR attribute 'capDate' declares 1862270977 bytes, more
// than the 54 bytes of the file".
std::string header_problem(const uint8_t* head, size_t size, uint64_t file_bytes, const DecodeOptions& options);

// The OpenImageIO reader ("openexr", "hdr", "tiff", "gif", "pnm", "psd",
// "targa") for the file at `path` whose first `size` bytes are `head`, from its
// signature (TGA, which has none, from a .tga or .targa name); nullptr for
// anything else, which rayform does not read.
const char* oiio_reader_for(const uint8_t* head, size_t size, const std::string& path);

// The formats oiio_reader_for admits, for messages: "TGA, HDR, EXR, TIFF, GIF, PNM, PSD".
extern const char* const oiio_read_formats;

}  // namespace rayform
