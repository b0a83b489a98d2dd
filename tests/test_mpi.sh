#!/usr/bin/env bash
# Distributed runs (issue 6; pd/window.hpp): the same scene under `mpirun -np 1, 2, 3` writes the
# same bytes as a plain one-rank run: every field of every snapshot (so every broken bond: damage
# is their volume share), the XDMF index and the history (energies, broken bonds, reactions,
# probes). Scenes whose cracks run along or across the cuts between ranks: a 2D PMB plate whose
# pre-crack grows and branches along the cut of two ranks (Ha and Bobaru 2010's set-up, coarse,
# with contact), and a 3D LPS bar pulled apart (the dilatation's halo exchange), also as VES (the
# bonds' viscous history on both sides of a cut). What a distributed run cannot take yet is
# refused with exit status 2 before anything is written.
set -euo pipefail
rift="$1"
mpirun=(mpirun --oversubscribe)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

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
SCENE

# the bar again, viscoelastic: the history of every bond, kept by lattice blocks (bond_slabs.hpp)
sed -e 's/model = "lps"/model = "ves"\nviscous_fraction = 0.5\nrelaxation_time = 2.0e-6/' -e 's/name = "bar"/name = "ves_bar"/' \
  "$tmp/bar.toml" > "$tmp/ves_bar.toml"

