#include "image/output_files.h"

#include "image/checked_write.h"
#include "image/interrupt_cleanup.h"
#include "image/replace_file.h"
#include "scene/error.h"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>
#include <utility>
#include <unistd.h>

namespace rayform {
namespace fs = std::filesystem;

OutputFiles::OutputFiles(std::string main) : main_(std::move(main)) {}

OutputFiles::~OutputFiles() {
  std::error_code ec;
  for (const std::string& t : temps_) {
    fs::remove(t, ec);
    untrack_temporary(t);
  }
  for (const std::string& d : temp_dirs_) {
    fs::remove_all(d, ec);
    untrack_temporary(d);
  }
}

std::string OutputFiles::beside(const std::string& file_name) const {
  return (fs::path(main_).parent_path() / file_name).string();
}

void OutputFiles::add(const std::string& path, std::vector<uint8_t> bytes) {
  for (Entry& e : entries_)
    if (e.path == path) {
      e.bytes = std::move(bytes);
      e.temp.clear();
      return;
    }
  entries_.push_back(Entry{path, std::move(bytes), {}});
}

void OutputFiles::add(const std::string& path, const std::string& text) {
  add(path, std::vector<uint8_t>(text.begin(), text.end()));
}

void OutputFiles::add_written(const std::string& path, const std::string& temp_path) {
  temps_.push_back(temp_path);
  track_temporary(temp_path);
  for (Entry& e : entries_)
    if (e.path == path) {
      e.bytes.clear();
      e.temp = temp_path;
      return;
    }
  entries_.push_back(Entry{path, {}, temp_path});
}

bool OutputFiles::has(const std::string& path) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.path == path; });
}

namespace {
std::string temp_name_for(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  fs::path p(path);
  // Appended piece by piece: GCC 12 at -O2 gives a false -Wrestrict warning
  // for "." + std::string&& (GCC bug 105329).
  std::string name = ".";
  name += p.filename().string();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return (p.parent_path() / name).string();
}
}  // namespace

std::string OutputFiles::temp_dir() {
  std::string d = temp_name_for(main_) + ".d";
  std::error_code ec;
  fs::create_directories(d, ec);
  if (ec) throw Error(main_ + ": cannot create a temporary folder '" + d + "': " + ec.message());
  temp_dirs_.push_back(d);
  track_temporary(d, /*folder*/ true);
  return d;
}

void OutputFiles::protect(const std::string& path) {
  if (!path.empty()) protected_.push_back(path);
}

namespace {
std::vector<uint8_t> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
}  // namespace

std::vector<std::string> OutputFiles::commit() {
  // A protected file may only be "replaced" by its own bytes (a texture
  // copied onto itself when a converted scene is converted again).
  for (const Entry& e : entries_)
    for (const std::string& p : protected_) {
      std::error_code ec;
      if (!fs::exists(e.path, ec) || !fs::equivalent(e.path, p, ec)) continue;
      if ((e.temp.empty() ? e.bytes : file_bytes(e.temp)) == file_bytes(p)) continue;
      throw Error(e.path + ": writing it would replace " + p +
                  ", which the scene was read from; choose another output name or folder");
    }
  // Main file last: readers never see it before what it names.
  std::stable_partition(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.path != main_; });
  std::vector<std::pair<std::string, std::string>> moves;  // temp -> final
  for (const Entry& e : entries_) {
    if (!e.temp.empty()) {
      moves.emplace_back(e.temp, e.path);
      continue;
    }
    std::string tmp = temp_name_for(e.path);
    temps_.push_back(tmp);
    track_temporary(tmp);
    if (std::string error; !write_file_checked(tmp, e.bytes.data(), e.bytes.size(), &error))
      throw Error(e.path + ": cannot write (" + error + ")");
    moves.emplace_back(tmp, e.path);
  }
  std::vector<std::string> done;
  for (const auto& [from, to] : moves) {
    std::error_code ec;
    replace_file(from, to, ec);
    if (ec) throw Error(to + ": cannot write (rename from '" + from + "' failed: " + ec.message() + ")");
    temps_.erase(std::remove(temps_.begin(), temps_.end(), from), temps_.end());
    untrack_temporary(from);
    done.push_back(to);
  }
  std::rotate(done.begin(), done.end() - (done.empty() ? 0 : 1), done.end());  // main first
  return done;
}

}  // namespace rayform
