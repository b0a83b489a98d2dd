#include "rift/run/runner.hpp"

#include <omp.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <optional>
#include <ostream>

#include "rift/core/phase_times.hpp"
#include "rift/core/progress.hpp"
#include "rift/io/damage_histogram.hpp"
#include "rift/io/damage_image.hpp"
#include "rift/io/field_writer.hpp"
#include "rift/io/history.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/pd/checkpoint_state.hpp"
#include "rift/geomech/interface_record.hpp"
#include "rift/hf/pore_stretch.hpp"
#include "rift/pd/laws/registry.hpp"
#include "rift/pd/stress.hpp"
#include "rift/run/cadence.hpp"
#include "rift/run/checkpointing.hpp"
#include "rift/run/distributed.hpp"
#include "rift/run/history_columns.hpp"
#include "rift/run/mpm_runner.hpp"
#include "rift/run/run_loop.hpp"
#include "rift/run/simulation.hpp"

namespace rift::run {

namespace {

/// The particle nearest to each [output] probe (reference positions); a probe farther than one
/// spacing from every particle lies outside the bodies and is a scene error.
template <int D>
std::vector<std::size_t> probe_particles(const scene::Scene& s, const pd::Model<D>& m) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < s.output.probes.size(); ++k) {
    const auto& p = s.output.probes[k];
    std::size_t best = 0;
    double best_d2 = 1e300;
    for (std::size_t i = 0; i < m.size(); ++i) {
      double d2 = 0.0;
      for (int q = 0; q < D; ++q) d2 += (m.reference_position[i][q] - p[q]) * (m.reference_position[i][q] - p[q]);
      if (d2 < best_d2) best_d2 = d2, best = i;
    }
    const double spacing = m.constants_of(best).spacing;
    if (std::sqrt(best_d2) > spacing)
      throw SceneError(s.output.probes_where, "output.probes",
                       fmt::format("probe {} lies {:g} m from the nearest particle, more than one spacing ({:g} m): it is not inside a body",
                                   k, std::sqrt(best_d2), spacing));
    out.push_back(best);
  }
  return out;
}

template <int D>
Plan make_plan(const Simulation<D>& p) {
  Plan plan;
  plan.particles = p.model.size();
  plan.bonds = p.model.bonds.size() / 2;
  // per particle: its fields, its row offset and the index of its row of factors (bonds.hpp)
  plan.bytes_per_particle = double(pd::Model<D>::bytes_per_particle()) + 2 * sizeof(std::int64_t);
  // both directions of a bond are stored
  plan.bytes_per_bond = 2.0 * p.model.bonds.bytes_per_directed_bond();
  plan.stable_time_step = p.stable_dt;
  plan.time_step = p.dt;
  plan.steps = p.steps;
  return plan;
}

