// The rock the fluid, in-situ and interface tests share: LPS, E = 10 GPa, nu = 0.25, 2500 kg/m^3.
#pragma once
#include <string>

namespace rift::test {

/// The [materials.rock] table, with `keys` added to it (a critical stretch, say).
inline std::string rock_material(const std::string& keys = "") {
  std::string s = "[materials.rock]\nmodel = \"lps\"\ndensity = 2500.0\nyoungs_modulus = 10e9\npoisson_ratio = 0.25\n";
  s += keys;
  return s;
}

/// A 2D plane strain scene, 1 mm thick, of that rock: the [scene] and [materials.rock] tables.
inline std::string plane_strain_rock(const std::string& material_keys = "") {
  std::string s = "[scene]\ndimension = 2\nplane = \"strain\"\nthickness = 0.001\n";
  s += rock_material(material_keys);
  return s;
}

}  // namespace rift::test
