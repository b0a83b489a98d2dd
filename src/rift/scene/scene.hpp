// Scene: the validated, SI-unit description of a run. Physics code sees only these plain structs,
// never TOML (parse.cpp turns a file into a Scene and reports every mistake with file:line:column).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rift/core/error.hpp"
#include "rift/core/vec.hpp"

namespace rift::scene {

/// The largest counts a scene may ask for: what the integers that hold them keep, and a bound on
/// files and steps no run reaches in practice (docs/scenes.md, "Limits"). The step loops multiply a
/// step by a count of snapshots or rows, so steps times either stays below 2^63.
namespace limits {
inline constexpr long long steps = 10'000'000'000;        // explicit time steps of a run
inline constexpr long long snapshots = 1'000'000;         // field snapshots (a file each)
inline constexpr long long history_rows = 100'000'000;    // rows of history.csv
inline constexpr long long load_steps = 1'000'000;        // load steps of relaxation (a snapshot each)
inline constexpr long long iterations = 2'147'483'647;    // iterations, passes and step intervals held as int
/// A given time step below this fraction of the stable one is a mistake (a unit, an exponent).
inline constexpr double smallest_time_step_fraction = 1e-6;
}  // namespace limits

enum class PlaneCondition { none, stress, strain };
enum class Method { peridynamics, mpm };
/// Peridynamic models (pmb, lps) and continuum models for the material point method.
enum class ModelKind { pmb, lps, ves, linear_elastic, neo_hookean, j2_plasticity, eps };
/// Influence function omega(|xi|): constant 1, or delta/|xi| ("inverse_distance", LAMMPS peri/lps).
enum class Influence { constant, inverse_distance };
// What breaks a bond: its stretch past s0 (Silling and Askari 2005; LAMMPS peri), or the normal
// stress along it past the tensile strength (a Rankine criterion on the bond-pair stress of its ends;
// state-based models).
enum class BondFailure { stretch, normal_stress };

struct Material {
  std::string name;
  SourceLocation where;
  ModelKind model = ModelKind::pmb;
  double density = 0.0;        // kg/m^3
  double bulk_modulus = 0.0;   // K, Pa (3D value; 2D models derive their in-plane modulus)
  double shear_modulus = 0.0;  // G, Pa
  Influence influence = Influence::constant;
  std::optional<double> fracture_energy;   // G0, J/m^2
  std::optional<double> critical_stretch;  // s00, given directly
  // K at which a grown crack advances steadily in the lattice with the critical stretch G0 gives,
  // over K_Ic (tests/test_crack_growth.cpp); s00 is divided by it
  double propagation_toughness_ratio = 1.0;
  double alpha = 0.0;                      // s0 = s00 - alpha * s_min (LAMMPS peri)
  BondFailure bond_failure = BondFailure::stretch;
  std::optional<double> tensile_strength;  // T, Pa (bond_failure = normal_stress)
  double viscous_fraction = 0.0;           // ves: lambda, share of the deviatoric response that relaxes
  double relaxation_time = 0.0;            // ves: tau, s
  bool surface_correction = true;
  double yield_stress = 0.0;       // j2_plasticity, eps: uniaxial yield stress, Pa
  double hardening_modulus = 0.0;  // j2_plasticity, linear isotropic hardening, Pa
  double youngs_modulus() const { return 9.0 * bulk_modulus * shear_modulus / (3.0 * bulk_modulus + shear_modulus); }
  double poisson_ratio() const {
    return (3.0 * bulk_modulus - 2.0 * shear_modulus) / (2.0 * (3.0 * bulk_modulus + shear_modulus));
  }
};

enum class Shape { box, cylinder, sphere, polygon, half_space, union_of, difference_of, intersection_of };

struct RegionDef {
  std::string name;
  SourceLocation where;
  Shape shape = Shape::box;
  Point3 min{}, max{};               // box
  Point3 center{};                   // sphere, cylinder (2D: disk centre)
  Point3 axis{0, 0, 1};              // cylinder: from base centre to top centre (3D)
  double radius = 0.0;               // sphere, cylinder
  std::vector<std::array<double, 2>> vertices;  // polygon (x, y), prism along z
  double z_min = -1e300, z_max = 1e300;         // polygon prism extent (3D)
  Point3 normal{};                   // half-space: points with (x - center) . normal <= 0
  std::vector<std::string> of;       // union/difference/intersection children
};

struct Body {
  std::string name;
  SourceLocation where;
  std::size_t material = 0;
  std::string region;
  double spacing = 0.0;  // lattice spacing dx, m
  double horizon = 0.0;  // delta, m
  Point3 lattice_origin{};
  /// Share of a neighbour's volume inside the horizon: "exact" (geometric fraction of its cell) or
  /// "lammps" (LAMMPS PERI: bonds up to delta, linear taper over the last half spacing).
  enum class PartialVolume { exact, lammps } partial_volume = PartialVolume::exact;
  int particles_per_cell = 2;  // MPM: material points per cell along each axis
};

enum class TimeFunctionKind { constant, ramp, step, table };
struct TimeFunction {
  TimeFunctionKind kind = TimeFunctionKind::constant;
  double start = 0.0, end = 0.0;  // ramp: 0 at start -> 1 at end; step: 0 before start, 1 after
  std::vector<std::array<double, 2>> table;  // (t, factor), piecewise linear, held at the ends
};

/// Pre-crack: a segment (2D, two points) or a planar polygon (3D, >= 3 points). Bonds that
/// cross it are never created.
struct Crack {
  SourceLocation where, points_where;
  std::vector<Point3> points;
  /// Peridynamics: fluid pressure on the crack faces, Pa, times its time function. The bonds the
  /// crack cuts carry it as the force state of the fluid's stress -p I (see pd/crack_pressure.hpp).
  double pressure = 0.0;
  TimeFunction pressure_time;
};

/// Peridynamics: a pre-existing fracture (a joint, a bedding plane, the paper sheet of Zhou et al.
/// 2008), a straight segment in 2D or a planar polygon in 3D. The bonds that cross it stay bonds
/// but follow an interface law (geomech/interface_law.hpp): they fail when the effective normal traction
/// on the interface is a tension above `tensile_strength`, or when the shear traction exceeds
/// cohesion + friction_coefficient * (sigma_n - p); a failed interface bond bears compression only
/// (the faces may open and close), and fluid enters it where it is open.
struct Interface {
  SourceLocation where, points_where;
  std::vector<Point3> points;
  double tensile_strength = 0.0;      // T, Pa: the effective normal tension at which the interface parts
  double cohesion = 0.0;              // tau_0, Pa
  double friction_coefficient = 0.0;  // mu
};

/// Peridynamics: a borehole (or perforation, or any cavity) given by a region. The bodies' lattice
/// sites inside it hold fluid instead of material, at `pressure` times its time function; the bonds
/// from the material to those sites carry it (pd/crack_pressure.hpp).
struct Borehole {
  SourceLocation where;
  std::string region;
  double pressure = 0.0;  // Pa (with injection: the pressure at t = 0)
  TimeFunction pressure_time;
  /// Injection instead of a prescribed pressure: fluid volume per second (at zero pressure) pumped
  /// into the borehole and the cracks joined to it (2D: into the modelled thickness), m^3/s, and the
  /// fluid's bulk modulus; the pressure follows from the mass balance (pd/fluid_network.hpp).
  std::optional<double> injection_rate;
  double fluid_bulk_modulus = 0.0;  // Pa
  /// The fluid's dynamic viscosity, Pa s: 0 keeps the lumped, inviscid fluid (one pressure in the
  /// borehole and every crack joined to it); above 0 the fluid flows along the cracks by the cubic
  /// law (pd/viscous_fluid.hpp).
  double fluid_viscosity = 0.0;
  /// Fluid in the injection system (pump, line) at the borehole's pressure, m^3 (2D: its share of
  /// the modelled thickness): its compliance V_s / K_f stores fluid as the pressure rises and gives
  /// it back as the pressure falls (a laboratory test's breakdown runs on it).
  double injection_system_volume = 0.0;
  /// The wall's breakdown pressure, Pa: the dry pre-cracks that start in the borehole (notches)
  /// stay shut to its fluid until its pressure first reaches this (pd/fluid_network.hpp). For a wall
  /// the lattice does not resolve (a hole a horizon or less across), e.g. Hubbert and Willis' 3
  /// sigma_h - sigma_H + T, which hf_breakdown checks on a resolved wall. Unset: open from the start.
  std::optional<double> breakdown_pressure;
};

/// Peridynamics: the far-field principal stresses of the rock (Pa, compression negative), applied
/// as tractions sigma . n on the faces of the bodies' bounding box: sigma_H along the axis
/// `sigma_H_axis` (x or y), sigma_h along the other horizontal axis, sigma_v along z (3D; in 2D
/// the section is horizontal and sigma_v is out of plane). Before the run the scene is brought to
/// equilibrium under them and every other load at t = 0, with no bond allowed to break (the
/// in-situ stage, adaptive dynamic relaxation); that state starts the run (the pressurization stage).
struct InSituStress {
  bool enabled = false;
  SourceLocation where;
  double sigma_v = 0.0, sigma_H = 0.0, sigma_h = 0.0;
  int sigma_H_axis = 0;  // 0: x, 1: y
  // how the faces are loaded: uniform tractions, or the rigid lubricated plates of a true tri-axial
  // frame (pd/platens.hpp: the low face on each axis held, the high one pushed with sigma times its area)
  enum class Faces { tractions, platens } faces = Faces::tractions;
  int max_iterations = 50000;
  double tolerance = 1e-6;
  // where the relaxation starts: the reference lattice, or the uniform strain of the far-field
  // stresses (pd/in_situ_strain.hpp), which saves it the interior's share of the iterations
  enum class Start { reference, uniform_strain } start = Start::reference;
  // how the equilibrium is found: preconditioned conjugate gradients (pd/static_equilibrium.hpp), or
  // adaptive dynamic relaxation; automatic: the conjugate gradients where the forces are smooth (no
  // pre-crack whose faces may touch, no interface's friction), else dynamic relaxation
  enum class Solver { automatic, conjugate_gradient, dynamic_relaxation } solver = Solver::automatic;
  /// Stress tensor component along axis k (principal axes = coordinate axes).
  double principal(int k) const { return k == 2 ? sigma_v : (k == sigma_H_axis ? sigma_H : sigma_h); }
};

enum class BoundaryKind { fixed, velocity, displacement, traction, body_force };
struct Boundary {
  SourceLocation where;
  std::string region;
  BoundaryKind kind = BoundaryKind::fixed;
  std::array<std::optional<double>, 3> value;  // per component; unset = free (traction: 0)
  TimeFunction time;
  double layer_depth = 0.0;  // traction: depth of the loaded particle layer (default: spacing)
};

struct InitialVelocity {
  SourceLocation where;
  std::string region;
  Point3 velocity{};
};

/// Explicit dynamics, or load steps each brought to equilibrium: by adaptive dynamic relaxation or
/// by the static solver (preconditioned conjugate gradients, pd/static_equilibrium.hpp).
enum class SolverKind { explicit_dynamics, dynamic_relaxation, static_equilibrium };
struct Solver {
  SolverKind kind = SolverKind::explicit_dynamics;
  /// Load steps to equilibrium (dynamic relaxation or static), not time steps.
  bool load_stepped() const { return kind != SolverKind::explicit_dynamics; }
  std::optional<double> time_step;
  SourceLocation time_step_where, end_time_where;
  double safety_factor = 0.8;
  double end_time = 0.0;
  // dynamic relaxation (Kilic and Madenci 2010) and the static solver
  int load_steps = 1;
  int max_iterations = 20000;
  double tolerance = 1e-6;
  /// When bonds may break: in every iteration (`during`, dynamic relaxation only), or only at each
  /// equilibrium, solving again until a pass breaks nothing (`at_equilibrium`: quasi-static growth,
  /// no transients; the static solver's only way).
  enum class Breaking { during, at_equilibrium } breaking = Breaking::during;
  int max_breaking_passes = 200;  // at_equilibrium: equilibria per load step
};

struct Contact {
  bool enabled = true;
  double distance = 0.9;   // contact distance in lattice spacings
  double stiffness = 15.0; // multiple of the micromodulus (LAMMPS/EMU: 15)
};

/// Material point method settings ([mpm]).
struct Mpm {
  enum class Shape { linear, gimp, bspline2, bspline3 } shape = Shape::bspline2;
  enum class Scheme { usl, usf, musl } scheme = Scheme::musl;
  enum class Transfer { flip, apic } transfer = Transfer::flip;
  /// Multi-material contact between bodies (Bardenhagen et al. 2001); none: one shared velocity field.
  enum class Contact { none, frictionless, friction, stick } contact = Contact::none;
  double friction = 0.0;  // Coulomb coefficient (contact or crack_contact = friction)
  /// Contact of the two faces of an explicit crack where it is closed (Nairn 2003).
  Contact crack_contact = Contact::frictionless;
  double cell_size = 0.0;
  double flip_fraction = 1.0;  // velocity update: flip_fraction * FLIP + (1 - flip_fraction) * PIC
  double damping = 0.0;        // mass-proportional (external) damping coefficient, 1/s
  std::optional<Point3> grid_min, grid_max;  // default: bodies' bounds grown by 3 cells
  SourceLocation cell_size_where, grid_max_where;  // where the scene gives them
  /// J-integral at explicit-crack tips (Guo and Nairn 2006): contour `j_contour` cells from the
  /// node nearest the tip; the area term of the dynamic J (their eq. 8).
  int j_contour = 2;
  bool j_area_term = true;
  /// K_I : K_II from the interaction integral on the J contour, or from the crack opening and
  /// sliding displacements behind the tip (Guo and Nairn 2006, eqs. 21-22).
  enum class ModePartition { interaction_integral, cod } mode_partition = ModePartition::interaction_integral;
};

/// Propagation of explicit MPM cracks ([crack_growth]): the direction of maximum hoop stress
/// (Erdogan and Sih 1963), growth when K_eq >= K_Ic or G >= G_c.
struct CrackGrowth {
  bool enabled = false;
  enum class Criterion { max_hoop_stress, energy_release_rate } criterion = Criterion::max_hoop_stress;
  double toughness = 0.0;                     // K_Ic, Pa m^0.5
  double critical_energy_release_rate = 0.0;  // G_c, J/m^2
  double increment = 0.0;                     // growth per event, m (0: half a cell)
  int check_every = 10;                       // steps between checks
};

struct Output {
  int count = 10;                   // number of field snapshots (plus the initial state)
  SourceLocation count_where;       // where the scene gives it (none: the default)
  std::vector<std::string> fields;  // position, displacement, velocity, damage, dilatation, ...
  int history_count = 200;          // history rows
  std::vector<std::string> history; // history columns after time and step (default: all)
  std::vector<std::string> reactions;  // region names whose reaction force is recorded
  bool damage_image = true;         // 2D: PNG of the final damage field
  bool damage_histogram = true;     // peridynamics: particles per damage interval of 0.1 at the end (CSV + PNG)
  std::vector<Point3> probes;       // peridynamics: points whose nearest particle's damage joins the history
  SourceLocation probes_where;
  bool crack_tip_plot = true;       // MPM with cracks: PNG of K_I, K_II against time per crack tip
};

/// [checkpoint]: when a run writes its whole state, to continue with `rift run SCENE --restart FILE`
/// (io/checkpoint.hpp). It also writes one when stopped by SIGTERM or SIGINT.
struct Checkpoint {
  long every_steps = 0;        // steps (load steps for relaxation) between checkpoints; 0: not by steps
  double every_seconds = 0.0;  // wall time between checkpoints, s; 0: not by time
  std::string file;            // relative to the output directory, or absolute; empty: checkpoint.rift
  SourceLocation file_where;   // where the scene gives it
};

struct Scene {
  std::string file;
  std::uint64_t fingerprint = 0;  // of the scene's text (FNV-1a): a restart refuses another scene's checkpoint, or one of this file since edited
  std::string name;
  int dimension = 3;
  Method method = Method::peridynamics;
  PlaneCondition plane = PlaneCondition::none;
  double thickness = 1.0;  // 2D only, m
  std::vector<Material> materials;
  std::vector<RegionDef> regions;
  std::vector<Body> bodies;
  std::vector<Crack> cracks;
  std::vector<Borehole> boreholes;
  std::vector<Interface> interfaces;
  std::vector<Boundary> boundaries;
  InSituStress in_situ;
  std::vector<InitialVelocity> initial_velocities;
  Solver solver;
  Contact contact;
  Mpm mpm;
  CrackGrowth crack_growth;
  Output output;
  Checkpoint checkpoint;
  /// What is legitimate but likely not meant ("file:line:column: warning: 'key': ..."): `rift check`
  /// and `rift run` print each before they start.
  std::vector<std::string> warnings;

  const RegionDef* find_region(const std::string& n) const {
    for (const auto& r : regions)
      if (r.name == n) return &r;
    return nullptr;
  }
};

}  // namespace rift::scene
