// Temporary output files that an interrupted run removes before it dies:
// SIGINT, SIGTERM and SIGHUP unlink every tracked file (then remove tracked
// folders, which must then be empty) and end the process with the signal's
// default action. So a run stopped while it writes leaves no temporary behind.
#pragma once

#include <string>

namespace rayform {

// Tracks `path` (a file, or with `folder` an empty-at-the-end folder) until
// untrack_temporary; installs the signal handlers on first use. Silently
// untracked when more than 64 are tracked at once.
void track_temporary(const std::string& path, bool folder = false);
void untrack_temporary(const std::string& path);

}  // namespace rayform
