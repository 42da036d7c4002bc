#include "rayform/image/checked_write.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace rayform {
namespace {
bool fail(std::string* error, const char* step) {
  *error = std::string(step) + ": " + std::strerror(errno);
  return false;
}

// fsync, where the file system can; devices and pipes (EINVAL) have nothing to sync.
bool sync_and_close(int fd, std::string* error) {
  if (::fsync(fd) != 0 && errno != EINVAL) {
    const int saved = errno;
    ::close(fd);
    errno = saved;
    return fail(error, "fsync");
  }
  if (::close(fd) != 0) return fail(error, "close");
  return true;
}
}  // namespace

CheckedFile::~CheckedFile() {
  if (fd_ >= 0) ::close(fd_);
}

bool CheckedFile::open(const std::string& path, std::string* error) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  return fd_ >= 0 || fail(error, "open");
}

bool CheckedFile::write(const void* data, size_t size, std::string* error) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd_, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;  // no progress: treat as a full disk
      return fail(error, "write");
    }
    p += n;
    size -= size_t(n);
  }
  return true;
}

bool CheckedFile::finish(std::string* error) {
  const int fd = fd_;
  fd_ = -1;
  return sync_and_close(fd, error);
}

bool write_file_checked(const std::string& path, const void* data, size_t size, std::string* error) {
  CheckedFile file;
  return file.open(path, error) && file.write(data, size, error) && file.finish(error);
}

bool sync_file(const std::string& path, std::string* error) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return fail(error, "open");
  return sync_and_close(fd, error);
}

}  // namespace rayform
