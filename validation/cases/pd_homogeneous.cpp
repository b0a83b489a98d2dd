// Validation 1: homogeneous deformation (uniaxial, shear, volumetric) in 3D and in 2D plane stress
// and plane strain; PMB where its Poisson ratio applies (1/4 in 3D and plane strain, 1/3 in plane
// stress), LPS for nu = 0.2 and 0.3. Strain energy density within 1% of classical elasticity in the
// bulk and within 5% near free surfaces (surface correction on).
#include <cstdio>

#include "case.hpp"
#include "homogeneous.hpp"

namespace rift::validation {

Result pd_homogeneous(const Settings& settings) {
  struct Combo {
    int dim;
    const char* model;
    double nu;
    const char* plane;
  };
  const Combo combos[] = {{3, "pmb", 0.25, ""},        {3, "lps", 0.2, ""},          {3, "lps", 0.3, ""},
                          {2, "pmb", 1.0 / 3, "stress"}, {2, "pmb", 0.25, "strain"},  {2, "lps", 0.2, "stress"},
                          {2, "lps", 0.3, "stress"},    {2, "lps", 0.2, "strain"},    {2, "lps", 0.3, "strain"}};
  double bulk = 0, surface = 0;
  std::FILE* data = nullptr;
  if (!settings.output_dir.empty()) {
    data = std::fopen((settings.output_dir + "/pd_homogeneous.csv").c_str(), "w");
    if (data) std::fprintf(data, "case,strain,bulk_error,surface_error\n");
  }
  for (const auto& c : combos) {
    const std::string scene = box_scene(c.dim, c.model, c.nu, "", "", 3.015, c.plane[0] ? c.plane : "stress");
    for (const auto* eps : {&uniaxial_strain, &shear_strain, &volumetric_strain}) {
      auto e = c.dim == 2 ? energy_errors<2>(scene, *eps) : energy_errors<3>(scene, *eps);
      bulk = std::max(bulk, e.bulk);
      surface = std::max(surface, e.surface);
      if (data)
        std::fprintf(data, "%s%dd%s nu=%.2f,%s,%.3e,%.3e\n", c.model, c.dim, c.plane, c.nu,
                     eps == &uniaxial_strain ? "uniaxial" : eps == &shear_strain ? "shear" : "volumetric", e.bulk, e.surface);
    }
  }
  if (data) std::fclose(data);
  Result r;
  r.name = "pd_homogeneous";
  r.measured = bulk;
  r.reference = 0.0;
  r.tolerance = 0.01;
  r.unit = "max relative error of W in the bulk";
  char buf[160];
  std::snprintf(buf, sizeof buf, "near-surface max error %.2e (tolerance 0.05); 9 model/dimension/Poisson cases x 3 strains", surface);
  r.details = buf;
  r.source = "classical linear elasticity";
  r.pass = bulk <= 0.01 && surface <= 0.05;
  return r;
}

}  // namespace rift::validation
