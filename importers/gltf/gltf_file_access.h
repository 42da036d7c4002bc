// What reaches tinygltf when a glTF file is read: the file's JSON adapted
// first where tinygltf 2.7 refuses valid files, file access confined to the
// model's folder, and the percent-decoding of relative URIs.
#pragma once

#include "rayform/importers/referenced_files.h"

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rayform {

// A relative URI's file name: %XX escapes decoded.
std::string percent_decode(const std::string& s);

bool is_data_uri(const std::string& uri);

// Key under which adapt_json_for_tinygltf keeps a Draco primitive's index
// accessor (inside the primitive's KHR_draco_mesh_compression object).
inline constexpr const char* draco_indices_key = "rayform_indices";

// Where the JSON text lies in a glTF file's bytes: all of a .gltf, a .glb's JSON chunk.
struct GltfJsonChunk {
  size_t offset = 0, length = 0;
};

// A glTF file's bytes taken apart once, before tinygltf sees them.
struct GltfContainer {
  // Where the JSON lies; none for a .glb whose first chunk is not a JSON chunk
  // that fits in the file (tinygltf reports the broken container).
  std::optional<GltfJsonChunk> json;
  // What is wrong with a .glb's container, "" when nothing (and for a .gltf):
  // the header's total length must not exceed the file, and every chunk must
  // lie inside that length (tinygltf 2.7 trusts both and reads past the end of
  // its buffer).
  std::string problem;
};
GltfContainer read_gltf_container(const std::vector<unsigned char>& bytes, bool glb);

// Two kinds of valid files that tinygltf 2.7 refuses, adapted before it sees them:
// - a buffer that EXT_meshopt_compression marks as a fallback may have no data
//   (no uri in a .gltf; in a .glb, no part of the BIN chunk): such buffers get
//   one byte of data instead; every bufferView that uses them is compressed,
//   and gltf_accessors.cpp reads the decoded bytes;
// - a KHR_draco_mesh_compression primitive's index accessor has no bufferView:
//   the primitive's "indices" moves into its extension object (under
//   draco_indices_key), where the reader's decode_draco_primitive finds it.
// And one kind of invalid file that tinygltf would take for a valid one: a
// KHR_draco_mesh_compression attribute id that is a number but not an
// integer from 0 to 2^31 - 1 (tinygltf casts 2^40 to the int 0) becomes a
// string of its JSON text, which decode_draco_primitive refuses, naming it.
// `container` is read_gltf_container's of `bytes`; its json follows the JSON
// where adapted. Returns false (bytes untouched) when the file needed neither.
bool adapt_json_for_tinygltf(std::vector<unsigned char>& bytes, bool glb, GltfContainer& container);

// Where the JSON of a .gltf (or a .glb's JSON chunk) first nests arrays and
// objects deeper than `max_depth`: "line L, column C" (of the JSON text), or
// "" when it never does (or the container has no JSON). Checked before
// tinygltf parses the file: its parser recurses once per level (20 000 nested
// arrays overflow the stack).
std::string json_too_deep(const std::vector<unsigned char>& bytes, const GltfContainer& container, uint64_t max_depth);

// File access for tinygltf: only names joined to the model's folder (tinygltf
// would also look in the working directory), each checked by
// referenced_file_problem before it is opened, no path expansion, no writing.
struct GltfFileAccess {
  std::string base;        // the model's folder, as passed to tinygltf
  std::string scene_file;  // the .gltf/.glb, for referenced_file_problem
  FileAccess access;
  std::string problem;                // the first file refused, for the reader's message
  tinygltf::FsCallbacks callbacks();  // user_data points at this object
};

}  // namespace rayform
