// rayform: the command-line program. A thin layer over src/ and importers/:
// the course's own flags verbatim, and subcommands built with CLI11.
#include "commands.h"
#include "messages.h"
#include "course_args.h"
#include "heap_reuse.h"
#include "rayform/distributed/ranks.h"
#include "read_flags.h"
#include "run_job.h"
#include "rayform/base/error.h"
#include "rayform/image/interrupt_cleanup.h"

#include <CLI/CLI.hpp>

#include <iostream>

#ifndef RAYFORM_VERSION
#define RAYFORM_VERSION "unknown"
#endif

namespace rayform::cli {
namespace {

const char* examples = R"(
Examples:
  Course command line (verbatim, single dash, any order):
    rayform -input scene01_plane.txt -size 200 200 -output 1.bmp -depth 8 12 d.bmp -normals n.bmp
    rayform -input scene06_bunny_1k.txt -size 200 200 -output b.png -dialect 2019
    rayform -input scene10_sphere.txt -size 200 200 -output s.png -dialect a5 -shadows -bounces 4
  Course flags: -input F -size W H -output IMG [-depth MIN MAX IMG] [-normals IMG]
    [-albedo IMG] [-dialect 2012|2019|a5] [-shadows] [-bounces N] [-jitter] [-filter]
    [-spp N] [-sampler stratified|random] [-target-error E] [-max-spp N]
    [-threads N] [-stats] [-generic] [-quiet]   (README.md explains each)
  Subcommands:
    rayform render scene.txt -o out.png --size 640x480 --depth 8:12:depth.png --normals normals.png
    rayform render duck.gltf -o duck.png --orbit 45,30      (camera around the model, which fits)
    rayform render duck.gltf -o duck.png --transparent --background '#336699'
    rayform render a.glb b.obj c.txt -o 'out/{stem}.png'   (a batch; status 1 if any file failed)
    rayform render duck.glb --frames 36 --orbit 0,20 -o 'spin/{frame}.png'   (a turntable)
    mpirun -np 4 rayform render scene.txt -o out.png   (one frame over MPI ranks; batches spread too)
    rayform info scene.txt
)";

// The exit status of every command (README.md, "Exit status").
const char* exit_status = R"(
Exit status:
  0  success
  1  an input or render error: a scene or file that cannot be read, an output that cannot be written
  2  a usage error: an unknown option, a missing or malformed value, options that do not combine
     (one line on stderr names the option; nothing is written)
)";

int run(int argc, char** argv) {
  // Ctrl-C: temporaries removed, a progress line ended, then this line.
  set_interrupt_message("rayform: interrupted");
  if (distributed::ranks().distributed())
    // mpirun ends the other ranks with SIGTERM when one fails or is killed.
    set_interrupt_message("rayform: rank " + std::to_string(distributed::ranks().rank) + " of " +
                          std::to_string(distributed::ranks().size) +
                          " stopped: the MPI job was ended (a rank failed, was killed or interrupted); no output "
                          "written");
  std::vector<std::string> args(argv + 1, argv + argc);
  if (is_course_command_line(args)) {
    const CourseCommand course = parse_course_command_line(args);
    run_job(course.job, course.reporting, true);
    return 0;
  }

  CLI::App app{"rayform " RAYFORM_VERSION ": a fast and accurate ray caster for course .txt, OBJ and glTF scenes"};
  app.set_version_flag("--version",
                       std::string("rayform " RAYFORM_VERSION) +
                           (distributed::built_with_mpi() ? " (MPI: mpirun spreads renders over ranks)" : ""));
  app.footer(std::string(examples) + exit_status);
  app.require_subcommand(1);
  add_quiet_before_command(app);

  add_render_command(app);
  add_info_command(app);
  add_convert_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    // `rayform --help` lists every subcommand's options; `rayform render --help` one's.
    if (app.get_subcommands().empty()) {
      std::cout << app.help("", CLI::AppFormatMode::All);
      return 0;
    }
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --version
    // CLI11's own exit codes (105-109) become the usage status 2.
    throw UsageError(e.what());
  }

  return 0;
}

}  // namespace
}  // namespace rayform::cli

int main(int argc, char** argv) {
  rayform::cli::keep_freed_heap_for_reuse();
  try {
    rayform::distributed::start_ranks();
    return rayform::cli::run(argc, argv);
  } catch (const rayform::UsageError& e) {
    // Every rank parses the same command line: one message is enough.
    if (rayform::distributed::ranks().root())
      std::cerr << "rayform: " + rayform::cli::terminal_text(e.what()) + "\n(run 'rayform --help' for usage)\n";
    return 2;
  } catch (const rayform::distributed::ReportedElsewhere&) {
    return 1;
  } catch (const rayform::Error& e) {
    std::cerr << "rayform: error: " + rayform::cli::terminal_text(e.what()) +
                     "\n";  // one write: ranks' lines stay whole
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "rayform: error: " + rayform::cli::terminal_text(e.what()) +
                     "\n";  // one write: ranks' lines stay whole
    return 1;
  }
}
