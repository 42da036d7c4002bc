#include "rayform/importers/gltf/gltf_extras.h"

// Debian's tinygltf is a prebuilt library: never define TINYGLTF_IMPLEMENTATION here.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace rayform {

namespace {

using Value = tinygltf::Value;

const Value* rayform_of(const Value& extras) {
  if (!extras.IsObject() || !extras.Has("rayform")) return nullptr;
  const Value& r = extras.Get("rayform");
  return r.IsObject() ? &r : nullptr;
}

bool get_float(const Value& obj, const char* key, float* out) {
  if (!obj.Has(key)) return false;
  const Value& v = obj.Get(key);
  if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) return false;
  *out = float(v.GetNumberAsDouble());
  return true;
}

bool get_vec3(const Value& obj, const char* key, vec3* out) {
  if (!obj.Has(key)) return false;
  const Value& v = obj.Get(key);
  if (!v.IsArray() || v.ArrayLen() != 3) return false;
  vec3 r;
  for (int i = 0; i < 3; ++i) {
    const Value& e = v.Get(i);
    if (!e.IsNumber() || !std::isfinite(e.GetNumberAsDouble())) return false;
    r[i] = float(e.GetNumberAsDouble());
  }
  *out = r;
  return true;
}

bool get_string(const Value& obj, const char* key, std::string* out) {
  if (!obj.Has(key) || !obj.Get(key).IsString()) return false;
  *out = obj.Get(key).Get<std::string>();
  return true;
}

bool get_bool(const Value& obj, const char* key, bool* out) {
  if (!obj.Has(key) || !obj.Get(key).IsBool()) return false;
  *out = obj.Get(key).Get<bool>();
  return true;
}

bool same_direction(vec3 a, vec3 b) {
  if (!(glm::length(a) > 0.f) || !(glm::length(b) > 0.f)) return false;
  return glm::length(glm::cross(glm::normalize(a), glm::normalize(b))) <= 1e-4f && glm::dot(a, b) > 0.f;
}

bool same_point(vec3 a, vec3 b) {
  return glm::length(a - b) <= 1e-4f * std::max({1.f, glm::length(a), glm::length(b)});
}

// One application of the extras: the file, how the reader mapped it to the
// Scene, the Scene and the warnings.
struct ExtrasInput {
  const tinygltf::Model& model;
  const GltfSceneMapping& map;
  Scene& scene;
  std::vector<std::string>* warnings;

  void warn(const std::string& w) const {
    if (warnings) warnings->push_back(w + "; that rayform extra is ignored");
  }
  // The Scene texture of glTF texture `ti`, or invalid.
  int scene_texture(int ti) const {
    if (ti < 0 || size_t(ti) >= model.textures.size() || !map.texture) return invalid;
    return map.texture(ti);
  }
};

// Textures: how the course reads them.
void apply_texture_extras(const ExtrasInput& in) {
  for (size_t ti = 0; ti < in.model.textures.size(); ++ti) {
    const Value* ex = rayform_of(in.model.textures[ti].extras);
    if (!ex) continue;
    int t = in.scene_texture(int(ti));
    if (t == invalid || size_t(t) >= in.scene.textures.size()) continue;
    std::string lookup;
    if (get_string(*ex, "lookup", &lookup))
      in.scene.textures[size_t(t)].lookup = lookup == "course" ? Texture::Lookup::course : Texture::Lookup::standard;
    bool srgb = true;
    if (get_bool(*ex, "srgb", &srgb)) in.scene.textures[size_t(t)].srgb = srgb;
  }
}

