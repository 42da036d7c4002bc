// A file's bytes in memory for a reader: a regular file is mapped read-only
// (mmap: no copy, and the threads of a chunked parse fault its pages in at
// once), anything else (a pipe, a device) is read to the end. The bytes live
// as long as the object. A mapped file that another program shortens while
// it is read ends the process with SIGBUS, as with any mapping.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace rayform {

class FileBytes {
 public:
  FileBytes() = default;
  // Throws rayform::Error "<path>: cannot open <what>" or "<path>: cannot read <what>".
  FileBytes(const std::string& path, const std::string& what);
  FileBytes(FileBytes&& o) noexcept { *this = std::move(o); }
  FileBytes& operator=(FileBytes&& o) noexcept;
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  ~FileBytes();

  std::string_view view() const { return mapped_ ? std::string_view(mapped_, size_) : std::string_view(read_); }

  // Lets the system take back the mapped pages wholly inside bytes [begin,
  // end) of view(): they stop counting as resident, and are read again (from
  // the page cache or the file) when next touched. Nothing for bytes that
  // were read, not mapped.
  void drop_pages(size_t begin, size_t end) const;

 private:
  const char* mapped_ = nullptr;  // the mapping, or nullptr
  size_t size_ = 0;               // its size
  std::string read_;              // the bytes of a file that is not mapped
};

}  // namespace rayform