template <int D>
Plan check_dim(const scene::Scene& s, std::ostream& out) {
  Simulation<D> p(s);
  const auto probes = probe_particles<D>(s, p.model);
  if (const auto w = snapshots_past_steps(s, p.steps); !w.empty()) std::fprintf(stderr, "%s\n", w.c_str());
  Plan plan = make_plan<D>(p);
  char line[256];
  out << "scene        " << s.name << " (" << s.file << ")\n";
  out << "dimension    " << D << (D == 2 ? (s.plane == scene::PlaneCondition::stress ? " (plane stress" : " (plane strain") : "")
      << (D == 2 ? ", thickness " + std::to_string(s.thickness) + " m)" : "") << "\n";
  for (const auto& b : p.model.bodies) {
    const auto& c = b.constants;
    std::snprintf(line, sizeof line, "body         %s: %zu particles, %s, spacing %g m, horizon %g m (%.3f spacings), s0 = %s\n",
                  b.name.c_str(), b.last - b.first, pd::law_traits(c.model).name, c.spacing, c.horizon,
                  c.horizon / c.spacing, c.breakable ? std::to_string(c.critical_stretch).c_str() : "unbreakable");
    out << line;
  }
  std::snprintf(line, sizeof line, "particles    %zu\nbonds        %lld (%lld directed, %.1f per particle)\n", plan.particles,
                static_cast<long long>(plan.bonds), 2LL * static_cast<long long>(plan.bonds),
                plan.particles ? 2.0 * double(plan.bonds) / double(plan.particles) : 0.0);
  out << line;
  // both directions of a bond are stored (bonds.hpp): per directed bond, half of a bond's bytes
  std::snprintf(line, sizeof line, "memory       %.0f bytes/particle, %.0f bytes/directed bond, %.1f MB in all\n", plan.bytes_per_particle,
                0.5 * plan.bytes_per_bond, (plan.bytes_per_particle * double(plan.particles) + plan.bytes_per_bond * double(plan.bonds)) / 1e6);
  out << line;
  std::snprintf(line, sizeof line, "time step    stable %.4g s", plan.stable_time_step);
  out << line;
  if (s.solver.kind == scene::SolverKind::explicit_dynamics) {
    std::snprintf(line, sizeof line, ", used %.4g s\nsteps        %ld (explicit, end time %.4g s)\n", plan.time_step, plan.steps,
                  s.solver.end_time);
  } else {
    const bool at_equilibrium = s.solver.breaking == scene::Solver::Breaking::at_equilibrium;
    if (s.solver.kind == scene::SolverKind::static_equilibrium)
      std::snprintf(line, sizeof line,
                    "\nsteps        %d load steps of the static solver (conjugate gradients, at most %d force evaluations each, tolerance %g; "
                    "bonds break at each equilibrium)\n",
                    s.solver.load_steps, s.solver.max_iterations, s.solver.tolerance);
    else
      std::snprintf(line, sizeof line, "\nsteps        %d load steps of dynamic relaxation (at most %d iterations each, tolerance %g; bonds break %s)\n",
                    s.solver.load_steps, s.solver.max_iterations, s.solver.tolerance,
                    at_equilibrium ? "at each equilibrium" : "during the iterations");
  }
  out << line;
  if (s.in_situ.enabled) {
    const auto& in_situ = s.in_situ;
    std::snprintf(line, sizeof line,
                  "in-situ      sigma_H = %g MPa along %c, sigma_h = %g MPa, sigma_v = %g MPa%s, %s: equilibrium first%s, no bond breaks\n",
                  in_situ.sigma_H / 1e6, "xy"[in_situ.sigma_H_axis], in_situ.sigma_h / 1e6, in_situ.sigma_v / 1e6,
                  D == 2 ? " (out of plane)" : "",
                  in_situ.faces == scene::InSituStress::Faces::platens ? "through rigid platens (low faces held)" : "as tractions on the faces",
                  in_situ.start == scene::InSituStress::Start::uniform_strain ? " (from their uniform strain)" : "");
    out << line;
  }
  std::string fields;
  for (const auto& f : s.output.fields) fields += " " + f;
  out << "output       " << s.output.count << " snapshots (position" << fields << ") -> fields_000000.h5 ... (one file each) + fields.xdmf\n";
  out << "             " << s.output.history_count << " history rows (time step";
  for (const auto& q : s.output.history) out << " " << q;
  out << ") -> history.csv";
  for (const auto& r : s.output.reactions) out << ", reaction on " << r;
  out << "\n";
  if (!s.interfaces.empty()) {
    const auto& ib = p.model.interface_bonds;
    for (std::size_t k = 0; k < s.interfaces.size(); ++k) {
      const auto& f = s.interfaces[k];
      const auto across = std::count(ib.interface.begin(), ib.interface.end(), static_cast<std::uint16_t>(k)) / 2;
      std::snprintf(line, sizeof line,
                    "interface %zu    %ld bonds across; parts at %g MPa tension, slips at %g MPa + %g (sigma_n - p); outcome -> "
                    "crossed/dilated_interface_%zu columns of history.csv\n",
                    k, long(across), f.tensile_strength / 1e6, f.cohesion / 1e6, f.friction_coefficient, k);
      out << line;
    }
  }
  if (!probes.empty()) out << "             damage at " << probes.size() << " probes -> damage_probe_0... columns of history.csv\n";
  if (D == 2 && s.output.damage_image) out << "             final damage image -> damage.png\n";
  if (s.output.damage_histogram) out << "             final damage histogram (intervals of 0.1) -> damage_histogram.csv + .png\n";
  out << checkpoint_plan(s);
  return plan;
}

template <int D>
std::vector<double> vector_field(const pd::Model<D>& m, const std::vector<Vec<D>>& v, bool relative_to_reference) {
  std::vector<double> out(3 * m.size(), 0.0);
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int k = 0; k < D; ++k) out[3 * i + k] = v[i][k] - (relative_to_reference ? m.reference_position[i][k] : 0.0);
  return out;
}

