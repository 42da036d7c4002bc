#include "commands.h"
#include "messages.h"
#include "read_flags.h"
#include "scene/scene_stats.h"

#include <iostream>
#include <memory>

namespace rayform::cli {

void add_info_command(CLI::App& app) {
  struct Args {
    std::string scene, dialect;
    ReadFlags read;
  };
  auto a = std::make_shared<Args>();
  CLI::App* info = app.add_subcommand("info", "Print counts and bounds of a scene, and the glTF extensions it uses");
  info->add_option("scene", a->scene, "Scene file")->required();
  info->add_option("--dialect", a->dialect, "Course dialect (default: detected)")
      ->check(CLI::IsMember({"2012", "2019"}));
  add_read_flags(*info, a->read);
  info->callback([a] {
    LoadOptions lo{dialect_from_string(a->dialect)};
    apply_read_flags(a->read, lo);
    LoadedScene loaded = load_scene(a->scene, lo);
    for (const std::string& w : loaded.warnings) warn(w);
    std::cout << "scene:       " << a->scene << "\n";
    if (loaded.format == SceneFormat::course_txt)
      std::cout << "format:      course .txt, dialect " << (loaded.dialect == CourseDialect::v2019 ? "2019" : "2012")
                << "\n";
    std::cout << format_scene_stats(scene_stats(loaded.scene, lo.limits.instances));
    if (!loaded.extensions.empty()) {
      std::cout << "extensions:\n";
      for (const ExtensionUse& e : loaded.extensions) {
        const char* how = e.support == ExtensionUse::Support::read           ? "read"
                          : e.support == ExtensionUse::Support::approximated ? "approximated"
                                                                             : "ignored";
        std::cout << "  " << e.name << ": " << how << (e.detail.empty() ? "" : " (" + e.detail + ")") << "\n";
      }
    }
  });
}

}  // namespace rayform::cli
