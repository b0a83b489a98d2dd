// Linear peridynamic solid (LPS), ordinary state-based (Silling et al. 2007, eq. 88-92; 2D: Le,
// Chan and Schwartz 2014). Strain energy density of particle i, with sigma_i its influence function
// and b_ij its dilatation weights (see surface_correction.hpp; without correction sigma = omega and
// b_ij = d omega |xi| / m_i, which is exactly LAMMPS peri/lps):
//   theta_i = sum_j b_ij e_ij V_j,   e = |y| - |xi|,
//   W_i = kappa/2 theta_i^2 + (A_dev / 2 m_i) sum_j sigma_ij (e_ij - theta_i |xi|/d)^2 V_j,
// A_dev = 15 G (3D) or 8 G (2D), m_i = sum sigma_ij |xi|^2 V_j. Its derivative is the force state
//   t_i<j> = b_ij (kappa theta_i - a_i P_i / d) + a_i sigma_ij (e_ij - theta_i |xi| / d),  a_i = A_dev / m_i,
//   P_i = sum_j sigma_ij (e_ij - theta_i |xi|/d) |xi| V_j  (zero without correction),
// and the force density is f_i = sum_j (t_i<j> + t_j<i>) V_j along the deformed bond. Two passes:
// dilatation (and P), then forces. Uncorrected in 3D: t = (3K - 5G) theta omega |xi| / m + 15 G omega e / m.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "rift/core/vector_isa.hpp"
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/breaking_policy.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/laws/ordinary_state.hpp"
#include "rift/pd/lps_runs.hpp"
#include "rift/pd/model.hpp"
#include "rift/pd/normal_stress_failure.hpp"
#include "rift/pd/viscous_step.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// The first pass of the LPS and VES, each bond once (bond_slabs.hpp): breaks the bonds stretched
/// past min(s0_i, s0_j) (both directions; in a crack's wet rock the effective stretch,
/// breaking_policy.hpp; with normal_stress failure the normal stress along the bond over d kappa,
/// normal_stress_failure.hpp) and sums over the rest theta_i = sum b_ij e V (into
/// m.dilatation), with Coupling also q_i = sum sigma_ij e |xi| V (into `coupling`), and the smallest
/// stretch of each particle (into `smallest`, none: no intact bond). e = |y| - |xi| is the same seen
/// from either end; b and sigma are each end's own (surface_correction.hpp). `broken_out`,
/// where given, receives the bonds the pass broke, (i, k) of the lower end's row, in no fixed order;
/// `rows_out` the rows' states after the pass (bond_runs.hpp RowStates), for the force pass.
template <int D, scene::Influence Omega, bool Coupling, bool Corrected>
void dilatation_pass(Model<D>& m, const BodyInfo& body, double* coupling, double* smallest,
                     std::vector<std::pair<std::size_t, std::int64_t>>* broken_out = nullptr, RowStates* rows_out = nullptr);

template <int D, scene::Influence Omega, bool Coupling>
void dilatation_pass(Model<D>& m, const BodyInfo& body, double* coupling, double* smallest,
                     std::vector<std::pair<std::size_t, std::int64_t>>* broken_out = nullptr, RowStates* rows_out = nullptr) {
  if (body.constants.surface_correction) dilatation_pass<D, Omega, Coupling, true>(m, body, coupling, smallest, broken_out, rows_out);
  else dilatation_pass<D, Omega, Coupling, false>(m, body, coupling, smallest, broken_out, rows_out);
}

