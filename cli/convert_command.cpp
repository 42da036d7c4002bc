#include "commands.h"

namespace rayform::cli {

// `rayform convert` arrives with the writers (issue: format conversion).
void add_convert_command(CLI::App&) {}

}  // namespace rayform::cli
