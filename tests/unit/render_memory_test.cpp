// render_memory.h: the bytes an image needs, per output, and the one-line
// refusal of a size that does not fit (also through render()).
#include "rayform/render/render_memory.h"
#include "rayform/base/error.h"

#include <gtest/gtest.h>

namespace rayform {
namespace {

TEST(RenderMemory, BytesPerOutput) {
  RenderOptions o;
  o.width = 100;
  o.height = 10;
  EXPECT_EQ(render_memory_bytes(o), 1000u * 24u);  // float colour: buffer + file
  o.color_format = ColorFormat::srgb8;
  EXPECT_EQ(render_memory_bytes(o), 1000u * 6u);
  o.depth = true;
  EXPECT_EQ(render_memory_bytes(o), 1000u * (6u + 19u));
  o.normals = true;
  o.albedo = true;
  EXPECT_EQ(render_memory_bytes(o), 1000u * (6u + 19u + 27u + 6u));
  o.width = o.height = 100000;
  EXPECT_EQ(render_memory_bytes(o), 10000000000ull * 58u);
}

TEST(RenderMemory, TooLargeIsOneLineNamingTheSize) {
  RenderOptions o;
  o.width = o.height = 100000;
  o.color_format = ColorFormat::unit8;
  EXPECT_EQ(render_memory_problem(o, 21'000'000'000ull),
            "size: a 100000x100000 image needs 60 GB for its buffers and files, more than the 21 GB of memory "
            "available");
  EXPECT_EQ(render_memory_problem(o, 61'000'000'000ull), "");
  EXPECT_EQ(render_memory_problem(o, 0), "");  // unknown: not refused
  o.width = o.height = 200;
  EXPECT_EQ(render_memory_problem(o, 1'000'000), "");
  EXPECT_GT(available_memory_bytes(), 0u);  // Linux: read from /proc/meminfo
}

TEST(RenderMemory, RenderRefusesBeforeAllocating) {
  Scene s;
  s.cameras.push_back(Camera{});
  const PreparedScene p = prepare_scene(s);
  RenderOptions o;
  o.width = o.height = 2'000'000'000;  // 4e18 pixels: more than any machine
  try {
    render(p, o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("render: size: a 2000000000x2000000000 image needs"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rayform
