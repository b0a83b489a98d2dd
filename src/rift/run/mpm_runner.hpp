// `rift check` and `rift run` for scenes with method = "mpm".
#pragma once
#include <iosfwd>

#include "rift/run/runner.hpp"

namespace rift::run {

Plan check_mpm(const scene::Scene& s, std::ostream& out);
Result run_mpm(const scene::Scene& s, const Options& options);

}  // namespace rift::run
