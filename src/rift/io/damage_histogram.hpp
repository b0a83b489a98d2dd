// Damage histogram: the share of particles whose damage falls in each interval of 0.1, as the thesis
// on hydraulic fracture with peri/ves reports its runs (003_a918a6800360952d.txt, Table 5.2 and
// Figure 5.11). Written as damage_histogram.csv and drawn as a bar chart by matplotlib.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rift::io {

/// Particles per interval [k/10, (k+1)/10), k = 0..9; damage 1 counts in the last interval.
std::array<std::int64_t, 10> damage_histogram(const std::vector<double>& damage);

/// Writes `directory`/damage_histogram.csv (damage_from, damage_to, particles, percent) and, when
/// Python/matplotlib is there, `png`; returns false (with a reason) when the PNG is not written.
bool write_damage_histogram(const std::string& directory, const std::string& png, const std::array<std::int64_t, 10>& counts,
                            const std::string& title, std::string& reason);

}  // namespace rift::io
