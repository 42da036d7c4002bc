// `rayform convert IN OUT`: reads any scene rayform reads and writes it as a
// course .txt, OBJ+MTL, .gltf or .glb (formats by extension; docs/convert.md).
// What the target cannot hold is printed on stderr, one "note:" line each.
#include "commands.h"
#include "course_args.h"
#include "messages.h"
#include "rayform/distributed/ranks.h"
#include "read_flags.h"
#include "rayform/pipeline/convert_checks.h"
#include "rayform/pipeline/job_outputs.h"
#include "run_job.h"
#include "rayform/base/error.h"
#include "rayform/base/file_extension.h"
#include "rayform/scene/scene_stats.h"
#include "rayform/importers/scene_writer.h"

#include <filesystem>
#include <iostream>
#include <memory>
#include <set>

namespace rayform::cli {
namespace fs = std::filesystem;
namespace {

struct ConvertArgs {
  std::string input, output, dialect;
  SaveOptions save;
  bool tessellate_only = false;
  bool stats = false;
  bool out_dir_given = false;
  ReadFlags read;
};

// One line of counts for --stats (and the conversion tests).
std::string counts(const Scene& scene) {
  SceneStats s = scene_stats(scene);
  MeshTotals m = mesh_totals(scene);
  return "nodes " + std::to_string(s.nodes) + ", instances " + std::to_string(s.instances) + ", spheres " +
         std::to_string(s.spheres) + ", planes " + std::to_string(s.planes) + ", triangles " +
         std::to_string(s.triangles) + ", meshes " + std::to_string(s.meshes) + ", mesh vertices " +
         std::to_string(m.vertices) + ", mesh uvs " + std::to_string(m.uvs) + ", mesh triangles " +
         std::to_string(m.triangles) + ", materials " + std::to_string(s.materials) + ", textures " +
         std::to_string(s.textures) + ", lights " + std::to_string(s.lights) + ", cameras " + std::to_string(s.cameras);
}

// --out-dir DIR: an existing folder, for an output that has side files.
void check_out_dir(const ConvertArgs& a) {
  const std::string& dir = a.save.side_folder;
  if (!a.out_dir_given) return;
  if (dir.empty()) throw UsageError("--out-dir expects a folder, got ''");
  if (std::string problem = side_folder_problem(a.output, dir, a.save.embed, "--embed"); !problem.empty())
    throw UsageError("--out-dir: " + problem);
}

void run_convert(const ConvertArgs& a) {
  // Before reading: an output that is the input or has an unknown extension.
  if (std::string problem = convert_output_problem(a.input, a.output); !problem.empty()) throw UsageError(problem);
  check_output_folder(a.output, "the scene");
  check_out_dir(a);
  LoadOptions lo{dialect_from_string(a.dialect)};
  apply_read_flags(a.read, lo);
  LoadedScene loaded = load_scene(a.input, lo);
  for (const std::string& w : loaded.warnings) warn(w);

  SaveOptions o = a.save;
  o.shape_extras = !a.tessellate_only;
  o.dialect = convert_dialect(dialect_from_string(a.dialect), loaded);
  std::vector<std::string> messages;
  const std::string ext = lower_extension(a.output);
  if (o.embed && ext != ".gltf")
    messages.push_back(fs::path(a.output).filename().string() + ": --embed applies to .gltf output only" +
                       (ext == ".glb" ? " (a .glb always holds everything)" : ""));
  if (a.tessellate_only && ext != ".gltf" && ext != ".glb")
    messages.push_back(fs::path(a.output).filename().string() + ": --tessellate-only applies to glTF output only");

  SaveResult r = save_scene(loaded.scene, a.output, o, &messages);
  // What came into the output from outside the input's folder (a scene from
  // elsewhere may name any file the user can read; --confine refuses them).
  std::error_code ec;
  const fs::path folder = fs::absolute(a.input, ec).parent_path();
  std::set<std::string> external;
  for (const Mesh& m : loaded.scene.meshes)
    if (!m.source_path.empty() && m.source_path != loaded.scene.source_path &&
        !lies_within_folder(m.source_path, folder))
      external.insert(m.source_path);
  for (const Texture& t : loaded.scene.textures)
    if (!t.path.empty() && !lies_within_folder(t.path, folder)) external.insert(t.path);
  for (const std::string& f : external)
    messages.push_back("copied " + f + ", from outside the input's folder, into the output");
  for (const std::string& m : messages) note(m);
  if (a.stats) {
    std::cout << "read: " << a.input << ": " << counts(loaded.scene) << "\n";
    std::cout << "wrote: " << a.output << ": stored triangles " << r.stored_triangles << ", files " << r.files.size()
              << "\n";
    for (const std::string& f : r.files) std::cout << "  " << f << "\n";
  }
}

}  // namespace

void add_convert_command(CLI::App& app) {
  auto a = std::make_shared<ConvertArgs>();
  CLI::App* c = app.add_subcommand("convert", "Convert a scene between course .txt, OBJ+MTL, .gltf and .glb");
  c->add_option("input", a->input, "Scene to read (.txt, .obj, .gltf, .glb)")->required();
  c->add_option("output", a->output, "Scene to write (.txt, .obj, .gltf, .glb; the extension decides)")->required();
  c->add_flag("--flatten", a->save.flatten, "Bake every transform into the geometry (one flat list of shapes)");
  c->add_flag("--embed", a->save.embed, "glTF: buffers and images inside the .gltf (a .glb always holds them)");
  c->add_option("--sphere-segments", a->save.sphere_segments, "Longitudes of tessellated spheres (bands: half as many)")
      ->check(CLI::Range(min_sphere_segments, max_sphere_segments))
      ->capture_default_str();
  c->add_option("--dialect", a->dialect, "Course dialect to read and write (default: the input's, else as needed)")
      ->check(CLI::IsMember({"2012", "2019", "a5"}));
  c->add_flag("--tessellate-only", a->tessellate_only,
              "glTF: spheres and planes as meshes only, without their exact form in extras");
  CLI::Option* out_dir = c->add_option("--out-dir", a->save.side_folder,
                                       "Folder (existing) for the side files: meshes, textures, .mtl, .bin (default: "
                                       "beside the output, which names them relative to itself)")
                             ->type_name("DIR");
  c->add_flag("--stats", a->stats, "Print the counts of the scene read and the files written on stdout");
  add_read_flags(*c, a->read);
  c->footer(R"(
Examples:
  rayform convert scene01_plane.txt scene01.glb
  rayform convert duck.obj duck.gltf --embed
  rayform convert scene01.glb scene01.txt
  rayform convert model.gltf model.obj --flatten
  rayform convert model.glb model.txt --out-dir model_files   (meshes and textures in model_files/))");
  c->callback([a, out_dir] {
    if (!distributed::ranks().root()) return;  // under mpirun, rank 0 alone writes the files
    a->out_dir_given = out_dir->count() > 0;
    run_convert(*a);
  });
}

}  // namespace rayform::cli
