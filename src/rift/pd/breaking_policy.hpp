// How a bond pass decides that a bond breaks, compiled into the pass (the law's kernels take these as
// template parameters, so a pass without wet rock is the dry code): the vector runs' limit,
// min(s0_i, s0_j) (StretchLimit) or less the wet rock's shift (1 + alpha) min(s_p,i, s_p,j)
// (PoreShiftedLimit); the bonds taken one by one, on the pass's own criterion (DryBreaking) or as the
// model's coupling decides (WetBreaking; bond_coupling.hpp, hydraulic fracture's wet rock: the effective
// stretch where the bond crosses a crack that holds fluid); and the BreakLog of the bonds a pass broke.
#pragma once
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "rift/pd/bond_coupling.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

/// A run's limit for bond t: the lower of its ends' stretch limits.
struct StretchLimit {
  [[gnu::always_inline]] static double lowered(double limit, const double* /*pore_a*/, const double* /*pore_b*/, std::size_t /*t*/,
                                               double /*scale*/) {
    return limit;
  }
};

/// A run's limit for bond t lowered by the wet rock's shift, `scale` (1 + alpha) times the lower of its
/// ends' pore stretches.
struct PoreShiftedLimit {
  [[gnu::always_inline]] static double lowered(double limit, const double* __restrict pore_a, const double* __restrict pore_b,
                                               std::size_t t, double scale) {
    return limit - scale * (pore_a[t] < pore_b[t] ? pore_a[t] : pore_b[t]);
  }
};

/// A bond taken one by one breaks where the pass's own test (`past`) says so.
struct DryBreaking {
  const double* pore_stretch() const { return nullptr; }  // the runs' limits are not shifted
  bool breaks(bool /*breakable*/, std::size_t, std::size_t, double /*xi*/, double /*value*/, double /*limit*/, bool past,
              bool& /*crossed*/) const {
    return past;
  }
};

/// A bond taken one by one where the model's coupling acts (bond_coupling.hpp; hydraulic fracture's
/// wet rock: on its effective stretch where it crosses a crack that holds fluid); `crossed` says
/// whether it crosses, where that matters.
struct WetBreaking {
  const BondBreaker* breaker = nullptr;  // the coupling's, for this pass
  const double* pore = nullptr;          // its pore stretch (nullptr: none yet, the runs' limits not shifted)
  double alpha = 0.0;                    // the body's: s0 = s00 - alpha s_min
  const double* pore_stretch() const { return pore; }
  bool breaks(bool breakable, std::size_t i, std::size_t j, double xi, double value, double limit, bool /*past*/, bool& crossed) const {
    return breakable && breaker->breaks(alpha, i, j, xi, value, limit, crossed);
  }
};

/// The bonds a pass broke, (i, k) of the lower end's row in no fixed order, and those of them that
/// cross a crack holding fluid (hf/crack_surface.hpp record_crossing_breaks); the team notes into one log.
struct BreakLog {
  std::vector<std::pair<std::size_t, std::int64_t>> broken, crossing;
  void note(std::size_t i, std::int64_t k, bool crossed) {
#pragma omp critical(rift_broken_bonds)
    {
      broken.emplace_back(i, k);
      if (crossed) crossing.emplace_back(i, k);
    }
  }
};

/// Calls pass(breaking) with the model's breaking policy: WetBreaking where its coupling acts, else
/// DryBreaking.
template <int D, class Pass>
void with_breaking(const Model<D>& m, double alpha, Pass&& pass) {
  if (!m.coupling && !m.fluid_network.crack_surface.empty())
    throw std::logic_error("a crack holds fluid but the model has no bond coupling (hf::FluidPressure installs the wet rock's)");
  if (m.coupling && m.coupling->active(m)) {
    const auto breaker = m.coupling->breaker(m);
    pass(WetBreaking{breaker.get(), breaker->pore_stretch(), alpha});
  } else {
    pass(DryBreaking{});
  }
}

/// After a pass: the model's coupling takes the bonds it broke across the crack.
template <int D>
void after_breaking(Model<D>& m, const BreakLog& log) {
  if (m.coupling) m.coupling->broke_across(m, log.crossing);
}

}  // namespace rift::pd
