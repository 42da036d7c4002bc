#include "rayform/importers/file_bytes.h"
#include "rayform/base/memory_budget.h"

#include "rayform/base/error.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <utility>

namespace rayform {

FileBytes::FileBytes(const std::string& path, const std::string& what) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(path + ": cannot open " + what);
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
    void* p = ::mmap(nullptr, size_t(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
    if (p != MAP_FAILED) {
      ::close(fd);
      mapped_ = static_cast<const char*>(p);
      size_ = size_t(st.st_size);
      job_memory().credit_input(size_);
      return;
    }
  }
  // Not a regular file (or not mappable): read to the end.
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      ::close(fd);
      throw Error(path + ": cannot read " + what);
    }
    read_.append(buffer, size_t(n));
  }
  ::close(fd);
  job_memory().credit_input(read_.size());
}

FileBytes& FileBytes::operator=(FileBytes&& o) noexcept {
  if (this != &o) {
    if (mapped_) ::munmap(const_cast<char*>(mapped_), size_);
    mapped_ = std::exchange(o.mapped_, nullptr);
    size_ = std::exchange(o.size_, 0);
    read_ = std::move(o.read_);
  }
  return *this;
}

void FileBytes::drop_pages(size_t begin, size_t end) const {
  if (!mapped_) return;
  const size_t page = size_t(::sysconf(_SC_PAGESIZE));
  begin = (begin + page - 1) / page * page;  // the mapping starts on a page
  end = std::min(end, size_) / page * page;
  // MADV_DONTNEED on a private read-only mapping: the pages are read again
  // from the file when touched, unchanged.
  if (begin < end) ::madvise(const_cast<char*>(mapped_) + begin, end - begin, MADV_DONTNEED);
}

FileBytes::~FileBytes() {
  if (mapped_) ::munmap(const_cast<char*>(mapped_), size_);
}

}  // namespace rayform
