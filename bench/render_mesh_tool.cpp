// Renders the procedural bumpy torus end to end, for peak-memory measurements
// (run it under /usr/bin/time -v): builds the mesh, prepares the scene (BVH)
// and renders one image, printing the time of each step and the memory of the
// acceleration structure.
//
// usage: rayform_render_mesh_tool [TRIANGLES=10000000] [WIDTH=1920] [HEIGHT=1080] [THREADS=0]
#include "bench_scene.h"

#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>

using namespace rayform;

namespace {
double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
}  // namespace

int main(int argc, char** argv) {
  try {
    size_t triangles = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 10'000'000;
    int width = argc > 2 ? std::atoi(argv[2]) : 1920;
    int height = argc > 3 ? std::atoi(argv[3]) : 1080;
    int threads = argc > 4 ? std::atoi(argv[4]) : 0;

    double t0 = now();
    Scene scene = bench::make_mesh_scene(make_bumpy_torus(triangles, 1));
    const Mesh& m = scene.meshes[0];
    double t1 = now();
    PreparedScene p = prepare_scene(scene);
    double t2 = now();
    RenderOptions o;
    o.width = width;
    o.height = height;
    o.threads = threads;
    RenderResult r = render(p, o);
    double t3 = now();

    double sum = 0.;
    for (float v : r.color.pixels) sum += v;
    size_t mesh_bytes =
        m.positions.size() * sizeof(vec3) + m.normals.size() * sizeof(vec3) + m.indices.size() * sizeof(uint32_t);
    std::printf("triangles        %zu\n", m.triangle_count());
    std::printf("mesh             %.1f MB\n", double(mesh_bytes) / 1048576.);
    std::printf("accel            %.1f MB (%.1f bytes/triangle)\n", double(p.memory_bytes()) / 1048576.,
                double(p.memory_bytes()) / double(m.triangle_count()));
    std::printf("make mesh        %.3f s\n", t1 - t0);
    std::printf("prepare (build)  %.3f s\n", t2 - t1);
    std::printf("render %dx%d   %.3f s (%.2f Mrays/s)\n", width, height, t3 - t2,
                double(width) * height / (t3 - t2) * 1e-6);
    std::printf("image checksum   %.6g\n", sum);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_mesh_tool: %s\n", e.what());
    return 1;
  }
}
