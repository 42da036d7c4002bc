// Files a scene names (meshes, .mtl files, textures, glTF buffers and
// images): the one check every reader applies before it opens one. By default
// rayform reads what the scene asks for; `confine` (--confine) keeps a scene
// to its own folder, for files from people you do not know.
#pragma once

#include <filesystem>
#include <string>

namespace rayform {

struct FileAccess {
  // Only files in the scene file's folder and its subfolders, after following
  // symlinks: no absolute names, no ".." leading out, no URI other than data:.
  bool confine = false;
};

// Why the file that `scene_file` names as `name` (as written), found at
// `resolved`, may not be read; "" when it may. Whatever `confine` says it must
// be a regular file if it exists (a device or a pipe, /dev/zero say, never
// ends). The answer is a phrase for a message that starts with the scene file
// and the place that names the file, e.g. "mtllib '../x.mtl' lies outside the
// scene's folder /data/in (refused by --confine)".
std::string referenced_file_problem(const std::string& scene_file, const std::string& what, const std::string& name,
                                    const std::filesystem::path& resolved, const FileAccess& access);

// Whether `path` lies in `folder` or below, both made absolute and canonical
// (symlinks followed).
bool lies_within_folder(const std::filesystem::path& path, const std::filesystem::path& folder);

// Whether a name written in a file is a URI with a scheme ("http:", "file:",
// "data:"; not a Windows drive letter such as "C:").
bool has_uri_scheme(const std::string& name);

}  // namespace rayform
