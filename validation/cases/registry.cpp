#include "case.hpp"

#ifndef RIFT_SOURCE_DIR
#error "RIFT_SOURCE_DIR must name the source tree"
#endif

namespace rift::validation {

const std::vector<Entry>& all_cases() {
  static const std::vector<Entry> cases{
      {"pd_homogeneous", pd_homogeneous},         {"pd_wave_speed", pd_wave_speed},
      {"pd_momentum", pd_momentum},               {"pd_fracture_energy", pd_fracture_energy},
      {"pd_quasistatic_plate", pd_quasistatic_plate}, {"pd_eps_bar", pd_eps_bar},
      {"pd_eps_bar_plane_stress", pd_eps_bar_plane_stress},
      {"kalthoff_winkler", kalthoff_winkler},
      {"glass_branching", glass_branching},       {"mpm_energy", mpm_energy},
      {"mpm_cantilever", mpm_cantilever},         {"mpm_disks", mpm_disks},
      {"mpm_dcb", mpm_dcb},
      {"mpm_enf", mpm_enf},
      {"mpm_mixed_mode", mpm_mixed_mode},
      {"mpm_cct", mpm_cct},
      {"mpm_sent", mpm_sent},
      {"mpm_denp", mpm_denp},
      {"mpm_crack_growth", mpm_crack_growth},
      {"hf_sneddon", hf_sneddon},
      {"hf_kirsch", hf_kirsch},
      {"hf_breakdown", hf_breakdown},
      {"hf_kgd_toughness", hf_kgd_toughness},
      {"hf_kgd_toughness_coarse", hf_kgd_toughness_coarse},
      {"hf_kgd_viscosity", hf_kgd_viscosity},
      {"hf_zhou_crossing", hf_zhou_crossing},
      {"hf_zhou_crossing_coarse", hf_zhou_crossing_coarse},
      {"hf_injection_rate", hf_injection_rate},
  };
  return cases;
}

std::string source_path(const std::string& relative) { return std::string(RIFT_SOURCE_DIR) + "/" + relative; }

}  // namespace rift::validation