void apply_background_extras(const ExtrasInput& in) {
  const tinygltf::Model& model = in.model;
  const GltfSceneMapping& map = in.map;
  Scene& scene = in.scene;
  if (map.scene >= 0 && size_t(map.scene) < model.scenes.size()) {
    if (const Value* ex = rayform_of(model.scenes[size_t(map.scene)].extras); ex && ex->Has("background")) {
      const Value& bg = ex->Get("background");
      if (bg.IsObject()) {
        get_vec3(bg, "color", &scene.background.color);
        get_vec3(bg, "ambient", &scene.background.ambient);
        if (bg.Has("cube_map") && bg.Get("cube_map").IsArray() && bg.Get("cube_map").ArrayLen() == 6) {
          std::array<int, 6> faces{};
          bool ok = true;
          for (int i = 0; i < 6; ++i) {
            const Value& f = bg.Get("cube_map").Get(i);
            faces[size_t(i)] = f.IsNumber() ? in.scene_texture(f.GetNumberAsInt()) : invalid;
            ok &= faces[size_t(i)] != invalid;
          }
          if (ok) {
            scene.background.cube_map = faces;
            get_string(bg, "cube_map_dir", &scene.background.cube_map_dir);
          } else {
            in.warn("scenes[" + std::to_string(map.scene) +
                    "].extras: the background's cube map names a missing texture");
          }
        }
      }
    }
  }
}

// Whether the material's PBR values are still those rayform wrote beside its
// Phong extras (its "pbr" extra).
bool pbr_as_written(const tinygltf::Material& gm, const Value& ex) {
  bool same = ex.Has("pbr") && ex.Get("pbr").IsObject();
  if (same) {
    const Value& p = ex.Get("pbr");
    const auto& bc = gm.pbrMetallicRoughness.baseColorFactor;
    if (!p.Has("base") || !p.Get("base").IsArray() || p.Get("base").ArrayLen() != 4 || bc.size() != 4) same = false;
    for (int i = 0; same && i < 4; ++i)
      same = std::abs(p.Get("base").Get(i).GetNumberAsDouble() - bc[size_t(i)]) <= 1e-9;
    float metallic = -1.f, roughness = -1.f;
    same = same && get_float(p, "metallic", &metallic) && get_float(p, "roughness", &roughness) &&
           std::abs(double(metallic) - gm.pbrMetallicRoughness.metallicFactor) <= 1e-6 &&
           std::abs(double(roughness) - gm.pbrMetallicRoughness.roughnessFactor) <= 1e-6;
  }
  return same;
}

// Materials: a material rayform wrote from the course's Phong model (its
// "phong" extra) is that Phong material again, if the PBR values are still
// those written; other extras restore the course's fields either model reads
// (sidedness, noise, ...).
void apply_material_extras(const ExtrasInput& in) {
  const tinygltf::Model& model = in.model;
  const GltfSceneMapping& map = in.map;
  for (size_t gi = 0; gi < model.materials.size() && gi < map.materials.size(); ++gi) {
    const tinygltf::Material& gm = model.materials[gi];
    const Value* ex = rayform_of(gm.extras);
    int mi = map.materials[gi];
    if (!ex || mi < 0 || size_t(mi) >= in.scene.materials.size()) continue;
    const std::string where = "materials[" + std::to_string(gi) + "]";
    if (!pbr_as_written(gm, *ex)) {
      in.warn(where +
              ": its metallic-roughness values are not those rayform wrote (edited?), so its Phong extras are stale");
      continue;
    }
    Material& m = in.scene.materials[size_t(mi)];
    if (ex->Has("phong") && ex->Get("phong").IsObject()) {
      const Value& ph = ex->Get("phong");
      get_vec3(ph, "diffuse", &m.diffuse);
      get_vec3(ph, "specular", &m.specular);
      get_float(ph, "shininess", &m.shininess);
      m.model = Material::Model::phong;
    }
    get_bool(*ex, "texture_modulates", &m.texture_modulates);
    get_bool(*ex, "two_sided_lighting", &m.two_sided_lighting);
    get_float(*ex, "refraction_index", &m.refraction_index);
    get_bool(*ex, "specular_highlight", &m.specular_highlight);
    get_bool(*ex, "back_faces_cast_shadows", &m.back_faces_cast_shadows);
    if (ex->Has("noise") && ex->Get("noise").IsObject()) {
      const Value& nv = ex->Get("noise");
      SolidNoise n;
      float octaves = -1.f;
      if (get_vec3(nv, "color1", &n.color1) && get_vec3(nv, "color2", &n.color2) &&
          get_float(nv, "octaves", &octaves) && get_float(nv, "frequency", &n.frequency) &&
          get_float(nv, "amplitude", &n.amplitude) && octaves >= 0.f && octaves <= 64.f &&
          octaves == std::floor(octaves)) {
        n.enabled = true;
        n.octaves = int(octaves);
        m.noise = n;
      } else {
        in.warn(where + ": its noise extras are incomplete or out of range; the noise is dropped");
      }
    }
    if (!get_vec3(*ex, "emission", &m.emission)) m.emission = vec3(0.f);
    get_float(*ex, "alpha_cutoff", &m.alpha_cutoff);
    if (ex->Has("bump_texture") && ex->Get("bump_texture").IsNumber())
      m.bump_texture = in.scene_texture(ex->Get("bump_texture").GetNumberAsInt());
  }
}

