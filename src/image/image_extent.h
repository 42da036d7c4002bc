// Where the image in a file ends, by the format's own structure, so that what
// follows it (a hostile file: a valid 8x8 PNG then 3 GB of zeros) is neither
// read nor copied: PNG ends after its IEND chunk, JPEG at its EOI marker, WebP
// at the end of its RIFF chunk (8 + the RIFF size, padded to even), our BMP
// after its last pixel row. Chunks and segments are walked without reading
// their data (JPEG's entropy-coded data is scanned for its markers), and the
// walk stops, refusing the file, once it passes what an image of the size the
// header declares can need (image_extent.cpp states each bound). A file that
// ends before that end is taken whole (its decoder judges it). Other
// formats are read by OpenImageIO from the file itself (by offsets): their
// extent is the whole file.
#pragma once

#include <cstdint>
#include <istream>
#include <string>

namespace rayform {

struct ImageExtent {
  uint64_t bytes = 0;       // of the image, from the start of the file
  uint64_t file_bytes = 0;  // of the whole file
  std::string format;       // "PNG", "JPEG", "WebP", "BMP"; "" for any other (bytes = file_bytes)
  std::string problem;      // "" or why the file is refused (no end where the format puts it)
};

// Reads the structure of the file `in` (positioned anywhere; left anywhere)
// of `file_bytes` bytes.
ImageExtent image_extent(std::istream& in, uint64_t file_bytes);

// The note for a file with bytes after its image: "PNG: 3000000000 bytes after
// the image's end (IEND) are ignored".
std::string trailing_bytes_note(const ImageExtent& extent);

}  // namespace rayform
