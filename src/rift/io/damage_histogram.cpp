#include "rift/io/damage_histogram.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "rift/io/plot_damage_histogram_script.hpp"  // generated from share/plot_damage_histogram.py
#include "rift/io/python_plot.hpp"

namespace rift::io {

std::array<std::int64_t, 10> damage_histogram(const std::vector<double>& damage) {
  std::array<std::int64_t, 10> counts{};
  for (double d : damage) {
    // scaled by 10 and rounded down; 1.0 (and any round-off above it) in the last interval
    const int k = std::clamp(static_cast<int>(d * 10.0), 0, 9);
    ++counts[static_cast<std::size_t>(k)];
  }
  return counts;
}

bool write_damage_histogram(const std::string& directory, const std::string& png, const std::array<std::int64_t, 10>& counts,
                            const std::string& title, std::string& reason) {
  const std::string csv = directory + "/damage_histogram.csv";
  std::int64_t total = 0;
  for (auto c : counts) total += c;
  {
    std::ofstream out(csv);
    out << "damage_from,damage_to,particles,percent\n";
    char line[128];
    for (std::size_t k = 0; k < counts.size(); ++k) {
      std::snprintf(line, sizeof line, "%.1f,%.1f,%lld,%.4f\n", 0.1 * double(k), 0.1 * double(k + 1), static_cast<long long>(counts[k]),
                    total > 0 ? 100.0 * double(counts[k]) / double(total) : 0.0);
      out << line;
    }
  }
  return run_python_script(plot_damage_histogram_script, {csv, png, title}, reason);
}

}  // namespace rift::io
