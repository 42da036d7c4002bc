#include "fuzz_targets.h"

#include "course_args.h"
#include "rayform/image/image.h"
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/base/error.h"
#include "rayform/scene/scene_stats.h"
#include "rayform/importers/scene_io.h"
#include "test_bytes.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace rayform::fuzz {
namespace fs = std::filesystem;
namespace {

// The extensions a texture part is visible under (all links to one file), and
// those the image target picks from with its first byte.
constexpr const char* texture_extensions[] = {".bmp", ".png", ".tga", ".jpg", ".hdr", ".ppm", ".psd", ".gif"};
constexpr const char* image_extensions[] = {".bmp", ".png", ".tga", ".jpg", ".jpeg", ".hdr",
                                            ".gif", ".ppm", ".pgm", ".psd", ".exr",  ".tif"};
constexpr float bait_value = 4242.5f;  // a coordinate of the bait mesh and the bait buffer's floats

void write_file(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out) throw std::runtime_error("fuzz: cannot write " + path.string());
}

// One private folder per process, removed at exit:
//   <tmp>/s/        the scene's folder, where the inputs are written
//   <tmp>/outside/  bait files beside it (a material, a mesh, a texture, a
//                   buffer) whose use the confinement checks detect.
class Workspace {
 public:
  Workspace() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/rayform-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) throw std::runtime_error("fuzz: cannot create a temporary folder");
    root_ = fs::canonical(pattern);
    scene_ = root_ / "s";
    fs::create_directory(scene_);
    const fs::path outside = root_ / "outside";
    fs::create_directory(outside);
    write_file(outside / "x.mtl", "newmtl bait_outside\nKd 1 0 0\nmap_Kd x.bmp\n");
    write_file(outside / "x.obj", "v 4242.5 0 0\nv 4243 0 0\nv 4242.5 1 0\nf 1 2 3\n");
    std::string floats;
    for (int i = 0; i < 36; ++i) floats.append(reinterpret_cast<const char*>(&bait_value), sizeof(float));
    write_file(outside / "x.bin", floats);
    // A 1x1 24-bit BMP.
    const unsigned char bmp[] = {'B', 'M', 58, 0, 0, 0, 0, 0, 0,  0, 54, 0, 0, 0, 40, 0, 0,   0, 1, 0,
                                 0,   0,   1,  0, 0, 0, 1, 0, 24, 0, 0,  0, 0, 0, 4,  0, 0,   0, 0, 0,
                                 0,   0,   0,  0, 0, 0, 0, 0, 0,  0, 0,  0, 0, 0, 0,  0, 255, 0};
    write_file(outside / "x.bmp", std::string_view(reinterpret_cast<const char*>(bmp), sizeof bmp));
    for (const char* ext : texture_extensions) fs::create_symlink("tex.bin", scene_ / (std::string("tex") + ext));
  }
  ~Workspace() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  const fs::path& scene_folder() const { return scene_; }
  // Writes `bytes` as scene-folder file `name`, or removes it when absent, so
  // that nothing of an earlier input remains.
  void put(const char* name, const std::string_view* bytes) const {
    const fs::path p = scene_ / name;
    if (bytes) write_file(p, *bytes);
    else {
      std::error_code ec;
      fs::remove(p, ec);
    }
  }

 private:
  fs::path root_, scene_;
};

const Workspace& workspace() {
  static const Workspace w;
  return w;
}

void put_parts(const std::vector<std::string_view>& parts, std::initializer_list<const char*> names) {
  size_t i = 0;
  for (const char* name : names) {
    workspace().put(name, i < parts.size() ? &parts[i] : nullptr);
    ++i;
  }
}

bool inside(const fs::path& folder, const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) p = fs::absolute(path).lexically_normal();
  const std::string f = folder.string() + "/";
  return p.string().rfind(f, 0) == 0;
}

// What of a loaded scene came from outside the scene's folder.
std::vector<std::string> outside_uses(const Scene& scene) {
  std::vector<std::string> found;
  const fs::path& folder = workspace().scene_folder();
  for (const Texture& t : scene.textures)
    if (!t.path.empty() && !inside(folder, t.path)) found.push_back("texture " + t.path);
  for (const Material& m : scene.materials)
    if (m.name == "bait_outside") found.push_back("material bait_outside (outside/x.mtl)");
  for (const Mesh& m : scene.meshes) {
    if (!m.source_path.empty() && !inside(folder, m.source_path)) found.push_back("mesh " + m.source_path);
    for (const vec3& p : m.positions)
      if (p.x == bait_value) {
        found.push_back("mesh data of outside/x.obj or outside/x.bin");
        break;
      }
  }
  return found;
}

