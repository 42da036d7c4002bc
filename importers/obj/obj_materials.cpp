#include "rayform/importers/obj/obj_materials.h"

#include "rayform/base/error.h"
#include "rayform/importers/obj/obj_pbr_material.h"
#include "rayform/importers/obj/obj_side_files.h"
#include "rayform/importers/referenced_files.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

namespace rayform::obj {

namespace {

// Grey of the material given to faces without a (known) material: light
// enough to read, dark enough that a head-on light does not clip it.
constexpr float default_grey = 0.8f;

// Every offset of `word` in `text`, in order. Blocks of the text are searched
// in parallel: this is the first pass over a large file's mapped pages, and
// their faults are shared among the threads.
std::vector<size_t> find_every(std::string_view text, std::string_view word) {
  constexpr size_t block = size_t(1) << 20;
  const size_t blocks = (text.size() + block - 1) / block;
  std::vector<std::vector<size_t>> found(blocks);
  tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
    const size_t begin = b * block, end = std::min(text.size(), begin + block + word.size() - 1);
    const std::string_view part = text.substr(begin, end - begin);
    for (size_t at = part.find(word); at != std::string_view::npos; at = part.find(word, at + 1))
      found[b].push_back(begin + at);  // starts in the block: the word.size() - 1 bytes past it cannot hold one
  });
  std::vector<size_t> all;
  for (const std::vector<size_t>& f : found) all.insert(all.end(), f.begin(), f.end());
  return all;
}

}  // namespace

ObjMaterials::ObjMaterials(const std::string& path, const fs::path& dir, const FileAccess& access, Scene& scene,
                           std::function<void(std::string)> warn)
    : path_(path), dir_(dir), access_(access), scene_(scene), warn_(std::move(warn)) {}

void ObjMaterials::load_libraries(std::string_view text) {
  size_t line_no = 1, counted_to = 0;  // line_no: the line at offset counted_to
  std::set<std::string> loaded;
  for (const size_t at : find_every(text, "mtllib")) {
    const size_t newline_before = text.rfind('\n', at);
    const size_t line_start = newline_before == std::string_view::npos ? 0 : newline_before + 1;
    const size_t b = at - line_start;  // where the word starts in its line
    if (text.substr(line_start, b).find_first_not_of(" \t") != std::string_view::npos) continue;
    const size_t line_end = std::min(text.find('\n', at), text.size());
    const std::string line(text.substr(line_start, line_end - line_start));
    line_no += size_t(std::count(text.begin() + counted_to, text.begin() + line_start, '\n'));
    counted_to = line_start;
    if (b + 6 < line.size() && line[b + 6] != ' ' && line[b + 6] != '\t') continue;
    std::string rest = trim(line.substr(b + 6));
    std::string where = path_ + ":" + std::to_string(line_no);
    if (rest.empty()) {
      warn_(where + ": mtllib names no file");
      continue;
    }
    for (const std::string& name : split_mtllib(rest, dir_)) {
      Resolved r = resolve_beside(dir_, name);
      if (!r.found) {
        warn_(where + ": cannot find material library '" + name +
              "'; its materials are replaced by the default material");
        continue;
      }
      if (std::string problem = referenced_file_problem(path_, "mtllib", name, r.path, access_); !problem.empty())
        throw Error(where + ": " + problem);
      if (r.by_name_only)
        warn_(where + ": material library '" + name + "' not found as written; using " + r.path.string());
      std::error_code ec;
      std::string key = fs::weakly_canonical(r.path, ec).string();
      if (!loaded.insert(key).second) continue;
      load_mtl(r.path);
    }
  }
}

