// The bounds an OBJ text is held to before anything parses it (or scans it
// for mtllib lines): every line at most max_obj_line_bytes (tinyobjloader
// copies each line into a string), and a face line (`f`) somewhere. The walk
// stops at the first face line; until it finds one it lets go of the pages
// it has read behind it (FileBytes::drop_pages), so that gigabytes without a
// face (or without a line end) fail at once, without becoming resident.
#pragma once

#include "rayform/importers/file_bytes.h"

#include <cstddef>
#include <string>

namespace rayform::obj {

// Longer than any line of numbers a tool writes (a polygon of a million corners).
inline constexpr size_t max_obj_line_bytes = size_t(64) << 20;

// Throws rayform::Error "<path>:<line>: line longer than N bytes" or
// "<path>: OBJ file has no faces".
void check_obj_text_bounds(const FileBytes& file, const std::string& path);

}  // namespace rayform::obj
