// Figures drawn by matplotlib (Debian python3-matplotlib): a script embedded in the binary is fed
// to python3 on standard input with its arguments.
#pragma once
#include <string>
#include <vector>

namespace rift::io {

/// Runs `script` with `args`; returns false (with a reason) when Python/matplotlib is missing or fails.
bool run_python_script(const char* script, const std::vector<std::string>& args, std::string& reason);

}  // namespace rift::io
