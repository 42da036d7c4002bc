// Rendering a scene with the rayform library, the way a program embedding it
// would: load (any supported format, by extension) -> prepare -> render ->
// write. Build target: rayform_example_render; tests/package builds it as
// another project would, linking rayform::importers (README, "Library use").
//
//   usage: rayform_example_render SCENE OUTPUT [WIDTH HEIGHT]
//   e.g.   rayform_example_render scenes/default.txt default.png 640 480
//
// Course scenes are written raw, as the course does; asset formats (OBJ,
// glTF) carry linear colour, encoded as sRGB for display.
#include <rayform/image/color.h>
#include <rayform/image/image.h>
#include <rayform/render/prepared_scene.h>
#include <rayform/render/render.h>
#include <rayform/scene/error.h>
#include <rayform/importers/scene_io.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  if (argc != 3 && argc != 5) {
    std::cerr << "usage: " << argv[0] << " SCENE OUTPUT [WIDTH HEIGHT]\n";
    return 2;
  }
  const std::string scene_path = argv[1], output = argv[2];
  rayform::RenderOptions options;
  options.width = argc == 5 ? std::atoi(argv[3]) : 640;
  options.height = argc == 5 ? std::atoi(argv[4]) : 480;

  try {
    // 1. Read the file into the plain-data Scene (throws rayform::Error with
    //    file:line:column on a bad file).
    rayform::LoadedScene loaded = rayform::load_scene(scene_path);
    for (const std::string& w : loaded.warnings) std::cerr << "warning: " << w << "\n";
    if (loaded.scene.cameras.empty()) throw rayform::Error(scene_path + ": the scene has no camera");

    // 2. Flatten the node tree, build the BVHs, decode the used textures.
    //    The prepared scene refers to loaded.scene, which must outlive it.
    rayform::PreparedScene prepared = rayform::prepare_scene(loaded.scene);

    // 3. Trace one ray per pixel, in parallel tiles.
    rayform::RenderResult result = rayform::render(prepared, options);

    // 4. Write the colour picture; the format follows the extension.
    rayform::Image image = std::move(result.color);
    if (loaded.format != rayform::SceneFormat::course_txt)
      for (float& v : image.pixels) v = rayform::linear_to_srgb(std::max(0.f, v));
    rayform::write_image(output, image);
    std::cout << "wrote " << output << " (" << image.width << "x" << image.height << ")\n";
  } catch (const rayform::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
