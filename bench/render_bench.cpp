// Whole renders through the public pipeline (prepare_scene + render): the
// course scene scene06_bunny_1k at 200x200 and the 1M-triangle bumpy torus at
// 1920x1080, with one thread and with two (the scaling goal: 2 threads
// at least 1.8x faster than 1; scripts/bench reports the ratio).
// Wall-clock time per render (prepare excluded, reported as prepare_ms).
// Counters: ours = ms per render, Mrays_per_s = camera rays per second.
#include "bench_main.h"
#include "bench_meshes.h"
#include "bench_scene.h"

#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/importers/scene_io.h"

#include <filesystem>
#include <optional>

using namespace rayform;
using namespace rayform::bench;

namespace {

struct RenderCase {
  std::string name;
  int width, height;
};

// A course scene, under RAYFORM_SHARED.
std::string course_scene_path(const std::string& name) { return shared_dir() + "/course/2012/" + name + ".txt"; }

// The scene of a case, loaded once; nullptr when its data is missing.
const Scene* case_scene(const std::string& name) {
  static std::map<std::string, std::optional<Scene>> cache;
  auto [it, inserted] = cache.try_emplace(name);
  std::optional<Scene>& s = it->second;
  if (inserted) {
    if (name == "torus1M") {
      s = make_mesh_scene(make_bumpy_torus(1'000'000, 1));
    } else {
      std::string path = course_scene_path(name);
      if (std::filesystem::exists(path)) s = load_scene(path).scene;
    }
  }
  return s ? &*s : nullptr;
}

void bm_render(benchmark::State& state, RenderCase c, int threads) {
  const Scene* scene = case_scene(c.name);
  if (!scene) {
    std::string msg = "skipped: " + course_scene_path(c.name) + " not found (set RAYFORM_SHARED)";
    state.SkipWithError(msg.c_str());
    return;
  }
  double t0 = wall_seconds();
  PreparedScene p = prepare_scene(*scene);
  double prepare_s = wall_seconds() - t0;
  RenderOptions o;
  o.width = c.width;
  o.height = c.height;
  o.threads = threads;
  double total = 0.;
  for (auto _ : state) {
    double s = wall_seconds();
    RenderResult r = render(p, o);
    double e = wall_seconds();
    benchmark::DoNotOptimize(r.color.pixels.data());
    total += e - s;
    state.SetIterationTime(e - s);
  }
  double it = double(state.iterations());
  state.counters["ours"] = 1e3 * total / it;
  state.counters["Mrays_per_s"] = double(c.width) * c.height * it / total * 1e-6;
  state.counters["prepare_ms"] = 1e3 * prepare_s;
  state.SetLabel("ms");
}

}  // namespace

int main(int argc, char** argv) {
  for (const RenderCase& c : {RenderCase{"scene06_bunny_1k", 200, 200}, RenderCase{"torus1M", 1920, 1080}})
    for (int threads : {1, 2})
      register_manual_ms("render/" + c.name + "/" + std::to_string(c.width) + "x" + std::to_string(c.height) +
                             "/threads:" + std::to_string(threads),
                         bm_render, c, threads);
  return run_benchmarks(argc, argv);
}
