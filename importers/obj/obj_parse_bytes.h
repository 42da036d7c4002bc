// What the parts of a shared chunked parse (obj_parallel_parse.h,
// rayform/base/work_share.h) send each other, as bytes:
// - each chunk's scan (obj_chunk_scan.h): its counts, and its state lines as
//   where they are in the text (every part has the same text);
// - each chunk's tinyobjloader parse: the vertex arrays the join uses
//   (positions, normals, uvs, colours), each shape's name and faces (corners,
//   corner counts, materials, smoothing groups), the warnings, and whether
//   the chunk parsed, must fall back, or failed (an exception, carried as
//   its message so that every part stops).
// Plain copies of the arrays with their sizes (a face's corners as their
// position indices alone where no corner names a uv or normal, per-face
// values as runs of one value), read back bounds-checked: a mismatch is a
// bug, reported as rayform::Error.
#pragma once

#include "rayform/importers/obj/obj_chunk_scan.h"

#include <tiny_obj_loader.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rayform::obj {

// A shape's face arrays left in a part's bytes (read_chunk_bytes `in_place`),
// to be read later straight into their place in the joined shape.
struct ShapeBytes {
  size_t corners = 0, faces = 0;  // how many
  bool positions_only = false;    // corners as their position indices alone
  const std::byte* corner_bytes = nullptr;
  // Runs of (value, length): of the corner counts, the materials, the smoothing groups.
  const std::byte* face_corner_runs = nullptr;
  const std::byte* material_runs = nullptr;
  const std::byte* smoothing_runs = nullptr;
  size_t face_corner_run_count = 0, material_run_count = 0, smoothing_run_count = 0;
};

struct ChunkParse {
  bool ok = false;    // parsed exactly as the whole-file parse would; false: fall back
  std::string error;  // not empty: parsing the chunk threw this
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::string warn;
  // Read in place: per shape, its face arrays still in the bytes (the
  // shapes' own face arrays are empty).
  std::vector<ShapeBytes> shape_bytes;
};

// How many bytes append_chunk_bytes adds for `parse`.
size_t chunk_bytes_size(const ChunkParse& parse);

// Appends chunk number `chunk` to `bytes` (its arrays only when it is ok).
void append_chunk_bytes(size_t chunk, const ChunkParse& parse, std::vector<std::byte>* bytes);

// Reads the chunks `bytes` holds into `chunks` (indexed by chunk number,
// their arrays moved in) and returns their numbers in order; `in_place`:
// each shape's face arrays are left in the bytes (ChunkParse::shape_bytes,
// for read_shape_bytes; `bytes` must outlive them). Throws rayform::Error
// when the bytes do not parse or name a chunk past the end.
std::vector<size_t> read_chunk_bytes(const std::vector<std::byte>& bytes, std::vector<ChunkParse>* chunks,
                                     bool in_place = false);

// A shape's face arrays from the bytes, to `corners` (s.corners of them)
// and the three per-face arrays (s.faces each).
void read_shape_bytes(const ShapeBytes& s, tinyobj::index_t* corners, unsigned char* face_corners, int* materials,
                      unsigned int* smoothing);

// The scans of `chunks` (numbers into `scans`) as one part's bytes: a byte
// 1, then each chunk's number and scan.
std::vector<std::byte> scan_bytes(const std::vector<size_t>& chunks, const std::vector<ChunkScan>& scans);

// The bytes of a part whose scan threw `what`: a byte 0, then the message.
std::vector<std::byte> failed_scan_bytes(const std::string& what);

// Whether a part's bytes are its scans (else it failed: *failure gets its
// message, empty if it sent none).
bool scan_bytes_ok(const std::vector<std::byte>& bytes, std::string* failure);

// Reads a part's scan_bytes into `scans` (indexed by chunk number, their
// lines views of `text`) and returns their chunk numbers in order. Throws
// rayform::Error when the bytes do not parse or name a chunk past the end or
// a line past the text.
std::vector<size_t> read_scan_bytes(const std::vector<std::byte>& bytes, std::string_view text,
                                    std::vector<ChunkScan>* scans);

}  // namespace rayform::obj
