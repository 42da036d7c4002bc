#include "rayform/render/prepared_scene.h"

#include "rayform/accel/duplicate_triangles.h"
#include "rayform/image/image.h"
#include "rayform/render/pbr_brdf.h"
#include "rayform/render/texture_decode_share.h"
#include "rayform/render/render_memory.h"
#include "rayform/scene/mesh_tangents.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <utility>

namespace rayform {
namespace {

// Meshes under this many triangles are built by one task each (below the
// mesh builder's threshold for parallel binning and partition), so several
// are built at once.
constexpr size_t small_mesh_triangles = size_t(1) << 15;

Bounds3 object_bounds(const Scene& scene, ShapeKind kind, int shape, const std::vector<MeshAccel>& meshes) {
  Bounds3 b;
  switch (kind) {
    case ShapeKind::sphere: {
      const Sphere& s = scene.spheres[shape];
      float r = std::abs(s.radius);
      b.expand(s.center - vec3(r));
      b.expand(s.center + vec3(r));
      break;
    }
    case ShapeKind::triangle:
      for (const vec3& v : scene.triangles[shape].vertices) b.expand(v);
      break;
    case ShapeKind::mesh: b = meshes[shape].bvh.bounds(); break;
    case ShapeKind::plane: break;
  }
  return b;
}

int shape_count(const Scene& s, ShapeKind k) {
  switch (k) {
    case ShapeKind::sphere: return int(s.spheres.size());
    case ShapeKind::plane: return int(s.planes.size());
    case ShapeKind::triangle: return int(s.triangles.size());
    case ShapeKind::mesh: return int(s.meshes.size());
  }
  return 0;
}

// The corner tangents (PreparedScene::corner_tangents) of the used meshes a
// normal texture is drawn on whose file gave no tangents.
void generate_tangents(PreparedScene& p) {
  const Scene& scene = *p.scene;
  p.corner_tangents.resize(scene.meshes.size());
  std::vector<int> tangent_uv_set(scene.meshes.size(), -1);
  auto needs_tangents = [&](int material) -> int {  // the uv set of its normal texture, or -1
    const Material& m = p.materials[size_t(material)];
    if (m.model != Material::Model::metallic_roughness) return -1;
    if (m.pbr.normal_texture.used()) return m.pbr.normal_texture.texcoord;
    if (m.pbr.clearcoat_normal_texture.used()) return m.pbr.clearcoat_normal_texture.texcoord;
    return -1;
  };
  for (const Instance& inst : p.instances) {
    if (inst.kind != ShapeKind::mesh) continue;
    const Mesh& m = scene.meshes[size_t(inst.shape)];
    if (!m.tangents.empty()) continue;
    int& set = tangent_uv_set[size_t(inst.shape)];
    if (set < 0) set = needs_tangents(inst.material);
    for (int fm : m.face_materials)
      if (set < 0 && fm >= 0 && fm < int(scene.materials.size())) set = needs_tangents(fm);
  }
  tbb::parallel_for(size_t(0), scene.meshes.size(), [&](size_t i) {
    if (tangent_uv_set[i] >= 0) p.corner_tangents[i] = corner_tangents(scene.meshes[i], tangent_uv_set[i]);
  });
}

// The six faces of a cube map are one picture's six sides: the same size.
void check_cube_map_faces(const PreparedScene& p) {
  const Scene& scene = *p.scene;
  for (size_t i = 1; i < p.cube_map.size(); ++i)
    if (p.cube_map[i].width != p.cube_map[0].width || p.cube_map[i].height != p.cube_map[0].height) {
      auto face = [&](size_t f) {
        return scene.textures[size_t(scene.background.cube_map[f])].path + " (" + std::to_string(p.cube_map[f].width) +
               "x" + std::to_string(p.cube_map[f].height) + ")";
      };
      throw Error(face(i) + ": cube map face of another size than " + face(0) +
                  ": the six faces must be the same size");
    }
}

// The Scene's environment, decoded with its sampling distribution and its
// noise-free approximations (features.environment), for scenes with
// metallic-roughness materials.
void prepare_environment(PreparedScene& p, const PrepareOptions& options) {
  const Scene& scene = *p.scene;
  SceneFeatures& f = p.features;
  const Environment& env = scene.background.environment;
  if (env.source == Environment::Source::none) return;
  f.environment = true;
  f.environment_shown = !scene.background.color_shown;
  const float rotation = radians(env.rotation_deg);
  if (env.source == Environment::Source::studio) {
    p.environment = studio_environment();
    p.environment.intensity = env.intensity;
    p.environment.rotation = rotation;
  } else {
    p.environment = environment_from_image(read_image(env.path, DecodeOptions{options.limits.texture_texels}),
                                           env.intensity, rotation);
  }
  p.environment_irradiance = environment_irradiance(p.environment);
  p.prefiltered_environment = prefilter_environment(p.environment);
}

// The node tree flattened into p.instances, each with its material (or the
// default one) and its transforms; returns which meshes they use.
std::vector<uint8_t> flatten_instances(const Scene& scene, const PrepareOptions& options, int default_material,
                                       PreparedScene& p) {
  std::vector<uint8_t> mesh_used(scene.meshes.size(), 0);
  for_each_shape_node(
      scene,
      [&](const Node& n, const mat4& to_world) {
        if (n.shape < 0 || n.shape >= shape_count(scene, n.shape_kind))
          throw Error("scene: node '" + n.name + "' references a missing shape");
        Instance inst;
        inst.kind = n.shape_kind;
        inst.shape = n.shape;
        inst.material = (n.material >= 0 && n.material < int(scene.materials.size())) ? n.material : default_material;
        inst.to_world = to_world;
        if (n.shape_kind == ShapeKind::mesh) mesh_used[n.shape] = 1;
        p.instances.push_back(inst);
      },
      options.limits.instances);
  // Each instance's inverse transforms, by parallel tasks.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, p.instances.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      Instance& inst = p.instances[i];
      inst.has_transform = !is_identity(inst.to_world);
      inst.to_object = glm::inverse(inst.to_world);
      inst.normal_to_world = glm::transpose(mat3(inst.to_object));
    }
  });
  return mesh_used;
}

