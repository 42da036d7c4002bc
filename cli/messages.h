// What the commands say on stderr besides errors: one "warning: " or "note: "
// line each. -q/--quiet (and the course line's -quiet) silences them, and the
// progress line; errors always print (main.cpp).
#pragma once

#include <string>

namespace rayform::cli {

void set_quiet(bool quiet);
bool quiet();

// "warning: MESSAGE" on stderr unless quiet.
void warn(const std::string& message);
// "note: MESSAGE" on stderr unless quiet.
void note(const std::string& message);

}  // namespace rayform::cli
