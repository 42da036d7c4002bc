#include "rayform/image/output_files.h"

#include "rayform/image/checked_write.h"
#include "rayform/image/interrupt_cleanup.h"
#include "rayform/image/replace_file.h"
#include "rayform/base/error.h"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>
#include <utility>
#include <sys/stat.h>
#include <unistd.h>

namespace rayform {
namespace fs = std::filesystem;

OutputFiles::OutputFiles(std::string main, std::string side_folder)
    : main_(std::move(main)), side_folder_(std::move(side_folder)) {
  if (side_folder_.empty()) return;
  std::error_code ec;
  const fs::path main_folder = fs::path(main_).parent_path();
  const fs::path from = fs::weakly_canonical(fs::absolute(main_folder.empty() ? fs::path(".") : main_folder, ec), ec);
  const fs::path to = fs::weakly_canonical(fs::absolute(side_folder_, ec), ec);
  const std::string rel = to.lexically_relative(from).generic_string();
  if (!rel.empty() && rel != ".") side_prefix_ = rel + "/";
}

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

std::string OutputFiles::side_path(const std::string& file_name) const {
  return ((side_folder_.empty() ? fs::path(main_).parent_path() : fs::path(side_folder_)) / file_name).string();
}

std::string OutputFiles::side_reference(const std::string& file_name) const { return side_prefix_ + file_name; }

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

// Whether `file` can be renamed into the folder of `target` (the same file system).
bool renames_to(const std::string& file, const std::string& target) {
  const fs::path folder = fs::path(target).parent_path();
  struct stat a {
  }, b{};
  return ::stat(file.c_str(), &a) == 0 && ::stat(folder.empty() ? "." : folder.c_str(), &b) == 0 &&
         a.st_dev == b.st_dev;
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
    if (!e.temp.empty() && renames_to(e.temp, e.path)) {
      moves.emplace_back(e.temp, e.path);
      continue;
    }
    // A file written on another file system (a side folder elsewhere) is copied beside its place first.
    const std::vector<uint8_t> copied = e.temp.empty() ? std::vector<uint8_t>{} : file_bytes(e.temp);
    const std::vector<uint8_t>& bytes = e.temp.empty() ? e.bytes : copied;
    std::string tmp = temp_name_for(e.path);
    temps_.push_back(tmp);
    track_temporary(tmp);
    if (std::string error; !write_file_checked(tmp, bytes.data(), bytes.size(), &error))
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
