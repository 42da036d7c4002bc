// Moving a finished temporary file into place.
#pragma once

#include <string>
#include <system_error>

namespace rayform {

// Moves `from` to `to` (same file system), replacing a file already at `to`
// atomically: a reader sees the old file or the new one, never neither. An
// existing regular file is swapped with renameat2(RENAME_EXCHANGE) and the
// old content, now at `from`, removed: a plain rename over an existing file
// makes ext4 (its auto_da_alloc heuristic) write the new file's data to disk
// before returning, 2 to 3 ms for a small image here, for a file not synced
// yet (the program's outputs are synced before they are moved: checked_write.h;
// a library's caller may not sync). Without
// a target, on file systems that refuse the exchange, and for targets that are
// not regular files: a plain rename. Sets `ec` on failure.
void replace_file(const std::string& from, const std::string& to, std::error_code& ec);

}  // namespace rayform
