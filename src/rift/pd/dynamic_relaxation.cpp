#include "rift/pd/dynamic_relaxation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "rift/core/stop_signal.hpp"
#include "rift/parallel/communicator.hpp"
#include "rift/parallel/ordered_sum.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/ghost_fields.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/rigid_motion.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

template <int D>
DynamicRelaxation<D>::DynamicRelaxation(const Model<D>& m) {
  // lambda_ii >= (1/4) dt^2 sum_j |dF/du| ~ (1/4) sum_j c omega / |xi| V_j (eq. 10, dt = 1); a factor 5
  // covers LPS coupling through the dilatation and the surface correction.
  fictitious_density_.assign(m.size(), 0.0);
  for (const auto& body : m.bodies) {
    const auto& c = body.constants;
    for (std::size_t i = body.first; i < body.last; ++i) {
      double sum = 0.0;
      for (auto k = m.bonds.offset[i]; k < m.bonds.offset[i + 1]; ++k) {
        const double xi = m.bonds.length(k);
        sum += std::max(1.0f, m.bonds.correction(i, k)) * c.equivalent_micromodulus * influence(c.influence, xi, c.horizon) / xi *
               m.bonds.volume(k);
      }
      fictitious_density_[i] = 0.25 * row_sum_factor * sum;
    }
  }
}

template <int D>
double DynamicRelaxation<D>::measure_fictitious_density(Model<D>& m, const Loads<D>& loads, Contact<D>* contact, double t,
                                                        int iterations, double safety) {
  const std::size_t n = m.size();
  // sums and maxima over the owned particles (a distributed run's: every rank's, in the one-rank
  // order, parallel/ordered_sum.hpp); the ghosts' probe from their owners
  const auto& comm = ranks_of<D>(m);
  const std::vector<IndexRange> owned = m.owned();
  if (comm.sum(static_cast<double>(count_of(owned))) == 0.0) return row_sum_factor;
  // the row-sum bound of eq. 10, lambda_i / row_sum_factor
  std::vector<double> bound(n);
  for (std::size_t i = 0; i < n; ++i) bound[i] = fictitious_density_[i] / row_sum_factor;
  double shortest = std::numeric_limits<double>::max();
  for (const auto& f : m.bonds.families) shortest = std::min(shortest, f.length);
  if (!(shortest < std::numeric_limits<double>::max())) return row_sum_factor;
  const std::vector<Vec<D>> start = m.position;
  auto total_force = [&] {  // internal and external force density at the current positions
    compute_forces<D>(m, contact);
    loads.apply_body_forces(m, t);
    std::vector<Vec<D>> f(n);
    for (std::size_t i = 0; i < n; ++i) f[i] = m.force[i] + m.body_force[i];
    return f;
  };
  const std::vector<Vec<D>> at_start = total_force();
  // a start with every mode in it: a fixed pseudo-random sign per component (splitmix64 of i d + q,
  // i the particle's number in the whole run)
  std::vector<Vec<D>> v(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int q = 0; q < D; ++q) {
      std::uint64_t z = (m.numbering.whole(i) * D + static_cast<std::size_t>(q) + 1) * 0x9e3779b97f4a7c15ull;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull, z = (z ^ (z >> 27)) * 0x94d049bb133111ebull, z ^= z >> 31;
      v[i][q] = m.constrained[i] >> q & 1 ? 0.0 : ((z & 1) ? 1.0 : -1.0);
    }
  const double probe = 1e-6 * shortest;  // the largest component of a probe's displacement
  double mu = 0.0;
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t i = 0; i < n; ++i) m.position[i] = start[i] + probe * v[i];
    const std::vector<Vec<D>> moved = total_force();
    // w = K v / bound (K v = -(F(x + probe v) - F(x)) / probe); Rayleigh's quotient in the bound's metric
    const auto sums = parallel::exact_sums<2>(comm, owned, line_of(m), [&](std::size_t i, std::array<double, 2>& acc) {
      for (int q = 0; q < D; ++q) {
        const double kv = m.constrained[i] >> q & 1 ? 0.0 : -(moved[i][q] - at_start[i][q]) / probe;
        acc[0] += m.volume[i] * v[i][q] * kv;
        acc[1] += m.volume[i] * bound[i] * v[i][q] * v[i][q];
        v[i][q] = bound[i] > 0.0 ? kv / bound[i] : 0.0;
      }
    });
    double largest = 0.0;
    for (const IndexRange& r : owned)
      for (std::size_t i = r.first; i < r.last; ++i)
        for (int q = 0; q < D; ++q) largest = std::max(largest, std::abs(v[i][q]));
    largest = comm.max(largest);
    if (sums[1] > 0.0) mu = sums[0] / sums[1];
    if (!(largest > 0.0) || !std::isfinite(largest)) break;
    for (auto& x : v) x = (1.0 / largest) * x;
    m.refresh_ghosts(v);
  }
  m.position = start;
  compute_forces<D>(m, contact);
  loads.apply_body_forces(m, t);
  if (!(mu > 0.0) || !std::isfinite(mu)) return row_sum_factor;
  const double factor = safety * mu / 4.0;
  for (std::size_t i = 0; i < n; ++i) fictitious_density_[i] = factor * bound[i];
  return factor;
}

