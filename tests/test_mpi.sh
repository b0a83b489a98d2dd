#!/usr/bin/env bash
# Distributed runs (issue 6; pd/window.hpp): the same scene under `mpirun -np 1, 2, 3` writes the
# same bytes as a plain one-rank run (the ranks write each snapshot file together, MPI-IO): every field of every snapshot (so every broken bond: damage
# is their volume share), the XDMF index and the history (energies, broken bonds, reactions,
# probes). Scenes whose cracks run along or across the cuts between ranks: a 2D PMB plate whose
# pre-crack grows and branches along the cut of two ranks (Ha and Bobaru 2010's set-up, coarse,
# with contact), the same plate as LPS whose bonds fail on the normal stress (the ghosts' strains
# exchanged), and a 3D LPS bar pulled apart (the dilatation's halo exchange), also as VES (the
# bonds' viscous history on both sides of a cut), and a rock block's in-situ stage (between
# platens, or under tractions by conjugate gradients or dynamic relaxation) followed by explicit
# steps that break its bonds, and fluids in rock (a borehole breaking down into a dry pre-crack, a
# pressurized pre-crack, the same pre-crack growing in rock whose bonds break, a viscous fluid
# flowing along the cracks it grows across a cut, and a pre-existing fracture that it crosses and
# dilates), and contact between two bodies and past the bonds' reach. The material point method (mpm/domain.hpp) adds
# the nodes' sums of neighbouring ranks in another order than one rank: its fields agree with the
# one-rank run's to 1e-12 of their size (compare_fields, the second argument). What a distributed
# run cannot take yet is refused with exit status 2 before anything is written.
set -euo pipefail
rift="$1"
compare_fields="$2"
examples="$(dirname "$0")/../examples"
mpirun=(mpirun --oversubscribe)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# one_rank ARGS...: rift without mpirun, the reference the distributed runs are compared with, on
# both of the cores this test has to itself (tests/CMakeLists.txt: its mpiruns take them; rift's sums
# do not depend on the number of threads, so its bytes are a one-thread run's)
one_rank() { OMP_NUM_THREADS=2 "$rift" "$@"; }
# RIFT_MPI_SANITIZED=1 (the sanitizer build, tests/CMakeLists.txt): each scene is compared on its
# largest rank count alone, and the scenes of minutes each under the sanitizers (thousands of dynamic
# relaxation iterations, the MPM crack's growth) are left out (skipped): the sanitizers look for
# memory errors and undefined behaviour on the exchanges' paths, which the other scenes take too;
# the release build runs and compares every scene on every rank count
sanitized() { [[ "${RIFT_MPI_SANITIZED:-0}" == 1 ]]; }
sanitizer_skips="borehole sealed relax_bar eps_relax_bar free_plate insitu_dr kgd_viscous mpm_growth"
# skipped SCENE: whether this run leaves SCENE out
skipped() { sanitized && [[ " $sanitizer_skips " == *" $1 "* ]]; }
sanitized && echo "note: each scene compared on its largest rank count only, and left out: $sanitizer_skips (RIFT_MPI_SANITIZED=1)"
# The plate and ns_plate write the damage image and histogram (final_damage.csv and
# damage_histogram.csv gathered on rank 0 are compared); the other scenes leave them out, whose
# plots (matplotlib) took most of each run's time.
# run_on_ranks SCENE NP: runs $tmp/SCENE.toml on NP ranks into $tmp/SCENE-npNP (its log beside it),
# which must report its load balance on more than one rank
run_on_ranks() {
  local out="$tmp/$1-np$2"
  "${mpirun[@]}" -np "$2" "$rift" run "$tmp/$1.toml" -o "$out" -q > "$out.log" 2>&1 || { cat "$out.log"; fail "$1: mpirun -np $2"; }
  [ "$2" -eq 1 ] || grep -q "load balance over $2 ranks" "$out.log" || fail "$1: no load-balance report on $2 ranks"
}
# same_outputs SERIAL OUT WHAT: every output of OUT is the bytes of the one-rank run's in SERIAL
# (the plots aside: matplotlib's bytes, drawn from the same data)
same_outputs() {
  local f name
  for f in "$1"/*; do
    name=$(basename "$f")
    case "$name" in *.png) continue ;; esac
    cmp -s "$f" "$2/$name" || fail "$3: $name differs from the one-rank run's"
  done
}
# ranks_compared NP...: the rank counts same_on_ranks NP... runs (the last alone with RIFT_MPI_SANITIZED=1)
ranks_compared() {
  if sanitized; then echo "${@: -1}"; else echo "$@"; fi
}
# same_on_ranks SCENE NP...: SCENE on each NP writes the bytes of its one-rank run in $tmp/SCENE-serial.
# With RIFT_MPI_SANITIZED=1 (the sanitizer build, tests/CMakeLists.txt) only on the largest NP:
# a rank with a neighbour on each side takes every path of the exchanges, and the sanitizers look
# for memory and undefined behaviour, which the release build's runs on every NP already compare
same_on_ranks() {
  local scene="$1" np
  shift
  for np in $(ranks_compared "$@"); do
    run_on_ranks "$scene" "$np"
    same_outputs "$tmp/$scene-serial" "$tmp/$scene-np$np" "$scene on $np ranks"
  done
}
# compared_on NP...: those rank counts in words, for the ok lines ("2 and 3", or "3" alone with
# RIFT_MPI_SANITIZED=1)
compared_on() {
  local counts=($(ranks_compared "$@"))
  local n=${#counts[@]}
  if [ "$n" -eq 1 ]; then echo "${counts[0]}"; return; fi
  local head="${counts[*]:0:n-1}"
  echo "${head// /, } and ${counts[n-1]}"
}

cat > "$tmp/plate.toml" <<'SCENE'
[scene]
name = "plate"
dimension = 2
plane = "stress"
thickness = 0.001
[materials.glass]
model = "pmb"
density = 2440.0
youngs_modulus = 72e9
poisson_ratio = 0.3333333333
fracture_energy = 3.8
[regions.plate]
shape = "box"
min = [0.0, 0.0]
max = [0.05, 0.02]
[regions.top]
shape = "box"
min = [0.0, 0.0195]
max = [0.05, 0.02]
[regions.bottom]
shape = "box"
min = [0.0, 0.0]
max = [0.05, 0.0005]
[bodies.plate]
material = "glass"
region = "plate"
spacing = 0.0005
horizon = 4.0
[[cracks]]
points = [[0.0, 0.01], [0.025, 0.01]]
[[boundaries]]
region = "top"
type = "traction"
y = 4.0e6
[[boundaries]]
region = "bottom"
type = "traction"
y = -4.0e6
[solver]
type = "explicit"
end_time = 2.5e-5
[output]
snapshots = 4
fields = ["displacement", "velocity", "damage", "stress", "strain_energy_density"]
history_rows = 25
history = ["kinetic_energy", "strain_energy", "total_energy", "broken_bonds", "max_damage"]
probes = [[0.03, 0.01]]
SCENE

cat > "$tmp/bar.toml" <<'SCENE'
[scene]
name = "bar"
dimension = 3
[materials.rock]
model = "lps"
density = 2000.0
youngs_modulus = 1.0e9
poisson_ratio = 0.25
fracture_energy = 1.0
[regions.bar]
shape = "box"
min = [0.0, 0.0, 0.0]
max = [0.006, 0.006, 0.012]
[regions.top]
shape = "box"
min = [0.0, 0.0, 0.011]
max = [0.006, 0.006, 0.012]
[regions.bottom]
shape = "box"
min = [0.0, 0.0, 0.0]
max = [0.006, 0.006, 0.001]
[bodies.bar]
material = "rock"
region = "bar"
spacing = 0.0005
horizon = 3.015
[[boundaries]]
region = "top"
type = "velocity"
z = 5.0
[[boundaries]]
region = "bottom"
type = "fixed"
[solver]
type = "explicit"
end_time = 2.0e-5
[output]
snapshots = 3
fields = ["displacement", "velocity", "damage", "dilatation", "stress"]
history_rows = 10
history = ["kinetic_energy", "strain_energy", "broken_bonds", "max_damage"]
reactions = ["top", "bottom"]
damage_histogram = false
SCENE

# the bar again, viscoelastic: the history of every bond, kept by lattice blocks (bond_slabs.hpp)
sed -e 's/model = "lps"/model = "ves"\nviscous_fraction = 0.5\nrelaxation_time = 2.0e-6/' -e 's/name = "bar"/name = "ves_bar"/' \
  "$tmp/bar.toml" > "$tmp/ves_bar.toml"

# the bar again, elastic-plastic (laws/eps.hpp): each rank commits the plastic extension of every
# direction it holds, a ghost's with its owner's return-map scale
sed -e 's/model = "lps"/model = "eps"\nyield_stress = 3.0e5/' -e 's/name = "bar"/name = "eps_bar"/' \
  "$tmp/bar.toml" > "$tmp/eps_bar.toml"

# the plate again, LPS, its bonds failing on the normal stress along them (normal_stress_failure.hpp):
# a bond across a cut reads the strains of both ends, the ghost's from its owner, and the
# dilatation pass goes row by row through each window's slabs, the first cut short (bond_slabs.hpp)
sed -e 's/model = "pmb"/model = "lps"/' -e 's/fracture_energy = 3.8/bond_failure = "normal_stress"\ntensile_strength = 15.0e6/' \
  -e 's/name = "plate"/name = "ns_plate"/' "$tmp/plate.toml" > "$tmp/ns_plate.toml"

for scene in plate bar ves_bar eps_bar ns_plate; do
  one_rank run "$tmp/$scene.toml" -o "$tmp/$scene-serial" -q > "$tmp/$scene-serial.log"
  same_on_ranks "$scene" 1 2 3
  echo "ok: $scene on $(compared_on 1 2 3) ranks: the same bytes in every output as one rank"
done
# pencils (pd/window.hpp partition_into_pencils): the 3D bars cut across y and z (1 x 2 x 2, on 4
# ranks) and across y alone (1 x 2 x 1), each lattice line along x whole: a box owns one range of the
# numbering per layer and its window holds many; the halo sends a peer's several ranges in one
# message and the sums over the owned particles are exact (parallel/exact_sum.hpp). A checkpoint of
# the 4 pencils (rank 0 gathers the ranges in the whole run's order) continues on 3 slabs and on 1.
# relax_bar: the bar pulled by dynamic relaxation, whose damping and residual sum over every
# rank's particles (exact, in units of lattice lines that no grid cuts)
sed -e 's/type = "velocity"/type = "displacement"/' -e 's/^z = 5.0/z = 2.0e-6\ntime = { function = "ramp", start = 0.0, end = 1.0 }/' \
  -e 's/type = "explicit"/type = "dynamic_relaxation"\nload_steps = 2\nmax_iterations = 400\ntolerance = 1e-4/' -e 's/end_time = 2.0e-5/end_time = 1.0/' \
  -e '/^snapshots = 3/d' -e '/^history_rows = 10/d' -e 's/name = "bar"/name = "relax_bar"/' "$tmp/bar.toml" > "$tmp/relax_bar.toml"
skipped relax_bar || one_rank run "$tmp/relax_bar.toml" -o "$tmp/relax_bar-serial" -q > /dev/null
# eps_relax_bar: the same, elastic-plastic: each load step's equilibrium commits the plastic extensions
sed -e 's/model = "lps"/model = "eps"\nyield_stress = 1.0e5/' -e 's/name = "relax_bar"/name = "eps_relax_bar"/' \
  "$tmp/relax_bar.toml" > "$tmp/eps_relax_bar.toml"
skipped eps_relax_bar || one_rank run "$tmp/eps_relax_bar.toml" -o "$tmp/eps_relax_bar-serial" -q > /dev/null
for scene in bar ves_bar relax_bar eps_relax_bar; do
  skipped "$scene" && continue
  for grid in 1x2x2 1x2x1; do
    IFS=x read -r _ py pz <<< "$grid"
    out="$tmp/$scene-$grid"
    "${mpirun[@]}" -np $((py * pz)) "$rift" run "$tmp/$scene.toml" -o "$out" -q --processor-grid "$grid" > "$out.log" 2>&1 ||
      { cat "$out.log"; fail "$scene: --processor-grid $grid"; }
    same_outputs "$tmp/$scene-serial" "$out" "$scene on a $grid grid"
  done
done
printf '[checkpoint]\nevery_steps = 20\nfile = "ckpt_*.rift"\n' | cat "$tmp/ves_bar.toml" - > "$tmp/ves_bar-pencils.toml"
"${mpirun[@]}" -np 4 "$rift" run "$tmp/ves_bar-pencils.toml" -o "$tmp/ves_bar-pencils" -q --processor-grid 1x2x2 > /dev/null 2>&1 ||
  fail "ves_bar: checkpointed run on a 1x2x2 grid"
for np in $(ranks_compared 1 3); do
  out="$tmp/ves_bar-pencils-restart-np$np"
  cp -r "$tmp/ves_bar-pencils" "$out"
  "${mpirun[@]}" -np "$np" "$rift" run "$tmp/ves_bar-pencils.toml" -o "$out" -q --restart "$out/ckpt_20.rift" > "$out.log" 2>&1 ||
    { cat "$out.log"; fail "ves_bar: restart on $np ranks from the pencils' checkpoint"; }
  same_outputs "$tmp/ves_bar-serial" "$out" "ves_bar restarted on $np ranks from a 1x2x2 grid's checkpoint"
done
echo "ok: $(skipped relax_bar && echo "bar and ves_bar" || echo "bar, ves_bar and relax_bar") on 1 x 2 x 2 and 1 x 2 x 1 pencils, and ves_bar from a checkpoint of 1 x 2 x 2 continued on $(compared_on 1 3) ranks: the same bytes as one rank"
# the plates' cracks must have grown (else the test shows nothing about breaking on the cut)
cmp -s "$tmp/bar-serial/history.csv" "$tmp/eps_bar-serial/history.csv" && fail "eps_bar: the same history as the elastic bar (no plastic flow)"
for scene in plate ns_plate; do
  awk -F, 'NR > 1 { b = $6 } END { exit !(b > 1000) }' "$tmp/$scene-serial/history.csv" || fail "$scene: fewer than 1000 bonds broke"
done

# contact beyond a rank's window (pd/contact_beyond_window.hpp): a striker, the second body (so
# numbered after the whole plate, on the last rank), hits the plate's lower face (the first rank's)
# at 30 m/s and shatters it; and the plate squeezed at 50 m/s until it shatters, its layers of
# different ranks pressed together past the bonds' reach
cat > "$tmp/impact.toml" <<'SCENE'
[scene]
name = "impact"
dimension = 2
plane = "stress"
thickness = 0.001
[materials.glass]
model = "pmb"
density = 2440.0
youngs_modulus = 72e9
poisson_ratio = 0.3333333333
fracture_energy = 3.8
[regions.plate]
shape = "box"
min = [0.0, 0.0]
max = [0.02, 0.01]
[regions.striker]
shape = "box"
min = [0.008, -0.003]
max = [0.012, -0.0001]
[bodies.plate]
material = "glass"
region = "plate"
spacing = 0.0005
horizon = 3.015
[bodies.striker]
material = "glass"
region = "striker"
spacing = 0.0005
horizon = 3.015
[[initial_velocity]]
region = "striker"
velocity = [0.0, 30.0]
[solver]
end_time = 2e-5
[output]
snapshots = 5
damage_image = false
damage_histogram = false
SCENE
sed -e 's/type = "traction"/type = "velocity"/' -e 's/^y = 4.0e6/y = -50.0/' -e 's/^y = -4.0e6/y = 0.0/' \
    -e 's/end_time = 2.5e-5/end_time = 4e-5/' -e 's/name = "plate"/name = "squeeze"/' "$tmp/plate.toml" > "$tmp/squeeze.toml"
for scene in impact squeeze; do
  one_rank run "$tmp/$scene.toml" -o "$tmp/$scene-serial" -q > /dev/null
  same_on_ranks "$scene" 2 3
done
awk -F, 'NR > 1 { b = $6 } END { exit !(b > 10000) }' "$tmp/impact-serial/history.csv" || fail "impact: the striker did not break the plate"
echo "ok: impact (contact between two bodies on different ranks) and squeeze (contact past the bonds' reach) on $(compared_on 2 3) ranks: the same bytes as one rank"

# quasi-static growth by dynamic relaxation, bonds breaking at each equilibrium: the ranks own
# whole blocks of the sums (12800 particles: three blocks of 4096 and the rest), add each other's
# block sums in the one-rank order, and so damp, converge and break as one rank does
sed -n '/^DR_SCENE$/,/^DR_SCENE_END$/p' "$0" | sed '1d;$d' > "$tmp/relax_plate.toml"
# the same plate held by tractions alone: its iterations take out the rigid motion of the whole
# body (rigid_motion.hpp), summed over every rank's owned particles in the one-rank order, as are
# the loads' norm and the residual
sed -e 's/type = "displacement"/type = "traction"/' -e 's/^y = 1.0e-5$/y = 3.0e6/' -e '/^reactions = /d' -e 's/name = "relax_plate"/name = "free_plate"/' \
  -e 's/^type = "fixed"$/type = "traction"\ny = -3.0e6\ntime = { function = "ramp", start = 0.0, end = 1.0 }/' \
  "$tmp/relax_plate.toml" > "$tmp/free_plate.toml"
grep -q 'type = "fixed"\|type = "displacement"' "$tmp/free_plate.toml" && fail "free_plate: still held"
# the same plate by the static solver (run/simulation.hpp solve_static): its conjugate gradients sum
# over the owned particles exactly, as the in-situ stage's do, and break as one rank does
sed -e 's/type = "dynamic_relaxation"/type = "static"/' -e 's/name = "relax_plate"/name = "static_plate"/' \
  "$tmp/relax_plate.toml" > "$tmp/static_plate.toml"
# scene, the fewest bonds its one-rank run must break
for case in "relax_plate 100" "free_plate 1000" "static_plate 100"; do
  read -r scene least <<< "$case"
  skipped "$scene" && continue
  one_rank run "$tmp/$scene.toml" -o "$tmp/$scene-serial" -q > /dev/null
  same_on_ranks "$scene" 2 3
  awk -F, -v least="$least" 'NR > 1 { b = $4 } END { exit !(b > least) }' "$tmp/$scene-serial/history.csv" || fail "$scene: fewer than $least bonds broke"
done
echo "ok: relax_plate (dynamic relaxation, breaking at equilibrium), free_plate (held by tractions alone) and static_plate (the static solver) on $(compared_on 2 3) ranks: the same bytes as one rank"

# the in-situ stage (static_equilibrium.cpp, dynamic_relaxation.cpp) on N ranks, then explicit
# steps in which a core pushed along x breaks bonds: a 10,201-particle plane-strain LPS block
# between rigid platens (platens.hpp: each plate's sums gather every rank's face particles in the
# face's order; conjugate gradients without the coarse space), the same block under tractions
# alone (conjugate gradients with the coarse space, summed in fixed point, and the free body's
# rigid motions projected out) and between platens by dynamic relaxation from the uniform in-situ
# strain (its measured fictitious density; the plates move in its iterations)
cat > "$tmp/insitu_platens.toml" <<'SCENE'
[scene]
name = "insitu_platens"
dimension = 2
plane = "strain"
thickness = 0.001
[materials.rock]
model = "lps"
density = 2500.0
youngs_modulus = 10e9
poisson_ratio = 0.25
fracture_energy = 20.0
[regions.block]
shape = "box"
min = [-0.05, -0.05]
max = [0.05, 0.05]
[regions.core]
shape = "box"
min = [-0.003, -0.003]
max = [0.003, 0.003]
[bodies.rock]
material = "rock"
region = "block"
spacing = 0.001
horizon = 3.015
[[boundaries]]
region = "core"
type = "traction"
x = 4e8
time = { function = "ramp", start = 0.0, end = 2e-6 }
[in_situ_stress]
sigma_H = -10e6
sigma_h = -5e6
faces = "platens"
tolerance = 1e-8
[solver]
end_time = 1e-5
[output]
snapshots = 2
fields = ["displacement", "damage"]
history = ["kinetic_energy", "broken_bonds"]
history_rows = 10
damage_image = false
damage_histogram = false
SCENE
sed -e 's/faces = "platens"/faces = "tractions"/' -e 's/name = "insitu_platens"/name = "insitu_coarse"/' \
  "$tmp/insitu_platens.toml" > "$tmp/insitu_coarse.toml"
sed -e 's/faces = "platens"/faces = "platens"\nsolver = "dynamic_relaxation"\nstart = "uniform_strain"/' -e 's/tolerance = 1e-8/tolerance = 1e-6/' \
  -e 's/name = "insitu_platens"/name = "insitu_dr"/' "$tmp/insitu_platens.toml" > "$tmp/insitu_dr.toml"
# scene, how its one-rank run's in-situ stage reached equilibrium
for case in "insitu_platens force evaluations of preconditioned conjugate gradients" \
  "insitu_coarse force evaluations of preconditioned conjugate gradients" "insitu_dr iterations of dynamic relaxation"; do
  read -r scene how <<< "$case"
  skipped "$scene" && continue
  one_rank run "$tmp/$scene.toml" -o "$tmp/$scene-serial" > "$tmp/$scene-serial.log" 2>&1 || { cat "$tmp/$scene-serial.log"; fail "$scene: one rank"; }
  grep -q "in-situ stage: equilibrium in [0-9]* $how" "$tmp/$scene-serial.log" || fail "$scene: its in-situ stage did not reach equilibrium by $how"
  awk -F, 'NR > 1 { b = $4 } END { exit !(b > 1000) }' "$tmp/$scene-serial/history.csv" || fail "$scene: fewer than 1000 bonds broke"
  same_on_ranks "$scene" 2 3
done
echo "ok: the in-situ stage (platens, the coarse space, dynamic relaxation between platens) and the explicit steps after it on $(compared_on 2 3) ranks: the same bytes as one rank"

# fluid in rock (fluid_network.hpp): a borehole fed
# by a lumped injection (its cavity volume summed over every rank's owned particles in the one-rank
# order) whose wall breaks down at 4 MPa into a dry pre-crack across both cuts (the fluid's labels
# spread across the ranks' cuts in rounds), after an in-situ stage between platens, by dynamic
# relaxation; and, in explicit steps, a pre-crack with a pressure of its own across both cuts beside
# a second, injected borehole on the cut of three ranks
cat > "$tmp/borehole.toml" <<'SCENE'
[scene]
name = "borehole"
dimension = 2
plane = "strain"
thickness = 0.001
[materials.rock]
model = "lps"
density = 2500.0
youngs_modulus = 10e9
poisson_ratio = 0.25
[regions.block]
shape = "box"
min = [-0.05, -0.05]
max = [0.05, 0.05]
[regions.borehole]
shape = "cylinder"
center = [0.0, 0.0]
radius = 0.005
[regions.rock]
shape = "difference"
of = ["block", "borehole"]
[bodies.rock]
material = "rock"
region = "rock"
spacing = 0.001
horizon = 3.015
[[cracks]]
points = [[0.0, -0.03], [0.0, 0.03]]
[[boreholes]]
region = "borehole"
injection_rate = 2e-9
fluid_bulk_modulus = 2.2e9
breakdown_pressure = 4e6
[in_situ_stress]
sigma_H = -6e6
sigma_h = -3e6
faces = "platens"
tolerance = 1e-6
[solver]
type = "dynamic_relaxation"
end_time = 1.0
load_steps = 3
max_iterations = 5000
tolerance = 1e-5
[output]
fields = ["displacement", "stress", "fluid_pressure"]
history = ["strain_energy"]
damage_image = false
damage_histogram = false
SCENE
cat > "$tmp/pressurized.toml" <<'SCENE'
[scene]
name = "pressurized"
dimension = 2
plane = "strain"
thickness = 0.001
[materials.rock]
model = "lps"
density = 2500.0
youngs_modulus = 10e9
poisson_ratio = 0.25
[regions.block]
shape = "box"
min = [-0.05, -0.05]
max = [0.05, 0.05]
[regions.borehole]
shape = "cylinder"
center = [0.02, 0.032]
radius = 0.004
[regions.rock]
shape = "difference"
of = ["block", "borehole"]
[bodies.rock]
material = "rock"
region = "rock"
spacing = 0.001
horizon = 3.015
[[cracks]]
points = [[0.0, -0.03], [0.0, 0.03]]
pressure = 1e6
time = { function = "ramp", start = 0.0, end = 2e-6 }
[[boreholes]]
region = "borehole"
injection_rate = 1e-6
fluid_bulk_modulus = 2.2e9
[solver]
end_time = 5e-5
[output]
snapshots = 2
fields = ["displacement", "fluid_pressure"]
history = ["kinetic_energy", "strain_energy"]
history_rows = 10
damage_image = false
damage_histogram = false
SCENE
if ! skipped borehole; then
  one_rank run "$tmp/borehole.toml" -o "$tmp/borehole-serial" -q > /dev/null
  sed -e 's/breakdown_pressure = 4e6/breakdown_pressure = 100e6/' -e 's/name = "borehole"/name = "sealed"/' "$tmp/borehole.toml" > "$tmp/sealed.toml"
  one_rank run "$tmp/sealed.toml" -o "$tmp/sealed-serial" -q > /dev/null
  # the fluid must have entered the pre-crack: the borehole's pressure at the end is under half the
  # sealed borehole's
  paste -d, "$tmp/borehole-serial/history.csv" "$tmp/sealed-serial/history.csv" | awk -F, 'NR > 1 { open = $4; shut = $12 } END { exit !(open < 0.5 * shut) }' ||
    fail "borehole: the fluid did not enter the dry pre-crack after breakdown"
fi
one_rank run "$tmp/pressurized.toml" -o "$tmp/pressurized-serial" -q > /dev/null
# growing: the pressurized pre-crack in rock whose bonds break (fracture_energy), the fluid's cracks
# growing across both cuts: the ghosts' bond states from their owners, the labels, fragments and
# network load made over the ranks (fluid_network.hpp, network_load.hpp)
sed -e 's/poisson_ratio = 0.25/poisson_ratio = 0.25\nfracture_energy = 0.5/' -e 's/name = "pressurized"/name = "growing"/' \
  -e 's/history = \["kinetic_energy", "strain_energy"\]/history = ["kinetic_energy", "strain_energy", "broken_bonds"]/' \
  "$tmp/pressurized.toml" > "$tmp/growing.toml"
one_rank run "$tmp/growing.toml" -o "$tmp/growing-serial" -q > /dev/null
# the cracks grew: over a thousand bonds broken by the end
awk -F, 'NR == 1 { for (c = 1; c <= NF; ++c) if ($c == "broken_bonds") column = c } NR > 1 { broken = $column } END { exit !(column && broken > 1000) }' \
  "$tmp/growing-serial/history.csv" || fail "growing: the fluid's cracks did not grow"
# growing_uncorrected: the same without the surface correction, whose network load the runs of
# bonds make over each rank's window (network_load_runs.hpp)
sed -e 's/fracture_energy = 0.5/fracture_energy = 0.5\nsurface_correction = false/' -e 's/name = "growing"/name = "growing_uncorrected"/' \
  "$tmp/growing.toml" > "$tmp/growing_uncorrected.toml"
one_rank run "$tmp/growing_uncorrected.toml" -o "$tmp/growing_uncorrected-serial" -q > /dev/null
awk -F, 'NR == 1 { for (c = 1; c <= NF; ++c) if ($c == "broken_bonds") column = c } NR > 1 { broken = $column } END { exit !(column && broken > 1000) }' \
  "$tmp/growing_uncorrected-serial/history.csv" || fail "growing_uncorrected: the fluid's cracks did not grow"
# flowing: the growing scene's borehole on the cut of 2 ranks, its water flowing along the cracks
# grown from its wall by the cubic law (viscous_fluid.hpp): the network's nodes on both sides of the
# cut, its pressures solved over the whole network on every rank
sed -e 's/fluid_bulk_modulus = 2.2e9/fluid_bulk_modulus = 2.2e9\nfluid_viscosity = 0.001/' -e 's/center = \[0.02, 0.032\]/center = [0.02, -0.009]/' \
  -e 's/name = "growing"/name = "flowing"/' "$tmp/growing.toml" > "$tmp/flowing.toml"
one_rank run "$tmp/flowing.toml" -o "$tmp/flowing-serial" -q > /dev/null
# the water flowed and held pressure: 0.62 MPa in the borehole at the end, where the lumped fluid
# of growing (no viscosity) had cavitated to zero
awk -F, 'NR == 1 { for (c = 1; c <= NF; ++c) if ($c == "pressure_borehole_0") column = c } NR > 1 { p = $column } END { exit !(column && p > 1e5) }' \
  "$tmp/flowing-serial/history.csv" || fail "flowing: the viscous fluid's pressure at the end is not above 0.1 MPa"
# interface: the growing scene with a pre-existing fracture parallel to the pressurized crack, 10 mm
# from it, across every cut (geomech/interface_law.hpp): the law of a bond with an owned end reads its
# ghost end's strain and fluid from their owners; the outcome is reduced over the ranks
awk '/^\[solver\]/ { print "[[interfaces]]\npoints = [[0.01, -0.045], [0.01, 0.045]]\ntensile_strength = 0.2e6\nfriction_coefficient = 0.6" } { print }' \
  "$tmp/growing.toml" | sed -e 's/name = "growing"/name = "interface"/' > "$tmp/interface.toml"
one_rank run "$tmp/interface.toml" -o "$tmp/interface-serial" > "$tmp/interface-serial.log" 2>&1
# its fracture crossed the interface and the fluid opened it: crossed+dilated (one rank's reading)
grep -q "interface 0: crossed+dilated" "$tmp/interface-serial.log" || { cat "$tmp/interface-serial.log"; fail "interface: not crossed+dilated on one rank"; }
# competing: the growing scene's borehole beside the pressurized crack and a dry pre-crack from
# one to the other across both cuts, which both fluids enter: the particles each takes follow one
# rank's search (fluid_network.hpp label_as_one_rank; the labels spread in rounds, as for one
# fluid, gave 3 ranks another split and another run)
awk '/^\[\[boreholes\]\]/ { print "[[cracks]]\npoints = [[-0.002, 0.02], [0.03, 0.0]]\n" } { print }' "$tmp/growing.toml" |
  sed -e 's/name = "growing"/name = "competing"/' -e 's/center = \[0.02, 0.032\]/center = [0.02, 0.0]/' -e 's/end_time = 5e-5/end_time = 3.5e-5/' \
  > "$tmp/competing.toml"
one_rank run "$tmp/competing.toml" -o "$tmp/competing-serial" -q > /dev/null
for scene in borehole pressurized growing growing_uncorrected flowing interface competing; do
  skipped "$scene" && continue
  same_on_ranks "$scene" 2 3
done
# kgd_viscous: the first 0.1 s of examples/hf_kgd_viscosity.toml (dynamic relaxation after an
# in-situ stage; a viscous fluid in a notch along the cut of 2 ranks, its crack growing at the
# first load step's equilibrium by 82 bonds)
sed -e 's/end_time = 1.0/end_time = 0.1/' -e 's/load_steps = 20/load_steps = 2/' -e 's/snapshots = 20/snapshots = 2\ndamage_image = false\ndamage_histogram = false/' \
  -e 's/name = "hf_kgd_viscosity"/name = "kgd_viscous"/' "$examples/hf_kgd_viscosity.toml" > "$tmp/kgd_viscous.toml"
if ! skipped kgd_viscous; then
  one_rank run "$tmp/kgd_viscous.toml" -o "$tmp/kgd_viscous-serial" -q > /dev/null
  awk -F, 'NR > 1 { b = $3 } END { exit !(b > 50) }' "$tmp/kgd_viscous-serial/history.csv" || fail "kgd_viscous: its crack did not grow"
  same_on_ranks kgd_viscous 2
fi
echo "ok: a borehole breaking down into a dry pre-crack (dynamic relaxation, in-situ stage), a pressurized pre-crack beside an injected borehole (explicit), the same pre-crack growing in breakable rock (with and without the surface correction), a viscous fluid flowing along the cracks it grows across a cut, a pre-existing fracture across every cut that the fluid's crack crosses and dilates, and two fluids competing for a dry pre-crack on $(compared_on 2 3) ranks (and a viscous KGD fracture by dynamic relaxation on 2): the same bytes as one rank"

# checkpoints written by 2 ranks restart on 3 and on 1, and the continued runs write the bytes of
# the uninterrupted one-rank run (rank 0 gathers the whole run's state: any number of ranks reads it;
# insitu_platens: a checkpoint of the explicit steps after the in-situ stage, which a restart skips)
# borehole: a checkpoint of the first load step, the wall broken down and the pre-crack wet;
# growing: the fluid's network, its load and the crack surface in the middle of the growth;
# flowing: the viscous fluid each node holds and its pressures too; interface: the interface
# bonds' slip, marks and strains
for case in "plate 20" "impact 100" "ves_bar 20" "insitu_platens 20" "borehole 1" "growing 80" "flowing 80" "interface 80"; do
  read -r scene step <<< "$case"
  skipped "$scene" && continue
  printf '[checkpoint]\nevery_steps = %s\nfile = "ckpt_*.rift"\n' "$step" | cat "$tmp/$scene.toml" - > "$tmp/$scene-ckpt.toml"
  "${mpirun[@]}" -np 2 "$rift" run "$tmp/$scene-ckpt.toml" -o "$tmp/$scene-ckpt" -q > /dev/null 2>&1 || fail "$scene: checkpointed run on 2 ranks"
  [ -s "$tmp/$scene-ckpt/ckpt_$step.rift" ] || fail "$scene: no checkpoint after step $step on 2 ranks"
  for np in $(ranks_compared 1 3); do
    out="$tmp/$scene-restart-np$np"
    cp -r "$tmp/$scene-ckpt" "$out"
    "${mpirun[@]}" -np "$np" "$rift" run "$tmp/$scene-ckpt.toml" -o "$out" -q --restart "$out/ckpt_$step.rift" > "$out.log" 2>&1 ||
      { cat "$out.log"; fail "$scene: restart on $np ranks"; }
    grep -q "continued from .*ckpt_$step.rift at step $step" "$out.log" || fail "$scene: restart on $np ranks did not say where it continued"
    same_outputs "$tmp/$scene-serial" "$out" "$scene restarted on $np ranks from 2 ranks' checkpoint"
  done
  echo "ok: $scene: a checkpoint of 2 ranks continues on $(compared_on 1 3) ranks, the same bytes as the run never stopped"
done

# SIGTERM to the ranks inside a relaxation solve (issue 81): every rank stops at the same iteration,
# rank 0 writes the checkpoint of the unfinished load step (its previous forces gathered), and it
# continues on 3 ranks and on 1 to the bytes of the one-rank run never stopped
cp "$(dirname "$0")/relax_under_traction.toml" "$tmp/relax_stop.toml"
if ! sanitized; then
  one_rank run "$tmp/relax_stop.toml" -o "$tmp/relax_stop-serial" -q > /dev/null
  out="$tmp/relax_stop-np2"
  "${mpirun[@]}" -np 2 "$rift" run "$tmp/relax_stop.toml" -o "$out" -q > "$out.log" 2>&1 &
  pid=$!
  until [ -e "$out/fields_000000.h5" ]; do sleep 0.02; done  # written before the solve
  sleep 0.5
  pkill -TERM -f "^$rift run $tmp/relax_stop.toml" || fail "relax_stop: no rank to stop"
  wait "$pid" && fail "relax_stop: the stopped run exited with status 0"
  grep -q "rift: stopped by signal 15 in load step 1 at iteration" "$out.log" || { cat "$out.log"; fail "relax_stop: not stopped within the solve"; }
  for np in 3 1; do
    cp -r "$out" "$out-restart-np$np"
    "${mpirun[@]}" -np "$np" "$rift" run "$tmp/relax_stop.toml" -o "$out-restart-np$np" -q --restart "$out-restart-np$np/checkpoint.rift" \
      > "$out-restart-np$np.log" 2>&1 || { cat "$out-restart-np$np.log"; fail "relax_stop: restart on $np ranks"; }
    rm "$out-restart-np$np/checkpoint.rift"
    same_outputs "$tmp/relax_stop-serial" "$out-restart-np$np" "relax_stop stopped within its solve on 2 ranks, continued on $np"
  done
  echo "ok: a relaxation stopped by SIGTERM within its load step on 2 ranks continues on 3 and 1 ranks: the same bytes as one rank never stopped"
fi

# The material point method on boxes of cells (mpm/domain.hpp): a 2D cantilever under its weight
# (MUSL, quadratic B-splines, fixed grid nodes, body force), two disks that fly across the cuts,
# collide and part (multi-material contact: the contact sums exchanged too; points migrating
# between ranks), and a 3D block (USL, APIC, uGIMP, a traction, fixed nodes) cut along z. The nodes
# two ranks share add their points' parts in another order than one rank does, so the fields agree
# to round-off: 1e-12 of each field's largest value in the run.
sed -e 's/end_time = 0.05/end_time = 0.001/' "$examples/mpm_cantilever.toml" > "$tmp/mpm_cantilever.toml"
sed -e 's/snapshots = 35/snapshots = 7/' "$examples/mpm_colliding_disks.toml" > "$tmp/mpm_disks.toml"
cat > "$tmp/mpm_block.toml" <<'SCENE'
[scene]
name = "mpm_block"
method = "mpm"
dimension = 3
[materials.steel]
model = "linear_elastic"
density = 7800.0
youngs_modulus = 2.0e11
poisson_ratio = 0.3
[regions.block]
shape = "box"
min = [0.0, 0.0, 0.0]
max = [0.008, 0.008, 0.016]
[regions.top]
shape = "box"
min = [0.0, 0.0, 0.015]
max = [0.008, 0.008, 0.016]
[regions.base]
shape = "box"
min = [-1.0, -1.0, -1.0]
max = [1.0, 1.0, 0.0]
[bodies.block]
material = "steel"
region = "block"
particles_per_cell = 2
[[boundaries]]
region = "base"
type = "fixed"
[[boundaries]]
region = "top"
type = "traction"
z = -1.0e8
[mpm]
cell_size = 0.001
shape = "gimp"
scheme = "usl"
transfer = "apic"
[solver]
end_time = 1.0e-5
safety_factor = 0.5
[output]
snapshots = 3
fields = ["displacement", "velocity", "stress", "strain_energy_density"]
history_rows = 20
SCENE
for scene in mpm_cantilever mpm_disks mpm_block; do
  one_rank run "$tmp/$scene.toml" -o "$tmp/$scene-serial" -q > /dev/null
  for np in $(ranks_compared 1 2 3); do
    run_on_ranks "$scene" "$np"
    out="$tmp/$scene-np$np"
    "$compare_fields" "$tmp/$scene-serial" "$out" 1e-12 || fail "$scene on $np ranks differs from the one-rank run"
  done
  echo "ok: $scene on $(compared_on 1 2 3) ranks: every field of every snapshot, and the history, within 1e-12 of the one-rank run's"
done
# --cut-along: the block (cut along z, its longest axis, above) cut along x on 2 ranks
"${mpirun[@]}" -np 2 "$rift" run "$tmp/mpm_block.toml" -o "$tmp/mpm_block-x" -q --cut-along x > "$tmp/mpm_block-x.log" 2>&1 ||
  { cat "$tmp/mpm_block-x.log"; fail "mpm_block: --cut-along x"; }
grep -q "slabs of cells along x" "$tmp/mpm_block-x.log" || fail "mpm_block: --cut-along x did not cut along x"
"$compare_fields" "$tmp/mpm_block-serial" "$tmp/mpm_block-x" 1e-12 || fail "mpm_block cut along x differs from the one-rank run"
# processor grids (mpm/domain.hpp CellBoxes): the disks on 4 ranks (2 x 2 boxes, chosen), the block
# on 8 (2 x 2 x 2: a node shared by 8 ranks at the corner, its parts added in the ranks' order on each)
# and on 4 as 2 x 1 x 2; the DCB's crack across the boxes of 2 x 2 ranks below
run_on_ranks mpm_disks 4
grep -q "boxes of cells, 2 x 2" "$tmp/mpm_disks-np4.log" || fail "mpm_disks: 4 ranks did not take 2 x 2 boxes"
"$compare_fields" "$tmp/mpm_disks-serial" "$tmp/mpm_disks-np4" 1e-12 || fail "mpm_disks on 2 x 2 ranks differs from the one-rank run"
for grid in 2x2x2 2x1x2; do
  np=$(( ${grid:0:1} * ${grid:2:1} * ${grid:4:1} ))
  "${mpirun[@]}" -np "$np" "$rift" run "$tmp/mpm_block.toml" -o "$tmp/mpm_block-$grid" -q --processor-grid "$grid" > "$tmp/mpm_block-$grid.log" 2>&1 ||
    { cat "$tmp/mpm_block-$grid.log"; fail "mpm_block: --processor-grid $grid"; }
  grep -q "boxes of cells, ${grid//x/ x }" "$tmp/mpm_block-$grid.log" || fail "mpm_block: not cut into $grid boxes"
  "$compare_fields" "$tmp/mpm_block-serial" "$tmp/mpm_block-$grid" 1e-12 || fail "mpm_block on $grid boxes differs from the one-rank run"
done
echo "ok: processor grids: mpm_disks on 2 x 2 ranks, mpm_block on 2 x 2 x 2 and 2 x 1 x 2, within 1e-12 of one rank"
# the disks must have met (else the test shows nothing about contact across a cut): strain energy
awk -F, 'NR > 1 && $4 > s { s = $4 } END { exit !(s > 1e-4) }' "$tmp/mpm_disks-serial/history.csv" || fail "mpm_disks: the disks did not collide"
# explicit cracks (CRAMP) across the cuts: the DCB's crack runs along x, the axis cut into slabs, and
# crosses two cuts on 3 ranks; each rank moves the crack particles in its slab and all add up the
# velocities; rank 0 takes J and K at the tip on the whole model gathered at the history rows
sed -e 's/end_time = 0.015/end_time = 0.0003/' -e 's/history_rows = 100/history_rows = 8/' "$examples/mpm_dcb.toml" > "$tmp/mpm_dcb.toml"
one_rank run "$tmp/mpm_dcb.toml" -o "$tmp/mpm_dcb-serial" -q > /dev/null
"${mpirun[@]}" -np 3 "$rift" run "$tmp/mpm_dcb.toml" -o "$tmp/mpm_dcb-np3" -q > "$tmp/mpm_dcb-np3.log" 2>&1 ||
  { cat "$tmp/mpm_dcb-np3.log"; fail "mpm_dcb: mpirun -np 3"; }
"$compare_fields" "$tmp/mpm_dcb-serial" "$tmp/mpm_dcb-np3" 1e-12 || fail "mpm_dcb on 3 ranks differs from the one-rank run"
"${mpirun[@]}" -np 4 "$rift" run "$tmp/mpm_dcb.toml" -o "$tmp/mpm_dcb-2x2" -q --processor-grid 2x2 > "$tmp/mpm_dcb-2x2.log" 2>&1 ||
  { cat "$tmp/mpm_dcb-2x2.log"; fail "mpm_dcb: --processor-grid 2x2"; }
"$compare_fields" "$tmp/mpm_dcb-serial" "$tmp/mpm_dcb-2x2" 1e-12 || fail "mpm_dcb on 2 x 2 ranks differs from the one-rank run"
echo "ok: mpm_dcb (an explicit crack across a cut, J and K at its tip on the middle rank) on 3 ranks and on 2 x 2 within 1e-12 of one rank"
# crack growth (maximum hoop stress, the toughness lowered so the crack grows within the short run):
# rank 0 grows the cracks on the whole model and every rank takes them. The growth direction
# amplifies round-off (a kinked crack's near-tip fields are steep), so the fields agree to 1e-10
# here; the crack grows by the same increments along the same path (crack_tips.csv to its 10 digits)
sed -e 's/end_time = 0.0076/end_time = 0.0005/' -e 's/history_rows = 200/history_rows = 10/' -e 's/toughness = 8.0e5/toughness = 1.0e4/' \
  "$examples/mpm_mixed_mode_growth.toml" > "$tmp/mpm_growth.toml"
if ! skipped mpm_growth; then
  one_rank run "$tmp/mpm_growth.toml" -o "$tmp/mpm_growth-serial" > "$tmp/mpm_growth-serial.log"
  "${mpirun[@]}" -np 2 "$rift" run "$tmp/mpm_growth.toml" -o "$tmp/mpm_growth-np2" > "$tmp/mpm_growth-np2.log" 2>&1 ||
    { cat "$tmp/mpm_growth-np2.log"; fail "mpm_growth: mpirun -np 2"; }
  grep -q "crack growth [1-9][0-9]* increments" "$tmp/mpm_growth-serial.log" || fail "mpm_growth: the crack did not grow"
  [ "$(grep -o 'crack growth [0-9]* increments' "$tmp/mpm_growth-serial.log")" = "$(grep -o 'crack growth [0-9]* increments' "$tmp/mpm_growth-np2.log")" ] ||
    fail "mpm_growth: 2 ranks grew the crack by another number of increments"
  "$compare_fields" "$tmp/mpm_growth-serial" "$tmp/mpm_growth-np2" 1e-10 || fail "mpm_growth on 2 ranks differs from the one-rank run"
  echo "ok: mpm_growth (crack growth) on 2 ranks: the same increments, fields within 1e-10 of one rank"
fi
# a checkpoint of 2 ranks continues on 3 (rank 0 gathers the points in the whole run's order)
printf '[checkpoint]\nevery_steps = 200\nfile = "ckpt_*.rift"\n' | cat "$tmp/mpm_disks.toml" - > "$tmp/mpm_disks-ckpt.toml"
"${mpirun[@]}" -np 2 "$rift" run "$tmp/mpm_disks-ckpt.toml" -o "$tmp/mpm_disks-ckpt" -q > /dev/null 2>&1 ||
  fail "mpm_disks: checkpointed run on 2 ranks"
[ -s "$tmp/mpm_disks-ckpt/ckpt_200.rift" ] || fail "mpm_disks: no checkpoint after step 200 on 2 ranks"
"${mpirun[@]}" -np 3 "$rift" run "$tmp/mpm_disks-ckpt.toml" -o "$tmp/mpm_disks-ckpt" -q --restart "$tmp/mpm_disks-ckpt/ckpt_200.rift" \
  > "$tmp/mpm_disks-restart.log" 2>&1 || { cat "$tmp/mpm_disks-restart.log"; fail "mpm_disks: restart on 3 ranks"; }
grep -q "continued from .*ckpt_200.rift at step 200" "$tmp/mpm_disks-restart.log" || fail "mpm_disks: the restart did not say where it continued"
"$compare_fields" "$tmp/mpm_disks-serial" "$tmp/mpm_disks-ckpt" 1e-12 || fail "mpm_disks: restarted on 3 ranks from 2 ranks' checkpoint"
# from 2 x 2 boxes' checkpoint (rank 0 gathers each box's points and nodes) to 3 slabs
"${mpirun[@]}" -np 4 "$rift" run "$tmp/mpm_disks-ckpt.toml" -o "$tmp/mpm_disks-ckpt4" -q > /dev/null 2>&1 || fail "mpm_disks: checkpointed run on 4 ranks"
"${mpirun[@]}" -np 3 "$rift" run "$tmp/mpm_disks-ckpt.toml" -o "$tmp/mpm_disks-ckpt4" -q --restart "$tmp/mpm_disks-ckpt4/ckpt_200.rift" \
  > "$tmp/mpm_disks-restart4.log" 2>&1 || { cat "$tmp/mpm_disks-restart4.log"; fail "mpm_disks: restart on 3 ranks from 4"; }
"$compare_fields" "$tmp/mpm_disks-serial" "$tmp/mpm_disks-ckpt4" 1e-12 || fail "mpm_disks: restarted on 3 ranks from 2 x 2 ranks' checkpoint"
# and a cracked run's: the crack particles and the tips' file go on too
printf '[checkpoint]\nevery_steps = 400\nfile = "ckpt_*.rift"\n' | cat "$tmp/mpm_dcb.toml" - > "$tmp/mpm_dcb-ckpt.toml"
"${mpirun[@]}" -np 2 "$rift" run "$tmp/mpm_dcb-ckpt.toml" -o "$tmp/mpm_dcb-ckpt" -q > /dev/null 2>&1 || fail "mpm_dcb: checkpointed run on 2 ranks"
"${mpirun[@]}" -np 3 "$rift" run "$tmp/mpm_dcb-ckpt.toml" -o "$tmp/mpm_dcb-ckpt" -q --restart "$tmp/mpm_dcb-ckpt/ckpt_400.rift" \
  > "$tmp/mpm_dcb-restart.log" 2>&1 || { cat "$tmp/mpm_dcb-restart.log"; fail "mpm_dcb: restart on 3 ranks"; }
"$compare_fields" "$tmp/mpm_dcb-serial" "$tmp/mpm_dcb-ckpt" 1e-12 || fail "mpm_dcb: restarted on 3 ranks from 2 ranks' checkpoint"
echo "ok: mpm_disks and mpm_dcb: a checkpoint of 2 ranks (and of 2 x 2) continues on 3, within 1e-12 of the one-rank run"

# refused on more than one rank, exit status 2, nothing written: an MPM grid too thin for its
# ranks, a cut along an axis a run cannot be cut along
refused() {  # scene file, what the message says, ranks (2 unless given), more options of `rift run`
  local scene="$1" message="$2" np="${3:-2}" name status
  shift $(($# < 3 ? $# : 3))
  name=$(basename "$scene" .toml)
  set +e
  "${mpirun[@]}" -np "$np" "$rift" run "$scene" -o "$tmp/$name-out" -q "$@" > "$tmp/$name.log" 2>&1
  status=$?
  set -e
  [ "$status" -eq 2 ] || { cat "$tmp/$name.log"; fail "$name on $np ranks: exit status $status, not 2"; }
  grep -q "$message" "$tmp/$name.log" || { cat "$tmp/$name.log"; fail "$name on $np ranks: no message \"$message\""; }
  [ ! -e "$tmp/$name-out" ] || fail "$name on $np ranks wrote its output directory"
}
# a grid of 8 cells along its longest axis on 3 ranks: 4 cells a rank at least (mpm/domain.hpp CellBoxes::min_cells)
sed -e 's/cell_size = 0.025/cell_size = 0.25/' -e 's/particles_per_cell = 2/particles_per_cell = 4/' \
  "$examples/mpm_colliding_disks.toml" > "$tmp/coarse_disks.toml"
refused "$tmp/coarse_disks.toml" "a rank needs 4 of them" 3
# --cut-along: a peridynamic run is cut across its slowest axis alone; a 2D grid has no z
refused "$tmp/bar.toml" "cut across its lattice's slowest axis" 2 --cut-along x
refused "$tmp/mpm_disks.toml" "has no z axis" 2 --cut-along z
# --processor-grid: its product is the ranks' number; a peridynamic run takes 1 x N (2D) or 1 x P x Q
# (3D) alone, each of whose boxes holds particles
refused "$tmp/mpm_disks.toml" "its numbers' product must be the ranks' number" 4 --processor-grid 3x3
refused "$tmp/impact.toml" "takes the grid 1x2 alone" 2 --processor-grid 2x1
refused "$tmp/bar.toml" "takes a grid 1x1x2 or 1xPxQ with P Q = 2" 2 --processor-grid 2x1x1
# a bar one lattice line wide across y: a grid that cuts y leaves a rank without particles
sed -e 's/max = \[0.006, 0.006, 0.012\]/max = [0.006, 0.0005, 0.012]/' -e 's/0.006, 0.006, 0.001\]/0.006, 0.0005, 0.001]/' \
  "$tmp/bar.toml" > "$tmp/thin_bar.toml"
refused "$tmp/thin_bar.toml" "leaves rank 1 without particles" 2 --processor-grid 1x2x1
echo "ok: what a distributed run cannot take is refused with exit status 2"

exit 0

DR_SCENE
[scene]
name = "relax_plate"
dimension = 2
plane = "stress"
thickness = 0.001
[materials.glass]
model = "pmb"
density = 2440.0
youngs_modulus = 72e9
poisson_ratio = 0.3333333333
fracture_energy = 3.8
[regions.plate]
shape = "box"
min = [0.0, 0.0]
max = [0.064, 0.05]
[regions.top]
shape = "box"
min = [0.0, 0.049]
max = [0.064, 0.05]
[regions.bottom]
shape = "box"
min = [0.0, 0.0]
max = [0.064, 0.001]
[bodies.plate]
material = "glass"
region = "plate"
spacing = 0.0005
horizon = 3.015
[[cracks]]
points = [[0.0, 0.025], [0.02, 0.025]]
[[boundaries]]
region = "top"
type = "displacement"
y = 1.0e-5
time = { function = "ramp", start = 0.0, end = 1.0 }
[[boundaries]]
region = "bottom"
type = "fixed"
[solver]
type = "dynamic_relaxation"
end_time = 1.0
load_steps = 2
max_iterations = 500
max_breaking_passes = 2
tolerance = 1e-4
breaking = "at_equilibrium"
[output]
fields = ["displacement", "damage"]
history = ["strain_energy", "broken_bonds", "max_damage"]
reactions = ["top"]
damage_image = false
damage_histogram = false
DR_SCENE_END
