// The render-ready form of a Scene: the node tree flattened into instances
// (shape + object-to-world matrix + material), a BVH per used mesh and one over
// the bounded instances, decoded textures (only those used), and the features
// the scene needs so the render loop can skip the rest.
#pragma once

#include "rayform/accel/bvh.h"
#include "rayform/accel/mesh_accel.h"
#include "rayform/render/environment_filter.h"
#include "rayform/render/environment_map.h"
#include "rayform/render/mesh_accel_cache.h"
#include "rayform/render/texture_sampler.h"
#include "rayform/base/limits.h"
#include "rayform/scene/node_walk.h"
#include "rayform/scene/scene.h"

#include <cstdint>
#include <vector>

namespace rayform {

struct Instance {
  ShapeKind kind = ShapeKind::mesh;
  int shape = invalid;         // index into the Scene's array of this kind
  int material = invalid;      // index into PreparedScene::materials
  bool has_transform = false;  // false: object space is world space
  mat4 to_world{1.f};
  mat4 to_object{1.f};
  mat3 normal_to_world{1.f};  // inverse transpose of to_world's linear part
  Bounds3 world_bounds;
};

// What a scene uses. The render loop chooses its compiled path from
// textures, specular and the skipped hits (alpha_cutout, single_sided),
// samples the background from cube_map, computes hit points for noise and
// traces closest-hit shadow rays for back_face_shadow_gaps. The renderer does not read the other
// flags (its per-light and per-instance branches test the data itself);
// prepare records them and tests/unit/prepare_test.cpp checks them.
struct SceneFeatures {
  bool textures = false;      // some hit material samples a texture
  bool specular = false;      // some material has a non-zero specular colour
  bool point_lights = false;  // point or spot lights
  bool transforms = false;    // some instance has a non-identity transform
  bool planes = false;        // unbounded planes, tested outside the BVH
  bool cube_map = false;      // background from a cube map
  bool alpha_cutout = false;  // some material has an alpha cut-out
  bool single_sided = false;  // some material is single-sided (back faces culled)
  bool vertex_colors = false;
  bool falloff = false;  // some point light attenuates with distance
  bool noise = false;    // some material's diffuse colour is solid noise (needs the hit point)
  // Some material's back faces cast no shadow (Material::back_faces_cast_shadows):
  // shadow rays then ask for the closest hit.
  bool back_face_shadow_gaps = false;
  // Some material is glTF's metallic-roughness model (Material::pbr): the
  // render takes the generic path, whose shading tests each hit's model.
  bool pbr = false;
  bool blend = false;         // some pbr material blends (alpha mode BLEND): shadows then pass it in part
  bool transmission = false;  // some pbr material transmits light
  // An environment lights the pbr materials (PreparedScene::environment);
  // shown: camera rays that miss see it (no background colour asked for).
  bool environment = false;
  bool environment_shown = false;
  bool emission = false;  // some material emits light
};

// A light with what shading needs at every hit computed once.
struct PreparedLight {
  Light light;
  vec3 to_light{0.f, 0.f, 1.f};              // directional: -normalize(light.direction)
  vec3 axis{0.f, 0.f, -1.f};                 // spot: normalize(light.direction)
  float cos_outer = -1.f, cos_inner = -1.f;  // spot: cosines of the cone angles
};

PreparedLight prepare_light(const Light& light);

struct PrepareOptions {
  BvhBuildOptions bvh;
  Limits limits{};  // instances: checked before flattening; texture_texels: before decoding
  // When shared (the ranks of a frame spread over MPI ranks), the BVHs of
  // meshes of at least bvh.share_min_triangles are built shared among its
  // parts (build_mesh_accel), one after another in mesh order: every part
  // must prepare the same scene with the same options; then the textures
  // and cube-map faces are decoded shared too (texture_decode_share.h).
  const WorkShare* share = nullptr;
  // BVHs kept from the previous frame (render/mesh_accel_cache.h): a used
  // mesh the cache holds an equal mesh's BVH for takes it instead of a
  // build. Not used with a shared `share` (every part must make the same builds).
  MeshAccelCache* cache = nullptr;
};

struct PreparedScene {
  const Scene* scene = nullptr;
  std::vector<Instance> instances;
  std::vector<uint32_t> plane_instances;  // instances of planes (unbounded, outside `top`)
  Bvh top;                                // over the bounded instances
  std::vector<MeshAccel> meshes;          // per Scene mesh; empty if unused
  // Per Scene mesh: generated tangents, three per triangle (one per corner,
  // scene/mesh_tangents.h), for a used mesh that a normal texture needs them
  // for and whose file gave none; else empty.
  std::vector<std::vector<vec4>> corner_tangents;
  std::vector<TextureImage> textures;  // per Scene texture; empty image if unused
  std::vector<Material> materials;     // the Scene's, then one default material
  std::vector<TextureImage> cube_map;  // six faces, or empty
  EnvironmentMap environment;          // features.environment: the Scene's, with its sampling distribution
  // Its noise-free approximations (the deterministic first picture): the
  // irradiance's spherical harmonics and the map blurred by roughness.
  EnvironmentIrradiance environment_irradiance;
  PrefilteredEnvironment prefiltered_environment;
  std::vector<PreparedLight> lights;  // the Scene's, in order
  SceneFeatures features;
  Bounds3 bounds;       // of the bounded instances, world space
  MemoryCharge memory;  // the meshes and their BVHs, charged to job_memory() before the builds

  size_t memory_bytes() const;
};

// Throws rayform::Error when a used texture cannot be decoded.
PreparedScene prepare_scene(const Scene& scene, const PrepareOptions& options = {});

}  // namespace rayform
