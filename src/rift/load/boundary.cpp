#include "rift/load/boundary.hpp"

#include <algorithm>

#include "rift/geometry/region.hpp"
#include "rift/scene/time_function.hpp"
#include "rift/scene/traction_layer.hpp"
#include "rift/parallel/exact_sum.hpp"
#include "rift/parallel/team.hpp"

namespace rift::load {

namespace {
template <int D>
std::vector<std::size_t> select(const scene::Scene& s, const pd::Model<D>& m, const std::string& region) {
  return geometry::indices_inside<D>(geometry::Region::build(s, region), m.size(),
                                     [&](std::size_t i) { return m.reference_position[i]; });
}
}  // namespace

template <int D>
Boundaries<D>::Boundaries(const scene::Scene& s, pd::Model<D>& m) {
  using K = scene::BoundaryKind;
  for (std::size_t bi = 0; bi < s.boundaries.size(); ++bi) {
    const auto& b = s.boundaries[bi];
    Applied a{b, select<D>(s, m, b.region)};
    if (a.particles.empty())
      throw SceneError(b.where, "boundaries[" + std::to_string(bi) + "].region", "region \"" + b.region + "\" selects no particle");
    if (b.kind == K::traction && b.layer_depth > 0)
      for (auto i : a.particles)
        if (b.layer_depth < (1.0 - 1e-9) * m.constants_of(i).spacing)
          throw SceneError(b.where, "boundaries[" + std::to_string(bi) + "].layer_depth",
                           scene::thinner_than_a_row(b.layer_depth, m.constants_of(i).spacing));
    if (b.kind == K::fixed || b.kind == K::velocity || b.kind == K::displacement) {
      any_kinematic_ = true;
      for (auto i : a.particles)
        for (int k = 0; k < D; ++k)
          if (b.kind == K::fixed || b.value[k]) m.constrained[i] |= std::uint8_t(1u << k);
    }
    applied_.push_back(std::move(a));
  }
  if (s.in_situ.enabled) add_in_situ_tractions(s.in_situ, m);
  for (const auto& name : s.output.reactions) {
    reaction_names_.push_back(name);
    reaction_particles_.push_back(select<D>(s, m, name));
    if (reaction_particles_.back().empty())
      throw SceneError({s.file, 0, 0}, "output.reactions", "region \"" + name + "\" selects no particle");
  }
}

template <int D>
void Boundaries<D>::add_in_situ_tractions(const scene::InSituStress& in_situ, pd::Model<D>& m) {
  const auto [lo, hi] = m.reference_bounds();
  // the outermost row of particles on each face carries sigma . n over its depth (one spacing);
  // between platens (pd/platens.hpp) the low face's row is held along the axis and the high face's
  // row moves as one plate under the same load
  const bool platens = in_situ.faces == scene::InSituStress::Faces::platens;
  for (int k = 0; k < D; ++k)
    for (int side : {-1, 1}) {
      Applied a;
      a.def.where = in_situ.where;
      a.def.region = std::string("in-situ face ") + (side < 0 ? "-" : "+") + "xyz"[k];
      const bool held = platens && side < 0;  // the frame's reaction plate: no normal displacement
      a.def.kind = held ? scene::BoundaryKind::displacement : scene::BoundaryKind::traction;
      a.def.value[k] = held ? 0.0 : side * in_situ.principal(k);
      for (std::size_t i = 0; i < m.size(); ++i) {
        const double half_row = 0.5 * m.constants_of(i).spacing;
        if (side > 0 ? m.reference_position[i][k] > hi[k] - half_row : m.reference_position[i][k] < lo[k] + half_row)
          a.particles.push_back(i);
      }
      if (platens)
        for (auto i : a.particles)
          if (m.constrained[i] >> k & 1)
            throw SceneError(in_situ.where, "in_situ_stress.faces",
                             std::string("a boundary prescribes the ") + "xyz"[k] + " motion of the " + a.def.region +
                                 ", which the platens move: drop that boundary or use faces = \"tractions\"");
      if (held) {
        any_kinematic_ = true;
        for (auto i : a.particles) m.constrained[i] |= std::uint8_t(1u << k);
      } else if (platens) {
        m.platens.push_back({k, a.particles});
      }
      applied_.push_back(std::move(a));
    }
}

template <int D>
void Boundaries<D>::apply_body_forces(pd::Model<D>& m, double t) const {
  using K = scene::BoundaryKind;
  // cleared by the team as kick splits the particles, so that each core clears the lines it reads
  // next: cleared by one thread, every line the other core's kick reads would come from this core's
  // cache, dear where the two cores share no L3 cache (bench/README.md)
  const std::size_t n = m.size();
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i) m.body_force[i] = Vec<D>{};
  for (const auto& a : applied_) {
    if (a.def.kind != K::traction && a.def.kind != K::body_force) continue;
    const double amp = scene::evaluate(a.def.time, t);
    for (auto i : a.particles) {
      double scale = amp;
      if (a.def.kind == K::traction) {
        const double depth = a.def.layer_depth > 0 ? a.def.layer_depth : m.constants_of(i).spacing;
        scale /= depth;
      }
      for (int k = 0; k < D; ++k)
        if (a.def.value[k]) m.body_force[i][k] += scale * *a.def.value[k];
    }
  }
}