// Loads a scene written into the workspace and does what `info` and `render`
// do before rendering: statistics, then prepare (node walk, BVHs, textures).
FuzzOutcome load_and_prepare(const std::string& file) {
  FuzzOutcome o;
  try {
    LoadOptions lo;
    lo.access.confine = true;  // files from strangers: rayform's --confine
    lo.limits.texture_texels = fuzz_texture_texels;
    lo.limits.unbacked_elements = fuzz_unbacked_elements;
    lo.limits.instances = fuzz_instances;
    LoadedScene loaded = load_scene((workspace().scene_folder() / file).string(), lo);
    o.outside = outside_uses(loaded.scene);
    (void)scene_stats(loaded.scene, lo.limits.instances);
    PrepareOptions po;
    po.limits = lo.limits;
    (void)prepare_scene(loaded.scene, po);
    o.ok = true;
  } catch (const Error& e) {
    o.message = e.what();
  }
  return o;
}

FuzzOutcome skipped() {
  FuzzOutcome o;
  o.skipped = true;
  o.message = "skipped: over the input size limit";
  return o;
}

std::string_view bytes_of(const uint8_t* data, size_t size) { return {reinterpret_cast<const char*>(data), size}; }

// Course scene: scene.txt %% mesh.obj %% texture (tex.bmp, tex.tga, ... all name it).
FuzzOutcome fuzz_course_txt(const uint8_t* data, size_t size, const FuzzLimits& limits) {
  if (size > limits.max_input_bytes) return skipped();
  put_parts(split_parts(bytes_of(data, size), 3), {"scene.txt", "mesh.obj", "tex.bin"});
  return load_and_prepare("scene.txt");
}

// The OBJ parse in chunks (obj_parallel_parse.h) must give what the parse in
// one piece gives, or the same error. Returns "" when they agree.
std::string chunked_obj_differs(const std::string& path, size_t chunk_bytes) {
  auto read = [&](size_t chunk, std::vector<std::string>* warnings, std::string* error) {
    ObjReadOptions o;
    o.access.confine = true;
    o.parse_chunk_bytes = chunk;
    try {
      return read_obj_scene(path, o, warnings);
    } catch (const Error& e) {
      *error = e.what();
    }
    return Scene{};
  };
  std::vector<std::string> warnings_one, warnings_chunked;
  std::string error_one, error_chunked;
  const Scene one = read(ObjReadOptions::serial, &warnings_one, &error_one);
  const Scene chunked = read(chunk_bytes, &warnings_chunked, &error_chunked);
  if (error_one != error_chunked) return "errors differ: '" + error_one + "' / '" + error_chunked + "'";
  if (warnings_one != warnings_chunked) return "warnings differ";
  if (one.meshes.size() != chunked.meshes.size()) return "mesh counts differ";
  for (size_t i = 0; i < one.meshes.size(); ++i) {
    const Mesh &a = one.meshes[i], &b = chunked.meshes[i];
    using test::same_bytes;
    if (a.name != b.name || !same_bytes(a.positions, b.positions) || !same_bytes(a.normals, b.normals) ||
        !same_bytes(a.uvs, b.uvs) || !same_bytes(a.colors, b.colors) || !same_bytes(a.indices, b.indices) ||
        a.face_materials != b.face_materials)
      return "mesh " + std::to_string(i) + " differs";
  }
  if (one.nodes.size() != chunked.nodes.size() || one.materials.size() != chunked.materials.size() ||
      one.textures.size() != chunked.textures.size())
    return "node, material or texture counts differ";
  for (size_t i = 0; i < one.nodes.size(); ++i)
    if (one.nodes[i].name != chunked.nodes[i].name || one.nodes[i].children != chunked.nodes[i].children ||
        one.nodes[i].material != chunked.nodes[i].material)
      return "node " + std::to_string(i) + " differs";
  return "";
}