// The iterations move a free body with F less its rigid-body part (rigid_motion.hpp) and measure
// their residual on it: Zhou's 2-7 block (hf_zhou_crossing) turned about its centre once its
// interface slipped, the residual stalled at 1.1e-5 and grew, and a load step took 36,621 iterations
// (2,333 without the turn); a square block turned by 0.02 rad before its in-situ stage turned on to
// 180 degrees, where the compressive tractions pull (tests/test_in_situ_stress.cpp).
template <int D>
RigidAcceleration<D> rigid_acceleration(const Model<D>& m, const std::vector<double>& mass, const parallel::Communicator& comm) {
  return rigid_acceleration<D>(
      m.position, [&](std::size_t i) { return mass[i] * m.volume[i]; },
      [&](std::size_t i) {
        Vec<D> f;
        for (int k = 0; k < D; ++k) f[k] = (m.force[i][k] + m.body_force[i][k]) * m.volume[i];
        return f;
      },
      line_of(m), &comm, m.owned());
}

template <int D>
RelaxationResult DynamicRelaxation<D>::relax(Model<D>& m, const Loads<D>& loads, Contact<D>* contact,
                                              double t, int max_iterations, double tolerance) {
  const std::size_t n = m.size();
  // a load step a stop cut short goes on where it stood: the model holds its positions, velocities
  // and loads (a checkpoint's), unfinished_ the iterations' own state
  const int first_iteration = unfinished_.iteration;
  const double unfinished_load_norm = unfinished_.load_norm;
  std::vector<Vec<D>> previous(n);  // F^{n-1} / lambda
  std::vector<Vec<D>> start;        // the displacement of Rayleigh's quotient from here (damping_from_start_)
  if (first_iteration > 0) {
    previous = std::move(unfinished_.previous), start = std::move(unfinished_.start);
  } else {
    m.time = t;
    loads.prescribe_position(m, t);
    loads.apply_body_forces(m, t);
    for (auto& v : m.velocity) v = Vec<D>{};
    if (damping_from_start_) start = m.position;
  }
  unfinished_.iteration = 0, unfinished_.load_norm = 0.0, unfinished_.previous = {}, unfinished_.start = {};
  RelaxationResult result;
  // sums over the owned particles of every rank, exact (parallel/exact_sum.hpp), so the damping and
  // the residual are the one-rank run's bits on any cut
  const auto& comm = ranks_of<D>(m);
  const bool distributed = comm.distributed();
  const std::vector<IndexRange> owned = m.owned();
  auto sum_over = [&](auto&& f) { return parallel::exact_sums<4>(comm, owned, line_of(m), f); };
  auto squared_load = [&] {  // ||external force||^2
    return sum_over([&](std::size_t i, std::array<double, 4>& acc) { acc[0] += dot<D>(m.body_force[i], m.body_force[i]) * m.volume[i] * m.volume[i]; })[0];
  };
  double load_norm = first_iteration > 0 ? unfinished_load_norm : squared_load();
  // held by tractions alone, no component of any particle prescribed: no rigid motion
  // (rigid_acceleration; a distributed run, pd/window.hpp: on no rank)
  const bool held_here = std::any_of(m.constrained.begin(), m.constrained.end(), [](std::uint8_t c) { return c != 0; });
  const bool free_body = !(distributed ? comm.any(held_here) : held_here);
  const std::vector<std::uint8_t> on_platen = platen_components(m);
  // the displacement of Rayleigh's quotient: from the reference, or from where this call started
  const std::vector<Vec<D>>& origin = damping_from_start_ ? start : m.reference_position;
  for (int it = first_iteration; it < max_iterations; ++it) {
    if (it > first_iteration && comm.any(stop_signal() != 0)) {  // every rank stops at the same iteration
      unfinished_.iteration = it, unfinished_.load_norm = load_norm;
      unfinished_.previous = std::move(previous), unfinished_.start = std::move(start);
      result.stopped = true;
      return result;  // the state of this iteration's start, for a checkpoint
    }
    advance_stretch_limits<D>(m);
    // a distributed run's ghosts are where their owners moved them, with their s0
    m.refresh_ghosts(m.position);
    m.refresh_ghosts(m.stretch_limit);
    compute_forces<D>(m, contact);
    if (loads.state_dependent() && it > 0) {  // an injected fluid's pressure follows the cavity volume
      loads.apply_body_forces(m, t);
      load_norm = squared_load();
    }
    const RigidAcceleration<D> rigid = free_body ? rigid_acceleration<D>(m, fictitious_density_, comm) : RigidAcceleration<D>{};
    // U^T K U with the local diagonal stiffness K_ii = -(F^n - F^{n-1}) / (lambda V^{n-1/2}) (eq. 12), U^T U,
    // squared residual of the free components and squared reactions of the constrained ones
    // (a platen's particle carries the plate's reaction; the plate's own residual is its net force)
    // over the owned particles
    auto sums = sum_over([&](std::size_t i, std::array<double, 4>& acc) {
      const Vec<D> rigid_i = free_body ? rigid.at(m.position[i]) : Vec<D>{};
      for (int k = 0; k < D; ++k) {
        const double total = m.force[i][k] + m.body_force[i][k] - fictitious_density_[i] * rigid_i[k];
        if (m.constrained[i] >> k & 1) {
          acc[3] += m.force[i][k] * m.force[i][k] * m.volume[i] * m.volume[i];
          continue;
        }
        if (on_platen[i] >> k & 1) acc[3] += total * total * m.volume[i] * m.volume[i];
        else acc[2] += total * total * m.volume[i] * m.volume[i];
        const double f = total / fictitious_density_[i];
        const double v = m.velocity[i][k];
        const double u = m.position[i][k] - origin[i][k];
        if (it > 0 && v != 0.0) acc[0] += u * (-(f - previous[i][k]) / v) * u;
        acc[1] += u * u;
      }
    });
    double residual = sums[2];
    for (const Platen& p : m.platens) {
      const double net = platen_sums<1>(m, p, [&](std::size_t i) {
        return std::array<double, 1>{(m.force[i][p.axis] + m.body_force[i][p.axis]) * m.volume[i]};
      })[0];
      residual += net * net;
    }
    const double num = sums[0], den = sums[1], reaction = sums[3];
    const double reference = std::sqrt(load_norm) + std::sqrt(reaction);
    result.iterations = it + 1;
    result.residual = reference > 0.0 ? std::sqrt(residual) / reference : std::sqrt(residual);
    if (observer_) observer_(it + 1, result.residual);
    if (it > 0 && reference > 0.0 && result.residual < tolerance) {
      result.converged = true;
      break;
    }
    const double cn = (den > 0.0 && num > 0.0) ? 2.0 * std::sqrt(num / den) : 0.0;
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec<D> rigid_i = free_body ? rigid.at(m.position[i]) : Vec<D>{};
      for (int k = 0; k < D; ++k) {
        if (m.constrained[i] >> k & 1) continue;
        const double f = (m.force[i][k] + m.body_force[i][k]) / fictitious_density_[i] - rigid_i[k];
        double& v = m.velocity[i][k];
        v = it == 0 ? 0.5 * f : ((2.0 - cn) * v + 2.0 * f) / (2.0 + cn);  // eq. 13-14, dt = 1
        m.position[i][k] += v;
        previous[i][k] = f;
      }
    }
    move_with_platens(m, [&](std::size_t i) { return fictitious_density_[i] * m.volume[i]; });
  }
  m.refresh_ghosts(m.position);  // the last iteration's moves
  compute_forces<D>(m, contact);
  for (auto& v : m.velocity) v = Vec<D>{};
  loads.at_equilibrium(m);  // the wet rock feels the fluid of this equilibrium
  return result;
}

