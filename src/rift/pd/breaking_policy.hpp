// How a bond pass decides that a bond breaks, compiled into the pass (the law's kernels take these as
// template parameters, so a pass without wet rock is the dry code): the vector runs' limit,
// min(s0_i, s0_j) (StretchLimit) or less the wet rock's shift (1 + alpha) min(s_p,i, s_p,j)
// (PoreShiftedLimit); the bonds taken one by one, on the pass's own criterion (DryBreaking) or on the
// effective stretch where the bond crosses a crack that holds fluid (WetBreaking,
// effective_stretch.hpp); and the BreakLog of the bonds a pass broke, for what it does after its loop.
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "rift/pd/effective_stretch.hpp"

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

/// A bond taken one by one in a crack's wet rock breaks on its effective stretch where it crosses the
/// crack (breaks_in_wet_rock; `value`: its stretch, or its normal stress in stretch units); `crossed`
/// says whether it crosses, where that matters.
template <int D>
struct WetBreaking {
  WetRock<D> wet;
  double alpha = 0.0;  // the body's: s0 = s00 - alpha s_min
  const double* pore_stretch() const { return wet.pore_stretch; }  // nullptr: no pressure yet, the runs' limits not shifted
  bool breaks(bool breakable, std::size_t i, std::size_t j, double xi, double value, double limit, bool /*past*/, bool& crossed) const {
    return breakable && breaks_in_wet_rock<D>(wet, alpha, i, j, xi, value, limit, crossed);
  }
};

/// The bonds a pass broke, (i, k) of the lower end's row in no fixed order, and those of them that
/// cross a crack holding fluid (crack_crossing.hpp record_crossing_breaks); the team notes into one log.
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

/// Calls pass(breaking) with the model's breaking policy: WetBreaking where a crack holds fluid, else
/// DryBreaking.
template <int D, class Pass>
void with_breaking(const Model<D>& m, double alpha, Pass&& pass) {
  if (const WetRock<D> wet = wet_rock(m)) pass(WetBreaking<D>{wet, alpha});
  else pass(DryBreaking{});
}

}  // namespace rift::pd
