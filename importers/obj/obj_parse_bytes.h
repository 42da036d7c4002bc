// One chunk's tinyobjloader parse (obj_parallel_parse.h) as bytes, for the
// parts of a shared parse (rayform/scene/work_share.h) to send each other:
// the vertex arrays the join uses (positions, normals, uvs, colours), each
// shape's name and faces (corners, corner counts, materials, smoothing
// groups), the warnings, and whether the chunk parsed, must fall back, or
// failed (an exception, carried as its message so that every part stops).
// Plain copies of the arrays with their sizes (a face's corners as their
// position indices alone where no corner names a uv or normal, per-face
// values as runs of one value), read back bounds-checked: a mismatch is a
// bug, reported as rayform::Error.
#pragma once

#include <tiny_obj_loader.h>

#include <cstddef>
#include <string>
#include <vector>

namespace rayform::obj {

struct ChunkParse {
  bool ok = false;    // parsed exactly as the whole-file parse would; false: fall back
  std::string error;  // not empty: parsing the chunk threw this
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::string warn;
};

// How many bytes append_chunk_bytes adds for `parse`.
size_t chunk_bytes_size(const ChunkParse& parse);

// Appends chunk number `chunk` to `bytes` (its arrays only when it is ok).
void append_chunk_bytes(size_t chunk, const ChunkParse& parse, std::vector<std::byte>* bytes);

// Reads the chunks `bytes` holds into `chunks` (indexed by chunk number,
// their arrays moved in) and returns their numbers in order. Throws
// rayform::Error when the bytes do not parse or name a chunk past the end.
std::vector<size_t> read_chunk_bytes(const std::vector<std::byte>& bytes, std::vector<ChunkParse>* chunks);

}  // namespace rayform::obj