template <int D>
void Boundaries<D>::prescribe_velocity(pd::Model<D>& m, double t, double dt) const {
  using K = scene::BoundaryKind;
  for (const auto& a : applied_) {
    if (a.def.kind == K::fixed) {
      for (auto i : a.particles) m.velocity[i] = Vec<D>{};
    } else if (a.def.kind == K::velocity) {
      const double amp = scene::evaluate(a.def.time, t + 0.5 * dt);
      for (auto i : a.particles)
        for (int k = 0; k < D; ++k)
          if (a.def.value[k]) m.velocity[i][k] = amp * *a.def.value[k];
    } else if (a.def.kind == K::displacement) {
      if (dt <= 0.0) continue;  // end of step: keep the drift velocity
      const double du = (scene::evaluate(a.def.time, t + dt) - scene::evaluate(a.def.time, t)) / dt;
      for (auto i : a.particles)
        for (int k = 0; k < D; ++k)
          if (a.def.value[k]) m.velocity[i][k] = du * *a.def.value[k];
    }
  }
}

template <int D>
void Boundaries<D>::prescribe_position(pd::Model<D>& m, double t) const {
  using K = scene::BoundaryKind;
  for (const auto& a : applied_) {
    if (a.def.kind == K::fixed) {
      for (auto i : a.particles) m.position[i] = m.reference_position[i];
    } else if (a.def.kind == K::displacement) {
      const double amp = scene::evaluate(a.def.time, t);
      for (auto i : a.particles)
        for (int k = 0; k < D; ++k)
          if (a.def.value[k]) m.position[i][k] = m.reference_position[i][k] + amp * *a.def.value[k];
    }
  }
}

template <int D>
std::vector<Vec<D>> Boundaries<D>::reactions(const pd::Model<D>& m, const parallel::Communicator& comm) const {
  // added exactly (parallel/exact_sum.hpp): the one-rank run's bits however the ranks share a region
  std::vector<parallel::ExactSum> sums(reaction_particles_.size() * D);
  for (std::size_t q = 0; q < reaction_particles_.size(); ++q)
    for (auto i : reaction_particles_[q])
      for (int k = 0; k < D; ++k) sums[q * D + static_cast<std::size_t>(k)].add(-m.force[i][k] * m.volume[i]);
  const std::vector<double> total = parallel::rounded_over_ranks(comm, std::move(sums));
  std::vector<Vec<D>> out(reaction_particles_.size());
  for (std::size_t q = 0; q < out.size(); ++q)
    for (int k = 0; k < D; ++k) out[q][k] = total[q * D + static_cast<std::size_t>(k)];
  return out;
}

template <int D>
void Boundaries<D>::restrict_to(const pd::Numbering& window, const std::vector<IndexRange>& owned) {
  // the particles the window holds (the owned ones alone), numbered as the window numbers them
  auto keep = [&](std::vector<std::size_t>& particles, bool owned_alone) {
    std::vector<std::size_t> kept;
    for (auto i : particles)
      if ((!owned_alone || any_contains(owned, i)) && window.holds(i)) kept.push_back(window.here(i));
    particles = std::move(kept);
  };
  for (auto& a : applied_) keep(a.particles, false);
  for (auto& parts : reaction_particles_) keep(parts, true);
}

template class Boundaries<2>;
template class Boundaries<3>;

}  // namespace rift::load
