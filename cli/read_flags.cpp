#include "read_flags.h"

#include "course_args.h"
#include "messages.h"

#include "rayform/base/memory_budget.h"

namespace rayform::cli {

namespace {
const char* quiet_help = "Print nothing but errors on stderr (no progress, notes or warnings)";
}

void add_quiet_before_command(CLI::App& app) {
  const std::string help = std::string(quiet_help) + "; before the subcommand as after it";
  app.add_flag("-q,--quiet", help);
}

void add_read_flags(CLI::App& command, ReadFlags& flags) {
  const Limits defaults;
  command.add_option(
      "--limit", flags.limits,
      "NAME=VALUE: raise or lower a limit on what a scene may claim (" + limit_names() +
          "; defaults: triangles and vertices " + std::to_string(defaults.triangles) + ", instances " +
          std::to_string(defaults.instances) + ", texture-texels " + std::to_string(defaults.texture_texels) +
          " (each side at most its square root), json-depth " + std::to_string(defaults.json_depth) + ", memory " +
          memory_size_text(defaults.memory) +
          " (bytes the job may hold at once: 1/16 of this machine's memory, growing by 16 bytes a byte of "
          "the files read up to 1/2; a value given here does not grow))");
  command.add_flag("--confine", flags.confine,
                   "Read only files in the scene file's folder and below (no absolute paths, '..', symlinks "
                   "out or URIs other than data:)");
  command.add_flag("-q,--quiet", flags.quiet, quiet_help);
  if (const CLI::App* program = command.get_parent())
    flags.quiet_before_command = program->get_option_no_throw("--quiet");
}

bool quiet_requested(const ReadFlags& flags) {
  return flags.quiet || (flags.quiet_before_command && flags.quiet_before_command->count() > 0);
}

void apply_read_flags(const ReadFlags& flags, LoadOptions& options) {
  for (const std::string& l : flags.limits) {
    const size_t eq = l.find('=');
    if (eq == std::string::npos) throw UsageError("--limit expects NAME=VALUE, got '" + l + "'");
    if (std::string problem = set_limit(options.limits, l.substr(0, eq), l.substr(eq + 1)); !problem.empty())
      throw UsageError("--" + problem);
  }
  // The default grows with the files read (memory_budget.h); a --limit memory does not.
  bool memory_set = false;
  for (const std::string& l : flags.limits) memory_set |= l.rfind("memory=", 0) == 0;
  job_memory().set_limit(options.limits.memory, !memory_set);
  options.access.confine = flags.confine;
  set_quiet(quiet_requested(flags));
}

}  // namespace rayform::cli
