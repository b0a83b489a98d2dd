#include "rift/run/mpm_runner.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <ostream>

#include <fstream>

#include "rift/core/progress.hpp"
#include "rift/io/field_writer.hpp"
#include "rift/io/history.hpp"
#include "rift/io/plot_crack_tips_script.hpp"  // generated from share/plot_crack_tips.py
#include "rift/io/python_plot.hpp"
#include "rift/mpm/checkpoint_state.hpp"
#include "rift/mpm/crack_growth.hpp"
#include "rift/mpm/discretize.hpp"
#include "rift/mpm/domain.hpp"
#include "rift/mpm/energy.hpp"
#include "rift/mpm/j_integral.hpp"
#include "rift/mpm/solver.hpp"
#include "rift/parallel/communicator.hpp"
#include "rift/run/cadence.hpp"
#include "rift/run/checkpointing.hpp"
#include "rift/run/history_columns.hpp"
#include "rift/run/run_loop.hpp"
#include "rift/run/time_step.hpp"

namespace rift::run {

namespace {

template <int D>
struct MpmRun {
  mpm::Model<D> model;
  mpm::Solver<D> solver;
  double stable_dt = 0.0, dt = 0.0;
  long steps = 0;

  explicit MpmRun(const scene::Scene& s) : model(mpm::discretize<D>(s)), solver(s, model) {
    stable_dt = solver.stable_time_step(model);
    const auto plan = explicit_steps(s.solver, stable_dt, "cell size / wave speed");
    dt = plan.dt;
    steps = plan.steps;
  }
};

template <int D>
Plan check_dim(const scene::Scene& s, std::ostream& out) {
  MpmRun<D> r(s);
  if (const auto w = snapshots_past_steps(s, r.steps); !w.empty()) std::fprintf(stderr, "%s\n", w.c_str());
  Plan plan;
  plan.particles = r.model.particles.size();
  plan.bytes_per_particle = sizeof(Vec<D>) * 4 + sizeof(double) * 3 + sizeof(mpm::Tensor<D>) * 2 + sizeof(material::State<D>) + 4;
  plan.stable_time_step = r.stable_dt;
  plan.time_step = r.dt;
  plan.steps = r.steps;
  const auto& g = r.model.grid;
  char line[256];
  out << "scene        " << s.name << " (" << s.file << "), material point method\n";
  std::snprintf(line, sizeof line, "grid         %ld x %ld%s nodes, cell %g m\n", g.nodes[0], g.nodes[1],
                D == 3 ? (" x " + std::to_string(g.nodes[2])).c_str() : "", g.cell_size);
  out << line;
  for (const auto& b : r.model.bodies) out << "body         " << b.name << ": " << (b.last - b.first) << " material points\n";
  std::snprintf(line, sizeof line, "particles    %zu\nmemory       %.0f bytes/particle, %.1f MB grid\n", plan.particles,
                plan.bytes_per_particle, double(g.size()) * (1 + 4 * D) * 8 / 1e6);
  out << line;
  std::snprintf(line, sizeof line, "time step    stable %.4g s, used %.4g s\nsteps        %ld (end time %.4g s)\n", r.stable_dt, r.dt,
                r.steps, s.solver.end_time);
  out << line;
  std::string fields;
  for (const auto& f : s.output.fields) fields += " " + f;
  out << "output       " << s.output.count << " snapshots (position" << fields << ") -> fields_000000.h5 ... (one file each) + fields.xdmf\n";
  out << "             " << s.output.history_count << " history rows -> history.csv\n";
  if constexpr (D == 2) {
    if (!s.cracks.empty()) {
      const auto tips = mpm::interior_tips(r.model, r.solver.cracks());
      std::snprintf(line, sizeof line,
                    "crack tips   %zu inside material: J (contour reaching %d cells from the tip, area term %s), G, K_I, K_II (split by %s)\n",
                    tips.size(), s.mpm.j_contour, s.mpm.j_area_term ? "on" : "off",
                    s.mpm.mode_partition == scene::Mpm::ModePartition::cod ? "the crack opening/sliding" : "the interaction integral");
      out << line << "             at every history row -> crack_tips.csv" << (s.output.crack_tip_plot ? " + crack_tips.png" : "") << "\n";
      if (s.crack_growth.enabled) {
        const auto& gr = s.crack_growth;
        const bool hoop = gr.criterion == scene::CrackGrowth::Criterion::max_hoop_stress;
        std::snprintf(line, sizeof line, "crack growth %s >= %g %s, direction of maximum hoop stress, %g m per event, checked every %d steps\n",
                      hoop ? "K_eq" : "G", hoop ? gr.toughness : gr.critical_energy_release_rate, hoop ? "Pa m^0.5" : "J/m^2",
                      gr.increment > 0.0 ? gr.increment : 0.5 * s.mpm.cell_size, gr.check_every);
        out << line;
      }
    }
  }
  out << checkpoint_plan(s);
  return plan;
}

/// A snapshot of the fields; the ranks of a distributed run write it together, each its points'
/// rows (runs of consecutive numbers of the whole run).
template <int D>
void write_snapshot(io::FieldWriter& w, const mpm::Model<D>& m, const scene::Scene& s, const mpm::Domain<D>* domain) {
  const auto& ps = m.particles;
  const std::size_t n = ps.size();
  std::vector<io::FieldWriter::Rows> rows;
  if (domain)
    for (auto id : domain->id()) {
      if (rows.empty() || rows.back().first + rows.back().count != id) rows.push_back({id, 0});
      ++rows.back().count;
    }
  auto write = [&](const std::string& name, const std::vector<double>& values, int components) {
    if (domain) w.write_rows(name, values, components, rows);
    else w.write(name, values, components);
  };
  auto vec = [&](auto get) {
    std::vector<double> out(3 * n, 0.0);
    for (std::size_t p = 0; p < n; ++p)
      for (int a = 0; a < D; ++a) out[3 * p + a] = get(p, a);
    return out;
  };
  w.begin_snapshot(m.time);
  write("position", vec([&](std::size_t p, int a) { return ps.position[p][a]; }), 3);
  for (const auto& f : s.output.fields) {
    if (f == "displacement") write(f, vec([&](std::size_t p, int a) { return ps.position[p][a] - ps.reference_position[p][a]; }), 3);
    else if (f == "velocity") write(f, vec([&](std::size_t p, int a) { return ps.velocity[p][a]; }), 3);
    else if (f == "stress") {
      // xx, yy, zz, xy, yz, xz (zz and the out-of-plane shears are 0 in 2D)
      std::vector<double> out(6 * n, 0.0);
      for (std::size_t p = 0; p < n; ++p) {
        const auto& sg = ps.state[p].stress;
        out[6 * p + 0] = sg(0, 0), out[6 * p + 1] = sg(1, 1), out[6 * p + 3] = sg(0, 1);
        if constexpr (D == 3) out[6 * p + 2] = sg(2, 2), out[6 * p + 4] = sg(1, 2), out[6 * p + 5] = sg(0, 2);
      }
      write(f, out, 6);
    } else {
      std::vector<double> out(n, 0.0);
      for (std::size_t p = 0; p < n; ++p) {
        if (f == "volume") out[p] = ps.volume[p];
        else if (f == "body") out[p] = ps.body[p];
        else if (f == "equivalent_plastic_strain") out[p] = ps.state[p].equivalent_plastic_strain;
        else if (f == "strain_energy_density")
          out[p] = material::strain_energy_density<D>(m.bodies[ps.body[p]].constants, ps.state[p], ps.deformation_gradient[p]);
      }
      write(f, out, 1);
    }
  }
  w.end_snapshot();
}

/// Per-tip fracture parameters at the history rows of a cracked 2D run (crack_tips.csv).
class CrackTipHistory {
 public:
  CrackTipHistory(const std::string& path, const mpm::Model<2>& m, const mpm::Solver<2>& solver, const scene::Mpm& settings)
      : path_(path), out_(path), contour_(mpm::contour_of(settings)) {
    tips_ = mpm::interior_tips(m, solver.cracks());
    out_ << "time,step,crack,tip,x,y,angle_deg,J_1,J_2,J_1_area,G,K_I,K_II,opening,sliding,K_I_cod,K_II_cod,K_I_interaction,K_II_interaction\n";
    out_.flush();
  }
  /// Continues the file of a restarted run from its first `bytes` (the rows up to the checkpoint;
  /// the runner has checked it holds them, run/checkpointing.hpp require_output_file).
  CrackTipHistory(const std::string& path, std::vector<mpm::CrackTip> tips, std::int64_t bytes, const scene::Mpm& settings)
      : path_(path), contour_(mpm::contour_of(settings)), tips_(std::move(tips)) {
    std::filesystem::resize_file(path, static_cast<std::uintmax_t>(bytes));
    out_.open(path, std::ios::app);
  }
  /// The tips the file follows, and its length so far (every row flushed), for a checkpoint.
  const std::vector<mpm::CrackTip>& tips() const { return tips_; }
  std::int64_t bytes() { return static_cast<std::int64_t>(out_.tellp()); }
  const std::string& path() const { return path_; }
  bool empty() const { return tips_.empty(); }
  void row(const mpm::Model<2>& m, const mpm::Solver<2>& solver, long step) {
    for (const auto& t : tips_) {
      const auto k = mpm::crack_tip_parameters(m, solver, t, contour_);
      if (!std::isfinite(k.J1) || !std::isfinite(k.KI) || !std::isfinite(k.KII))
        throw PhysicsError("step " + std::to_string(step) + ": the J-integral at crack " + std::to_string(t.crack) + " is not finite");
      char line[512];
      std::snprintf(line, sizeof line, "%.9g,%ld,%zu,%s,%.9g,%.9g,%.6g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", m.time,
                    step, t.crack, t.end == mpm::TipEnd::end ? "end" : "start", k.position[0], k.position[1], k.angle * 180.0 / M_PI, k.J1,
                    k.J2, k.J1_area, k.G, k.KI, k.KII, k.opening, k.sliding, k.KI_cod, k.KII_cod, k.KI_interaction, k.KII_interaction);
      out_ << line;
    }
    out_.flush();
  }

