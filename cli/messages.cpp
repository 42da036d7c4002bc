#include "messages.h"

#include <iostream>

namespace rayform::cli {
namespace {
bool quiet_ = false;

void say(const char* kind, const std::string& message) {
  if (!quiet_) std::cerr << kind << message << "\n";
}
}  // namespace

void set_quiet(bool quiet) { quiet_ = quiet; }
bool quiet() { return quiet_; }

void warn(const std::string& message) { say("warning: ", message); }
void note(const std::string& message) { say("note: ", message); }

}  // namespace rayform::cli