// OBJ: model.obj %% model.mtl %% texture (tex.bmp, tex.tga, ... all name it).
FuzzOutcome fuzz_obj(const uint8_t* data, size_t size, const FuzzLimits& limits) {
  if (size > limits.max_input_bytes) return skipped();
  put_parts(split_parts(bytes_of(data, size), 3), {"model.obj", "model.mtl", "tex.bin"});
  // Differential: chunks of 1 to 64 bytes (the input's size picks), so that
  // state lines land on chunk ends; not for the expanded regression files of
  // many MB (two scenes would pass the memory bound).
  if (std::string d = size > (1u << 20)
                          ? std::string()
                          : chunked_obj_differs((workspace().scene_folder() / "model.obj").string(), 1 + size % 64);
      !d.empty()) {
    std::fprintf(stderr, "fuzz_obj: the chunked OBJ parse differs from the parse in one piece: %s\n", d.c_str());
    std::abort();
  }
  return load_and_prepare("model.obj");
}

// glTF: one file, model.glb when it starts with the GLB magic, else model.gltf.
FuzzOutcome fuzz_gltf(const uint8_t* data, size_t size, const FuzzLimits& limits) {
  if (size > limits.max_input_bytes) return skipped();
  const std::string_view bytes = bytes_of(data, size);
  const bool glb = bytes.substr(0, 4) == "glTF";
  workspace().put("model.glb", glb ? &bytes : nullptr);
  workspace().put("model.gltf", glb ? nullptr : &bytes);
  return load_and_prepare(glb ? "model.glb" : "model.gltf");
}

// Image: the first byte picks the extension (image_extensions), the rest is the file.
FuzzOutcome fuzz_image(const uint8_t* data, size_t size, const FuzzLimits& limits) {
  if (size > limits.max_input_bytes) return skipped();
  FuzzOutcome o;
  if (size == 0) {
    o.ok = true;  // no extension, no file
    return o;
  }
  constexpr size_t n = sizeof image_extensions / sizeof image_extensions[0];
  const std::string name = std::string("image") + image_extensions[data[0] % n];
  const std::string_view bytes = bytes_of(data + 1, size - 1);
  workspace().put(name.c_str(), &bytes);
  const std::string path = (workspace().scene_folder() / name).string();
  try {
    (void)to_float_image(read_image_file(
        path, DecodeOptions{fuzz_texture_texels}));  // as textures are read: samples as stored, then floats
    o.ok = true;
  } catch (const Error& e) {
    o.message = e.what();
  }
  workspace().put(name.c_str(), nullptr);
  return o;
}

// The course command line: arguments are the bytes split at NUL and white
// space. Parsing only: nothing is loaded or rendered.
FuzzOutcome fuzz_course_args(const uint8_t* data, size_t size, const FuzzLimits& limits) {
  if (size > limits.max_input_bytes) return skipped();
  std::vector<std::string> args;
  std::string word;
  for (size_t i = 0; i <= size; ++i) {
    const char c = i < size ? char(data[i]) : '\0';
    if (c == '\0' || c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') {
      if (!word.empty()) args.push_back(std::move(word));
      word.clear();
    } else word.push_back(c);
  }
  FuzzOutcome o;
  try {
    (void)cli::is_course_command_line(args);
    const cli::CourseCommand command = cli::parse_course_command_line(args);
    check_render_job_memory(command.job);  // what `rayform` checks before it reads the scene
    o.ok = true;
  } catch (const UsageError& e) {
    o.message = e.what();
  } catch (const Error& e) {
    o.message = e.what();
  }
  return o;
}

constexpr FuzzTarget targets[] = {
    {"course_txt", &fuzz_course_txt, "course scene: scene.txt %% mesh.obj %% texture"},
    {"obj", &fuzz_obj, "OBJ: model.obj %% model.mtl %% texture"},
    {"gltf", &fuzz_gltf, "glTF: a .glb (starts with 'glTF') or a .gltf"},
    {"image", &fuzz_image, "image: extension-selector byte, then the file"},
    {"course_args", &fuzz_course_args, "course command line: words split at NUL or white space"},
};

}  // namespace

std::vector<std::string_view> split_parts(std::string_view input, size_t max_parts) {
  std::vector<std::string_view> parts;
  while (parts.size() + 1 < max_parts) {
    const size_t at = input.find(part_separator);
    if (at == std::string_view::npos) break;
    parts.push_back(input.substr(0, at + 1));  // the part keeps its last newline
    input.remove_prefix(at + part_separator.size());
  }
  parts.push_back(input);
  return parts;
}

std::span<const FuzzTarget> fuzz_targets() { return targets; }

const FuzzTarget* find_fuzz_target(std::string_view name) {
  for (const FuzzTarget& t : targets)
    if (name == t.name) return &t;
  return nullptr;
}

}  // namespace rayform::fuzz