 private:
  std::string path_;
  std::ofstream out_;
  mpm::JContour contour_;
  std::vector<mpm::CrackTip> tips_;
};

/// Rank 0's cracks, on every rank of a distributed run (every rank holds them all).
mpm::CrackSet broadcast_cracks(const parallel::Communicator& comm, const mpm::CrackSet& cracks) {
  std::vector<double> flat;  // per crack: its particle count, then the particles' and surfaces' coordinates
  for (const auto& c : cracks.cracks()) {
    flat.push_back(double(c.points.size()));
    for (const auto* v : {&c.points, &c.above, &c.below})
      for (const auto& x : *v) flat.insert(flat.end(), x.begin(), x.end());
  }
  comm.broadcast(flat);
  mpm::CrackSet out = cracks;
  std::size_t at = 0;
  for (auto& c : out.cracks()) {
    const auto n = static_cast<std::size_t>(flat[at++]);
    for (auto* v : {&c.points, &c.above, &c.below}) {
      v->resize(n);
      for (auto& x : *v) x = {flat[at], flat[at + 1]}, at += 2;
    }
  }
  out.update_bounds();
  return out;
}

/// Each point's weight in the cut into boxes (mpm/domain.hpp cut_into_boxes): 1, and 2 for a point
/// within the solver's reach of an explicit crack (two cells of its box), which takes a velocity
/// field per node by the line-crossing test (crack.hpp) on nodes that solve per field. 2 lies
/// between a near point's measured work with linear shapes (about 1.5 ordinary points') and with
/// quadratic B-splines (about 2.4) (docs/decisions/performance-notes.md).
template <int D>
std::vector<double> crack_work_weights(const mpm::Model<D>& m, const mpm::CrackSet& cracks) {
  std::vector<double> weight(m.particles.size(), 1.0);
  if constexpr (D == 2)
    for (std::size_t p = 0; p < weight.size(); ++p)
      if (cracks.near(m.particles.position[p], 2.0 * m.grid.cell_size)) weight[p] = 2.0;
  return weight;
}

template <int D>
Result run_dim(const scene::Scene& s, const Options& o) {
  const auto& comm = parallel::Communicator::world();
  MpmRun<D> r(s);  // every scene error is raised here, before anything is written
  if (const auto w = snapshots_past_steps(s, r.steps); !w.empty() && comm.root()) std::fprintf(stderr, "%s\n", w.c_str());
  auto& m = r.model;
  const std::size_t points = m.particles.size();  // the whole run's
  Result res;
  res.output_dir = o.output_dir.empty() ? "results/" + s.name : o.output_dir;
  io::FieldWriter fields(res.output_dir, "fields", points, comm.distributed());
  res.fields_h5 = fields.h5_pattern();
  res.fields_xdmf = fields.xdmf_path();
  const bool cracked = D == 2 && !s.cracks.empty();
  std::optional<mpm::CrackPropagation> propagation;
  if constexpr (D == 2)
    if (cracked && s.crack_growth.enabled) propagation.emplace(s, m, r.solver);

  // The loop's own state, which a checkpoint holds with the model's (mpm/checkpoint_state.hpp).
  // history rows at the starts of steps 1 + k steps / rows (energy at t = 0 first): due at step - 1
  Cadence snapshots{s.output.count, r.steps}, history_rows{s.output.history_count, r.steps, 0};
  std::int64_t history_bytes = 0, tip_bytes = 0;
  std::vector<mpm::CrackTip> tip_list;
  // (a distributed run's checkpoint holds the whole run's points, gathered on rank 0 into `whole`)
  auto visit_run = [&](auto& a, mpm::Model<D>& model) {
    a("run.next_snapshot", snapshots.next), a("run.next_history", history_rows.next), a("run.history_bytes", history_bytes);
    a("run.crack_growth_events", res.crack_growth_events);
    fields.visit_state(a);
    mpm::visit(a, model);
    r.solver.visit_state(a);
    if (cracked) a("run.tips", tip_list), a("run.tip_bytes", tip_bytes);
    if (propagation) propagation->visit_state(a);
  };
  const bool restarted = !o.restart.empty();
  if (restarted) {
    // the whole checkpoint is read before any output is touched
    res.first_step = 1 + read_checkpoint(s, o, r.steps, [&](io::CheckpointReader& checkpoint) { visit_run(checkpoint, m); });
  }
  // mpirun -np N: from here on each rank holds its box of the model (a restart read the whole
  // run's checkpoint first, so it continues on any number of ranks)
  std::optional<mpm::Domain<D>> domain;
  std::optional<mpm::Model<D>> whole;  // rank 0's, for the checkpoints of a distributed run
  // and for its crack tips: rank 0 takes J, K and crack growth on the whole model, with a solver of
  // its own holding the cracks and the points' last accelerations and velocity gradients
  std::optional<mpm::Solver<D>> whole_solver;
  if (comm.distributed()) {
    const auto weight = crack_work_weights<D>(m, r.solver.cracks());
    domain.emplace(comm, mpm::cut_into_boxes<D>(m, comm.size(), s.file, o.cut_axis, o.processor_grid, &weight), m);
    auto part = domain->part_of(m);
    r.solver.distribute(m, part, *domain);
    if (comm.root()) whole.emplace(std::move(m));
    m = std::move(part);
    if (comm.root() && cracked) whole_solver.emplace(s, *whole);
  }
  const mpm::Domain<D>* in = domain ? &*domain : nullptr;
  // a distributed run's failure found by one rank (a point off the grid; J not finite at a tip)
  // while the others wait for it in an exchange ends them all
  auto on_this_rank = [&](auto&& f) {
    if (!domain) return f();
    try {
      f();
    } catch (const PhysicsError& e) {
      std::fprintf(stderr, "rift: run stopped (rank %d): %s\n", comm.rank(), e.what());
      parallel::MpiSession::abort(1);
    }
  };
  // rank 0's whole model and solver as they stand after `step` (collective; once a step)
  long mirrored = -1;
  auto mirror = [&](long step) {
    if (!domain || mirrored == step) return;
    mirrored = step;
    domain->gather_points(m, whole ? &*whole : nullptr);
    domain->gather_grid(m.grid, whole ? &whole->grid : nullptr);
    if (!cracked) return;
    auto acceleration = domain->gather(r.solver.accelerations());
    auto velocity_gradient = domain->gather(r.solver.velocity_gradients());
    if (whole_solver) whole_solver->mirror(r.solver.cracks(), std::move(acceleration), std::move(velocity_gradient));
  };
  mpm::Model<D>& tip_model = whole ? *whole : m;
  mpm::Solver<D>& tip_solver = whole_solver ? *whole_solver : r.solver;
  if (restarted) {
    require_output_file(o, res.output_dir + "/history.csv", history_bytes);
    if (cracked) require_output_file(o, res.output_dir + "/crack_tips.csv", tip_bytes);
  }
  if (comm.root()) make_output_folders(s, res.output_dir);
  comm.barrier();  // before the ranks open the snapshot files together
  // rows hold the time-centred energy at the start of the sampled step (see Solver::measure_energy)
  double row_kinetic = 0.0, row_strain = 0.0;
  HistoryColumns columns;
  columns.add(s.output.history, [&](std::vector<double>& row) {
    for (const auto& q : s.output.history)
      row.push_back(q == "kinetic_energy" ? row_kinetic : q == "strain_energy" ? row_strain : row_kinetic + row_strain);
  });
  std::optional<io::History> history;  // rank 0 writes the history
  if (comm.root() && restarted) history.emplace(res.output_dir + "/history.csv", history_bytes);
  if (comm.root() && !restarted) history.emplace(res.output_dir + "/history.csv", columns.names());
  res.history_csv = res.output_dir + "/history.csv";
  auto history_row = [&](long step, double time, double kinetic, double strain) {
    if (!std::isfinite(kinetic) || !std::isfinite(strain))
      throw PhysicsError("step " + std::to_string(step) + ": energy is not finite; the time step may be above the stable limit");
    row_kinetic = kinetic, row_strain = strain;
    const std::vector<double> row = columns.row(time, step);
    if (history) history->row(row);
  };
  std::optional<CrackTipHistory> tips;  // rank 0 writes them
  if constexpr (D == 2) {
    if (cracked && comm.root()) {
      const std::string path = res.output_dir + "/crack_tips.csv";
      if (restarted) tips.emplace(path, tip_list, tip_bytes, s.mpm);
      else tips.emplace(path, tip_model, tip_solver, s.mpm);
      res.files.push_back({"cracks", tips->path()});
    }
  }
  Checkpointing checkpoints(s, o, res.output_dir);
  const auto start = std::chrono::steady_clock::now();
  const double mpi_at_start = parallel::seconds_in_mpi();
  Progress progress(r.steps, s.solver.end_time, o.quiet || !comm.root());
  if (!restarted) write_snapshot<D>(fields, m, s, in);
  // MPM steps (mpm/solver.hpp), with crack growth, the history rows (each step's time-centred energy,
  // sampled before it) and the crack tips' rows, and the snapshots due
  bool sample = false;
  Stepper steps{[&](long step) {
                  sample = history_rows.due(step - 1);
                  if (sample) r.solver.measure_energy();
                  on_this_rank([&] { r.solver.step(m, r.dt); });
                  res.particle_steps += double(points);
                  if constexpr (D == 2) {
                    if (propagation && step % s.crack_growth.check_every == 0) {
                      // rank 0 grows the cracks of its whole model, and every rank takes them
                      mirror(step);
                      if (comm.root()) on_this_rank([&] { res.crack_growth_events += propagation->check(tip_model, tip_solver, step); });
                      if (domain) r.solver.set_cracks(broadcast_cracks(comm, tip_solver.cracks()));
                    }
                  }
                  return true;
                },
                [&](long step) {
                  if (sample) {
                    const auto& e = r.solver.measured_energy();
                    history_row(step - 1, e.time, e.kinetic, e.strain);
                    if constexpr (D == 2) {
                      if (cracked) mirror(step);
                      if (tips) on_this_rank([&] { tips->row(tip_model, tip_solver, step); });
                    }
                    progress.update(step, m.time, 0.0);
                    history_rows.passed(step - 1);
                  }
                  if (snapshots.due(step)) {
                    write_snapshot<D>(fields, m, s, in);
                    snapshots.passed(step);
                  }
                },
                mirror,
                [&](io::CheckpointWriter& w) {
                  history_bytes = history->bytes();
                  if (tips) tip_list = tips->tips(), tip_bytes = tips->bytes();
                  visit_run(w, whole ? *whole : m);
                }};
  run_steps(steps, res.first_step, r.steps, m.time, checkpoints, res);
  res.loop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double in_mpi = parallel::seconds_in_mpi() - mpi_at_start;
  if (res.stopped) {
    res.time = m.time;
    return res;  // the final state's reports belong to the run that ends
  }
  progress.finish(r.steps, m.time, 0.0);
  if (tips && s.output.crack_tip_plot && !tips->empty()) {
    const std::string png = res.output_dir + "/crack_tips.png";
    std::string reason;
    if (io::run_python_script(io::plot_crack_tips_script, {tips->path(), png, s.name + ": stress intensity factors"}, reason))
      res.files.push_back({"K(t)", png});
    else
      res.notes.push_back("crack tip plot not written: " + reason);
  }
  auto e = mpm::summarize<D>(m);
  double sums[2] = {e.kinetic, e.strain};
  comm.sum(sums, 2);
  res.final_energy.kinetic = sums[0];
  res.final_energy.strain = sums[1];
  if (domain) res.notes.push_back(domain->load_balance(m, res.loop_seconds, in_mpi));
  res.steps = r.steps;
  res.time = m.time;
  return res;
}

}  // namespace

Plan check_mpm(const scene::Scene& s, std::ostream& out) { return s.dimension == 2 ? check_dim<2>(s, out) : check_dim<3>(s, out); }
Result run_mpm(const scene::Scene& s, const Options& o) { return s.dimension == 2 ? run_dim<2>(s, o) : run_dim<3>(s, o); }

}  // namespace rift::run