/// A snapshot of the fields; the ranks of a distributed run write it together, each its owned
/// particles' rows (at their whole-run numbers, Model::numbering).
template <int D>
void write_snapshot(io::FieldWriter& fields, pd::Model<D>& m, const scene::Scene& s, const parallel::Communicator& comm) {
  pd::update_damage<D>(m);
  struct Together {
    io::FieldWriter& fields;
    const pd::Model<D>& m;
    const parallel::Communicator& comm;
    void write(const std::string& name, const std::vector<double>& values, int components) {
      if (!comm.distributed()) return fields.write(name, values, components);
      const auto width = static_cast<std::size_t>(components);
      std::vector<double> owned_values;
      std::vector<io::FieldWriter::Rows> rows;
      for (const IndexRange& r : m.owned()) {
        owned_values.insert(owned_values.end(), values.begin() + static_cast<std::ptrdiff_t>(r.first * width),
                            values.begin() + static_cast<std::ptrdiff_t>(r.last * width));
        if (r.size() > 0) rows.push_back({m.numbering.whole(r.first), r.size()});
      }
      fields.write_rows(name, owned_values, components, rows);
    }
  } w{fields, m, comm};
  fields.begin_snapshot(m.time);
  w.write("position", vector_field<D>(m, m.position, false), 3);
  for (const auto& f : s.output.fields) {
    if (f == "displacement") w.write(f, vector_field<D>(m, m.position, true), 3);
    else if (f == "velocity") w.write(f, vector_field<D>(m, m.velocity, false), 3);
    else if (f == "damage") w.write(f, m.damage, 1);
    else if (f == "dilatation") w.write(f, m.dilatation, 1);
    else if (f == "stress") w.write(f, pd::particle_stress<D>(m), 6);  // xx, yy, zz, xy, yz, xz
    else if (f == "weighted_volume") w.write(f, m.weighted_volume, 1);
    else if (f == "fluid_pressure") {  // of the injected or pressurized fluid that reaches the particle
      std::vector<double> p(m.size());
      for (std::size_t i = 0; i < m.size(); ++i) p[i] = hf::fluid_pressure_at<D>(m, i);
      w.write(f, p, 1);
    }
    else if (f == "volume") w.write(f, m.volume, 1);
    else if (f == "body") {
      std::vector<double> b(m.size());
      for (std::size_t i = 0; i < m.size(); ++i) b[i] = m.body[i];
      w.write(f, b, 1);
    } else if (f == "strain_energy_density") {
      std::vector<double> e(m.size());
      pd::strain_energy_densities<D>(m, e.data());
      w.write(f, e, 1);
    }
  }
  fields.end_snapshot();
}

template <int D>
void check_finite(const pd::Model<D>& m, long step, const pd::EnergySummary& e) {
  if (std::isfinite(e.kinetic) && std::isfinite(e.strain)) return;
  for (const IndexRange& owned : m.owned())
    for (std::size_t i = owned.first; i < owned.last; ++i)
      for (int k = 0; k < D; ++k)
        if (!std::isfinite(m.position[i][k]) || !std::isfinite(m.velocity[i][k])) {
          std::string where;
          for (int q = 0; q < D; ++q) where += (q ? ", " : "") + std::to_string(m.reference_position[i][q]);
          throw PhysicsError("step " + std::to_string(step) + ": particle " + std::to_string(m.numbering.whole(i)) + " of body \"" +
                             m.bodies[m.body[i]].name + "\" (reference position " + where +
                             ") has a non-finite position or velocity; the time step is likely above the stable limit or a load is unbounded");
        }
  throw PhysicsError("step " + std::to_string(step) + ": energy is not finite");
}

/// A distributed run's load balance: its processor grid, each rank's owned particles, ghosts, step-loop time and the
/// part of it spent in MPI calls (waiting for the others included: the loop time less it is the
/// rank's own work).
template <int D>
std::string load_balance(const parallel::Communicator& comm, const pd::Model<D>& m, double loop_seconds, double in_mpi, std::size_t ghosts,
                         const std::vector<int>& grid) {
  constexpr std::size_t k = 5;
  const auto all = comm.gather(std::vector<double>{double(m.owned_count()), double(ghosts), double(m.owned_bonds()), loop_seconds, in_mpi});
  std::string out = fmt::format("load balance over {} ranks, {} of a {} grid (owned particles, ghosts, directed bonds, loop time, of it in MPI calls):",
                                comm.size(), grid.size() == 3 && grid[1] > 1 ? "pencils along x" : "slabs", fmt::join(grid, " x "));
  for (std::size_t r = 0; k * r < all.size(); ++r)
    out += fmt::format("{} rank {}: {:.0f}, {:.0f}, {:.0f}, {:.3g} s, {:.3g} s", r ? ";" : "", r, all[k * r], all[k * r + 1], all[k * r + 2],
                       all[k * r + 3], all[k * r + 4]);
  return out;
}