for scene in plate bar ves_bar; do
  "$rift" run "$tmp/$scene.toml" -o "$tmp/$scene-serial" -q > "$tmp/$scene-serial.log"
  for np in 1 2 3; do
    out="$tmp/$scene-np$np"
    "${mpirun[@]}" -np "$np" "$rift" run "$tmp/$scene.toml" -o "$out" -q > "$out.log" 2>&1 || { cat "$out.log"; fail "$scene: mpirun -np $np"; }
    for f in "$tmp/$scene-serial"/*; do
      name=$(basename "$f")
      case "$name" in *.png) continue ;; esac  # drawn by matplotlib (its version's bytes), from the same data
      cmp -s "$f" "$out/$name" || fail "$scene: $name of mpirun -np $np differs from the one-rank run's"
    done
    if [ "$np" -gt 1 ]; then
      grep -q "load balance over $np ranks" "$out.log" || fail "$scene: no load-balance report on $np ranks"
    fi
  done
  echo "ok: $scene on 1, 2 and 3 ranks: the same bytes in every output as one rank"
done
# the plate's crack must have grown (else the test shows nothing about breaking on the cut)
awk -F, 'NR > 1 { b = $6 } END { exit !(b > 1000) }' "$tmp/plate-serial/history.csv" || fail "plate: fewer than 1000 bonds broke"

# quasi-static growth by dynamic relaxation, bonds breaking at each equilibrium: the ranks own
# whole blocks of the sums (12800 particles: three blocks of 4096 and the rest), add each other's
# block sums in the one-rank order, and so damp, converge and break as one rank does
sed -n '/^DR_SCENE$/,/^DR_SCENE_END$/p' "$0" | sed '1d;$d' > "$tmp/relax_plate.toml"
"$rift" run "$tmp/relax_plate.toml" -o "$tmp/relax_plate-serial" -q > /dev/null
for np in 2 3; do
  out="$tmp/relax_plate-np$np"
  "${mpirun[@]}" -np "$np" "$rift" run "$tmp/relax_plate.toml" -o "$out" -q > "$out.log" 2>&1 || { cat "$out.log"; fail "relax_plate: mpirun -np $np"; }
  for f in "$tmp/relax_plate-serial"/*; do
    name=$(basename "$f")
    case "$name" in *.png) continue ;; esac
    cmp -s "$f" "$out/$name" || fail "relax_plate: $name of mpirun -np $np differs from the one-rank run's"
  done
done
awk -F, 'NR > 1 { b = $4 } END { exit !(b > 100) }' "$tmp/relax_plate-serial/history.csv" || fail "relax_plate: fewer than 100 bonds broke"
echo "ok: relax_plate (dynamic relaxation, breaking at equilibrium) on 2 and 3 ranks: the same bytes as one rank"

# checkpoints written by 2 ranks restart on 3 and on 1, and the continued runs write the bytes of
# the uninterrupted one-rank run (rank 0 gathers the whole run's state: any number of ranks reads it)
for scene in plate ves_bar; do
  printf '[checkpoint]\nevery_steps = 20\nfile = "ckpt_*.rift"\n' | cat "$tmp/$scene.toml" - > "$tmp/$scene-ckpt.toml"
  "${mpirun[@]}" -np 2 "$rift" run "$tmp/$scene-ckpt.toml" -o "$tmp/$scene-ckpt" -q > /dev/null 2>&1 || fail "$scene: checkpointed run on 2 ranks"
  [ -s "$tmp/$scene-ckpt/ckpt_20.rift" ] || fail "$scene: no checkpoint after step 20 on 2 ranks"
  for np in 3 1; do
    out="$tmp/$scene-restart-np$np"
    cp -r "$tmp/$scene-ckpt" "$out"
    "${mpirun[@]}" -np "$np" "$rift" run "$tmp/$scene-ckpt.toml" -o "$out" -q --restart "$out/ckpt_20.rift" > "$out.log" 2>&1 ||
      { cat "$out.log"; fail "$scene: restart on $np ranks"; }
    grep -q "continued from .*ckpt_20.rift at step 20" "$out.log" || fail "$scene: restart on $np ranks did not say where it continued"
    for f in "$tmp/$scene-serial"/*; do
      name=$(basename "$f")
      case "$name" in *.png) continue ;; esac
      cmp -s "$f" "$out/$name" || fail "$scene: $name after a restart on $np ranks from 2 ranks' checkpoint differs from the one-rank run's"
    done
  done
  echo "ok: $scene: a checkpoint of 2 ranks continues on 3 and on 1 rank, the same bytes as the run never stopped"
done

# refused on more than one rank, exit status 2, nothing written: relaxation of a body held by
# tractions alone (the plate), MPM
sed -e 's/type = "explicit"/type = "dynamic_relaxation"\nload_steps = 2/' "$tmp/plate.toml" > "$tmp/relax.toml"
refused() {  # scene file, what the message says
  local name
  name=$(basename "$1" .toml)
  set +e
  "${mpirun[@]}" -np 2 "$rift" run "$1" -o "$tmp/$name-out" -q > "$tmp/$name.log" 2>&1
  local status=$?
  set -e
  [ "$status" -eq 2 ] || { cat "$tmp/$name.log"; fail "$name on 2 ranks: exit status $status, not 2"; }
  grep -q "$2" "$tmp/$name.log" || { cat "$tmp/$name.log"; fail "$name on 2 ranks: no message \"$2\""; }
  [ ! -e "$tmp/$name-out" ] || fail "$name on 2 ranks wrote its output directory"
}
refused "$tmp/relax.toml" "held by tractions alone"
refused "$(dirname "$0")/../examples/mpm_cantilever.toml" "material point method runs on one rank"
echo "ok: what a distributed run cannot take is refused with exit status 2"

# contact is found among a rank's ghosts: a plate squeezed until its layers of two ranks may touch
# past the ghosts stops with exit status 1 and says why (one rank runs it to the end)
sed -e 's/type = "traction"/type = "velocity"/' -e 's/^y = 4.0e6/y = -50.0/' -e 's/^y = -4.0e6/y = 0.0/' \
    -e 's/end_time = 2.5e-5/end_time = 4e-5/' "$tmp/plate.toml" > "$tmp/squeeze.toml"
set +e
"${mpirun[@]}" -np 2 "$rift" run "$tmp/squeeze.toml" -o "$tmp/squeeze-out" -q > "$tmp/squeeze.log" 2>&1
status=$?
set -e
[ "$status" -eq 1 ] || { cat "$tmp/squeeze.log"; fail "squeezed plate on 2 ranks: exit status $status, not 1"; }
grep -q "finds contact among its ghosts only" "$tmp/squeeze.log" || { cat "$tmp/squeeze.log"; fail "squeezed plate: no message"; }
echo "ok: a distributed run whose contact could reach past the ghosts stops with exit status 1"
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
DR_SCENE_END