// Untextured copies of materials (for primitives without uvs) fold back
// into their originals.
void fold_untextured_copies(const ExtrasInput& in) {
  const tinygltf::Model& model = in.model;
  const GltfSceneMapping& map = in.map;
  Scene& scene = in.scene;
  std::vector<int> remap(scene.materials.size());
  for (size_t i = 0; i < remap.size(); ++i) remap[i] = int(i);
  bool any = false;
  for (size_t gi = 0; gi < model.materials.size() && gi < map.materials.size(); ++gi) {
    const Value* ex = rayform_of(model.materials[gi].extras);
    if (!ex || !ex->Has("variant_of") || !ex->Get("variant_of").IsNumber()) continue;
    int of = ex->Get("variant_of").GetNumberAsInt();
    int from = map.materials[gi];
    if (of < 0 || size_t(of) >= map.materials.size() || from < 0 || size_t(from) >= remap.size()) continue;
    int to = map.materials[size_t(of)];
    if (to < 0 || size_t(to) >= remap.size() || to == from) continue;
    remap[size_t(from)] = to;
    any = true;
  }
  if (!any) return;
  std::vector<int> index(scene.materials.size(), invalid);
  std::vector<Material> kept;
  for (size_t i = 0; i < scene.materials.size(); ++i)
    if (remap[i] == int(i)) {
      index[i] = int(kept.size());
      kept.push_back(std::move(scene.materials[i]));
    }
  for (size_t i = 0; i < remap.size(); ++i) remap[i] = index[size_t(remap[i])];
  scene.materials = std::move(kept);
  auto fix = [&](int m) { return m >= 0 && size_t(m) < remap.size() ? remap[size_t(m)] : m; };
  for (Node& n : scene.nodes) n.material = fix(n.material);
  for (Mesh& m : scene.meshes)
    for (int& fm : m.face_materials) fm = fix(fm);
}

// Cameras, found by the name the reader gave them.
void apply_camera_extras(const ExtrasInput& in) {
  for (size_t ci = 0; ci < in.model.cameras.size(); ++ci) {
    const tinygltf::Camera& gc = in.model.cameras[ci];
    const Value* ex = rayform_of(gc.extras);
    if (!ex) continue;
    const std::string name = gc.name.empty() ? "cameras[" + std::to_string(ci) + "]" : gc.name;
    for (Camera& c : in.scene.cameras) {
      if (c.name != name) continue;
      std::string aspect, up_vector, original;
      if (get_string(*ex, "aspect", &aspect))
        c.aspect = aspect == "stretch" ? Camera::Aspect::stretch : Camera::Aspect::fit;
      vec3 center, direction, up;
      float fov = c.fov_deg, height = c.ortho_height;
      bool ok = get_vec3(*ex, "center", &center) && get_vec3(*ex, "direction", &direction) && get_vec3(*ex, "up", &up);
      get_float(*ex, "fov_deg", &fov);
      get_float(*ex, "ortho_height", &height);
      ok = ok && same_point(center, c.center) && same_direction(direction, c.direction) &&
           (c.projection == Camera::Projection::perspective ? std::abs(fov - c.fov_deg) <= 1e-4f * fov
                                                            : std::abs(height - c.ortho_height) <= 1e-4f * height);
      if (!ok) {
        in.warn("cameras[" + std::to_string(ci) + "]: its node no longer places it where its extras say (moved?)");
        continue;
      }
      c.center = center;
      c.direction = direction;
      c.up = up;
      c.fov_deg = fov;
      c.ortho_height = height;
      if (get_string(*ex, "up_vector", &up_vector))
        c.up_vector = up_vector == "raw" ? Camera::UpVector::raw : Camera::UpVector::orthonormal;
      if (get_string(*ex, "name", &original)) c.name = original;
    }
  }
}

