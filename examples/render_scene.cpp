// Rendering any model with the rayform library, the way a program embedding
// it would. Build target: rayform_example_render; tests/package builds it as
// another project would, linking rayform::importers (README, "Library use").
//
//   usage: rayform_example_render SCENE OUTPUT [WIDTH HEIGHT]
//   e.g.   rayform_example_render duck.glb duck.png
//
// load_ready_scene reads any supported file (.txt course scene, .obj, .gltf,
// .glb) and gives a model without a camera or lights a camera that frames it
// and a light rig; the picture is 512x512 for OBJ and glTF, 200x200 for
// course scenes, unless WIDTH and HEIGHT are given. write_color_image picks
// the encoding from the scene and the file: sRGB in 8-bit files (png, jpg,
// ...), linear in float files (exr, hdr), course scenes as the course writes.
#include <rayform/pipeline/scene_ready.h>
#include <rayform/render/color_output.h>
#include <rayform/render/prepared_scene.h>
#include <rayform/render/render.h>
#include <rayform/base/error.h>

#include <cstdlib>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  if (argc != 3 && argc != 5) {
    std::cerr << "usage: " << argv[0] << " SCENE OUTPUT [WIDTH HEIGHT]\n";
    return 2;
  }
  try {
    rayform::ReadyScene scene = rayform::load_ready_scene(argv[1]);
    if (argc == 5) scene.render.width = std::atoi(argv[3]), scene.render.height = std::atoi(argv[4]);
    rayform::PreparedScene prepared = rayform::prepare_scene(scene.scene);  // refers to scene.scene
    rayform::RenderResult result = rayform::render(prepared, scene.render);
    rayform::write_color_image(argv[2], result, scene.color);

    for (const std::string& w : scene.warnings) std::cerr << "warning: " << w << "\n";
    for (const std::string& n : scene.notes) std::cerr << "note: " << n << "\n";
    std::cout << "wrote " << argv[2] << " (" << result.width << "x" << result.height << ")\n";
  } catch (const rayform::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
