// Text the writers produce: numbers that read back exactly, name lists for
// messages, names safe as file names.
#pragma once

#include "rayform/math/math.h"

#include <set>
#include <string>

namespace rayform {

// Shortest decimal text that reads back as the same float ("0.9", "-2", "1e-07").
std::string format_float(float v);
// The three components by format_float, separated by spaces ("0.5 1 -2").
std::string format_vec3(vec3 v);
// Names quoted and joined for messages: 'a', 'b', 'c'.
std::string quoted_list(const std::set<std::string>& names);

// The longest name safe_file_name returns: with an extension and a "_k"
// suffix it stays far below the 255 bytes a file name may have.
inline constexpr size_t max_safe_file_name = 100;

// A file name made of [A-Za-z0-9._-] only (others become '_'), never empty;
// a longer name than max_safe_file_name is cut to its first 91 bytes and
// "_" and 8 hexadecimal digits of a hash of the whole name.
std::string safe_file_name(const std::string& name);

}  // namespace rayform
