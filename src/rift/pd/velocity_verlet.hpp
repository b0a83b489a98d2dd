// Explicit dynamics: velocity-Verlet (kick-drift-kick), as LAMMPS fix nve.
//   v(t+dt/2) = v(t) + dt/2 a(t);  x(t+dt) = x(t) + dt v(t+dt/2);  forces;  v(t+dt) = v(t+dt/2) + dt/2 a(t+dt)
#pragma once
#include "rift/pd/contact.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/loads.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

template <int D>
void kick(Model<D>& m, double half_dt) {
  const std::size_t n = m.size();
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const double inv_rho = 1.0 / m.constants_of(i).density;
    for (int k = 0; k < D; ++k) m.velocity[i][k] += half_dt * (m.force[i][k] + m.body_force[i][k]) * inv_rho;
  }
}

template <int D>
void drift(Model<D>& m, double dt) {
  const std::size_t n = m.size();
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < D; ++k) m.position[i][k] += dt * m.velocity[i][k];
}

/// One velocity-Verlet step from m.time to m.time + dt. Forces of m.time must be current.
template <int D>
void velocity_verlet_step(Model<D>& m, const Loads<D>& loads, Contact<D>* contact, double dt) {
  auto mass = [&](std::size_t i) { return m.constants_of(i).density * m.volume[i]; };
  kick<D>(m, 0.5 * dt);
  move_with_platens(m, mass);  // a rigid plate's momentum is its particles' (pd/platens.hpp)
  loads.prescribe_velocity(m, m.time, dt);
  drift<D>(m, dt);
  loads.prescribe_position(m, m.time + dt);
  m.time += dt;
  advance_stretch_limits<D>(m);
  // a distributed run's ghosts are where their owners moved them, with their s0 (pd/window.hpp)
  m.refresh_ghosts(m.position);
  m.refresh_ghosts(m.stretch_limit);
  compute_forces<D>(m, contact, dt);
  loads.apply_body_forces(m, m.time);
  kick<D>(m, 0.5 * dt);
  move_with_platens(m, mass);
  loads.prescribe_velocity(m, m.time, 0.0);
  loads.at_equilibrium(m);  // the wet rock of the next step feels this pressure
}

}  // namespace rift::pd
