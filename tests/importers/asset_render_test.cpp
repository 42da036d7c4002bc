// Real assets through the one shader, by the library API: the duck exported
// as OBJ (+MTL) and as glTF, with the same camera AND the same light, one
// key light set here in place of the light rig each file would get (see
// tests/scripts/asset_duck_obj_vs_gltf.sh for the CLI's pictures).
#include "rayform/image/color.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/importers/scene_io.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rayform {
namespace {

// 8-bit sRGB code of a linear value, as the CLI writes asset pictures.
int srgb8(float v) { return int(std::floor(linear_to_srgb(std::clamp(v, 0.f, 1.f)) * 255.f)); }

// Share (percent) of pixels where any channel's 8-bit sRGB codes differ by more than `codes`.
double percent_over(const Image& a, const Image& b, int codes) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  size_t n = a.pixels.size() / 3, over = 0;
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      if (std::abs(srgb8(a.pixels[3 * i + c]) - srgb8(b.pixels[3 * i + c])) > codes) {
        ++over;
        break;
      }
  return 100.0 * double(over) / double(n);
}

RenderResult render_duck(const std::string& file) {
  LoadedScene l = load_scene((test::shared_dir() / "assets" / "duck" / file).string());
  Scene& s = l.scene;
  Camera c;
  c.projection = Camera::Projection::perspective;
  c.aspect = Camera::Aspect::fit;
  c.center = vec3(2.5f, 2.2f, -2.8f);
  c.direction = vec3(0.1f, 0.8f, 0.f) - c.center;
  c.up = vec3(0.f, 1.f, 0.f);
  c.fov_deg = 40.f;
  s.cameras = {c};
  Light key;  // from above the camera's right shoulder
  key.kind = Light::Kind::directional;
  key.direction = glm::normalize(vec3(-0.4f, -1.f, 0.6f));
  key.color = vec3(0.9f);
  s.lights = {key};
  s.background.ambient = vec3(0.1f);
  PreparedScene p = prepare_scene(s);
  RenderOptions o;
  o.width = o.height = 200;
  o.depth = o.normals = o.albedo = true;
  return render(p, o);
}

// The OBJ's materials are the course's Phong model (Kd/Ks/Ns) and the glTF's
// the metallic-roughness model, so only geometry and albedo must agree; both
// ducks must be lit.
TEST(AssetRender, DuckObjAndGltfAgreeInGeometryAndAlbedo) {
  RAYFORM_REQUIRE_SHARED();
  RenderResult obj = render_duck("duck.obj"), gltf = render_duck("duck.gltf");
  ASSERT_EQ(obj.depth.size(), gltf.depth.size());
  size_t hits = 0, depth_over = 0, normal_over = 0;
  for (size_t i = 0; i < obj.depth.size(); ++i) {
    bool ho = std::isfinite(obj.depth[i]), hg = std::isfinite(gltf.depth[i]);
    if (ho != hg) {
      ++depth_over;
      ++normal_over;
      continue;
    }
    if (!ho) continue;
    ++hits;
    if (std::abs(obj.depth[i] - gltf.depth[i]) > 1e-3f) ++depth_over;
    if (glm::dot(obj.normals[i], gltf.normals[i]) < 0.9999f) ++normal_over;
  }
  const double n = double(obj.depth.size());
  const double colour = percent_over(obj.color, gltf.color, 4), albedo = percent_over(obj.albedo, gltf.albedo, 4);
  std::printf(
      "duck obj vs gltf, 200x200, %zu duck pixels: colour %.3f%%, albedo %.3f%% over 4/255; "
      "depth %.3f%% over 1e-3; normals %.3f%% over 0.8 degrees\n",
      hits, colour, albedo, 100.0 * double(depth_over) / n, 100.0 * double(normal_over) / n);
  EXPECT_GT(hits, 5000u);                // the duck fills a good part of the picture
  double red_obj = 0.0, red_gltf = 0.0;  // and each is lit: a yellow duck, not a black one
  for (size_t i = 0; i < obj.depth.size(); ++i)
    if (std::isfinite(obj.depth[i])) {
      red_obj += obj.color.pixels[3 * i];
      red_gltf += gltf.color.pixels[3 * i];
    }
  EXPECT_GT(red_obj / double(hits), 0.3);
  EXPECT_GT(red_gltf / double(hits), 0.3);
  EXPECT_LE(albedo, 1.0);
  EXPECT_LE(100.0 * double(depth_over) / n, 1.0);
  EXPECT_LE(100.0 * double(normal_over) / n, 1.0);
}

}  // namespace
}  // namespace rayform