// Lights, found by the name the reader gave them.
void apply_light_extras(const ExtrasInput& in) {
  for (size_t li = 0; li < in.model.lights.size(); ++li) {
    const tinygltf::Light& gl = in.model.lights[li];
    const Value* ex = rayform_of(gl.extras);
    if (!ex) continue;
    const std::string name =
        gl.name.empty() ? "extensions.KHR_lights_punctual.lights[" + std::to_string(li) + "]" : gl.name;
    for (Light& l : in.scene.lights) {
      if (l.name != name) continue;
      vec3 color, position, direction;
      float falloff = 0.f;
      bool ok = get_vec3(*ex, "color", &color) && get_vec3(*ex, "position", &position) &&
                get_vec3(*ex, "direction", &direction) && get_float(*ex, "falloff", &falloff);
      ok = ok && (l.kind == Light::Kind::directional || same_point(position, l.position)) &&
           (l.kind == Light::Kind::point || same_direction(direction, l.direction));
      // The colour must still be what the light's colour and intensity say,
      // up to the intensity scaling the writer chose.
      ok = ok && (l.kind != Light::Kind::directional ||
                  glm::length(color - l.color) <= 1e-4f * std::max(1.f, glm::length(color)));
      if (!ok) {
        in.warn("KHR_lights_punctual.lights[" + std::to_string(li) +
                "]: its node or colour no longer match its extras (edited?)");
        continue;
      }
      l.color = color;
      l.position = position;
      l.direction = direction;
      l.falloff = falloff;
      if (!get_float(*ex, "attenuation_constant", &l.attenuation_constant)) l.attenuation_constant = 0.f;
      std::string original;
      if (get_string(*ex, "name", &original)) l.name = original;
    }
  }
}

// Scene mesh -> the analytic shape that replaces its tessellation.
using ShapeReplacements = std::map<int, std::pair<ShapeKind, int>>;

// The analytic shape of one primitive's extras `ex` added to the Scene and
// recorded in `replace`, when the tessellation `mesh` (Scene mesh k) still
// lies on it; `where` names the primitive in warnings.
void add_analytic_shape(const ExtrasInput& in, const Value& ex, int k, const std::string& where,
                        ShapeReplacements& replace) {
  Scene& scene = in.scene;
  Mesh& mesh = scene.meshes[size_t(k)];
  std::string name;
  if (get_string(ex, "name", &name)) mesh.name = name;
  if (ex.Has("sphere") && ex.Get("sphere").IsObject()) {
    Sphere s;
    const Value& sv = ex.Get("sphere");
    bool ok = get_vec3(sv, "center", &s.center) && get_float(sv, "radius", &s.radius) && s.radius > 0.f &&
              !mesh.positions.empty();
    for (size_t i = 0; ok && i < mesh.positions.size(); ++i)
      ok = std::abs(glm::length(mesh.positions[i] - s.center) - s.radius) <=
           1e-4f * s.radius + 1e-6f * glm::length(s.center);
    if (!ok) {
      in.warn(where + ": its vertices no longer lie on the sphere its extras describe (edited?)");
      return;
    }
    scene.spheres.push_back(s);
    replace[k] = {ShapeKind::sphere, int(scene.spheres.size()) - 1};
  } else if (ex.Has("plane") && ex.Get("plane").IsObject()) {
    Plane p;
    const Value& pv = ex.Get("plane");
    bool ok = get_vec3(pv, "normal", &p.normal) && get_float(pv, "offset", &p.offset) && glm::length(p.normal) > 0.f &&
              !mesh.positions.empty();
    for (size_t i = 0; ok && i < mesh.positions.size(); ++i) {
      const vec3& q = mesh.positions[i];
      float scale = std::max({1.f, std::abs(q.x), std::abs(q.y), std::abs(q.z)});
      ok = std::abs(glm::dot(glm::normalize(p.normal), q) - p.offset / glm::length(p.normal)) <= 1e-5f * scale;
    }
    if (!ok) {
      in.warn(where + ": its vertices no longer lie on the plane its extras describe (edited?)");
      return;
    }
    scene.planes.push_back(p);
    replace[k] = {ShapeKind::plane, int(scene.planes.size()) - 1};
  } else if (ex.Has("triangle")) {
    if (mesh.positions.size() != 3 || mesh.indices.size() != 3) {
      in.warn(where + ": its extras describe one triangle but it holds " + std::to_string(mesh.triangle_count()));
      return;
    }
    Triangle t;
    for (int c = 0; c < 3; ++c) t.vertices[size_t(c)] = mesh.positions[mesh.indices[size_t(c)]];
    scene.triangles.push_back(t);
    replace[k] = {ShapeKind::triangle, int(scene.triangles.size()) - 1};
  }
}