/// What a history row's providers read besides the model: the row's energies, largest damage and
/// solver columns, and whether a fluid has broken through by now.
struct RowState {
  pd::EnergySummary energy;
  double max_damage = 0.0;
  std::vector<double> solver;
  bool vented = false;
};

/// The history's columns of a PD run, each group from its provider: the energies, the probes'
/// damage, the injected boreholes' pressure, cavity volume and venting, the interfaces' outcomes,
/// the reactions, and the relaxation's own.
template <int D>
HistoryColumns pd_history_columns(const scene::Scene& s, Simulation<D>& p, std::vector<std::size_t> probes, RowState& row,
                                  geomech::InterfaceRecord& interfaces) {
  const auto& comm = parallel::Communicator::world();
  auto& m = p.model;
  HistoryColumns columns;
  columns.add(s.output.history, [&s, &row](std::vector<double>& r) {
    for (const auto& q : s.output.history) {
      if (q == "kinetic_energy") r.push_back(row.energy.kinetic);
      else if (q == "strain_energy") r.push_back(row.energy.strain);
      else if (q == "total_energy") r.push_back(row.energy.kinetic + row.energy.strain);
      else if (q == "broken_bonds") r.push_back(double(row.energy.broken_bonds));
      else if (q == "max_damage") r.push_back(row.max_damage);
    }
  });
  {
    // the damage of probe k: its owner's (the others add nothing)
    std::vector<std::string> names;
    for (std::size_t k = 0; k < probes.size(); ++k) names.push_back("damage_probe_" + std::to_string(k));
    columns.add(names, [&comm, &m, probes](std::vector<double>& r) {
      for (auto g : probes) {
        const std::size_t i = m.numbering.here(g);
        r.push_back(comm.sum(i != pd::Numbering::none && m.owns(i) ? m.damage[i] : 0.0));
      }
    });
  }
  {
    std::vector<std::size_t> injected;  // pressure sources fed by an injection rate: their pressure and cavity volume
    std::vector<std::string> names;
    for (std::size_t k = 0; k < s.boreholes.size(); ++k)
      if (s.boreholes[k].injection_rate) {
        injected.push_back(s.cracks.size() + k);
        for (const char* q : {"pressure_borehole_", "cavity_volume_borehole_", "vented_borehole_"}) names.push_back(q + std::to_string(k));
      }
    columns.add(names, [&m, &row, injected](std::vector<double>& r) {
      bool& vented = row.vented;
      vented = false;
      for (auto c : injected) {
        const bool v = c < m.fluid_network.broke_through.size() && m.fluid_network.broke_through[c] != 0;
        r.insert(r.end(), {m.fluid_network.pressure[c], m.fluid_network.cavity_volume[c], double(v)});
        vented = vented || v;
      }
    });
  }
  columns.add(geomech::InterfaceRecord::column_names(s.interfaces.size()),
              [&m, &row, &interfaces](std::vector<double>& r) { interfaces.row<D>(m, m.time, row.vented, r); });
  {
    std::vector<std::string> names;
    for (const auto& r : p.loads.boundaries.reaction_names())
      for (int k = 0; k < D; ++k) names.push_back("reaction_" + r + "_" + "xyz"[k]);
    columns.add(names, [&comm, &m, &p](std::vector<double>& r) {
      for (const auto& f : p.loads.boundaries.reactions(m, comm)) r.insert(r.end(), f.begin(), f.end());
    });
  }
  if (s.solver.load_stepped()) {
    std::vector<std::string> names{"iterations", "residual"};
    if (s.solver.breaking == scene::Solver::Breaking::at_equilibrium) names.push_back("breaking_passes");
    columns.add(names, [&row](std::vector<double>& r) { r.insert(r.end(), row.solver.begin(), row.solver.end()); });
  }
  return columns;
}

