// Writing an output file so that a failure is seen: every write() checked (a
// full disk is ENOSPC here, not a short file found later), then fsync, then
// close, each checked. Every output goes through here (or, when a library
// wrote the file, through sync_file) before it is renamed into place.
#pragma once

#include <cstddef>
#include <string>

namespace rayform {

// Writes `size` bytes to `path` (created or truncated). Returns false and sets
// *error ("No space left on device", ...) on any failure; the caller removes
// the file.
bool write_file_checked(const std::string& path, const void* data, size_t size, std::string* error);

// fsync of a file another library wrote (OpenImageIO): its data on disk, or
// false with *error.
bool sync_file(const std::string& path, std::string* error);

}  // namespace rayform