void ObjMaterials::load_mtl(const fs::path& file) {
  std::ifstream f(file, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  if (!f) {
    warn_(file.string() + ": cannot read material library");
    return;
  }
  std::string text = ss.str();
  std::map<std::string, std::set<std::string>> keywords = mtl_keywords(text);
  std::istringstream in(text);
  std::string w, e;
  size_t first = lib_.materials.size();
  tinyobj::LoadMtl(&lib_.names, &lib_.materials, &in, &w, &e);
  for (size_t i = first; i < lib_.materials.size(); ++i) {
    lib_.dirs.push_back(file.parent_path());
    lib_.keywords.push_back(keywords[lib_.materials[i].name]);
  }
  std::istringstream wl(w + e);
  std::string l;
  while (std::getline(wl, l))
    if (!trim(l).empty()) warn_(file.string() + ": " + trim(l));
}

std::string ObjMaterials::texture_path(const std::string& name, const fs::path& mtl_dir, const std::string& material,
                                       const char* slot) {
  Resolved r = resolve_beside(mtl_dir, name);
  if (!r.found) {
    warn_(path_ + ": material '" + material + "': cannot find " + slot + " texture '" + name + "' (looked in " +
          mtl_dir.string() + "); the material has no " + slot + " texture");
    return {};
  }
  if (std::string problem = referenced_file_problem(path_, slot, name, r.path, access_); !problem.empty())
    throw Error(path_ + ": material '" + material + "': " + problem);
  if (r.by_name_only)
    warn_(path_ + ": material '" + material + "': " + slot + " texture '" + name + "' not found as written; using " +
          r.path.string());
  return r.path.lexically_normal().string();
}

int ObjMaterials::texture(const std::string& name, const fs::path& mtl_dir, const std::string& material,
                          const char* slot, bool srgb, bool clamp) {
  if (name.empty()) return invalid;
  const std::string path = texture_path(name, mtl_dir, material, slot);
  if (path.empty()) return invalid;
  std::string key = path + (srgb ? "|srgb" : "|raw") + (clamp ? "|clamp" : "|repeat");
  auto it = texture_cache_.find(key);
  if (it != texture_cache_.end()) return it->second;
  Texture t;
  t.name = name;
  t.path = path;
  t.srgb = srgb;
  t.lookup = Texture::Lookup::standard;
  t.wrap_u = t.wrap_v = clamp ? Texture::Wrap::clamp : Texture::Wrap::repeat;
  t.filter = Texture::Filter::linear;
  scene_.textures.push_back(std::move(t));
  int index = int(scene_.textures.size()) - 1;
  texture_cache_[key] = index;
  return index;
}

MtlTextures& ObjMaterials::pbr_textures(const fs::path& dir) {
  pbr_textures_.resolve = [this, dir](const std::string& name, const char* slot) {
    return texture_path(name, dir, current_material_, slot);
  };
  pbr_textures_.file_texture = [this, dir](const std::string& name, const char* slot, bool srgb, bool clamp) {
    return texture(name, dir, current_material_, slot, srgb, clamp);
  };
  pbr_textures_.add = [this](Texture t) {
    scene_.textures.push_back(std::move(t));
    return int(scene_.textures.size()) - 1;
  };
  pbr_textures_.warn = [this](const std::string& w) { warn_(path_ + ": " + w); };
  return pbr_textures_;
}

void ObjMaterials::convert() {
  for (size_t i = 0; i < lib_.materials.size(); ++i) {
    const tinyobj::material_t& tm = lib_.materials[i];
    const fs::path& dir = lib_.dirs[i];
    current_material_ = tm.name;
    Material m;
    m.name = tm.name;
    m.texture_modulates = true;
    m.double_sided = true;
    m.two_sided_lighting = true;  // OBJ has no culling: both sides are lit alike
    bool srgb = tm.diffuse_texopt.colorspace != "linear";
    m.diffuse_texture = texture(tm.diffuse_texname, dir, tm.name, "map_Kd", srgb, tm.diffuse_texopt.clamp);
    // Kd absent: with a map_Kd the texel is the colour (Kd = 1, as
    // exporters that leave Kd out mean); without one, the default grey.
    // (tinyobjloader would give 0.6 or black.)
    if (lib_.has(i, "Kd")) m.diffuse = vec3(tm.diffuse[0], tm.diffuse[1], tm.diffuse[2]);
    else m.diffuse = vec3(m.diffuse_texture != invalid ? 1.f : default_grey);
    if (is_pbr_material(lib_.keywords[i])) {
      scene_.materials.push_back(pbr_material(tm, lib_.keywords[i], m.diffuse, m.diffuse_texture, pbr_textures(dir)));
      continue;
    }
    if (m.diffuse_texture != invalid) {
      // map_Kd -s/-o: uv' = uv * s + o, the shader's transform with no rotation.
      m.uv_transform.scale = vec2(tm.diffuse_texopt.scale[0], tm.diffuse_texopt.scale[1]);
      m.uv_transform.offset = vec2(tm.diffuse_texopt.origin_offset[0], tm.diffuse_texopt.origin_offset[1]);
    }
    m.specular = vec3(tm.specular[0], tm.specular[1], tm.specular[2]);
    m.shininess = tm.shininess;
    // Ns 0 would make (L.R)^0 = 1: a constant "highlight" over the whole lit
    // side. Exporters write Ns 0 for "no highlight" (Blender: roughness 1).
    if (!(m.shininess > 0.f)) {
      m.shininess = 0.f;
      m.specular = vec3(0.f);
    }
    m.emission = vec3(tm.emission[0], tm.emission[1], tm.emission[2]);
    m.bump_texture = texture(tm.bump_texname, dir, tm.name, "map_Bump", false, tm.bump_texopt.clamp);
    if (tm.dissolve < 1.f)
      warn_(path_ + ": material '" + tm.name + "': transparency (d " + std::to_string(tm.dissolve) +
            ") is not rendered; the material is opaque");
    // Ka has no place in the course Phong model (ambient = scene ambient x K).
    std::vector<std::string> unused;
    if (!tm.ambient_texname.empty()) unused.push_back("map_Ka");
    if (!tm.specular_texname.empty()) unused.push_back("map_Ks");
    if (!tm.specular_highlight_texname.empty()) unused.push_back("map_Ns");
    if (!tm.emissive_texname.empty()) unused.push_back("map_Ke");
    if (!tm.alpha_texname.empty()) unused.push_back("map_d");
    if (!tm.displacement_texname.empty()) unused.push_back("disp");
    if (!tm.reflection_texname.empty()) unused.push_back("refl");
    if (!unused.empty()) {
      std::string list;
      for (const std::string& u : unused) list += (list.empty() ? "" : ", ") + u;
      warn_(path_ + ": material '" + tm.name + "': " + list + " not used by the Phong shader; ignored");
    }
    scene_.materials.push_back(std::move(m));
  }
}

int ObjMaterials::default_material() {
  if (default_material_ == invalid) {
    Material m;
    m.name = "default";
    m.diffuse = vec3(default_grey);
    m.texture_modulates = true;
    m.two_sided_lighting = true;
    scene_.materials.push_back(m);
    default_material_ = int(scene_.materials.size()) - 1;
  }
  return default_material_;
}

}  // namespace rayform::obj
