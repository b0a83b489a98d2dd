#include "rift/io/python_plot.hpp"

#include <unistd.h>

#include <cstdio>
#include <sstream>

namespace rift::io {

namespace {
std::string python() {
  // Debian's interpreter carries python3-matplotlib; a python3 earlier on PATH may not.
  if (access("/usr/bin/python3", X_OK) == 0) return "/usr/bin/python3";
  return "python3";
}
// (streams, not string concatenation: GCC 12 warns falsely on the latter with -Wrestrict)
void quote(std::ostringstream& out, const std::string& s) {
  out << '\'';
  for (char c : s) {
    if (c == '\'') out << "'\\''";
    else out << c;
  }
  out << '\'';
}
}  // namespace

bool run_python_script(const char* script, const std::vector<std::string>& args, std::string& reason) {
  std::ostringstream cmd;
  cmd << python() << " -";
  for (const auto& a : args) {
    cmd << ' ';
    quote(cmd, a);
  }
  cmd << " >/dev/null 2>&1";
  std::FILE* p = popen(cmd.str().c_str(), "w");
  if (!p) {
    reason = "cannot start python3";
    return false;
  }
  std::fputs(script, p);
  if (pclose(p) != 0) {
    reason = "python3 with matplotlib failed (install python3-matplotlib)";
    return false;
  }
  return true;
}

}  // namespace rift::io
