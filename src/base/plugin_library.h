// Finding and opening one of rayform's plugins: a shared library of ours that
// a program opens with dlopen only when a run needs it (librayform_oiio.so
// for OpenImageIO, librayform_mpi.so for MPI), so that runs which do not
// need the library behind it do not pay its start-up cost.
#pragma once

#include <string>

namespace rayform {

// Opens the plugin file `file_name` (e.g. "librayform_oiio.so") with
// RTLD_NOW | RTLD_LOCAL. When $`env_var` is set (a path to the file), there
// only; otherwise in turn: beside the executable, ../lib/rayform relative to it (the installed layout,
// <prefix>/bin and <prefix>/lib/rayform, which the build tree mirrors), then
// the install folder and the build's <build>/lib/rayform, both compiled in
// (for programs elsewhere that link the library). Returns dlopen's handle, or
// nullptr with the reason (dlerror's text, or every path looked at) in
// *failure. Not thread-safe: callers open a plugin once.
void* open_plugin(const char* file_name, const char* env_var, std::string* failure);

}  // namespace rayform
