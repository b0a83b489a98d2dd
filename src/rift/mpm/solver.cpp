#include "rift/mpm/solver.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

#include "rift/core/error.hpp"
#include "rift/geometry/region.hpp"
#include "rift/scene/time_function.hpp"
#include "rift/scene/traction_layer.hpp"
#include "rift/mpm/energy.hpp"
#include "rift/mpm/stencil.hpp"
#include "rift/parallel/shared_blocks.hpp"
#include "rift/parallel/team.hpp"

namespace rift::mpm {

namespace {

template <int D>
std::vector<std::size_t> nodes_in(const scene::Scene& s, const Grid<D>& g, const std::string& region) {
  return geometry::indices_inside<D>(geometry::Region::build(s, region), g.size(), [&](std::size_t n) { return g.node_position(n); });
}

template <int D>
std::vector<std::size_t> particles_in(const scene::Scene& s, const Particles<D>& ps, const std::string& region) {
  return geometry::indices_inside<D>(geometry::Region::build(s, region), ps.size(),
                                     [&](std::size_t i) { return ps.reference_position[i]; });
}

}  // namespace

template <int D>
Solver<D>::Solver(const scene::Scene& s, Model<D>& m) : settings_(s.mpm) {
  using K = scene::BoundaryKind;
  for (std::size_t bi = 0; bi < s.boundaries.size(); ++bi) {
    const auto& b = s.boundaries[bi];
    const std::string key = "boundaries[" + std::to_string(bi) + "]";
    if (b.kind == K::displacement)
      throw SceneError(b.where, key + ".type", "the material point method takes fixed or velocity conditions on grid nodes, "
                                               "traction or body_force on particles (not displacement)");
    if (b.kind == K::fixed || b.kind == K::velocity) {
      GridCondition c;
      c.nodes = nodes_in<D>(s, m.grid, b.region);
      if (c.nodes.empty()) throw SceneError(b.where, key + ".region", "region \"" + b.region + "\" holds no grid node");
      for (int a = 0; a < D; ++a) c.value[a] = b.kind == K::fixed ? std::optional<double>(0.0) : b.value[a];
      c.time = b.time;
      conditions_.push_back(std::move(c));
    } else {
      ParticleLoad l;
      l.particles = particles_in<D>(s, m.particles, b.region);
      if (l.particles.empty()) throw SceneError(b.where, key + ".region", "region \"" + b.region + "\" selects no material point");
      const double depth = b.layer_depth > 0 ? b.layer_depth : s.mpm.cell_size;
      if (b.kind == K::traction)
        for (auto p : l.particles) {
          const double spacing = s.mpm.cell_size / s.bodies[m.particles.body[p]].particles_per_cell;
          if (depth < (1.0 - 1e-9) * spacing) throw SceneError(b.where, key + ".layer_depth", scene::thinner_than_a_row(depth, spacing));
        }
      for (int a = 0; a < D; ++a) l.density[a] = b.value[a].value_or(0.0) / (b.kind == K::traction ? depth : 1.0);
      l.time = b.time;
      loads_.push_back(std::move(l));
    }
  }
  if (!s.cracks.empty()) {
    if constexpr (D == 3) {
      throw SceneError(s.cracks.front().where, "cracks", "explicit cracks in the material point method are 2D (polylines)");
    } else {
      if (s.mpm.contact != scene::Mpm::Contact::none && s.bodies.size() > 1)
        throw SceneError(s.cracks.front().where, "cracks", "explicit cracks with multi-material contact are not available yet; use one body or [mpm] contact = \"none\"");
      cracks_ = CrackSet(s, m.grid.cell_size);
      crack_contact_ = s.mpm.crack_contact;
      // a crack segment lying on a grid line leaves nodes on the crack itself; CRAMP then goes
      // unstable, so ask for the half-cell shift that avoids it
      for (std::size_t c = 0; c < s.cracks.size(); ++c) {
        const auto& pts = s.cracks[c].points;
        for (std::size_t k = 0; k + 1 < pts.size(); ++k)
          for (int a = 0; a < 2; ++a) {
            const double u0 = (pts[k][a] - m.grid.origin[a]) / m.grid.cell_size, u1 = (pts[k + 1][a] - m.grid.origin[a]) / m.grid.cell_size;
            if (std::abs(u0 - u1) < 1e-9 && std::abs(u0 - std::round(u0)) < 1e-6)
              throw SceneError(s.cracks[c].where, "cracks[" + std::to_string(c) + "].points",
                               std::string("a crack segment lies on a grid line (") + (a == 0 ? "x" : "y") + " = " +
                                   std::to_string(pts[k][a]) + " m); shift it or [mpm] grid_min by half a cell");
          }
      }
    }
  }
  thread_buffers_.resize(static_cast<std::size_t>(omp_get_max_threads()));
  index_conditions(m.grid.size());
  for (auto& l : loads_) l.ids.assign(l.particles.begin(), l.particles.end());
  tiny_mass_ = 1e-12 * (m.particles.size() ? m.particles.mass[0] : 1.0);
  cell_volume_ = std::pow(m.grid.cell_size, D) * (D == 2 ? s.thickness : 1.0);
}

template <int D>
void Solver<D>::index_conditions(std::size_t nodes) {
  // the conditions of each node, for the node-by-node grid passes
  node_conditions_.first.assign(nodes + 1, 0);
  for (const auto& c : conditions_)
    for (auto node : c.nodes) ++node_conditions_.first[node + 1];
  for (std::size_t node = 0; node < nodes; ++node) node_conditions_.first[node + 1] += node_conditions_.first[node];
  node_conditions_.condition.resize(node_conditions_.first.back());
  auto next = node_conditions_.first;
  for (std::size_t c = 0; c < conditions_.size(); ++c)
    for (auto node : conditions_[c].nodes) node_conditions_.condition[next[node]++] = static_cast<std::uint32_t>(c);
}

template <int D>
void Solver<D>::select_loads(const std::vector<std::uint64_t>& id) {
  for (auto& l : loads_) {
    l.particles.clear();
    for (std::size_t p = 0; p < id.size(); ++p)
      if (std::binary_search(l.ids.begin(), l.ids.end(), id[p])) l.particles.push_back(p);
  }
}

template <int D>
void Solver<D>::distribute(const Model<D>& whole, const Model<D>& part, Domain<D>& domain) {
  domain_ = &domain;
  // the grid conditions' nodes in this rank's part of the grid
  const auto& wg = whole.grid;
  const auto& pg = part.grid;
  for (auto& c : conditions_) {
    std::vector<std::size_t> mine;
    for (auto n : c.nodes) {
      long rest = static_cast<long>(n), ijk[3];
      ijk[0] = rest % wg.nodes[0], rest /= wg.nodes[0];
      ijk[1] = rest % wg.nodes[1], ijk[2] = rest / wg.nodes[1];
      bool inside = true;
      for (int a = 0; a < 3; ++a) ijk[a] -= pg.offset[a], inside = inside && ijk[a] >= 0 && ijk[a] < pg.nodes[a];
      if (inside) mine.push_back(pg.index(ijk[0], ijk[1], ijk[2]));
    }
    c.nodes = std::move(mine);
  }
  index_conditions(pg.size());
  select_loads(domain.id());
}

template <int D>
double Solver<D>::stable_time_step(const Model<D>& m) const {
  double c = 0.0, v = 0.0;
  for (const auto& b : m.bodies) c = std::max(c, b.constants.wave_speed());
  for (const auto& u : m.particles.velocity) v = std::max(v, norm<D>(u));
  return m.grid.cell_size / (c + v);
}

template <int D>
template <class BeforePoint>
void Solver<D>::scatter(Model<D>& m, bool momentum_only, bool internal_force, BeforePoint before_point) {
  auto& ps = m.particles;
  auto& g = m.grid;
  const std::size_t fields = static_cast<std::size_t>(g.fields);
  const bool normals = fields > 1 && !momentum_only;
  const bool apic = settings_.transfer == scene::Mpm::Transfer::apic;
  const bool external = !loads_.empty();
  const std::size_t n_points = stencils_.size();
  // One team for the whole transfer. Thread t takes a fixed block of points and sums their shares
  // into its own buffer, over the slots its block reaches: [first, last) from the stencils (their
  // nodes come in increasing order), zeroed by the thread itself. The buffers are then summed slot
  // by slot in thread order, so a run is bit-reproducible for a given thread count. A body's points
  // are laid out row by row (discretize.cpp), so a block reaches a band of grid rows, and the bands
  // of neighbouring blocks overlap only at their edges. before_point(p, stencil) runs on each point
  // just before its shares are taken (MUSL's grid-to-particle update, step()). momentum_only:
  // MUSL's remap, which sums the new momenta alone; the masses are the step's first transfer's, the
  // same points, weights and order giving the same sums bit for bit.
  const int team = rift::parallel::worth_a_team(n_points) ? static_cast<int>(thread_buffers_.size()) : 1;
  int used = 1;
  slot_blocks_.split(g.slots(), static_cast<std::size_t>(team));
#pragma omp parallel num_threads(team) if(team > 1)
  {
    const int threads = omp_get_num_threads();
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
#pragma omp single
    used = threads;
    auto& buffer = thread_buffers_[t];
    const std::size_t p_begin = n_points * t / static_cast<std::size_t>(threads);
    const std::size_t p_end = n_points * (t + 1) / static_cast<std::size_t>(threads);
    std::size_t first = g.slots(), last = 0;
    for (std::size_t p = p_begin; p < p_end; ++p) {
      const auto st = stencils_[p];
      if (st.count == 0) continue;
      first = std::min(first, st.node[0] * fields);
      last = std::max(last, (st.node[static_cast<std::size_t>(st.count - 1)] + 1) * fields);
    }
    buffer.first = first, buffer.last = std::max(first, last);
    buffer.resize(g.slots());
    const auto zero = [&](auto& values) { std::fill(values.begin() + first, values.begin() + buffer.last, std::decay_t<decltype(values[0])>{}); };
    zero(buffer.momentum);
    if (!momentum_only) zero(buffer.mass), zero(buffer.force);
    if (normals) zero(buffer.mass_gradient), zero(buffer.volume), zero(buffer.displacement);
    // The point loop, compiled apart for the plain transfer (one velocity field, no APIC, no loads):
    // the flags are the same for every point, and without them the loop keeps its pointers in
    // registers (the 2D linear beam's scatter: 385 instructions a point with the flags read per node).
    auto accumulate = [&](auto plain_transfer) {
      constexpr bool plain = decltype(plain_transfer)::value;
      for (std::size_t p = p_begin; p < p_end; ++p) {
        const auto st = stencils_[p];
        before_point(p, st);
        const double mp = ps.mass[p], volume = ps.volume[p];
        const Vec<D> vp = ps.velocity[p];
        // read only by the forces' scatter: MUSL's remap does not touch the points' states
        const Tensor<D> sigma = internal_force ? ps.state[p].stress : Tensor<D>::Zero();
        for (int q = 0; q < st.count; ++q) {
          const std::size_t node = st.node[static_cast<std::size_t>(q)];
          const std::size_t n = plain ? node : node * fields + field_of(m, p, q);
          const double w = st.weight[static_cast<std::size_t>(q)];
          if (w == 0.0) continue;
          Vec<D> v = vp;
          if (!plain && apic) {
            const Vec<D> dx = g.node_position(node) - start_position_[p];
            for (int a = 0; a < D; ++a)
              for (int b = 0; b < D; ++b) v[a] += ps.affine_velocity[p](a, b) * dx[b];
          }
          for (int a = 0; a < D; ++a) buffer.momentum[n][a] += w * mp * v[a];
          if (!plain && normals) {
            for (int a = 0; a < D; ++a) buffer.mass_gradient[n][a] += mp * st.gradient[static_cast<std::size_t>(q)][a];
            buffer.volume[n] += w * volume;
            for (int a = 0; a < D; ++a) buffer.displacement[n][a] += w * mp * (start_position_[p][a] - ps.reference_position[p][a]);
          }
          if (momentum_only) continue;
          buffer.mass[n] += w * mp;
          if (!plain && external)
            for (int a = 0; a < D; ++a) buffer.force[n][a] += w * ps.external_force[p][a];
          if (internal_force) {
            const auto& grad = st.gradient[static_cast<std::size_t>(q)];
            for (int a = 0; a < D; ++a) {
              double f = 0.0;
              for (int b = 0; b < D; ++b) f += sigma(a, b) * grad[b];
              buffer.force[n][a] -= volume * f;
            }
          }
        }
      }
    };
    if (!apic && !external && one_velocity_field(m)) accumulate(std::true_type{});
    else accumulate(std::false_type{});
#pragma omp barrier
    // sum the buffers that reach each slot, in thread order
    slot_blocks_.take(t, [&](std::size_t n) {
      double mass = 0.0, volume = 0.0;
      Vec<D> mom{}, f{}, grad{}, u{};
      for (std::size_t b = 0; b < static_cast<std::size_t>(used); ++b) {
        const auto& tb = thread_buffers_[b];
        if (n < tb.first || n >= tb.last) continue;
        for (int a = 0; a < D; ++a) mom[a] += tb.momentum[n][a];
        if (!momentum_only) {
          mass += tb.mass[n];
          for (int a = 0; a < D; ++a) f[a] += tb.force[n][a];
        }
        if (normals) {
          for (int a = 0; a < D; ++a) grad[a] += tb.mass_gradient[n][a], u[a] += tb.displacement[n][a];
          volume += tb.volume[n];
        }
      }
      g.momentum[n] = mom;
      if (!momentum_only) g.mass[n] = mass, g.force[n] = f;
      if (normals) g.mass_gradient[n] = grad, g.volume[n] = volume, g.displacement[n] = u;
    });
  }
  // a distributed run: the neighbours' parts of the sums at the shared nodes (domain.hpp)
  if (domain_) domain_->sum_shared_nodes(g, !momentum_only, !momentum_only, normals);
}

template <int D>
void Solver<D>::apply_grid_conditions(Model<D>& m, std::size_t node, const std::vector<double>& amplitude) const {
  auto& g = m.grid;
  for (auto c = node_conditions_.first[node]; c < node_conditions_.first[node + 1]; ++c) {
    const auto& condition = conditions_[node_conditions_.condition[c]];
    const double amp = amplitude[node_conditions_.condition[c]];
    for (int f = 0; f < g.fields; ++f) {
      const std::size_t n = node * static_cast<std::size_t>(g.fields) + static_cast<std::size_t>(f);
      for (int a = 0; a < D; ++a)
        if (condition.value[a]) {
          g.velocity[n][a] = amp * *condition.value[a];
          g.momentum[n][a] = g.mass[n] * g.velocity[n][a];
        }
    }
  }
}

template <int D>
std::vector<double> Solver<D>::condition_amplitudes(double t) const {
  std::vector<double> amplitude(conditions_.size());
  for (std::size_t c = 0; c < conditions_.size(); ++c) amplitude[c] = scene::evaluate(conditions_[c].time, t);
  return amplitude;
}

template <int D>
bool Solver<D>::one_velocity_field(const Model<D>& m) const {
  if constexpr (D == 2) {
    if (!cracks_.empty()) return false;
  }
  return m.grid.fields == 1;
}

template <int D>
std::size_t Solver<D>::field_of(const Model<D>& m, std::size_t p, int q) const {
  if constexpr (D == 2) {
    if (!cracks_.empty())
      return near_crack_[p] ? crack_field_[p * Stencil<D>::capacity + static_cast<std::size_t>(q)] : 0;
  }
  return m.grid.fields > 1 ? m.particles.body[p] : 0;
}

template <int D>
bool Solver<D>::apply_contact(Model<D>& m, std::size_t node) const {
  // Multi-material contact (Bardenhagen et al. 2001): at a node where two or more bodies have mass,
  // a body approaching the others along the contact normal gets the normal part of its velocity
  // relative to the centre of mass removed (frictionless), also its tangential part within the
  // Coulomb limit (friction), or all of it (stick). The normal of body f points from f to the
  // others: n = (grad m_others - grad m_f) / |.|, equal and opposite for two bodies, so the
  // corrections conserve momentum.
  auto& g = m.grid;
  const std::size_t fields = static_cast<std::size_t>(g.fields);
  const double tiny = tiny_mass_;
  using C = scene::Mpm::Contact;
  const std::size_t base = node * fields;
  int present = 0;
  double mass = 0.0, volume = 0.0;
  Vec<D> momentum{}, gradient{};
  for (std::size_t f = 0; f < fields; ++f) {
    if (g.mass[base + f] <= tiny) continue;
    ++present;
    mass += g.mass[base + f];
    volume += g.volume[base + f];
    for (int a = 0; a < D; ++a) momentum[a] += g.momentum[base + f][a], gradient[a] += g.mass_gradient[base + f][a];
  }
  if (present < 2) return false;
  scene::Mpm::Contact kind = settings_.contact;
  Vec<D> crack_normal{};  // crack faces: the crack's normal, pointing to its "above" side
  bool node_above = false;
  if constexpr (D == 2) {
    if (!cracks_.empty()) {
      kind = crack_contact_;
      if (kind == C::none) return false;
      const auto near = cracks_.nearest(g.node_position(node));
      crack_normal = cracks_.normal(near.crack, near.particle);
      node_above = dot<D>(g.node_position(node) - cracks_.cracks()[near.crack].points[near.particle], crack_normal) >= 0.0;
      // the faces touch only where the crack is closed: the displacements of the material above
      // and below, extrapolated to this node, must not have opened it (the displacement check of
      // Guo and Nairn 2006, sec. 2; the crack starts closed). Field 1 is above material, field 2
      // below, field 0 the node's own side.
      const std::size_t above = g.mass[base + 1] > tiny ? 1 : node_above ? 0 : fields;
      const std::size_t below = g.mass[base + 2] > tiny ? 2 : !node_above ? 0 : fields;
      if (above == fields || below == fields) return false;
      const Vec<D> u_above = (1.0 / g.mass[base + above]) * g.displacement[base + above];
      const Vec<D> u_below = (1.0 / g.mass[base + below]) * g.displacement[base + below];
      if (dot<D>(u_above - u_below, crack_normal) > 0.0) return false;
    }
  }
  // bodies touch at this node only when together they fill its cell (their stencils already
  // overlap a couple of cells before they meet)
  if (cracks_.empty() && volume < contact_volume_ * cell_volume_) return false;
  const Vec<D> v_cm = (1.0 / mass) * momentum;
  for (std::size_t f = 0; f < fields; ++f) {
    const std::size_t n = base + f;
    if (g.mass[n] <= tiny) continue;
    Vec<D> normal;
    if (!cracks_.empty()) {
      // field 1 holds the material above the crack, field 2 below, field 0 the node's own side;
      // each is pushed toward the other face
      const bool above = f == 1 || (f == 0 && node_above);
      normal = (above ? -1.0 : 1.0) * crack_normal;
    } else {
      // mass_gradient holds sum m_p dS/dx_p = -grad m (the gradient with respect to the node is the
      // opposite), so grad m_others - grad m_f = 2 mass_gradient_f - sum of all
      normal = 2.0 * g.mass_gradient[n] - gradient;
      const double length = norm<D>(normal);
      if (length == 0.0) continue;
      normal = (1.0 / length) * normal;
    }
    const Vec<D> dv = g.velocity[n] - v_cm;
    const double approach = dot<D>(dv, normal);
    if (approach <= 0.0) continue;  // separating: free
    Vec<D> correction = approach * normal;
    if (kind == C::stick) {
      correction = dv;
    } else if (kind == C::friction) {
      const Vec<D> tangential = dv - approach * normal;
      const double slip = norm<D>(tangential);
      const double limit = settings_.friction * approach;
      if (slip > 0.0) correction = correction + (slip <= limit ? 1.0 : limit / slip) * tangential;
    }
    g.velocity[n] = g.velocity[n] - correction;
    g.momentum[n] = g.mass[n] * g.velocity[n];
  }
  return true;
}

template <int D>
void Solver<D>::node_velocities(Model<D>& m, std::size_t node, double tiny, bool record_start, bool contact,
                                const std::vector<double>& amplitude) {
  auto& g = m.grid;
  const std::size_t fields = static_cast<std::size_t>(g.fields);
  for (std::size_t n = node * fields; n < (node + 1) * fields; ++n) {
    for (int a = 0; a < D; ++a) g.velocity[n][a] = g.mass[n] > tiny ? g.momentum[n][a] / g.mass[n] : 0.0;
    // FLIP increments are taken from the plain projection, so that contact and boundary
    // corrections reach the particles too
    if (record_start) g.velocity_start[n] = g.velocity[n];
  }
  if (fields > 1 && contact) touching_[node] = apply_contact(m, node);
  apply_grid_conditions(m, node, amplitude);
}

template <int D>
void Solver<D>::grid_velocities(Model<D>& m, double t, bool record_start, bool contact, bool restore_stage) {
  auto& g = m.grid;
  const double tiny = tiny_mass_;
  const std::size_t fields = static_cast<std::size_t>(g.fields);
  const auto amplitude = condition_amplitudes(t);
  if (fields > 1 && contact) touching_.resize(g.size());
  rift::parallel::for_each_in_shared_blocks(g.size(), [&](std::size_t node) {
    node_velocities(m, node, tiny, record_start, contact, amplitude);
    if (restore_stage && touching_[node])
      for (std::size_t n = node * fields; n < (node + 1) * fields; ++n) g.velocity[n] = stage_velocity_[n];
  });
}

template <int D>
void Solver<D>::grid_update(Model<D>& m, double t, double dt) {
  // node by node (every part is local to a node): velocities at t^n from the scattered momenta,
  // contact and conditions; the momentum update with mass-proportional damping,
  // dp/dt = f - damping p; velocities at t^n+1, contact and conditions again
  auto& g = m.grid;
  const double tiny = tiny_mass_, alpha = settings_.damping;
  const std::size_t fields = static_cast<std::size_t>(g.fields);
  const auto amplitude_start = condition_amplitudes(t), amplitude_end = condition_amplitudes(t + dt);
  if (fields > 1) touching_.resize(g.size());
  const bool keep_stage = fields > 1 && settings_.scheme == scene::Mpm::Scheme::musl;
  if (keep_stage) stage_velocity_.resize(g.slots());
  rift::parallel::for_each_in_shared_blocks(g.size(), [&](std::size_t node) {
    node_velocities(m, node, tiny, true, true, amplitude_start);
    for (std::size_t n = node * fields; n < (node + 1) * fields; ++n)
      for (int a = 0; a < D; ++a) g.momentum[n][a] += dt * (g.force[n][a] - alpha * g.momentum[n][a]);
    node_velocities(m, node, tiny, false, true, amplitude_end);
    // MUSL: the velocities the points move with, kept where the fields touch (step())
    if (keep_stage && touching_[node])
      for (std::size_t n = node * fields; n < (node + 1) * fields; ++n) stage_velocity_[n] = g.velocity[n];
  });
}

template <int D>
void Solver<D>::update_stress(Model<D>& m, double dt) {
  auto& ps = m.particles;
  // compiled apart for one velocity field, as the scatter's point loop is
  auto each_point = [&](auto plain_transfer) {
    constexpr bool plain = decltype(plain_transfer)::value;
    for_each_cached_stencil<D>(stencils_, [&](std::size_t p, const auto& st) {
      const std::size_t fields = static_cast<std::size_t>(m.grid.fields);
      Tensor<D> L = Tensor<D>::Zero();  // velocity gradient L_ab = sum v_a dS/dx_b
      for (int q = 0; q < st.count; ++q) {
        const std::size_t node = st.node[static_cast<std::size_t>(q)];
        const auto& v = m.grid.velocity[plain ? node : node * fields + field_of(m, p, q)];
        const auto& grad = st.gradient[static_cast<std::size_t>(q)];
        for (int a = 0; a < D; ++a)
          for (int b = 0; b < D; ++b) L(a, b) += v[a] * grad[b];
      }
      if (!velocity_gradient_.empty()) velocity_gradient_[p] = L;
      Tensor<D>& F = ps.deformation_gradient[p];
      F = (Tensor<D>::Identity() + dt * L) * F;
      ps.volume[p] = ps.reference_volume[p] * F.determinant();
      material::update_stress<D>(m.bodies[ps.body[p]].constants, ps.state[p], L, F, dt);
    });
  };
  if (one_velocity_field(m)) each_point(std::true_type{});
  else each_point(std::false_type{});
}

template <int D>
void Solver<D>::step(Model<D>& m, double dt) {
  auto& ps = m.particles;
  auto& g = m.grid;
  const double t = m.time;
  if (domain_ && domain_->migrate(m)) select_loads(domain_->id());
  stencils_.fill(m, ps.position, &start_position_);  // S_ip(x_p^n) for every transfer of the step, and x_p^n
  if constexpr (D == 2) {
    if (!cracks_.empty()) {
      // points farther than the stencil reach (2 cells) from every crack's box see no crack
      near_crack_.resize(ps.size());
      crack_field_.resize(ps.size() * Stencil<D>::capacity);
      acceleration_.resize(ps.size());
      velocity_gradient_.resize(ps.size());
      const double reach = 2.0 * g.cell_size;
#pragma omp parallel for if(rift::parallel::worth_a_team(ps.size())) schedule(static)
      for (std::size_t p = 0; p < ps.size(); ++p) {
        near_crack_[p] = cracks_.near(ps.position[p], reach);
        if (!near_crack_[p]) continue;
        const auto st = stencils_[p];
        for (int q = 0; q < st.count; ++q)
          crack_field_[p * Stencil<D>::capacity + static_cast<std::size_t>(q)] =
              static_cast<std::uint8_t>(cracks_.field(ps.position[p], g.node_position(st.node[static_cast<std::size_t>(q)])));
      }
    }
  }
  const bool measure = measure_;
  measure_ = false;
  if (measure) {
    start_velocity_ = ps.velocity;
    energy_.time = t;
    energy_.strain = summarize<D>(m).strain;
  }
  // external forces of the step (without loads they stay the zeros discretize() gave them)
  if (!loads_.empty()) {
    for (auto& f : ps.external_force) f = Vec<D>{};
    for (const auto& l : loads_) {
      const double amp = scene::evaluate(l.time, t);
      for (auto p : l.particles)
        for (int a = 0; a < D; ++a) ps.external_force[p][a] += amp * l.density[a] * ps.volume[p];
    }
  }
  using S = scene::Mpm::Scheme;
  if (settings_.scheme == S::usf) {
    scatter(m, false, false);
    grid_velocities(m, t, false);
    update_stress(m, dt);
    scatter(m, false, true);  // forces from the updated stress (mass and momentum unchanged)
  } else {
    scatter(m, false, true);
  }
  grid_update(m, t, dt);
  // grid to particles, one point at a time; compiled apart for the plain transfer (one velocity
  // field, no APIC), as the scatter's point loop is
  const bool apic = settings_.transfer == scene::Mpm::Transfer::apic;
  const double flip = settings_.flip_fraction, alpha = settings_.damping;
  auto grid_to_particle_of = [&](auto plain_transfer) {
    using Plain = decltype(plain_transfer);
    return [&](std::size_t p, const auto& st) {
      constexpr bool plain = Plain::value;
      const std::size_t fields = static_cast<std::size_t>(g.fields);
      Vec<D> pic{}, increment{}, start{};
      Tensor<D> B = Tensor<D>::Zero(), Dp = Tensor<D>::Zero();
      for (int q = 0; q < st.count; ++q) {
        const std::size_t node = st.node[static_cast<std::size_t>(q)];
        const std::size_t n = plain ? node : node * fields + field_of(m, p, q);
        const double w = st.weight[static_cast<std::size_t>(q)];
        for (int a = 0; a < D; ++a) {
          pic[a] += w * g.velocity[n][a];
          start[a] += w * g.velocity_start[n][a];
          increment[a] += w * (g.velocity[n][a] - g.velocity_start[n][a]);
        }
        if (!plain && apic) {
          const Vec<D> dx = g.node_position(node) - start_position_[p];
          for (int a = 0; a < D; ++a)
            for (int b = 0; b < D; ++b) B(a, b) += w * g.velocity[n][a] * dx[b], Dp(a, b) += w * dx[a] * dx[b];
        }
      }
      if (!plain && apic) {
        ps.velocity[p] = pic;
        ps.affine_velocity[p] = B * Dp.inverse();  // C = B D^-1 (Jiang et al. 2015)
      } else {
        // FLIP keeps the part of v_p the grid does not see; the grid's damping does not reach it, so
        // it is damped here at the same rate (else a damped run settles on the grid but its
        // particles keep their noise)
        for (int a = 0; a < D; ++a)
          ps.velocity[p][a] = flip * (ps.velocity[p][a] + increment[a] - dt * alpha * (ps.velocity[p][a] - start[a])) + (1.0 - flip) * pic[a];
      }
      for (int a = 0; a < D; ++a) ps.position[p][a] += dt * pic[a];
      if (!acceleration_.empty()) acceleration_[p] = (1.0 / dt) * increment;
    };
  };
  auto to_particles = [&](auto grid_to_particle) {
    if (settings_.scheme == S::musl) {
      // MUSL: the new particle momenta back to the grid (Sulsky et al. 1995), each point's as soon
      // as it is known, in the same pass (its stencil read once). Neither moving the cracks nor
      // the energy below reads the grid's momenta, which this changes.
      scatter(m, true, false, grid_to_particle);
    } else {
      for_each_cached_stencil<D>(stencils_, grid_to_particle);
    }
  };
  if (!apic && one_velocity_field(m)) to_particles(grid_to_particle_of(std::true_type{}));
  else to_particles(grid_to_particle_of(std::false_type{}));
  if constexpr (D == 2) {
    if (!cracks_.empty()) move_cracks(m, dt);
  }
  if (measure) {
    energy_.kinetic = parallel::ordered_sums<1>(ps.size(), [&](std::size_t p, std::array<double, 1>& acc) {
      acc[0] += 0.5 * ps.mass[p] * dot<D>(start_velocity_[p], ps.velocity[p]);
    })[0];
    if (domain_) {  // every rank's points
      double sums[2] = {energy_.kinetic, energy_.strain};
      domain_->communicator().sum(sums, 2);
      energy_.kinetic = sums[0], energy_.strain = sums[1];
    }
  }
  if (settings_.scheme == S::usl) {
    update_stress(m, dt);
  } else if (settings_.scheme == S::musl) {
    // where the fields touch (closed crack faces, bodies in contact) the strain rate comes from
    // the contact-corrected velocities the points moved with (kept by grid_update): remapped ones
    // differ in their normal parts by the FLIP history, and contact, which only removes approach,
    // would ratchet the faces open. Elsewhere the fields are independent and take the remapped
    // velocities like every other node: a field holding only the edge of a few points' support
    // would otherwise feed f / m_field (unbounded as m_field -> 0) into the stress and go unstable.
    grid_velocities(m, t + dt, false, false, g.fields > 1);
    update_stress(m, dt);
  }
  m.time = t + dt;
}

template <int D>
template <class Weighted>
std::optional<Vec<2>> Solver<D>::side_mean(const Model<D>& m, const Vec<2>& x, const Vec<2>* probe, Weighted weighted) const {
  if constexpr (D == 2) {
    // sum S_i q_i / sum S_i m_i over the stencil of x, q_i a mass-weighted nodal quantity: light
    // nodes (across the crack, where only the edge of a few points' support reaches) carry erratic
    // values and little weight
    const auto& g = m.grid;
    const std::size_t fields = static_cast<std::size_t>(g.fields);
    Stencil<2> st;
    if (!make_stencil<2>(m, x, st)) return std::nullopt;
    Vec<2> sum{};
    double mass = 0.0;
    for (int q = 0; q < st.count; ++q) {
      const std::size_t node = st.node[static_cast<std::size_t>(q)];
      const double w = st.weight[static_cast<std::size_t>(q)];
      const std::size_t first = probe ? static_cast<std::size_t>(cracks_.field(*probe, g.node_position(node))) : 0;
      const std::size_t last = probe ? first + 1 : fields;
      for (std::size_t f = first; f < last; ++f) {
        const std::size_t n = node * fields + f;
        mass += w * g.mass[n];
        sum = sum + w * weighted(n);
      }
    }
    if (mass <= 0.0) return std::nullopt;
    return (1.0 / mass) * sum;
  }
  return std::nullopt;
}

template <int D>
bool Solver<D>::faces_closed(const Model<D>& m, std::size_t c, std::size_t k) const {
  if constexpr (D == 2) {
    if (crack_contact_ == scene::Mpm::Contact::none || m.grid.displacement.empty()) return false;
    // the contact test at a point: displacements of the material on each side, extrapolated to
    // the crack particle through the nodes of its stencil
    const auto& g = m.grid;
    const Vec<2> x = cracks_.cracks()[c].points[k];
    const double eps = 1e-6 * g.cell_size;
    const Vec<2> above = cracks_.side_point(c, k, x, 1, eps), below = cracks_.side_point(c, k, x, 2, eps);
    auto displacement = [&](std::size_t n) { return g.displacement[n]; };  // sum m_p u_p S_ip already
    const auto u_above = side_mean(m, x, &above, displacement), u_below = side_mean(m, x, &below, displacement);
    if (!u_above || !u_below) return false;
    return dot<2>(*u_above - *u_below, cracks_.normal(c, k)) <= 0.0;
  }
  return false;
}

template <int D>
void Solver<D>::move_cracks(const Model<D>& m, double dt) {
  if constexpr (D == 2) {
    // crack particles move with the centre-of-mass velocity of the nodes, each surface with the
    // field it belongs to: the field a point just above (below) the crack would use
    const auto& g = m.grid;
    // velocity at x: the stencil's momenta over its masses (v = sum S_i p_i / sum S_i m_i), of all
    // fields or of the side seen from `probe`
    auto velocity = [&](const Vec<2>& x, const Vec<2>* probe) {
      return side_mean(m, x, probe, [&](std::size_t n) { return g.mass[n] * g.velocity[n]; }).value_or(Vec<2>{});
    };
    auto& cracks = cracks_.cracks();
    for (std::size_t c = 0; c < cracks.size(); ++c) {
      auto& crack = cracks[c];
      const std::size_t n = crack.points.size();
      std::vector<Vec<2>> v_mid(n), v_up(n), v_down(n);
      const double eps = 1e-6 * g.cell_size;
      // a crack particle's three velocities take three stencils and their crossing tests against the
      // crack: the work of some tens of grid-node updates, so a few dozen particles fill a team
      // (a distributed run: the rank whose box holds a position, whose grid holds its stencil, takes
      // its velocity, the others 0, and the ranks add them up, so all move the crack alike)
      auto mine = [&](const Vec<2>& x) { return !domain_ || domain_->owns(g, x); };
#pragma omp parallel for if(rift::parallel::worth_a_team(n * 32)) schedule(dynamic, 4)
      for (std::size_t k = 0; k < n; ++k) {
        const Vec<2> above = cracks_.side_point(c, k, crack.above[k], 1, eps), below = cracks_.side_point(c, k, crack.below[k], 2, eps);
        v_mid[k] = mine(crack.points[k]) ? velocity(crack.points[k], nullptr) : Vec<2>{};
        v_up[k] = mine(crack.above[k]) ? velocity(crack.above[k], &above) : Vec<2>{};
        v_down[k] = mine(crack.below[k]) ? velocity(crack.below[k], &below) : Vec<2>{};
      }
      if (domain_)
        for (auto* v : {&v_mid, &v_up, &v_down}) domain_->communicator().sum(v->data()->data(), 2 * n);
      for (std::size_t k = 0; k < n; ++k) {
        crack.points[k] = crack.points[k] + dt * v_mid[k];
        crack.above[k] = crack.above[k] + dt * v_up[k];
        crack.below[k] = crack.below[k] + dt * v_down[k];
      }
    }
    cracks_.update_bounds();
  }
}

template class Solver<2>;
template class Solver<3>;

}  // namespace rift::mpm
