// The library's exception types. Messages name the file and, where it
// helps, line and column: "scene.txt:12:5: expected a number, found 'x'".
#pragma once

#include <stdexcept>
#include <string>

namespace rayform {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A mistake in what the caller asked for (an option, not a file): a command
// line reports it with a hint to its usage and exit status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The message of the exception being handled (call inside a catch block):
// what() of a std::exception, else "an unknown exception".
inline std::string current_exception_message() {
  try {
    throw;
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "an unknown exception";
  }
}

}  // namespace rayform
