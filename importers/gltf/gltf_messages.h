// How glTF error messages and warnings name things: JSON paths such as
// "meshes[2].primitives[0]" and tinygltf's multi-line messages as one line.
#pragma once

#include <string>

namespace rayform {

// "array[i]".
std::string gltf_path(const char* array, long i);

// A multi-line message as one line: lines trimmed, empty ones dropped, "; " between.
std::string gltf_one_line(const std::string& text);

}  // namespace rayform
