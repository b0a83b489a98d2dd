// A validation case measures one number against an analytic or published reference. Each case is
// a function (one per file); rift-validate prints `CASE PASS|FAIL measured=... reference=...
// tolerance=...` and the tests call the quick versions and assert on the same result.
#pragma once
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace rift::validation {

struct Settings {
  bool quick = true;        // coarse version (CI)
  std::string output_dir;   // where to write data for plots (empty: none)
  bool verbose = false;
};

struct Result {
  std::string name;
  double measured = 0.0, reference = 0.0, tolerance = 0.0;
  bool pass = false;
  std::string unit;     // of measured/reference
  std::string details;  // one line of supporting numbers
  std::string source;   // where the reference comes from
  /// |measured - reference| <= tolerance (absolute) unless a case sets pass itself.
  void decide() { pass = std::abs(measured - reference) <= tolerance; }
};

using Case = std::function<Result(const Settings&)>;

Result pd_homogeneous(const Settings&);
Result pd_wave_speed(const Settings&);
Result pd_momentum(const Settings&);
Result pd_fracture_energy(const Settings&);
Result pd_quasistatic_plate(const Settings&);
Result pd_eps_bar(const Settings&);
Result pd_eps_bar_plane_stress(const Settings&);
Result kalthoff_winkler(const Settings&);
Result glass_branching(const Settings&);
Result mpm_energy(const Settings&);
Result mpm_cantilever(const Settings&);
Result mpm_disks(const Settings&);
Result mpm_dcb(const Settings&);
Result mpm_enf(const Settings&);
Result mpm_mixed_mode(const Settings&);
Result mpm_cct(const Settings&);
Result mpm_sent(const Settings&);
Result mpm_denp(const Settings&);
Result mpm_crack_growth(const Settings&);
Result hf_sneddon(const Settings&);
Result hf_kirsch(const Settings&);
Result hf_breakdown(const Settings&);
Result hf_kgd_toughness(const Settings&);
Result hf_kgd_toughness_coarse(const Settings&);
Result hf_kgd_viscosity(const Settings&);
Result hf_zhou_crossing(const Settings&);
Result hf_zhou_crossing_coarse(const Settings&);
Result hf_injection_rate(const Settings&);

struct Entry {
  const char* name;
  Case run;
};
const std::vector<Entry>& all_cases();

/// Path of a file in the source tree (examples, validation scenes).
std::string source_path(const std::string& relative);

}  // namespace rift::validation