template <int D>
RelaxationResult DynamicRelaxation<D>::relax_breaking_at_equilibrium(Model<D>& m, const Loads<D>& loads,
                                                                      Contact<D>* contact, double t, int max_iterations,
                                                                      double tolerance, int max_passes) {
  return breaking_at_equilibrium(m, loads, contact, max_passes, [&] { return relax(m, loads, contact, t, max_iterations, tolerance); });
}

template <int D>
RelaxationResult DynamicRelaxation<D>::breaking_at_equilibrium(Model<D>& m, const Loads<D>& loads, Contact<D>* contact,
                                                               int max_passes, const std::function<RelaxationResult()>& equilibrium) {
  RelaxationResult total;
  total.breaking_passes = 0;
  std::size_t broken_through = loads.broken_through(m);
  int first_pass = 0;
  if (passes_unfinished()) {  // a load step a stop cut short, in its pass `pass`
    first_pass = unfinished_.pass, total.breaking_passes = unfinished_.pass, total.iterations = unfinished_.iterations;
    broken_through = static_cast<std::size_t>(unfinished_.broken_through);
    unfinished_.pass = 0, unfinished_.iterations = 0, unfinished_.broken_through = 0;
  }
  for (int pass = first_pass; pass < max_passes; ++pass) {
    RelaxationResult r;
    {
      HeldBreaking<D> held(m);
      r = equilibrium();
    }
    if (r.stopped) {
      unfinished_.pass = pass, unfinished_.iterations = total.iterations, unfinished_.broken_through = broken_through;
      total.iterations += r.iterations, total.residual = r.residual, total.stopped = true;
      return total;
    }
    total.iterations += r.iterations;
    total.residual = r.residual;
    total.converged = r.converged;
    ++total.breaking_passes;
    if (loads.broken_through(m) > broken_through) break;  // the test is over: no more growth
    const std::size_t before = failed_bonds<D>(m);
    compute_forces<D>(m, contact);  // breaks what is past its limit at this equilibrium
    // (a bond a rank breaks its owner breaks too: every rank of a distributed run goes on alike)
    if (!parallel::Communicator::world().any(failed_bonds<D>(m) != before)) break;
    total.converged = false;  // bonds broke after the last equilibrium (if the passes run out here)
  }
  return total;
}

template class DynamicRelaxation<2>;
template class DynamicRelaxation<3>;

}  // namespace rift::pd