// Each used mesh's BVH, built once however often it is instanced (or taken
// from the cache). Small meshes (whose builds are one task each) are built at
// once, large ones one after another, each by parallel tasks; under a
// WorkShare all in mesh order, each build a collective, the same on every part.
void build_used_meshes(const Scene& scene, const std::vector<uint8_t>& mesh_used, const PrepareOptions& options,
                       PreparedScene& p) {
  p.meshes.resize(scene.meshes.size());
  p.memory = charge_mesh_memory(scene, mesh_used);  // (render_memory.h)
  const WorkShare* share = options.share && options.share->shared() ? options.share : nullptr;
  MeshAccelCache* cache = share ? nullptr : options.cache;
  std::vector<size_t> to_build, small;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    if (!mesh_used[i]) continue;
    if (cache)
      if (std::optional<MeshAccel> kept = take_cached_mesh_accel(*cache, scene, i, options.bvh)) {
        p.meshes[i] = std::move(*kept);
        continue;
      }
    (!share && scene.meshes[i].triangle_count() < small_mesh_triangles ? small : to_build).push_back(i);
  }
  tbb::parallel_for(size_t(0), small.size(), [&](size_t j) {
    p.meshes[small[j]] = build_mesh_accel_without_duplicates(scene.meshes[small[j]], options.bvh, nullptr);
  });
  for (size_t i : to_build)
    p.meshes[i] = build_mesh_accel_without_duplicates(scene.meshes[i], options.bvh, options.share);
}

// The instances' world bounds and the top-level BVH over the bounded ones;
// planes stay outside it (p.plane_instances).
void build_top_level(const Scene& scene, const PrepareOptions& options, PreparedScene& p) {
  std::vector<Bounds3> bounds(p.instances.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, p.instances.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      Instance& inst = p.instances[i];
      if (inst.kind == ShapeKind::plane) continue;  // empty bounds: left out of the BVH
      Bounds3 ob = object_bounds(scene, inst.kind, inst.shape, p.meshes);
      inst.world_bounds = inst.has_transform ? transform_bounds(inst.to_world, ob) : ob;
      bounds[i] = inst.world_bounds;
    }
  });
  for (size_t i = 0; i < p.instances.size(); ++i) {
    if (p.instances[i].kind == ShapeKind::plane) p.plane_instances.push_back(uint32_t(i));
    else p.bounds.expand(bounds[i]);
  }
  BvhBuildOptions top_options = options.bvh;
  top_options.max_leaf_size = 1;
  p.top = build_bvh(bounds, top_options);
}

}  // namespace

size_t PreparedScene::memory_bytes() const {
  size_t bytes = instances.capacity() * sizeof(Instance) + top.memory_bytes();
  for (const MeshAccel& m : meshes) bytes += m.memory_bytes();
  for (const std::vector<vec4>& t : corner_tangents) bytes += t.capacity() * sizeof(vec4);
  auto map_bytes = [](const EnvironmentMap& m) {
    return (m.rgb.capacity() + m.texel_weight.capacity() + m.row_cdf.capacity() + m.column_cdf.capacity()) *
           sizeof(float);
  };
  bytes += map_bytes(environment);
  for (const EnvironmentMap& level : prefiltered_environment.levels) bytes += map_bytes(level);
  for (const TextureImage& t : textures) bytes += t.memory_bytes();
  for (const TextureImage& t : cube_map) bytes += t.memory_bytes();
  return bytes;
}

PreparedLight prepare_light(const Light& light) {
  PreparedLight p;
  p.light = light;
  if (light.kind == Light::Kind::directional) p.to_light = -glm::normalize(light.direction);
  if (light.kind == Light::Kind::spot) {
    p.axis = glm::normalize(light.direction);
    p.cos_outer = std::cos(radians(light.spot_outer_deg));
    p.cos_inner = std::cos(radians(light.spot_inner_deg));
  }
  return p;
}