/// The dilatation pass's bonds in runs (bond_runs.hpp, lps_runs.hpp), the stretch criterion: the
/// same terms as the rows of dilatation_pass. The bonds of a run that may break are taken one by one.
template <int D, scene::Influence Omega, bool Coupling, bool Corrected>
void dilatation_runs(Model<D>& m, const BodyInfo& body, const RowStates& rows, double* coupling, double* smallest,
                     BreakLog& log) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  const BondView v = b.view();
  const auto x = positions_by_component<D>(m.position, body);
  const double* const limits = m.stretch_limit.data();
  double* const theta = m.dilatation.data();
  const VectorIsa isa = vector_isa();
  // bond t of a run, as a row takes it
  auto settle = [&](const auto& breaking, const BondRun& run, std::size_t t) {
    // the rows' states as the pass found them: a run holds each pair once, and the pass breaks the
    // lower end's bond (the mirrors after it), so they are the bond's own state here
    if (!run_bond_intact(b, run, rows, t)) return;
    const auto [i, j, eta] = run_ends_at<D>(run, t, x);
    const FamilyOffset& family = v.families[run.family];
    const double xi = family.length;
    const double e = norm<D>(eta) - xi;
    const double limit = std::min(limits[i], limits[j]);
    const double value = e * family.inverse_length;
    bool crossed = false;
    const bool past = breaking.breaks(c.breakable, i, j, xi, value, limit, e > xi * limit, crossed);
    if (c.breakable && past) {
      const std::int64_t k = run_bond(b, run, t);
      v.intact[k] = bond_broken;
      log.note(i, k, crossed);
      return;
    }
    smallest[i] = std::min(smallest[i], value);
    smallest[j] = std::min(smallest[j], value);
    const double ev = e * family.volume;
    const double w = influence(Omega, xi, c.horizon) * xi * ev;
    if constexpr (Corrected) {
      const BondFactors& own = v.factors[v.factor_row[i] + run.family];
      const BondFactors& other = v.factors[v.factor_row[j] + family.mirror];
      theta[i] += own.dilatation_weight * ev;
      theta[j] += other.dilatation_weight * ev;
      if constexpr (Coupling) {
        coupling[i] += own.correction * w;
        coupling[j] += other.correction * w;
      }
    } else {
      theta[i] += w;
      theta[j] += w;
      if constexpr (Coupling) {
        coupling[i] += w;
        coupling[j] += w;
      }
    }
  };
  auto run_terms = [&](const auto& breaking, const BondRun& run) {
    const std::size_t length = run.length, i = static_cast<std::size_t>(run.i), j = static_cast<std::size_t>(run.j);
    if (length < short_run) {
      for (std::size_t t = 0; t < length; ++t) settle(breaking, run, t);
      return;
    }
    const FamilyOffset& family = v.families[run.family];
    alignas(64) double alive[max_run_length], weight_a[max_run_length], weight_b[max_run_length], correction_a[max_run_length],
        correction_b[max_run_length], flagged[max_run_length];
    static thread_local DilatationRun a;  // the thread's: every run sets what its form reads (not zeroed each run)
    const bool masked = run_mask(b, run, rows, alive, a.mask);  // the kernel skips a run whose bonds are all broken
    if constexpr (Corrected)
      for (std::size_t t = 0; t < length; ++t) {
        const BondFactors& own = v.factors[v.factor_row[i + t] + run.family];
        const BondFactors& other = v.factors[v.factor_row[j + t] + family.mirror];
        weight_a[t] = own.dilatation_weight, weight_b[t] = other.dilatation_weight;
        correction_a[t] = own.correction, correction_b[t] = other.correction;
      }
    const double* const pore = breaking.pore_stretch();
    a.length = length;
    a.xa = x[0] + i, a.ya = x[1] + i, a.xb = x[0] + j, a.yb = x[1] + j;
    if constexpr (D == 3) a.za = x[2] + i, a.zb = x[2] + j;
    a.limit_a = limits + i, a.limit_b = limits + j;
    if (pore) a.pore_a = pore + i, a.pore_b = pore + j;
    a.shift_scale = 1.0 + c.alpha;
    a.weight_a = weight_a, a.weight_b = weight_b, a.correction_a = correction_a, a.correction_b = correction_b;
    a.bond_length = family.length, a.inverse_length = family.inverse_length, a.volume = family.volume;
    a.omega_length = influence(Omega, family.length, c.horizon) * family.length;
    a.theta_a = theta + i, a.theta_b = theta + j;
    if constexpr (Coupling) a.coupling_a = coupling + i, a.coupling_b = coupling + j;
    a.smallest_a = smallest + i, a.smallest_b = smallest + j;
    a.breakable = c.breakable;
    a.may_break = flagged;
    a.ends_apart = ends_apart_in_vectors(run);
    bool may_break;
    if (pore)
      may_break = masked ? vector_clone<DilatationRunKernel<D, Corrected, Coupling, PoreShiftedLimit, true>, DilatationRun>(isa)(a)
                         : vector_clone<DilatationRunKernel<D, Corrected, Coupling, PoreShiftedLimit, false>, DilatationRun>(isa)(a);
    else
      may_break = masked ? vector_clone<DilatationRunKernel<D, Corrected, Coupling, StretchLimit, true>, DilatationRun>(isa)(a)
                         : vector_clone<DilatationRunKernel<D, Corrected, Coupling, StretchLimit, false>, DilatationRun>(isa)(a);
    if (!may_break) return;
    // the rest of the run is added: the bonds that may break one by one (each bond of a run has its
    // own two ends, so the order of their terms does not matter)
    for (std::size_t t = 0; t < length; ++t)
      if (flagged[t] != 0.0) settle(breaking, run, t);
  };
  with_breaking(m, c.alpha, [&](const auto& breaking) { for_each_run_by_slabs(body, [&](const BondRun& r) { run_terms(breaking, r); }); });
}

