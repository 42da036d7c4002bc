// Atomic, all-or-nothing output: a set of files committed together, used by
// the scene writers and by the CLI for rendered images.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rayform {

// A set of output files committed together: each is written to a temporary
// name in its final folder, then all are renamed into place, the main file
// last. On failure nothing is renamed and the temporaries are removed.
class OutputFiles {
 public:
  // `main` is written last; its folder must exist. Side files (a scene's
  // meshes, textures, buffers) go to `side_folder` (it must exist), or beside
  // the main file when it is empty.
  explicit OutputFiles(std::string main, std::string side_folder = {});
  ~OutputFiles();
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;

  const std::string& main() const { return main_; }
  // The path of the side file `file_name` (in the side folder).
  std::string side_path(const std::string& file_name) const;
  // How the main file names the side file `file_name`: relative to the main
  // file's folder, with '/' ("mesh.obj", "assets/mesh.obj", "../assets/mesh.obj").
  std::string side_reference(const std::string& file_name) const;
  // Content of a file (a later add of the same path replaces it).
  void add(const std::string& path, std::vector<uint8_t> bytes);
  void add(const std::string& path, const std::string& text);
  // A file already written at `temp_path` (on the same file system) that
  // becomes `path` at commit; removed with the other temporaries when the
  // set is not committed.
  void add_written(const std::string& path, const std::string& temp_path);
  bool has(const std::string& path) const;
  // A file that must never be replaced (an input of the conversion): commit
  // refuses, before renaming anything, when an output is that file with
  // other content.
  void protect(const std::string& path);
  // A fresh temporary folder beside the main file, removed by the destructor.
  std::string temp_dir();
  // Writes and renames everything; returns the final paths, main first.
  std::vector<std::string> commit();

 private:
  struct Entry {
    std::string path;
    std::vector<uint8_t> bytes;
    std::string temp;  // non-empty: already written there
  };
  std::string main_;
  std::string side_folder_;  // empty: the main file's folder
  std::string side_prefix_;  // side_reference's folder part: "" or "assets/"
  std::vector<Entry> entries_;
  std::vector<std::string> temps_, temp_dirs_, protected_;
};

}  // namespace rayform
