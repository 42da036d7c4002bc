// Writing an output file so that a failure is seen: every write() checked (a
// full disk is ENOSPC here, not a short file found later), then fsync, then
// close, each checked. Every output goes through here (or, when a library
// wrote the file, through sync_file) before it is renamed into place.
#pragma once

#include <cstddef>
#include <string>

namespace rayform {

// An output file written in pieces: open, write as often as needed, finish
// (fsync, close). Each call returns false and sets *error ("No space left on
// device", ...) on failure; the caller then removes the file. A file not
// finished is closed by the destructor.
class CheckedFile {
 public:
  CheckedFile() = default;
  CheckedFile(const CheckedFile&) = delete;
  CheckedFile& operator=(const CheckedFile&) = delete;
  ~CheckedFile();

  // Creates or truncates `path`.
  bool open(const std::string& path, std::string* error);
  bool write(const void* data, size_t size, std::string* error);
  bool finish(std::string* error);

 private:
  int fd_ = -1;
};

// Writes `size` bytes to `path` (created or truncated) through a CheckedFile.
bool write_file_checked(const std::string& path, const void* data, size_t size, std::string* error);

// fsync of a file another library wrote (OpenImageIO): its data on disk, or
// false with *error.
bool sync_file(const std::string& path, std::string* error);

}  // namespace rayform
