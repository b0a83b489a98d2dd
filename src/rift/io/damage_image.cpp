#include "rift/io/damage_image.hpp"

#include <cstdio>
#include <fstream>

#include "rift/io/plot_damage_script.hpp"  // generated from share/plot_damage.py
#include "rift/io/python_plot.hpp"

namespace rift::io {

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
  return run_python_script(plot_damage_script, {csv, png, title}, reason);
}

}  // namespace rift::io
