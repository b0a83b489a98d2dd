// PNG of the final damage field of a 2D run, drawn by matplotlib (Debian python3-matplotlib).
#pragma once
#include <string>
#include <vector>

namespace rift::io {

/// Writes `png`; returns false (with a reason) when Python/matplotlib is missing or fails.
bool write_damage_image(const std::string& directory, const std::string& png, const std::vector<double>& x,
                        const std::vector<double>& y, const std::vector<double>& damage, const std::string& title,
                        std::string& reason);

}  // namespace rift::io
