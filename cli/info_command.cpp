#include "commands.h"
#include "messages.h"
#include "rayform/distributed/ranks.h"
#include "read_flags.h"
#include "rayform/pipeline/scene_info.h"
#include "rayform/scene/scene_stats.h"

#include <iostream>
#include <memory>

namespace rayform::cli {

void add_info_command(CLI::App& app) {
  struct Args {
    std::string scene, dialect;
    ReadFlags read;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* info = app.add_subcommand("info", "Print counts and bounds of a scene, and the glTF extensions it uses");
  info->add_option("scene", a->scene, "Scene file")->required();
  info->add_option("--dialect", a->dialect, "Course dialect: 2012, 2019 or a5 (default: detected)")
      ->check(CLI::IsMember({"2012", "2019", "a5"}));
  info->add_flag("--json", a->json, "Print the same as one JSON object on stdout, the warnings in it too");
  add_read_flags(*info, a->read);
  info->callback([a] {
    if (!distributed::ranks().root()) return;  // under mpirun, one report (rank 0's), not one per rank
    LoadOptions lo{dialect_from_string(a->dialect)};
    apply_read_flags(a->read, lo);
    LoadedScene loaded = load_scene(a->scene, lo);
    for (const std::string& w : loaded.warnings) warn(w);
    const SceneStats stats = scene_stats(loaded.scene, lo.limits.instances);
    if (a->json) {
      std::cout << scene_info_json(a->scene, loaded, stats) << "\n";
      return;
    }
    std::cout << "scene:       " << a->scene << "\n";
    if (loaded.format == SceneFormat::course_txt)
      std::cout << "format:      course .txt, dialect " << course_dialect_name(loaded.dialect) << "\n";
    std::cout << format_scene_stats(stats);
    if (!loaded.extensions.empty()) {
      std::cout << "extensions:\n";
      for (const ExtensionUse& e : loaded.extensions)
        std::cout << "  " << e.name << ": " << extension_support_name(e.support)
                  << (e.detail.empty() ? "" : " (" + e.detail + ")") << "\n";
    }
  });
}

}  // namespace rayform::cli
