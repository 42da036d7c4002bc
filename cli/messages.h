// What the commands say on stderr besides errors: one "warning: " or "note: "
// line each. -q/--quiet (and the course line's -quiet) silences them, and the
// progress line; errors always print (main.cpp).
#pragma once

#include <string>

namespace rayform::cli {

// `text` as it may be written to a terminal: control characters (C0, DEL
// and C1: ESC, BEL, CR, newline, ...) escaped as JSON writes them (\u001b;
// names read from files cannot move the cursor, retitle the window or start
// a new line), and bytes that are not UTF-8 replaced by U+FFFD. Every line
// the commands write to stderr goes through it.
std::string terminal_text(const std::string& text);

void set_quiet(bool quiet);
bool quiet();

// "warning: MESSAGE" on stderr unless quiet.
void warn(const std::string& message);
// "note: MESSAGE" on stderr unless quiet.
void note(const std::string& message);

}  // namespace rayform::cli