/// The in-situ stage ([in_situ_stress]; Simulation::equilibrate_in_situ) and its note; false where a
/// stop cut it short (its checkpoint, written here, starts the run again from the beginning).
template <int D>
bool in_situ_stage(Simulation<D>& p, const scene::Scene& s, const Options& o, Result& res) {
  const auto in_situ_start = std::chrono::steady_clock::now();
  const auto r = p.equilibrate_in_situ(s.in_situ);
  res.in_situ_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - in_situ_start).count();
  if (r.stopped) {  // its solves do not resume: the checkpoint starts the run again
    Checkpointing(s, o, res.output_dir).after_stop_before_start(res, [](io::CheckpointWriter& w) {
      std::uint8_t from_start = 1;
      w("run.from_start", from_start);
    });
    res.stopped_in = "in the in-situ stage (its checkpoint starts the run again from the beginning)";
    return false;
  }
  const bool cg = p.uses_conjugate_gradients(s.in_situ);
  const std::string how = !(r.density_factor > 0.0) ? std::string("force evaluations of preconditioned conjugate gradients")
                          : fmt::format("{} (fictitious density {:.3g} times the row-sum bound, measured)",
                                        cg ? "force evaluations, conjugate gradients then dynamic relaxation" : "iterations of dynamic relaxation",
                                        r.density_factor);
  res.notes.push_back(fmt::format("in-situ stage: {} in {} {} (residual {:.3g}, tolerance {:g})", r.converged ? "equilibrium" : "NOT converged",
                                  r.iterations, how, r.residual, s.in_situ.tolerance));
  if (!r.converged && !o.quiet)
    std::fprintf(stderr, "rift: warning: the in-situ stage did not converge in %d iterations (residual %.3g > %.3g)\n", r.iterations,
                 r.residual, s.in_situ.tolerance);
  return true;
}

/// The final outcome at each interface, in the result and its notes.
template <int D>
void report_interfaces(const pd::Model<D>& m, geomech::InterfaceRecord& interfaces, Result& res) {
  const auto& outcomes = interfaces.final_outcomes<D>(m);
  for (std::size_t k = 0; k < outcomes.size(); ++k) {
    const auto& o = outcomes[k];
    res.interface_outcomes.push_back(o.name());
    const std::string when = interfaces.vent_time < 0.0
                                 ? ""
                                 : fmt::format(", as at t = {:g} s, when the fluid broke through to the outer surface", interfaces.vent_time);
    res.notes.push_back(fmt::format("interface {}: {} (broken rock up to {:.3g} mm past it, open and wet along {:.3g} mm of it{})", k, o.name(),
                                    1e3 * o.crossing_distance, 1e3 * o.opened_length, when));
  }
}

/// The final damage's histogram and (2D) image, drawn on rank 0 from every particle's damage and
/// position.
template <int D>
void draw_final_damage(const scene::Scene& s, const pd::Model<D>& m, const parallel::Communicator& comm, std::size_t particles, Result& res) {
  const auto damage = gather_owned<D>(comm, m, m.damage, 1);
  const auto positions = gather_owned<D>(comm, m, vector_field<D>(m, m.position, false), 3);
  if (!comm.root()) return;
  if (s.output.damage_histogram) {
    std::string png = res.output_dir + "/damage_histogram.png", reason;
    const bool drawn = io::write_damage_histogram(res.output_dir, png, io::damage_histogram(damage),
                                                  s.name + ": damage at t = " + std::to_string(m.time) + " s", reason);
    res.files.push_back({"histogram", res.output_dir + "/damage_histogram.csv"});
    if (drawn) res.files.push_back({"chart", png});
    else res.notes.push_back("damage histogram chart not written: " + reason);
  }
  if (D == 2 && s.output.damage_image) {
    std::vector<double> x(particles), y(particles);
    for (std::size_t i = 0; i < particles; ++i) x[i] = positions[3 * i], y[i] = positions[3 * i + 1];
    std::string png = res.output_dir + "/damage.png", reason;
    if (io::write_damage_image(res.output_dir, png, x, y, damage, s.name + ": damage at t = " + std::to_string(m.time) + " s", reason))
      res.files.push_back({"damage", png});
    else
      res.notes.push_back("damage image not written: " + reason);
  }
}

