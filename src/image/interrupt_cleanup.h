// Temporary output files that an interrupted run removes before it dies:
// SIGINT, SIGTERM and SIGHUP unlink every tracked file (then remove tracked
// folders, which must then be empty) and end the process with the signal's
// default action. So a run stopped while it writes leaves no temporary behind.
// Before that it prints the interrupt message, if one is set, on stderr: on
// a line of its own even when a progress line is open.
#pragma once

#include <string>

namespace rayform {

// Tracks `path` (a file, or with `folder` an empty-at-the-end folder) until
// untrack_temporary; installs the signal handlers on first use. Silently
// untracked when more than 64 are tracked at once.
void track_temporary(const std::string& path, bool folder = false);
void untrack_temporary(const std::string& path);

// The line an interrupted run prints on stderr (e.g. "rayform: interrupted";
// at most 255 characters, a newline is added); installs the signal handlers.
void set_interrupt_message(const std::string& message);
// Whether a line is open on stderr (a progress line drawn with \r): an
// interrupted run then ends it with a newline before its message.
void set_interrupt_line_open(bool open);

}  // namespace rayform