// Analytic shapes in place of their tessellations: the shapes of the
// primitives' extras added to the Scene.
ShapeReplacements add_analytic_shapes(const ExtrasInput& in) {
  ShapeReplacements replace;
  for (size_t mi = 0; mi < in.model.meshes.size() && mi < in.map.mesh_primitives.size(); ++mi) {
    const auto& prims = in.model.meshes[mi].primitives;
    if (in.map.mesh_primitives[mi].size() != prims.size()) continue;
    for (size_t j = 0; j < prims.size(); ++j) {
      const Value* ex = rayform_of(prims[j].extras);
      int k = in.map.mesh_primitives[mi][j];
      if (!ex || k < 0 || size_t(k) >= in.scene.meshes.size()) continue;
      const std::string where = "meshes[" + std::to_string(mi) + "].primitives[" + std::to_string(j) + "]";
      add_analytic_shape(in, *ex, k, where, replace);
    }
  }
  return replace;
}

// The shape nodes of replaced meshes point at their analytic shapes, and the
// tessellations no node uses any more are dropped.
void replace_tessellations(const ShapeReplacements& replace, Scene& scene) {
  for (Node& n : scene.nodes) {
    if (n.kind != Node::Kind::shape || n.shape_kind != ShapeKind::mesh) continue;
    auto it = replace.find(n.shape);
    if (it == replace.end()) continue;
    n.shape_kind = it->second.first;
    n.shape = it->second.second;
    n.name = n.shape_kind == ShapeKind::sphere ? "sphere" : n.shape_kind == ShapeKind::plane ? "plane" : "triangle";
  }
  std::vector<int> remap(scene.meshes.size(), invalid);
  std::vector<Mesh> kept;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    if (replace.count(int(i))) continue;
    remap[i] = int(kept.size());
    kept.push_back(std::move(scene.meshes[i]));
  }
  scene.meshes = std::move(kept);
  for (Node& n : scene.nodes)
    if (n.kind == Node::Kind::shape && n.shape_kind == ShapeKind::mesh && n.shape >= 0 &&
        size_t(n.shape) < remap.size())
      n.shape = remap[size_t(n.shape)];
}

}  // namespace

void apply_gltf_rayform_extras(const tinygltf::Model& model, const GltfSceneMapping& map, Scene& scene,
                               std::vector<std::string>* warnings) {
  const ExtrasInput in{model, map, scene, warnings};
  apply_texture_extras(in);
  apply_background_extras(in);
  apply_material_extras(in);
  fold_untextured_copies(in);  // after the materials: it moves them
  apply_camera_extras(in);
  apply_light_extras(in);
  const ShapeReplacements replace = add_analytic_shapes(in);
  if (!replace.empty()) replace_tessellations(replace, scene);
}

}  // namespace rayform
