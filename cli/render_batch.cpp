#include "render_batch.h"

#include "course_args.h"
#include "output_names.h"
#include "rayform/distributed/ranks.h"
#include "rayform/distributed/work_counter.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

namespace rayform::cli {
namespace fs = std::filesystem;

std::vector<RenderJob> batch_jobs(const RenderJob& job, const std::vector<std::string>& inputs,
                                  const Turntable& turntable) {
  if (inputs.size() > 1 && !has_placeholder(job.output, "stem"))
    throw UsageError("-o " + job.output + ": several inputs need {stem} in the output name, e.g. 'out/{stem}.png'");
  if (turntable.frames > 1 && !has_placeholder(job.output, "frame"))
    throw UsageError("-o " + job.output + ": --frames needs {frame} in the output name, e.g. 'spin_{frame}.png'");
  // Largest first: the longest renders start early and the short ones fill
  // the gaps at the end (a missing file counts as empty; it fails at once).
  std::vector<std::pair<uintmax_t, std::string>> sized;
  for (const std::string& in : inputs) {
    std::error_code ec;
    const uintmax_t size = fs::file_size(in, ec);
    sized.emplace_back(ec ? 0 : size, in);
  }
  std::stable_sort(sized.begin(), sized.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<RenderJob> jobs;
  std::map<std::string, std::string> written;  // output -> the input writing it
  const int frames = std::max(1, turntable.frames);
  for (const auto& sized_input : sized) {
    // A named reference, not a structured binding: clang 14 (the fuzz build's
    // compiler) does not let the lambda below capture a binding.
    const std::string& input = sized_input.second;
    for (int frame = 0; frame < frames; ++frame) {
      RenderJob j = job;
      j.input = input;
      auto expand = [&](std::string& path, const char* option) {
        if (path.empty()) return;
        path = expand_output_name(path, input, frame, option);
        auto [at, fresh] = written.emplace(path, input);
        if (!fresh)
          throw UsageError(std::string(option) + ": " + at->second + " and " + input + " would both write " + path);
      };
      expand(j.output, "-o");
      if (j.depth) expand(j.depth->file, "--depth");
      expand(j.normals, "--normals");
      expand(j.albedo, "--albedo");
      if (turntable.frames > 0) {
        Orbit o = job.orbit.value_or(Orbit{});
        o.azimuth_deg += float(frame) * turntable.sweep_deg / float(turntable.frames);
        j.orbit = o;
      }
      jobs.push_back(std::move(j));
    }
  }
  return jobs;
}

int run_render_batch(const std::vector<RenderJob>& jobs, bool turntable, const Reporting& reporting) {
  using clock = std::chrono::steady_clock;
  const distributed::Ranks& r = distributed::ranks();
  const auto start = clock::now();
  long long done = 0, failed = 0;
  double busy_s = 0.0;
  {
    distributed::WorkCounter counter;
    // The scene of this rank's last turntable frame: the next frame of the
    // same file starts from it instead of reading the file again.
    std::shared_ptr<const LoadedScene> last;
    std::shared_ptr<MeshAccelCache> last_accels;  // its meshes' BVHs, kept from frame to frame
    std::string last_input;
    for (long long i; (i = counter.next()) < (long long)jobs.size();) {
      RenderJob job = jobs[size_t(i)];
      const auto t = clock::now();
      try {
        if (job.orbit && turntable) {
          if (!last || last_input != job.input) {
            last_accels.reset();
            last.reset();  // one scene in memory at a time
            last = std::make_shared<const LoadedScene>(load_job_scene(job));
            last_accels = std::make_shared<MeshAccelCache>();
            last_accels->source = &last->scene;
            last_input = job.input;
          }
          job.preloaded = last;
          job.mesh_cache = last_accels;
        }
        run_job(job, reporting, false);
        ++done;
      } catch (const std::exception& e) {
        // One line naming the input (the readers' messages start with it),
        // written at once so that mpirun does not mix it with another rank's.
        const std::string what = e.what();
        std::cerr << "rayform: error: " + (what.rfind(job.input, 0) == 0 ? "" : job.input + ": ") + what + "\n"
                  << std::flush;
        ++failed;
      }
      busy_s += std::chrono::duration<double>(clock::now() - t).count();
    }
  }  // the counter's window is freed together, once every rank has taken its last number
  const long long failed_total = distributed::sum_over_ranks(failed);
  const double wall_s = std::chrono::duration<double>(clock::now() - start).count();
  if (reporting.stats) {
    std::ostringstream line;
    line << "stats: rank " << r.rank << " of " << r.size << ": " << done + failed << " renders (" << failed
         << " failed), busy " << busy_s << " s of " << wall_s << " s\n";
    for (const std::string& text : distributed::gather_text(line.str())) std::cerr << text;
  }
  if (failed_total > 0 && r.root())
    std::cerr << "rayform: " << failed_total << " of " << jobs.size() << " renders failed\n";
  return failed_total > 0 ? 1 : 0;
}

}  // namespace rayform::cli
