// Traversal throughput, single thread: closest hit (intersect_mesh vs
// rtcIntersect1) and any hit (occluded_mesh vs rtcOccluded1) on the very same
// rays and triangles, in the same process. Each iteration traces the whole
// ray set with ours and then with Embree (interleaved, so that both see the
// same machine load); thread CPU time is measured for each.
//
// Counters: ours and embree in Mrays/s, ratio = ours / embree (> 1: we are
// faster), mismatches = rays on which the two disagree (checked before timing).
#include "bench_meshes.h"

#include <cstdio>

using namespace rayform;
using namespace rayform::bench;

namespace {

struct Fixture {
  const BenchMesh* mesh = nullptr;
  MeshAccel ours;
  EmbreeScene embree;
  std::map<std::string, std::vector<Ray>> rays;
  std::map<std::string, Agreement> agreement;
};

// One mesh's structures at a time (the 10M mesh is large): benchmarks run mesh by mesh.
Fixture* get_fixture(const std::string& name) {
  static std::unique_ptr<Fixture> current;
  if (current && current->mesh->name == name) return current.get();
  current.reset();
  const BenchMesh* m = get_mesh(name);
  if (!m) return nullptr;
  current = std::make_unique<Fixture>();
  current->mesh = m;
  current->ours = build_mesh_accel(m->vertex_span(), m->indices);
  current->embree = EmbreeScene(*m, RTC_BUILD_QUALITY_MEDIUM);
  return current.get();
}

void bm_traversal(benchmark::State& state, std::string mesh, std::string kind, bool closest) {
  Fixture* f = get_fixture(mesh);
  if (!f) {
    state.SkipWithError(mesh_unavailable(mesh).c_str());
    return;
  }
  auto rit = f->rays.find(kind);
  if (rit == f->rays.end()) rit = f->rays.emplace(kind, make_rays(*f->mesh, kind)).first;
  const std::vector<Ray>& rays = rit->second;
  // Verify before timing.
  auto ait = f->agreement.find(kind);
  if (ait == f->agreement.end())
    ait = f->agreement.emplace(kind, compare_with_embree(f->ours, f->embree.scene, rays)).first;
  const Agreement& a = ait->second;
  size_t mismatches = closest ? a.closest_mismatches : a.any_mismatches;
  if (mismatches * 1000 > rays.size()) {
    std::string msg = "ours and Embree disagree on " + std::to_string(mismatches) + " of " +
                      std::to_string(rays.size()) + " rays";
    state.SkipWithError(msg.c_str());
    return;
  }

  double ours_s = 0., embree_s = 0.;
  for (auto _ : state) {
    double t0 = thread_cpu_seconds();
    if (closest) benchmark::DoNotOptimize(ours_closest(f->ours, rays));
    else benchmark::DoNotOptimize(ours_any(f->ours, rays));
    double t1 = thread_cpu_seconds();
    if (closest) benchmark::DoNotOptimize(embree_closest(f->embree.scene, rays));
    else benchmark::DoNotOptimize(embree_any(f->embree.scene, rays));
    double t2 = thread_cpu_seconds();
    ours_s += t1 - t0;
    embree_s += t2 - t1;
    state.SetIterationTime(t1 - t0);
  }
  double n = double(rays.size()) * double(state.iterations());
  double ours = n / ours_s * 1e-6, emb = n / embree_s * 1e-6;
  state.counters["ours"] = ours;
  state.counters["embree"] = emb;
  state.counters["ratio"] = ours / emb;
  state.counters["mismatches"] = double(mismatches);
  state.counters["rays"] = double(rays.size());
  state.counters["hit_fraction"] = double(a.hits) / double(rays.size());
  state.counters["triangles"] = double(f->mesh->triangle_count());
  state.SetLabel("Mrays/s");
}

}  // namespace

int main(int argc, char** argv) {
  for (const std::string& mesh : mesh_names()) {
    std::string why = mesh_unavailable(mesh);
    if (!why.empty()) std::fprintf(stderr, "%s: %s\n", mesh.c_str(), why.c_str());
    for (const char* kind : {"camera", "random"})
      for (bool closest : {true, false}) {
        std::string name = std::string("traversal/") + (closest ? "closest/" : "any/") + kind + "/" + mesh;
        benchmark::RegisterBenchmark(name.c_str(), bm_traversal, mesh, std::string(kind), closest)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
      }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