template <int D, scene::Influence Omega, bool Coupling, bool Corrected>
void dilatation_pass(Model<D>& m, const BodyInfo& body, double* coupling, double* smallest,
                     std::vector<std::pair<std::size_t, std::int64_t>>* broken_out, RowStates* rows_out) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  constexpr double none = std::numeric_limits<double>::max();
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) {
    m.dilatation[i] = 0.0;
    if constexpr (Coupling) coupling[i] = 0.0;
    smallest[i] = none;
  }
  BreakLog log;
  const double* const strain = m.failure_strain.data();
  const double stress_to_stretch = 1.0 / (D * c.kappa), lambda = c.lame_lambda(), p_wave = c.p_wave_modulus();
  constexpr int C = stress_components<D>;
  std::uint8_t* const state = b.intact.writable();  // counted as changed with the mirrors (break_mirror_bonds)
  // the wet rock's shift is compiled in only where there is wet rock (breaking_policy.hpp)
  auto row = [&]<bool Normal>(const auto& breaking, std::size_t i) {
    const Vec<D> xi_pos = m.position[i];
    const double s0_i = m.stretch_limit[i];
    const std::int64_t row_i = b.factor_row[i];
    double s_min = smallest[i], theta = 0.0, q = 0.0;
    for (auto k = first_forward_bond(b, i); k < b.offset[i + 1]; ++k) {
      if (b.intact[k] != bond_intact) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const double r = norm<D>(m.position[j] - xi_pos);
      const FamilyOffset& family = b.families[b.family[k]];
      const double xi = family.length;
      const double e = r - xi;
      const double limit = std::min(s0_i, m.stretch_limit[j]);
      double value;  // the bond's stretch, or its normal stress over d kappa
      if constexpr (Normal) {
        Vec<D> n = m.position[j] - xi_pos;
        for (int q = 0; q < D; ++q) n[q] /= r;
        value = bond_normal_stress<D>(strain + C * i, strain + C * j, n, e / xi, lambda, p_wave) * stress_to_stretch;
      } else {
        value = e * family.inverse_length;
      }
      bool crossed = false;
      const bool past = breaking.breaks(c.breakable, i, j, xi, value, limit, Normal ? value > limit : e > xi * limit, crossed);
      if (c.breakable && past) {
        state[k] = bond_broken;
        log.note(i, k, crossed);
        continue;
      }
      const double s = e * family.inverse_length;
      s_min = std::min(s_min, s);
      smallest[j] = std::min(smallest[j], s);
      const double ev = e * family.volume;
      if constexpr (Corrected) {
        const BondFactors& own = b.factors[static_cast<std::size_t>(row_i + b.family[k])];
        const BondFactors& other = b.factors[static_cast<std::size_t>(b.factor_row[j] + family.mirror)];
        theta += own.dilatation_weight * ev;
        m.dilatation[j] += other.dilatation_weight * ev;
        if constexpr (Coupling) {
          const double w = influence(Omega, xi, c.horizon) * xi * ev;
          q += own.correction * w;
          coupling[j] += other.correction * w;
        }
      } else {
        // omega |xi| e V, scaled by d / m after the pass (dilatation_scale)
        const double w = influence(Omega, xi, c.horizon) * xi * ev;
        theta += w;
        m.dilatation[j] += w;
        if constexpr (Coupling) {
          q += w;
          coupling[j] += w;
        }
      }
    }
    m.dilatation[i] += theta;
    if constexpr (Coupling) coupling[i] += q;
    smallest[i] = s_min;
  };
  // the normal stress only where a bond may break (the strain is not made while breaking is held):
  // row by row; the stretch in runs of bonds (bond_runs.hpp, lps_runs.hpp)
  RowStates rows;
  if (c.normal_stress_failure && c.breakable) {
    with_breaking(m, c.alpha, [&](const auto& breaking) {
      for_each_row_by_slabs(body, m.numbering, [&](std::size_t i) { row.template operator()<true>(breaking, i); });
    });
  } else {
    rows = whole_rows(b, body);
    dilatation_runs<D, Omega, Coupling, Corrected>(m, body, rows, coupling, smallest, log);
  }
  break_mirror_bonds(b, body, log.broken);
  // the rows as the pass leaves the states: those of the bonds it broke made again (or all, where it
  // went row by row)
  if (rows) refresh_rows(b, body, rows, log.broken);
  else if (rows_out) rows = whole_rows(b, body);
  if (rows_out) *rows_out = rows;
  after_breaking<D>(m, log);
  if (broken_out) *broken_out = std::move(log.broken);
  if constexpr (!Corrected) {
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
    for (std::size_t i = body.first; i < body.last; ++i) m.dilatation[i] *= dilatation_scale<D>(m.weighted_volume[i]);
  }
}