PreparedScene prepare_scene(const Scene& scene, const PrepareOptions& options) {
  PreparedScene p;
  p.scene = &scene;
  p.materials = scene.materials;
  p.materials.push_back(Material{});  // default material, for shapes with none
  const int default_material = int(p.materials.size()) - 1;

  const std::vector<uint8_t> mesh_used = flatten_instances(scene, options, default_material, p);
  build_used_meshes(scene, mesh_used, options, p);
  build_top_level(scene, options, p);

  // Features, and decode only the textures that hit materials use.
  SceneFeatures& f = p.features;
  std::vector<uint8_t> material_used(p.materials.size(), 0);
  for (const Instance& inst : p.instances) {
    material_used[inst.material] = 1;
    if (inst.kind == ShapeKind::mesh) {
      const Mesh& m = scene.meshes[inst.shape];
      for (int fm : m.face_materials)
        if (fm >= 0 && fm < int(scene.materials.size())) material_used[fm] = 1;
      if (!m.colors.empty()) f.vertex_colors = true;
    }
    f.transforms |= inst.has_transform;
    f.planes |= inst.kind == ShapeKind::plane;
  }
  bool sheen = false;  // some used pbr material has a sheen
  p.textures.resize(scene.textures.size());
  std::vector<std::pair<int, TextureImage*>> to_decode;  // scene texture handle, destination
  std::vector<uint8_t> queued(scene.textures.size(), 0);
  for (size_t i = 0; i < p.materials.size(); ++i) {
    if (!material_used[i]) continue;
    Material& m = p.materials[i];
    if (m.model == Material::Model::metallic_roughness) {
      // What the integrator's common tests read, from the pbr fields: the
      // cut-out threshold of MASK, and no culling of a transmissive
      // surface's back faces (rays inside a volume leave through them).
      // A blended texel of alpha 0 adds nothing and lets everything through:
      // it is skipped as a hole (alpha below the smallest positive float),
      // so that the albedo and depth outputs show what lies behind it.
      m.alpha_cutoff = m.pbr.alpha_mode == PbrMaterial::AlphaMode::mask    ? m.pbr.alpha_cutoff
                       : m.pbr.alpha_mode == PbrMaterial::AlphaMode::blend ? std::numeric_limits<float>::denorm_min()
                                                                           : -1.f;
      if (m.pbr.transmission > 0.f || m.pbr.transmission_texture.used()) m.double_sided = true;
    }
    if (m.specular != vec3(0.f)) f.specular = true;
    f.emission |= m.model == Material::Model::metallic_roughness ? m.pbr.emissive * m.pbr.emissive_strength != vec3(0.f)
                                                                 : m.emission != vec3(0.f);
    if (m.alpha_cutoff >= 0.f) f.alpha_cutout = true;
    if (!m.double_sided) f.single_sided = true;
    if (m.noise.enabled) f.noise = true;
    if (!m.back_faces_cast_shadows) f.back_face_shadow_gaps = true;
    auto use_texture = [&](int t) {
      if (t < 0 || t >= int(scene.textures.size())) return;
      f.textures = true;
      if (!queued[t]) {
        queued[t] = 1;
        to_decode.push_back({t, &p.textures[t]});
      }
    };
    if (m.model == Material::Model::metallic_roughness) {
      const PbrMaterial& pm = m.pbr;
      f.pbr = true;
      f.specular = true;  // reflection rays
      if (pm.alpha_mode != PbrMaterial::AlphaMode::opaque) f.alpha_cutout = true;
      f.blend |= pm.alpha_mode == PbrMaterial::AlphaMode::blend;
      f.transmission |= pm.transmission > 0.f || pm.transmission_texture.used();
      sheen |= pm.sheen_color != vec3(0.f);
      for (const TextureSlot* slot : pbr_texture_slots(pm)) use_texture(slot->texture);
    } else {
      use_texture(m.diffuse_texture);
    }
  }
  generate_tangents(p);
  if (f.pbr) prepare_environment(p, options);
  if (f.pbr) {  // the BRDF's tables, made once before the render's threads need them
    ggx_split_sum(1.f, 1.f);
    if (sheen) sheen_directional_albedo(1.f, 1.f);
  }
  for (const Light& l : scene.lights) {
    p.lights.push_back(prepare_light(l));
    if (l.kind != Light::Kind::directional) f.point_lights = true;
    if (l.kind != Light::Kind::directional && l.falloff > 0.f) f.falloff = true;
  }
  if (scene.background.cube_map[0] != invalid) {
    f.cube_map = true;
    p.cube_map.resize(scene.background.cube_map.size());
    for (size_t i = 0; i < p.cube_map.size(); ++i) {
      const int face = scene.background.cube_map[i];
      if (face < 0 || face >= int(scene.textures.size())) throw Error("scene: cube map face texture missing");
      to_decode.push_back({face, &p.cube_map[i]});
    }
  }
  // The used textures and cube-map faces, shared among the parts of a shared prepare.
  decode_textures(scene, to_decode, DecodeOptions{options.limits.texture_texels}, options.share);
  check_cube_map_faces(p);
  return p;
}

}  // namespace rayform
