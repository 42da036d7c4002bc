// Where a face index of an OBJ names no element, for the reader's messages.
#pragma once

#include <cstddef>
#include <string>

namespace rayform::obj {

// Where an OBJ index goes wrong: the first face corner whose index of
// `kind` (0 vertex, 1 uv, 2 normal) names no element, counting elements as
// they are declared (as OBJ resolves relative indices).
struct BadIndex {
  size_t line = 0;   // 1-based line of the face
  long index = 0;    // the index as written
  size_t count = 0;  // elements of that kind declared before the line
};

// Whether `text` (a whole OBJ file) has such a corner; *bad says where.
bool find_bad_index(const std::string& text, int kind, BadIndex* bad);

}  // namespace rayform::obj
