// Rendering an image in parts (render_tiles_from, render.h) and bringing the
// parts together (tile_pixels.h) gives render()'s image bit for bit: every
// buffer, whichever part renders which tile, in linear and 8-bit colour, with
// coverage, for the eight-ray packet path and the sampled path. This is what
// the MPI driver of the command line (distributed/distributed_frame.cpp) does across processes.
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/render/tile_pixels.h"
#include "rayform/base/error.h"
#include "rayform/scene/scene_defaults.h"
#include "rayform/importers/scene_io.h"
#include "test_paths.h"
#include "test_bytes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <mutex>

namespace rayform {
namespace {

using test::same_bytes;

void expect_identical(const RenderResult& a, const RenderResult& b, const std::string& what) {
  EXPECT_TRUE(same_bytes(a.color.pixels, b.color.pixels)) << what << ": colour";
  EXPECT_TRUE(same_bytes(a.color8.pixels, b.color8.pixels)) << what << ": 8-bit colour";
  EXPECT_TRUE(same_bytes(a.depth, b.depth)) << what << ": depth";
  EXPECT_TRUE(same_bytes(a.normals, b.normals)) << what << ": normals";
  EXPECT_TRUE(same_bytes(a.albedo.pixels, b.albedo.pixels)) << what << ": albedo";
  EXPECT_TRUE(same_bytes(a.albedo8.pixels, b.albedo8.pixels)) << what << ": 8-bit albedo";
  EXPECT_TRUE(same_bytes(a.coverage, b.coverage)) << what << ": coverage";
}

// Renders the image as `parts` processes would: one shared counter hands out
// the tiles, tile t going to part (t * 7 / 3) % parts (an uneven, interleaved
// split); each part keeps its tiles, packs them, and the bytes are unpacked
// into one result.
RenderResult render_in_parts(const PreparedScene& p, const RenderOptions& o, int parts) {
  const TileGrid grid = tile_grid(o);
  std::vector<RenderResult> results;
  std::vector<std::vector<int>> tiles(parts);
  for (int part = 0; part < parts; ++part) {
    results.push_back(allocate_render_result(p, o));
    std::mutex m;
    int next = 0;
    render_tiles_from(
        p, o,
        [&]() {
          std::lock_guard lock(m);
          while (next < grid.count() && (next * 7 / 3) % parts != part) ++next;
          if (next >= grid.count()) return -1;
          tiles[part].push_back(next);
          return next++;
        },
        results.back());
  }
  RenderResult whole = allocate_render_result(p, o);
  size_t handed = 0;
  for (int part = 0; part < parts; ++part) {
    std::vector<unsigned char> bytes = pack_tile_pixels(results[part], grid, tiles[part]);
    EXPECT_EQ(bytes.size(), tile_pixel_bytes(results[part], grid, tiles[part]));
    unpack_tile_pixels(whole, grid, tiles[part], bytes);
    handed += tiles[part].size();
  }
  EXPECT_EQ(handed, size_t(grid.count()));
  return whole;
}

Scene torus_scene() {
  LoadedScene l = load_scene((test::source_dir() / "scenes" / "assets" / "torus.obj").string());
  add_default_camera(l.scene);
  add_headlight(l.scene, 0);
  return l.scene;
}

TEST(TilePixels, PartsGiveTheWholeImage) {
  struct Case {
    const char* what;
    Scene scene;
    RenderOptions o;
  };
  LoadedScene textured = load_scene((test::source_dir() / "scenes" / "tests" / "textures_transformed.txt").string());
  std::vector<Case> cases;
  RenderOptions o;
  o.width = 61;  // not a multiple of the tile size: partial tiles at the right and bottom
  o.height = 47;
  o.depth = o.normals = o.albedo = true;
  cases.push_back({"torus, packets, linear", torus_scene(), o});
  o.color_format = ColorFormat::srgb8;
  o.alpha = AlphaMode::straight;
  cases.push_back({"torus, packets, sRGB 8-bit, coverage", torus_scene(), o});
  o.spp = 4;
  o.shadows = true;
  o.bounces = 3;
  o.tile_size = 7;
  o.alpha = AlphaMode::premultiplied;
  o.color_format = ColorFormat::linear_float;
  cases.push_back({"textured, spp 4, shadows, bounces 3, premultiplied", textured.scene, o});
  o.threads = 1;
  o.color_format = ColorFormat::unit8;
  o.depth = o.normals = false;
  cases.push_back({"textured, one thread, 8-bit, colour and albedo", textured.scene, o});
  for (const Case& c : cases) {
    PreparedScene p = prepare_scene(c.scene);
    const RenderResult reference = render(p, c.o);
    for (int parts : {1, 2, 3}) {
      const RenderResult whole = render_in_parts(p, c.o, parts);
      expect_identical(reference, whole, std::string(c.what) + ", " + std::to_string(parts) + " parts");
    }
  }
}

TEST(TilePixels, UnrenderedTilesKeepTheEmptyValues) {
  const Scene scene = torus_scene();  // outlives the prepared scene, which points to it
  PreparedScene p = prepare_scene(scene);
  RenderOptions o;
  o.width = o.height = 40;
  o.depth = true;
  RenderResult r = allocate_render_result(p, o);
  // Only tile 0 (pixels 0..15 of rows 0..15) is rendered.
  int handed = 0;
  render_tiles_from(
      p, o, [&] { return handed++ == 0 ? 0 : -1; }, r);
  const RenderResult reference = render(p, o);
  size_t inside = 0, outside_on_torus = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) {
      const size_t i = size_t(y) * 40 + size_t(x);
      if (x < 16 && y < 16) {  // tile 0: render()'s values
        EXPECT_EQ(r.depth[i], reference.depth[i]);
        EXPECT_EQ(r.color.pixels[i * 3 + 1], reference.color.pixels[i * 3 + 1]);
        inside += std::isfinite(r.depth[i]);
      } else if (std::isfinite(reference.depth[i])) {  // elsewhere on the torus: nothing rendered
        ++outside_on_torus;
        EXPECT_EQ(r.depth[i], infinity);
        EXPECT_EQ(r.color.pixels[i * 3 + 1], 0.f);
      }
    }
  EXPECT_GT(inside, 0u);  // tile 0 shows part of the torus
  EXPECT_GT(outside_on_torus, 100u);
}

TEST(TilePixels, RefusesBytesOrTilesThatDoNotFit) {
  const Scene scene = torus_scene();  // outlives the prepared scene, which points to it
  PreparedScene p = prepare_scene(scene);
  RenderOptions o;
  o.width = o.height = 40;  // 3 x 3 tiles of 16
  o.normals = true;
  RenderResult r = render(p, o);
  const TileGrid grid = tile_grid(o);
  EXPECT_EQ(grid.count(), 9);
  const std::vector<int> tiles{0, 8};
  // 16 x 16 + 8 x 8 pixels of colour and normals, 24 bytes each.
  EXPECT_EQ(tile_pixel_bytes(r, grid, tiles), size_t(16 * 16 + 8 * 8) * 24);
  std::vector<unsigned char> bytes = pack_tile_pixels(r, grid, tiles);
  bytes.pop_back();
  EXPECT_THROW(unpack_tile_pixels(r, grid, tiles, bytes), Error);
  EXPECT_THROW(pack_tile_pixels(r, grid, std::vector<int>{9}), Error);
  EXPECT_THROW(render_tiles_from(
                   p, o, [n = 0]() mutable { return n++ == 0 ? 9 : -1; }, r),
               Error);
}

}  // namespace
}  // namespace rayform
