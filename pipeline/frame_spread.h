// One frame rendered by several processes at once (the distributed layer,
// distributed/, implements this for the ranks of an MPI job): every process
// runs the same render job, shares the load's and prepare's large work
// through `work_share`, renders a share of the tiles, and one of them, the
// writer, writes the outputs. run_render_job calls these in this order, on
// every process, each call collective unless said otherwise.
#pragma once

#include "rayform/base/work_share.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"

#include <exception>
#include <string>

namespace rayform {

class FrameSpread {
 public:
  virtual ~FrameSpread() = default;

  // This process writes the outputs and reports the job's messages (not collective).
  virtual bool writer() const = 0;
  // The exchanges of a shared load (a large OBJ's parse) and of shared BVH
  // builds; every process makes each exchange (not collective itself).
  virtual const WorkShare& work_share() = 0;
  // After this process's load, whether it failed (`failure`) or not: checks
  // what must agree before shared work (the processes read the same file)
  // and returns the failure to go on with (this one's, or the disagreement).
  virtual std::exception_ptr after_load(std::exception_ptr failure) = 0;
  // Whether every process loaded the scene (`ok`: this one did); prepare's
  // shared BVH builds start only then. An implementation may answer `ok`
  // at once and check the others at prepare's first exchange (which then
  // throws) or in agree_ready, so that no process waits here.
  virtual bool all_loaded(bool ok) = 0;
  // After prepare: returns when every process has its scene ready, else
  // throws (this process's failure, or one naming the process that failed).
  virtual void agree_ready(std::exception_ptr failure) = 0;
  // Renders this process's share of the tiles; the writer's result holds
  // the whole frame.
  virtual RenderResult render(const PreparedScene& scene, const RenderOptions& options) = 0;
  // After the render, before the writer writes: the seconds this process
  // spent loading and preparing, for an implementation that reports each
  // process's stages (the command line's --stats).
  virtual void after_render(double load_s, double prepare_s) = 0;
};

}  // namespace rayform
