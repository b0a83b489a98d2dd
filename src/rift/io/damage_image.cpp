#include "rift/io/damage_image.hpp"

#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "rift/io/plot_damage_script.hpp"  // generated from share/plot_damage.py

namespace rift::io {

namespace {
std::string python() {
  // Debian's interpreter carries python3-matplotlib; a python3 earlier on PATH may not.
  if (access("/usr/bin/python3", X_OK) == 0) return "/usr/bin/python3";
  return "python3";
}
std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

bool write_damage_image(const std::string& directory, const std::string& png, const std::vector<double>& x,
                        const std::vector<double>& y, const std::vector<double>& damage, const std::string& title,
                        std::string& reason) {
  const std::string csv = directory + "/final_damage.csv";
  {
    std::ofstream out(csv);
    out << "x,y,damage\n";
    char line[96];
    for (std::size_t i = 0; i < x.size(); ++i) {
      std::snprintf(line, sizeof line, "%.9g,%.9g,%.6g\n", x[i], y[i], damage[i]);
      out << line;
    }
  }
  const std::string cmd = python() + " - " + quote(csv) + " " + quote(png) + " " + quote(title) + " 2>&1";
  std::FILE* p = popen(cmd.c_str(), "w");
  if (!p) {
    reason = "cannot start python3";
    return false;
  }
  std::fputs(plot_damage_script, p);
  int status = pclose(p);
  if (status != 0) {
    reason = "python3 with matplotlib failed (install python3-matplotlib)";
    return false;
  }
  return true;
}

}  // namespace rift::io
