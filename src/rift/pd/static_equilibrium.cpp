#include "rift/pd/static_equilibrium.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "rift/core/stop_signal.hpp"
#include "rift/parallel/ordered_sum.hpp"
#include "rift/parallel/team.hpp"
#include "rift/pd/coarse_space.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/ghost_fields.hpp"
#include "rift/pd/platens.hpp"
#include "rift/pd/rigid_motion.hpp"

namespace rift::pd {

template <int D>
RelaxationResult solve_static_equilibrium(Model<D>& m, const Loads<D>& loads, Contact<D>* contact, double t,
                                          const std::vector<double>& diagonal, int max_iterations, double tolerance,
                                          const std::function<void(int, double)>& observe) {
  const std::size_t n = m.size();
  m.time = t;
  loads.prescribe_position(m, t);
  loads.apply_body_forces(m, t);
  for (auto& v : m.velocity) v = Vec<D>{};
  RelaxationResult result;
  result.converged = false;
  double shortest = std::numeric_limits<double>::max();
  for (const auto& f : m.bonds.families) shortest = std::min(shortest, f.length);
  // Sums over the owned particles of every rank (pd/window.hpp), exact (parallel/exact_sum.hpp),
  // and the ghosts' iterates come from their owners, so the iterations are the one-rank run's bits
  // (a rank that owns none goes along).
  const auto& comm = ranks_of<D>(m);
  const std::vector<IndexRange> owned = m.owned();
  const double particles = comm.sum(static_cast<double>(count_of(owned)));  // the whole run's
  if (particles == 0.0 || !(shortest < std::numeric_limits<double>::max())) return result;
  auto sum_over = [&](auto&& f) { return parallel::exact_sums<2>(comm, owned, line_of(m), f); };
  const bool held_here = std::any_of(m.constrained.begin(), m.constrained.end(), [](std::uint8_t c) { return c != 0; });
  const bool free_body = !comm.any(held_here);
  const std::vector<std::uint8_t> on_platen = platen_components(m);
  std::array<int, D> no_platen;
  no_platen.fill(-1);
  std::vector<std::array<int, D>> platen_of(m.platens.empty() ? 0 : n, no_platen);  // each component's plate (an edge's two)
  std::vector<double> platen_weight(m.platens.size(), 0.0);
  for (std::size_t a = 0; a < m.platens.size(); ++a) {
    for (const auto i : m.platens[a].particles) platen_of[i][m.platens[a].axis] = static_cast<int>(a);
    platen_weight[a] = platen_sums<1>(m, m.platens[a], [&](std::size_t i) { return std::array<double, 1>{diagonal[i] * m.volume[i]}; })[0];
  }
  auto weight = [&](std::size_t i) { return diagonal[i] * m.volume[i]; };
  auto held = [&](std::size_t i, int k) { return (m.constrained[i] >> k & 1) != 0; };
  auto moves_with_platen = [&](std::size_t i, int k) { return (on_platen[i] >> k & 1) != 0; };
  // the force on each component that is not held (N), as the evaluation at m.position left it
  auto force = [&](std::size_t i) {
    Vec<D> f{};
    for (int k = 0; k < D; ++k)
      if (!held(i, k)) f[k] = (m.force[i][k] + m.body_force[i][k]) * m.volume[i];
    return f;
  };
  auto evaluate = [&](bool true_state) {
    if (true_state) {
      advance_stretch_limits<D>(m);
      m.refresh_ghosts(m.stretch_limit);
    }
    compute_forces<D>(m, contact);
    if (loads.state_dependent()) loads.apply_body_forces(m, t);  // an injected fluid's pressure follows the cavity
    ++result.iterations;
  };

  std::vector<Vec<D>> x = m.position, base, at_base(n), r(n), p(n, Vec<D>{});
  double reference = 0.0;
  // Newton's step: the forces at the iterate are the new base and residual
  auto linearize = [&] {
    m.position = x;
    evaluate(true);
    base = x;
    auto sums = sum_over([&](std::size_t i, std::array<double, 2>& acc) {
      at_base[i] = force(i);
      r[i] = at_base[i];
      for (int k = 0; k < D; ++k) {
        const double b = m.body_force[i][k] * m.volume[i], f = m.force[i][k] * m.volume[i];
        acc[0] += b * b;
        if (held(i, k)) acc[1] += f * f;  // reactions
      }
    });
    reference = std::sqrt(sums[0]) + std::sqrt(sums[1]);
  };
  // The preconditioned residual z = P (M^-1 + P_c K_c^-1 P_c^T) P^T r: M the diagonal (a platen one
  // unknown), P the projection off a free body's rigid motions, P_c the coarse space of aggregates
  // (coarse_space.hpp, where the body is large enough and has no platen). From the rigid part a of
  // r, the platens' net forces, the coarse solution u_c of P^T r and the rigid part b of u_c:
  // z = r / w - a + u_c - b.
  RigidAcceleration<D> rigid, coarse_rigid;
  std::vector<double> platen_force(m.platens.size());
  CoarseSpace<D> coarse;
  auto prepare = [&] {
    if (free_body) rigid = rigid_acceleration<D>(base, weight, [&](std::size_t i) { return r[i]; }, line_of(m), &comm, owned);
    for (std::size_t a = 0; a < m.platens.size(); ++a) {
      const int k = m.platens[a].axis;
      platen_force[a] = platen_sums<1>(m, m.platens[a], [&](std::size_t i) { return std::array<double, 1>{r[i][k]}; })[0];
    }
    if (!coarse.ready()) return;
    coarse.solve([&](std::size_t i) {
      const Vec<D> rigid_i = free_body ? rigid.at(base[i]) : Vec<D>{};
      Vec<D> y{};
      for (int k = 0; k < D; ++k)
        if (!held(i, k)) y[k] = r[i][k] - weight(i) * rigid_i[k];
      return y;
    });
    if (free_body)
      coarse_rigid = rigid_acceleration<D>(base, weight, [&](std::size_t i) { return weight(i) * coarse.at(i); }, line_of(m), &comm, owned);
  };
  auto preconditioned = [&](std::size_t i) {
    Vec<D> z{};
    const Vec<D> rigid_i = free_body ? rigid.at(base[i]) : Vec<D>{};
    Vec<D> coarse_i{};
    if (coarse.ready()) {
      coarse_i = coarse.at(i);
      if (free_body) coarse_i = coarse_i - coarse_rigid.at(base[i]);
    }
    for (int k = 0; k < D; ++k) {
      if (held(i, k)) continue;
      if (moves_with_platen(i, k)) {
        const auto a = static_cast<std::size_t>(platen_of[i][k]);
        z[k] = platen_weight[a] > 0.0 ? platen_force[a] / platen_weight[a] : 0.0;
      } else {
        z[k] = r[i][k] / weight(i) - rigid_i[k] + coarse_i[k];
      }
    }
    return z;
  };
  // r . z, and the squared residual as relax measures it (free components less the rigid part; a
  // platen's net force)
  auto measure = [&](double& rz) {
    prepare();
    auto sums = sum_over([&](std::size_t i, std::array<double, 2>& acc) {
      const Vec<D> z = preconditioned(i);
      const Vec<D> rigid_i = free_body ? rigid.at(base[i]) : Vec<D>{};
      for (int k = 0; k < D; ++k) {
        acc[0] += r[i][k] * z[k];
        if (held(i, k) || moves_with_platen(i, k)) continue;
        const double free = r[i][k] - weight(i) * rigid_i[k];
        acc[1] += free * free;
      }
    });
    rz = sums[0];
    double squared = sums[1];
    for (const double f : platen_force) squared += f * f;
    return reference > 0.0 ? std::sqrt(squared) / reference : std::sqrt(squared);
  };

  linearize();
  // the coarse operator, probed at the first base: for each colour of aggregates and axis, the
  // forces' change as that colour's aggregates move along the axis by a millionth of the shortest bond
  double reach = 0.0, spacing = std::numeric_limits<double>::max();
  for (const auto& body : m.bodies) reach = std::max(reach, body.constants.horizon), spacing = std::min(spacing, body.constants.spacing);
  if (m.platens.empty() && coarse.make_aggregates(m.reference_position, 2.0 * reach + spacing, comm, owned)) {
    const double probe = 1e-6 * shortest;
    coarse.assemble(held, [&](auto direction) {
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
      for (std::size_t i = 0; i < n; ++i) m.position[i] = base[i] + probe * direction(i);
      evaluate(false);
      return [&](std::size_t i) { return (-1.0 / probe) * (force(i) - at_base[i]); };
    });
  }
  double rz = 0.0, previous_rz = 0.0;
  result.residual = measure(rz);
  // The linear solve at a base goes to a hundredth of the base's residual (Eisenstat and Walker
  // 1996's forcing term, fixed): further, the geometric terms left out (about the strain times the
  // stiffness) are the larger error. The directions go on through a new base (as nonlinear
  // conjugate gradients, Fletcher and Reeves 1964): starting them again cost the thesis example at
  // 2 mm 247 force evaluations against 234.
  constexpr double forcing = 1e-2;
  double newton_at = std::max(tolerance, forcing * result.residual), at_last_base = result.residual;
  // A linear solve takes of the order of the lattice's sites along the body (the square root of
  // K's condition number); many more, and something in the forces switches (a contact): stop.
  const int stage_limit = 100 + static_cast<int>(20.0 * std::pow(particles, 1.0 / D));
  int stage_start = result.iterations;
  bool restart = true;
  while (result.residual >= tolerance && result.iterations < max_iterations && result.iterations - stage_start < stage_limit) {
    if (comm.any(stop_signal() != 0)) {  // every rank stops at the same iteration
      result.stopped = true;
      break;
    }
    // p = z + beta p (beta = 0 on a restart)
    const double beta = restart ? 0.0 : rz / previous_rz;
    restart = false;
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
    for (std::size_t i = 0; i < n; ++i) p[i] = preconditioned(i) + beta * p[i];
    m.refresh_ghosts(p);  // a ghost's preconditioned residual is its owner's to make
    double largest = 0.0;
    for (const IndexRange& r : owned)
      for (std::size_t i = r.first; i < r.last; ++i)
        for (int k = 0; k < D; ++k) largest = std::max(largest, std::abs(p[i][k]));
    largest = comm.max(largest);
    if (!(largest > 0.0) || !std::isfinite(largest)) break;
    // K p from a probe of a millionth of the shortest bond at the base
    const double probe = 1e-6 * shortest / largest;
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
    for (std::size_t i = 0; i < n; ++i) m.position[i] = base[i] + probe * p[i];
    evaluate(false);
    auto kp = [&](std::size_t i) { return (-1.0 / probe) * (force(i) - at_base[i]); };
    const double pkp = sum_over([&](std::size_t i, std::array<double, 2>& acc) { acc[0] += dot<D>(p[i], kp(i)); })[0];
    if (!(pkp > 0.0) || !std::isfinite(pkp)) break;  // not positive along p: no longer a held elastic body
    const double alpha = rz / pkp;
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = x[i] + alpha * p[i];
      r[i] = r[i] - alpha * kp(i);
    }
    previous_rz = rz;
    result.residual = measure(rz);
    if (result.residual < newton_at) {  // the linear residual is under: Newton's step
      linearize();
      result.residual = measure(rz);
      newton_at = std::max(tolerance, forcing * result.residual);
      if (!(result.residual < 0.5 * at_last_base)) break;  // Newton's steps no longer converge
      at_last_base = result.residual, stage_start = result.iterations;
    }
    if (observe) observe(result.iterations, result.residual);
  }
  result.converged = result.residual < tolerance;
  m.position = result.converged ? x : base;  // where stopped short: the last evaluated iterate
  advance_stretch_limits<D>(m);
  m.refresh_ghosts(m.stretch_limit);
  compute_forces<D>(m, contact);
  loads.apply_body_forces(m, t);
  for (auto& v : m.velocity) v = Vec<D>{};
  if (result.converged) loads.at_equilibrium(m);  // the wet rock feels the fluid of this equilibrium
  return result;
}

template RelaxationResult solve_static_equilibrium<2>(Model<2>&, const Loads<2>&, Contact<2>*, double, const std::vector<double>&,
                                                       int, double, const std::function<void(int, double)>&);
template RelaxationResult solve_static_equilibrium<3>(Model<3>&, const Loads<3>&, Contact<3>*, double, const std::vector<double>&,
                                                       int, double, const std::function<void(int, double)>&);

}  // namespace rift::pd
