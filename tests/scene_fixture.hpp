// Helpers to build small scenes in tests.
#pragma once
#include <string>

#include "rift/scene/parse.hpp"

namespace rift::test {

/// A box body of one material; `extra` is appended (boundaries, solver, ...).
inline std::string box_scene(int dim, const std::string& model, double nu, const std::string& extra,
                             const std::string& size = "", double horizon = 3.015, const std::string& plane = "stress",
                             const std::string& material_extra = "", const std::string& body_extra = "") {
  std::string s = "[scene]\ndimension = " + std::to_string(dim) + "\n";
  if (dim == 2) s += "plane = \"" + plane + "\"\nthickness = 0.001\n";
  s += "[materials.m]\nmodel = \"" + model + "\"\ndensity = 2000.0\nyoungs_modulus = 1.0e9\npoisson_ratio = " + std::to_string(nu) + "\n" +
       material_extra + "\n";
  std::string box = size.empty() ? (dim == 2 ? "max = [0.02, 0.02]" : "max = [0.012, 0.012, 0.012]") : size;
  s += "[regions.all]\nshape = \"box\"\nmin = " + std::string(dim == 2 ? "[0.0, 0.0]" : "[0.0, 0.0, 0.0]") + "\n" + box + "\n";
  s += "[bodies.b]\nmaterial = \"m\"\nregion = \"all\"\nspacing = 0.001\nhorizon = " + std::to_string(horizon) + "\n" + body_extra + "\n";
  s += extra;
  if (extra.find("[solver]") == std::string::npos) s += "\n[solver]\nend_time = 1e-6\n";
  return s;
}

}  // namespace rift::test
