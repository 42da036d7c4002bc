// The physically based part of a Scene material, as glTF 2.0 means it: the
// metallic-roughness model of the core specification and the material
// extensions that layer on it. Plain data: what the file says, no
// approximation (those live in the shading code, render/shade_pbr.h, and in
// the writers of formats that cannot hold a field). Defaults are the
// specification's. Colours are linear RGB; factors multiply their textures.
#pragma once

#include "rayform/math/math.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace rayform {

// Affine transform of texture coordinates (glTF KHR_texture_transform), in
// the Scene's uv convention (v = 1 at the top of the picture).
struct UvTransform {
  vec2 offset{0.f};
  float rotation = 0.f;  // radians
  vec2 scale{1.f};
  bool is_identity() const { return offset == vec2(0.f) && rotation == 0.f && scale == vec2(1.f); }
  // uv' = T R S uv, R = rows (cos, sin), (-sin, cos) (KHR_texture_transform).
  vec2 apply(vec2 uv) const {
    float c = std::cos(rotation), s = std::sin(rotation);
    vec2 scaled = uv * scale;
    return vec2(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y) + offset;
  }
};

// A texture as one material field uses it: which Scene texture, which set of
// texture coordinates (0: Mesh::uvs, 1: Mesh::uvs1) and the transform applied
// to them. `texture` invalid (-1): the field has no texture.
struct TextureSlot {
  int texture = -1;
  int texcoord = 0;
  UvTransform transform;
  bool used() const { return texture >= 0; }
};

// glTF metallic-roughness with its extensions. Channels each texture is read
// from are the specification's (noted per field); colour textures (base
// colour, emissive, specular colour, sheen colour) are sRGB-encoded, the
// others linear.
struct PbrMaterial {
  // glTF alphaMode.
  enum class AlphaMode : uint8_t {
    opaque,  // alpha ignored
    mask,    // alpha < alpha_cutoff: a hole, else opaque
    blend,   // the surface covers the fraction alpha of what lies behind it
  };
  // pbrMetallicRoughness
  vec4 base_color{1.f};            // rgb and alpha (opacity)
  TextureSlot base_color_texture;  // RGBA, sRGB
  float metallic = 1.f, roughness = 1.f;
  TextureSlot metallic_roughness_texture;  // B: metallic, G: roughness
  // Core textures and factors
  TextureSlot normal_texture;     // tangent-space normal, RGB = (x, y, z) * 0.5 + 0.5
  float normal_scale = 1.f;       // scales the x and y of the texel's normal
  TextureSlot occlusion_texture;  // R
  float occlusion_strength = 1.f;
  vec3 emissive{0.f};
  TextureSlot emissive_texture;   // RGB, sRGB
  float emissive_strength = 1.f;  // KHR_materials_emissive_strength
  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;  // AlphaMode::mask
  // KHR_materials_ior (0 is allowed: a material that reflects as a mirror)
  float ior = 1.5f;
  // KHR_materials_specular: scales the dielectric Fresnel term
  float specular = 1.f;
  TextureSlot specular_texture;  // A
  vec3 specular_color{1.f};
  TextureSlot specular_color_texture;  // RGB, sRGB
  // KHR_materials_transmission: the fraction of the dielectric base that lets
  // light through (specular transmission, rough with `roughness`)
  float transmission = 0.f;
  TextureSlot transmission_texture;  // R
  // KHR_materials_volume: thickness 0 is a thin-walled surface; above 0 the
  // mesh bounds a volume that attenuates light by Beer-Lambert's law,
  // transmittance = attenuation_color ^ (distance / attenuation_distance)
  float thickness = 0.f;          // in the mesh's object space
  TextureSlot thickness_texture;  // G
  vec3 attenuation_color{1.f};
  float attenuation_distance = std::numeric_limits<float>::infinity();  // world units
  // KHR_materials_clearcoat: a dielectric (ior 1.5) coat over the base
  float clearcoat = 0.f;
  TextureSlot clearcoat_texture;  // R
  float clearcoat_roughness = 0.f;
  TextureSlot clearcoat_roughness_texture;  // G
  TextureSlot clearcoat_normal_texture;
  float clearcoat_normal_scale = 1.f;
  // KHR_materials_sheen
  vec3 sheen_color{0.f};
  TextureSlot sheen_color_texture;  // RGB, sRGB
  float sheen_roughness = 0.f;
  TextureSlot sheen_roughness_texture;  // A
};

// Every texture slot of a material, for code that treats them alike.
inline std::array<const TextureSlot*, 14> pbr_texture_slots(const PbrMaterial& m) {
  return {&m.base_color_texture,
          &m.metallic_roughness_texture,
          &m.normal_texture,
          &m.occlusion_texture,
          &m.emissive_texture,
          &m.specular_texture,
          &m.specular_color_texture,
          &m.transmission_texture,
          &m.thickness_texture,
          &m.clearcoat_texture,
          &m.clearcoat_roughness_texture,
          &m.clearcoat_normal_texture,
          &m.sheen_color_texture,
          &m.sheen_roughness_texture};
}

}  // namespace rayform
