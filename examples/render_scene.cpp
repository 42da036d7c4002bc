// Rendering any model with the rayform library, the way a program embedding
// it would (README, "Library use"). Build target: rayform_example_render;
// tests/package builds it as another project would, linking rayform::pipeline.
//
//   usage: rayform_example_render SCENE OUTPUT [WIDTH HEIGHT]
//   e.g.   rayform_example_render duck.glb duck.png
//
// A render job (rayform/pipeline/render_job.h) reads any supported file, gives
// a model without camera or lights a framing camera and a light rig, renders
// it (512x512 for OBJ and glTF, 200x200 for course scenes, unless WIDTH and
// HEIGHT are given) and writes the picture in the encoding the scene and the
// file call for (sRGB in 8-bit files, linear in float files).
#include <rayform/pipeline/render_job.h>

#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  if (argc != 3 && argc != 5) {
    std::cerr << "usage: " << argv[0] << " SCENE OUTPUT [WIDTH HEIGHT]\n";
    return 2;
  }
  rayform::RenderJob job;
  job.input = argv[1];
  job.output = argv[2];
  if (argc == 5)
    job.default_size = false, job.render.width = std::atoi(argv[3]), job.render.height = std::atoi(argv[4]);
  rayform::JobHooks hooks;  // the library prints nothing: warnings and notes come here
  hooks.warn = [](const std::string& w) { std::cerr << "warning: " << w << "\n"; };
  hooks.note = [](const std::string& n) { std::cerr << "note: " << n << "\n"; };
  try {
    const rayform::JobReport report = rayform::run_render_job(job, hooks);
    std::cout << "wrote " << job.output << " (" << report.width << "x" << report.height << ")\n";
  } catch (const std::exception& e) {  // rayform::Error (a file), rayform::UsageError (the arguments)
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
