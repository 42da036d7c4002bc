// What each format writer (course_writer.h, obj_writer.h, gltf_writer.h)
// holds for the one file it writes: the output's path and the names derived
// from it, the set of files written together (image/output_files.h), and the
// messages on what the format could not hold.
#pragma once

#include "rayform/image/output_files.h"
#include "rayform/scene/scene.h"

#include <set>
#include <string>
#include <vector>

namespace rayform {

class WriterContext {
 public:
  // The output `path` with its side files in `side_folder` (SaveOptions::
  // side_folder; empty: beside it); the files `scene` was read from are
  // protected from being replaced (protect_scene_inputs). `messages` may be null.
  WriterContext(const Scene& scene, const std::string& path, const std::string& side_folder,
                std::vector<std::string>* messages);

  // Appends "<name>: <message>" to the messages, if any.
  void note(const std::string& message);
  // When `names` is not empty, notes "<kind> '<a>', '<b>'<what>" (text_format.h's
  // quoted_list): the things of one kind that the format could not hold alike.
  void note_names(const std::string& kind, const std::set<std::string>& names, const std::string& what);

  const std::string path;  // the main output file
  const std::string name;  // its file name, which starts every message
  const std::string stem;  // its file name without extension, which starts the side files' names
  OutputFiles out;         // the output and its side files, committed together

 private:
  std::vector<std::string>* messages_;
};

}  // namespace rayform
