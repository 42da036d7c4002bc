// The library's one exception type. Messages name the file and, where it
// helps, line and column: "scene.txt:12:5: expected a number, found 'x'".
#pragma once

#include <stdexcept>
#include <string>

namespace rayform {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace rayform