template <int D>
Result run_dim(const scene::Scene& s, const Options& o) {
  const auto run_start = std::chrono::steady_clock::now();
  Simulation<D> p(s);  // every scene error is raised here, before anything is written
  const auto probes = probe_particles<D>(s, p.model);
  // mpirun -np N: each rank keeps its window of the model (pd/window.hpp); rank 0 writes the outputs
  const auto& comm = parallel::Communicator::world();
  if (const auto w = snapshots_past_steps(s, p.steps); !w.empty() && comm.root()) std::fprintf(stderr, "%s\n", w.c_str());
  const std::size_t particles = p.model.size();
  auto& m = p.model;
  Result res;
  res.output_dir = o.output_dir.empty() ? "results/" + s.name : o.output_dir;
  io::FieldWriter fields(res.output_dir, "fields", particles, comm.distributed());
  res.fields_h5 = fields.h5_pattern();
  res.fields_xdmf = fields.xdmf_path();
  const bool relaxation = s.solver.load_stepped();  // load steps: a DynamicRelaxation holds their unfinished state
  std::optional<pd::DynamicRelaxation<D>> dr;

  // The loop's own state, which a checkpoint holds with the model's (pd/checkpoint_state.hpp): the
  // outputs' cadences, the outcome at the interfaces, the notes, the history's length.
  geomech::InterfaceRecord interfaces;
  Cadence snapshots{s.output.count, p.steps}, history_rows{s.output.history_count, p.steps};
  std::int64_t history_bytes = 0;
  // a distributed run's checkpoint holds the whole run's model, gathered on rank 0 (`whole`)
  auto visit_run = [&](auto& a, Simulation<D>& state) {
    a("run.next_snapshot", snapshots.next), a("run.next_history", history_rows.next);
    interfaces.visit(a);
    a("run.notes", res.notes);
    a("run.history_bytes", history_bytes);
    fields.visit_state(a);
    pd::visit(a, state.model);
    pd::visit(a, state.contact);
  };
  // A checkpoint written by a stop in the in-situ stage holds no state (run.from_start): the run
  // starts again from the beginning. Any other holds the whole run after its step, and where a stop
  // cut a load step of relaxation short, that load step's iterations (DynamicRelaxation::unfinished).
  bool restarted = false;
  if (!o.restart.empty()) {
    // the whole checkpoint is read before any output is touched
    res.first_step = 1 + read_checkpoint(s, o, p.steps, [&](io::CheckpointReader& checkpoint) {
                       std::uint8_t from_start = 0;
                       checkpoint("run.from_start", from_start);
                       if (from_start) return;
                       restarted = true;
                       visit_run(checkpoint, p);
                       if (relaxation) {
                         dr.emplace(m);
                         pd::visit(checkpoint, *dr);
                       }
                     });
  }
  if (restarted) require_output_file(o, res.output_dir + "/history.csv", history_bytes);
  // mpirun -np N: from here on each rank holds its window of the model (a restart read the whole
  // run's checkpoint first, so it continues on any number of ranks)
  std::optional<Simulation<D>> whole;  // rank 0's, for the checkpoints of a distributed run
  std::optional<pd::DynamicRelaxation<D>> whole_dr;  // and of its relaxation
  if (comm.distributed()) {
    p.distribute(s, comm, o.cut_axis, o.processor_grid);
    if (dr) {  // its fictitious densities from the window's rows (an owned row is whole); an unfinished load step's to the window
      auto unfinished = std::move(dr->unfinished());
      dr.emplace(m);
      for (auto* whole_run : {&unfinished.previous, &unfinished.start}) {
        if (whole_run->empty()) continue;
        std::vector<Vec<D>> window(m.size());
        for (std::size_t i = 0; i < m.size(); ++i) window[i] = (*whole_run)[m.numbering.whole(i)];
        *whole_run = std::move(window);
      }
      dr->unfinished() = std::move(unfinished);
    }
  }
  if (comm.root()) make_output_folders(s, res.output_dir);
  comm.barrier();  // before the ranks open the snapshot files together
  // the history's columns, each group from its provider; a row's energies and the solver's own
  // columns are the row's (history_row)
  const bool at_equilibrium = s.solver.breaking == scene::Solver::Breaking::at_equilibrium;
  RowState row_state;
  const HistoryColumns columns = pd_history_columns<D>(s, p, probes, row_state, interfaces);
  std::optional<io::History> history;  // rank 0's
  if (comm.root() && restarted) history.emplace(res.output_dir + "/history.csv", history_bytes);
  if (comm.root() && !restarted) history.emplace(res.output_dir + "/history.csv", columns.names());
  res.history_csv = res.output_dir + "/history.csv";
  // the strain energy only where the history has a column for it (a pass over every bond)
  const bool strain_column = std::any_of(s.output.history.begin(), s.output.history.end(),
                                         [](const std::string& q) { return q == "strain_energy" || q == "total_energy"; });
  auto history_row = [&](long step, std::vector<double> solver) {
    row_state.energy = pd::summarize_and_update_damage<D>(m, strain_column);
    check_finite<D>(m, step, row_state.energy);
    row_state.max_damage = max_damage<D>(comm, m);
    row_state.solver = std::move(solver);
    const std::vector<double> row = columns.row(m.time, step);
    if (history) history->row(row);
    return row_state.energy;
  };

  if (s.in_situ.enabled && !restarted && !in_situ_stage<D>(p, s, o, res)) return res;
  if (!restarted) interfaces.start<D>(m);
  // the whole run's directed bonds (a distributed run's ranks each count their owned rows): the
  // in-situ stage's share broken and the bonds per second printed at the end
  const double bonds = comm.sum(double(m.owned_bonds()));
  auto failed_bonds = [&] { return static_cast<std::size_t>(comm.sum(static_cast<double>(pd::failed_bonds<D>(m)))); };
  const std::size_t failed_before_start = s.in_situ.enabled && !restarted ? failed_bonds() : 0;
  if (!restarted) p.start();  // a checkpoint holds the forces of its step
  if (s.in_situ.enabled && !restarted) {
    // the in-situ stage holds every bond; those its equilibrium strains past their limit break now
    const auto broken = static_cast<std::int64_t>((failed_bonds() - failed_before_start) / 2);
    if (broken > 0) {
      const double percent = 100.0 * double(2 * broken) / std::max(1.0, bonds);
      res.notes.push_back(fmt::format("in-situ stage: {} bonds ({:.3g}%) past their limit at its equilibrium broke at the start", broken, percent));
      if (!o.quiet)
        std::fprintf(stderr,
                     "rift: warning: %lld bonds (%.3g%%) are past their limit at the in-situ equilibrium and broke at the start: the "
                     "in-situ stresses are more than the material holds ([in_situ_stress] of %s)\n",
                     static_cast<long long>(broken), percent, s.file.c_str());
    }
  }
  const auto loop_start = std::chrono::steady_clock::now();
  res.setup_seconds = std::chrono::duration<double>(loop_start - run_start).count() - res.in_situ_seconds;
  const double mpi_at_start = parallel::seconds_in_mpi();
  PhaseTimes::run().reset();
  Progress progress(p.steps, s.solver.end_time, o.quiet || !comm.root());
  Checkpointing checkpoints(s, o, res.output_dir);
  auto gather = [&] {
    if (!comm.distributed()) return;
    if (comm.root() && !whole) whole.emplace(s);
    gather_model<D>(comm, m, comm.root() ? &whole->model : nullptr);
    // its contact pairs as one rank would find them (the forces do not depend on when they were
    // found); the fictitious densities of its relaxation, as one rank makes them
    if (comm.root()) whole->contact = pd::Contact<D>(s.contact, whole->model);
    if (comm.root() && dr && !whole_dr) whole_dr.emplace(whole->model);
    if (!dr) return;
    // an unfinished load step's iterations (the same on every rank but for its particles')
    auto& u = dr->unfinished();
    auto* w = comm.root() ? &whole_dr->unfinished() : nullptr;
    if (w)
      w->iteration = u.iteration, w->load_norm = u.load_norm, w->pass = u.pass, w->iterations = u.iterations, w->broken_through = u.broken_through,
      w->spent = u.spent;
    if (w) w->previous.clear(), w->start.clear();
    gather_into<D>(comm, m, u.previous, w ? &w->previous : nullptr);
    gather_into<D>(comm, m, u.start, w ? &w->start : nullptr);
  };
  auto write_state = [&](io::CheckpointWriter& w) {
    std::uint8_t from_start = 0;
    w("run.from_start", from_start);
    history_bytes = history ? history->bytes() : 0;
    visit_run(w, whole ? *whole : p);
    if (dr) pd::visit(w, whole_dr ? *whole_dr : *dr);
  };
  if (s.solver.kind == scene::SolverKind::explicit_dynamics) {
    if (!restarted) {
      write_snapshot<D>(fields, m, s, comm);
      history_row(0, {});
    }
    // velocity-Verlet steps (pd/velocity_verlet.hpp), with the history rows and snapshots due
    Stepper explicit_steps{[&](long) {
                             p.step();
                             res.bond_updates += bonds;
                             return true;
                           },
                           [&](long step) {
                             if (history_rows.due(step)) {
                               auto e = history_row(step, {});
                               progress.update(step, m.time, e.broken_fraction);
                               history_rows.passed(step);
                             }
                             if (snapshots.due(step)) {
                               write_snapshot<D>(fields, m, s, comm);
                               snapshots.passed(step);
                             }
                           },
                           [&](long) { gather(); }, write_state};
    run_steps(explicit_steps, res.first_step, p.steps, m.time, checkpoints, res);
  } else {
    if (!dr) dr.emplace(m);
    if (!restarted) write_snapshot<D>(fields, m, s, comm);
    long relaxing = 0, iterations = 0;  // the load step of the progress lines, the iterations of this process
    dr->observe([&](int iteration, double residual) {
      if (comm.root()) progress.iteration(relaxing, iteration, s.solver.max_iterations, residual, s.solver.tolerance);
      if (o.stop_after_iterations > 0 && ++iterations == o.stop_after_iterations) set_stop_signal(SIGTERM);
    });
    // load steps of dynamic relaxation (run::Simulation::relax), each with its history row and snapshot
    pd::RelaxationResult r;
    Stepper load_steps{
        [&](long step) {
          relaxing = step;
          r = p.relax(*dr, s.solver, s.solver.end_time * double(step) / double(p.steps));
          if (r.stopped) {  // the checkpoint holds the load steps done and this one's iterations so far
            res.stopped_in = dr->is_unfinished()
                                 ? fmt::format("in load step {} at iteration {} (its checkpoint goes on from there)", step, dr->unfinished().iteration)
                                 : fmt::format("in load step {} (its checkpoint solves it again from the positions it holds)", step);
            PhaseClock output_clock(Phase::output);
            checkpoints.stop_within(step, m.time, res, gather, write_state);
            return false;
          }
          res.bond_updates += double(r.iterations) * bonds;
          return true;
        },
        [&](long step) {
          std::vector<double> extra{double(r.iterations), r.residual};
          if (at_equilibrium) extra.push_back(double(r.breaking_passes));
          auto e = history_row(step, extra);
          write_snapshot<D>(fields, m, s, comm);
          progress.update(step, m.time, e.broken_fraction, true);
          if (!r.converged && !o.quiet && comm.root()) {  // rank 0 speaks for a distributed run
            if (at_equilibrium && r.residual <= s.solver.tolerance)  // the last equilibrium was reached but broke bonds
              std::fprintf(stderr, "rift: warning: load step %ld: bonds still breaking after %d equilibria (solver max_breaking_passes)\n",
                           step, r.breaking_passes);
            else
              std::fprintf(stderr, "rift: warning: load step %ld did not converge in %d iterations (residual %.3g > %.3g)\n", step,
                           r.iterations, r.residual, s.solver.tolerance);
          }
        },
        [&](long) { gather(); }, write_state};
    run_steps(load_steps, res.first_step, p.steps, m.time, checkpoints, res);
  }
  if (o.stop_after_iterations > 0) set_stop_signal(0);  // the tests' stop, not a signal to the process
  res.loop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
  const double in_mpi = parallel::seconds_in_mpi() - mpi_at_start;
  res.phases = phase_summary(PhaseTimes::run(), res.loop_seconds);
  res.final_energy = pd::summarize<D>(m);
  pd::update_damage<D>(m);
  res.max_damage = max_damage<D>(comm, m);
  if (comm.distributed()) res.notes.push_back(load_balance(comm, m, res.loop_seconds, in_mpi, p.halo->ghosts(), p.processor_grid()));
  res.time = m.time;
  if (res.stopped) return res;  // the final state's reports belong to the run that ends
  res.steps = p.steps;
  report_interfaces<D>(m, interfaces, res);
  progress.finish(p.steps, m.time, res.final_energy.broken_fraction);
  draw_final_damage<D>(s, m, comm, particles, res);
  return res;
}

}  // namespace

Plan check(const scene::Scene& s, std::ostream& out) {
  if (s.method == scene::Method::mpm) return check_mpm(s, out);
  return s.dimension == 2 ? check_dim<2>(s, out) : check_dim<3>(s, out);
}

Result run(const scene::Scene& s, const Options& o) {
  if (o.threads > 0) omp_set_num_threads(o.threads);
  if (s.method == scene::Method::mpm) return run_mpm(s, o);
  return s.dimension == 2 ? run_dim<2>(s, o) : run_dim<3>(s, o);
}

}  // namespace rift::run
