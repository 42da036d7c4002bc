#include "rayform/image/replace_file.h"

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fcntl.h>

namespace rayform {
namespace fs = std::filesystem;

void replace_file(const std::string& from, const std::string& to, std::error_code& ec) {
  ec.clear();
#if defined(__linux__) && defined(RENAME_EXCHANGE)
  std::error_code status_ec;
  if (fs::symlink_status(to, status_ec).type() == fs::file_type::regular &&
      ::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_EXCHANGE) == 0) {
    fs::remove(from, ec);  // the old content; the new file is in place whatever happens here
    ec.clear();
    return;
  }
#endif
  fs::rename(from, to, ec);
}

}  // namespace rayform
