// The peridynamic laws, and the one place that turns a scene's model into a law's type. A law is a
// struct (laws/pmb.hpp is the shortest) that states its kind and name, its traits (state_based: the
// force pass reads the dilatations; bond_history: a history of each direction of every bond), its
// separation work (critical stretch from G0), its passes, strain energy and bond-pair force; a new
// law is its file and one entry in `Laws` (tests/test_law_conformance.cpp then runs it through the
// checks every law passes).
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "rift/pd/laws/eps.hpp"
#include "rift/pd/laws/lps.hpp"
#include "rift/pd/laws/pmb.hpp"
#include "rift/pd/laws/ves.hpp"

namespace rift::pd {

template <class... L>
struct LawList {};

using Laws = LawList<laws::Pmb, laws::Lps, laws::Ves, laws::Eps>;

namespace detail {
template <class F, class First, class... Rest>
decltype(auto) with_law_in(scene::ModelKind kind, F&& f, LawList<First, Rest...>) {
  if constexpr (sizeof...(Rest) == 0) {
    if (kind != First::kind) throw std::logic_error("no peridynamic law of model kind " + std::to_string(static_cast<int>(kind)));
    return f.template operator()<First>();
  } else {
    if (kind == First::kind) return f.template operator()<First>();
    return with_law_in(kind, f, LawList<Rest...>{});
  }
}
}  // namespace detail

/// f.template operator()<Law>() with the law of `kind`: called once per body, outside the loops.
template <class F>
decltype(auto) with_law(scene::ModelKind kind, F&& f) {
  return detail::with_law_in(kind, f, Laws{});
}

/// What the code around the passes asks of a law (the law's constants of the same names).
struct LawTraits {
  const char* name;
  bool state_based, bond_history, commits_at_equilibrium;
  int energy_moment_power;
};

inline LawTraits law_traits(scene::ModelKind kind) {
  return with_law(kind, []<class Law>() {
    return LawTraits{Law::name, Law::state_based, Law::bond_history, Law::commits_at_equilibrium, Law::energy_moment_power};
  });
}

/// The traits of each body's law, by body number (for loops over particles of several bodies).
inline std::vector<LawTraits> body_laws(const std::vector<BodyInfo>& bodies) {
  std::vector<LawTraits> laws;
  for (const BodyInfo& body : bodies) laws.push_back(law_traits(body.constants.model));
  return laws;
}

}  // namespace rift::pd