/// `rows_out`, where given, receives the rows' states after the pass (dilatation_pass).
template <int D, scene::Influence Omega>
void lps_dilatation(Model<D>& m, const BodyInfo& body, RowStates* rows_out = nullptr) {
  double* const q = pass_buffer(m.size(), PassBuffer::coupling);
  double* const smallest = pass_buffer(m.size(), PassBuffer::smallest_stretch);
  dilatation_pass<D, Omega, true>(m, body, q, smallest, nullptr, rows_out);
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) m.dilatation_coupling[i] = q[i] - m.dilatation[i] * m.weighted_volume[i] / D;
  next_stretch_limits<D>(m, body, smallest);
}

/// Second pass of the LPS and of its viscoelastic variant (ves.hpp, Viscous: the deviatoric
/// extension of each end less lambda times its back extension, which first advances over
/// history_dt, viscous_step.hpp; 0 holds it), each bond once (bond_slabs.hpp): the pair force
/// density (t_i<j> + t_j<i>) V along the deformed bond, on i and, opposite, on j. `rows`: the rows'
/// states as the dilatation pass left them (null: read from the bonds). `deviatoric_scale`, where
/// given, scales each particle's deviatoric term a_i (EPS: its return map's beta_i, eps.hpp).
template <int D, scene::Influence Omega, bool Viscous, bool Corrected>
void state_based_forces(Model<D>& m, const BodyInfo& body, double history_dt, const RowStates* rows, const double* deviatoric_scale);

template <int D, scene::Influence Omega, bool Viscous>
void state_based_forces(Model<D>& m, const BodyInfo& body, double history_dt = 0.0, const RowStates* rows = nullptr,
                        const double* deviatoric_scale = nullptr) {
  if (body.constants.surface_correction) state_based_forces<D, Omega, Viscous, true>(m, body, history_dt, rows, deviatoric_scale);
  else state_based_forces<D, Omega, Viscous, false>(m, body, history_dt, rows, deviatoric_scale);
}

