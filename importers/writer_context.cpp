#include "rayform/importers/writer_context.h"

#include "rayform/importers/scene_writer.h"
#include "rayform/importers/text_format.h"

#include <filesystem>

namespace rayform {
namespace fs = std::filesystem;

WriterContext::WriterContext(const Scene& scene, const std::string& path, const std::string& side_folder,
                             std::vector<std::string>* messages)
    : path(path),
      name(fs::path(path).filename().string()),
      stem(fs::path(path).stem().string()),
      out(path, side_folder),
      messages_(messages) {
  protect_scene_inputs(scene, out);
}

void WriterContext::note(const std::string& message) {
  if (messages_) messages_->push_back(name + ": " + message);
}

void WriterContext::note_names(const std::string& kind, const std::set<std::string>& names, const std::string& what) {
  if (!names.empty()) note(kind + " " + quoted_list(names) + what);
}

}  // namespace rayform
