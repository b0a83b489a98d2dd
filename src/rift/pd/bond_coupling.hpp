// What a stage outside the peridynamic core couples into its bond passes: hydraulic fracture's wet
// rock (hf/wet_rock.hpp), which a crack holding fluid makes active. The passes reach it only through
// their breaking policy (breaking_policy.hpp WetBreaking): per pass, a BondBreaker (the pore stretch
// that lowers the vector runs' limits, whether a bond taken one by one breaks), and after it the bonds
// the pass broke across the crack. The model holds a pointer to it (Model::coupling; none: every
// bond breaks dry).
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "rift/pd/model.hpp"

namespace rift::pd {

/// What one pass reads of the coupling, made once per pass from the model as it stands.
class BondBreaker {
 public:
  virtual ~BondBreaker() = default;
  /// Per particle, the stretch that lowers the limit of a bond across the crack ((1 + alpha) times
  /// the lower of its ends'); nullptr: none yet.
  virtual const double* pore_stretch() const = 0;
  /// Whether bond i-j (reference length xi; `value` its stretch, or its normal stress in stretch
  /// units) breaks against `limit`; `crossed`: whether it crosses the crack, where that matters.
  virtual bool breaks(double alpha, std::size_t i, std::size_t j, double xi, double value, double limit, bool& crossed) const = 0;

 protected:
  BondBreaker() = default;
  BondBreaker(const BondBreaker&) = default;
  BondBreaker& operator=(const BondBreaker&) = default;
};

template <int D>
class BondCoupling {
 public:
  virtual ~BondCoupling() = default;
  /// Whether it acts on the model's passes now.
  virtual bool active(const Model<D>& m) const = 0;
  /// The breaker of a pass over the model as it stands (valid while the model's fluid state is unchanged).
  virtual std::unique_ptr<const BondBreaker> breaker(const Model<D>& m) const = 0;
  /// After a pass: the bonds it broke that cross the crack, (i, k) of row i's entry k.
  virtual void broke_across(Model<D>& m, const std::vector<std::pair<std::size_t, std::int64_t>>& crossing) const = 0;

 protected:
  BondCoupling() = default;
  BondCoupling(const BondCoupling&) = default;
  BondCoupling& operator=(const BondCoupling&) = default;
};

}  // namespace rift::pd