template <int D, scene::Influence Omega, bool Viscous, bool Corrected>
void state_based_forces(Model<D>& m, const BodyInfo& body, double history_dt, const RowStates* given_rows, const double* deviatoric_scale) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  const double horizon = c.horizon, kappa = c.kappa, a_dev = c.lps_deviatoric_coefficient(), lambda = c.viscous_fraction;
  const ViscousStep step = Viscous ? ViscousStep(history_dt, c.relaxation_time) : ViscousStep();
  // bonds join particles of one body (bodies meet through contact only). Per particle, one array per
  // quantity (the runs read them contiguously; bond_runs.hpp): the calling thread's buffers, which
  // the team reads and writes through these pointers
  const std::size_t n = m.size();
  const auto x = positions_by_component<D>(m.position, body);
  std::array<double*, 3> f{};
  for (int q = 0; q < D; ++q) f[q] = pass_buffer(n, component(PassBuffer::force_x, q));
  double* const pressure = pass_buffer(n, PassBuffer::pressure);  // without the surface correction times d / m (dilatation_scale)
  double* const coefficient = pass_buffer(n, PassBuffer::deviatoric_coefficient);  // a = A_dev / m
  const double* const theta = m.dilatation.data();
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t j = body.first; j < body.last; ++j) {
    const double a_j = m.weighted_volume[j] > 0.0 ? a_dev / m.weighted_volume[j] : 0.0;
    double p_j = pressure_factor<D>(kappa, m.dilatation[j], a_j, m.dilatation_coupling[j]);
    if constexpr (!Corrected) p_j *= dilatation_scale<D>(m.weighted_volume[j]);
    pressure[j] = p_j, coefficient[j] = deviatoric_scale ? a_j * deviatoric_scale[j] : a_j;
    for (int q = 0; q < D; ++q) f[q][j] = 0.0;
  }
  const RowStates rows = given_rows ? *given_rows : whole_rows(b, body);
  const VectorIsa isa = vector_isa();
  // bond t of a run, as a row takes it
  auto settle = [&](const BondRun& run, std::size_t t) {
    if (!run_bond_intact(b, run, rows, t)) return;
    const auto [i, j, eta] = run_ends_at<D>(run, t, x);
    const double r = norm<D>(eta);
    const FamilyOffset& family = b.families[run.family];
    const double xi = family.length;
    const double e = r - xi;
    const double omega = influence(Omega, xi, horizon);
    double dev_i = e - theta[i] * (xi / D), dev_j = e - theta[j] * (xi / D);  // as the runs (lps_runs.hpp)
    if constexpr (Viscous) {
      const std::size_t h_i = history_index(body, i, run.family, 0), h_j = mirror_history_slot(h_i);
      if (step.advance) {
        const double last_i = last_deviatoric_extension<D>(b, h_i, i, xi), last_j = last_deviatoric_extension<D>(b, h_i, j, xi);
        b.back_extension[h_i] = next_back_extension(last_i, b.back_extension[h_i], dev_i, step.one_minus_decay, step.decay, step.beta);
        b.back_extension[h_j] = next_back_extension(last_j, b.back_extension[h_j], dev_j, step.one_minus_decay, step.decay, step.beta);
        b.last_extension[pair_slot(h_i)] = static_cast<float>(e);
      }
      dev_i -= lambda * b.back_extension[h_i];
      dev_j -= lambda * b.back_extension[h_j];
    }
    double t_i, t_j;
    if constexpr (Corrected) {
      const BondFactors& g_i = b.factors[static_cast<std::size_t>(b.factor_row[i] + run.family)];
      const BondFactors& g_j = b.factors[static_cast<std::size_t>(b.factor_row[j] + family.mirror)];
      t_i = force_state(g_i.dilatation_weight, pressure[i], coefficient[i], g_i.correction, omega, dev_i);
      t_j = force_state(g_j.dilatation_weight, pressure[j], coefficient[j], g_j.correction, omega, dev_j);
    } else {
      t_i = force_state(omega * xi, pressure[i], coefficient[i], 1.0, omega, dev_i);
      t_j = force_state(omega * xi, pressure[j], coefficient[j], 1.0, omega, dev_j);
    }
    const double scalar = (t_i + t_j) * family.volume / r;
    for (int q = 0; q < D; ++q) {
      f[q][i] += scalar * eta[q];
      f[q][j] -= scalar * eta[q];
    }
  };
  // a run of bonds (bond_runs.hpp, lps_runs.hpp): the pair force density (t_i<j> + t_j<i>) V along
  // the deformed bond, on i and, opposite, on j
  for_each_run_by_slabs(body, [&](const BondRun& run) {
    const std::size_t length = run.length, i = static_cast<std::size_t>(run.i), j = static_cast<std::size_t>(run.j);
    if (length < short_run) {
      for (std::size_t t = 0; t < length; ++t) settle(run, t);
      return;
    }
    const FamilyOffset& family = b.families[run.family];
    alignas(64) double alive[max_run_length], weight_a[max_run_length], weight_b[max_run_length], correction_a[max_run_length],
        correction_b[max_run_length];
    static thread_local StateForceRun a;  // the thread's: every run sets what its form reads (not zeroed each run)
    const bool masked = run_mask(b, run, rows, alive, a.mask);  // the kernel skips a run whose bonds are all broken
    if constexpr (Corrected)
      for (std::size_t t = 0; t < length; ++t) {
        const BondFactors& own = b.factors[static_cast<std::size_t>(b.factor_row[i + t] + run.family)];
        const BondFactors& other = b.factors[static_cast<std::size_t>(b.factor_row[j + t] + family.mirror)];
        weight_a[t] = own.dilatation_weight, weight_b[t] = other.dilatation_weight;
        correction_a[t] = own.correction, correction_b[t] = other.correction;
      }
    a.length = length;
    a.xa = x[0] + i, a.ya = x[1] + i, a.xb = x[0] + j, a.yb = x[1] + j;
    a.fxa = f[0] + i, a.fya = f[1] + i, a.fxb = f[0] + j, a.fyb = f[1] + j;
    if constexpr (D == 3) a.za = x[2] + i, a.zb = x[2] + j, a.fza = f[2] + i, a.fzb = f[2] + j;
    a.pressure_a = pressure + i, a.pressure_b = pressure + j, a.coefficient_a = coefficient + i, a.coefficient_b = coefficient + j;
    a.theta_a = theta + i, a.theta_b = theta + j;
    a.weight_a = weight_a, a.weight_b = weight_b, a.correction_a = correction_a, a.correction_b = correction_b;
    if constexpr (Viscous) {
      const std::size_t h = history_index(body, i, run.family, 0);  // both directions contiguous (bonds.hpp)
      a.last_extension = b.last_extension.data() + pair_slot(h);
      a.last_theta_a = b.history_dilatation.data() + i, a.last_theta_b = b.history_dilatation.data() + j;
      a.back_a = b.back_extension.data() + h, a.back_b = b.back_extension.data() + mirror_history_slot(h), a.lambda = lambda;
      a.one_minus_decay = step.one_minus_decay, a.decay = step.decay, a.beta = step.beta;
    }
    a.bond_length = family.length, a.omega = influence(Omega, family.length, horizon), a.volume = family.volume;
    a.ends_apart = ends_apart_in_vectors(run);
    auto kernel = [&]<bool Advance>() {
      if (masked)
        vector_clone<StateForceRunKernel<D, Corrected, Viscous, Advance, true>, StateForceRun>(isa)(a);
      else
        vector_clone<StateForceRunKernel<D, Corrected, Viscous, Advance, false>, StateForceRun>(isa)(a);
    };
    if constexpr (Viscous)
      if (step.advance) return kernel.template operator()<true>();
    kernel.template operator()<false>();
  });
  // Viscous: the dilatations the history advanced to, for e_d(n) of the next step (viscous_step.hpp
  // last_deviatoric_extension; the pairs' extensions are kept by the loop above)
  const bool keep_history_state = Viscous && step.advance;
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t j = body.first; j < body.last; ++j) {
    for (int q = 0; q < D; ++q) m.force[j][q] = f[q][j];
    if (keep_history_state) b.history_dilatation[j] = theta[j];
  }
}

/// W_i (uses the current dilatation; Viscous: and back extensions, ves.hpp).
template <int D, bool Viscous>
double state_based_energy_density(const Model<D>& m, const BodyInfo& body, std::size_t i) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  const double theta = m.dilatation[i], lambda = c.viscous_fraction;
  double dev = 0.0;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    if (b.intact[k] != bond_intact) continue;
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    const double xi = b.length(k);
    const double e = norm<D>(m.position[j] - m.position[i]) - xi;
    const double ed = e - theta * xi / D;
    if constexpr (Viscous) {
      const double ev = ed - b.back_extension[history_slot(b, body, i, k)];
      dev += b.correction(i, k) * influence(c.influence, xi, c.horizon) * ((1.0 - lambda) * ed * ed + lambda * ev * ev) * b.volume(k);
    } else {
      dev += b.correction(i, k) * influence(c.influence, xi, c.horizon) * ed * ed * b.volume(k);
    }
  }
  return 0.5 * c.kappa * theta * theta + 0.5 * c.lps_deviatoric_coefficient() / m.weighted_volume[i] * dev;
}

}  // namespace rift::pd
