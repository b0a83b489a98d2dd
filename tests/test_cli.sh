#!/usr/bin/env bash
# End-to-end checks of the command line: a small 2D run writes every output (HDF5 + XDMF that
# parses and names existing datasets, history CSV, damage PNG); a bad scene exits with status 2
# and writes nothing; --version answers.
set -euo pipefail
rift="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/plate.toml" <<'SCENE'
[scene]
dimension = 2
plane = "stress"
thickness = 0.001
[materials.glass]
model = "lps"
density = 2440.0
youngs_modulus = 72e9
poisson_ratio = 0.25
fracture_energy = 3.8
[regions.plate]
shape = "box"
min = [0.0, 0.0]
max = [0.02, 0.01]
[regions.left]
shape = "box"
min = [0.0, 0.0]
max = [0.001, 0.01]
[bodies.plate]
material = "glass"
region = "plate"
spacing = 0.0005
horizon = 3.015
[[cracks]]
points = [[0.01, 0.0], [0.01, 0.004]]
[[boundaries]]
region = "left"
type = "velocity"
x = -5.0
time = { function = "ramp", start = 0.0, end = 1e-6 }
[solver]
end_time = 4e-6
[output]
snapshots = 3
history_rows = 5
reactions = ["left"]
probes = [[0.0101, 0.0041], [0.019, 0.009]]
SCENE
"$rift" --version | grep -q '^rift '
"$rift" check "$tmp/plate.toml" | grep -q 'bytes/directed bond'
"$rift" run "$tmp/plate.toml" -o "$tmp/out" --threads 2 > "$tmp/run.log"
grep -q "damage   $tmp/out/damage.png" "$tmp/run.log"
grep -q "M bonds/s)" "$tmp/run.log"  # throughput at the end of the run
test -s "$tmp/out/fields_000000.h5" && test -s "$tmp/out/fields_000003.h5"  # a file per snapshot
test ! -e "$tmp/out/fields_000004.h5"
no_tmp_files() {  # (a negated pipeline never stops a `set -e` script: tested with if)
  if ls "$1" | grep -q '\.tmp$'; then echo "FAIL: a .tmp file in $1"; exit 1; fi
}
no_tmp_files "$tmp/out"  # every file renamed into place
# a snapshot's file left half-written by a run killed while it wrote (*.h5.tmp) is removed at the next start
touch "$tmp/out/fields_000007.h5.tmp" "$tmp/out/checkpoint.rift.tmp"
"$rift" run "$tmp/plate.toml" -o "$tmp/out" --threads 2 -q > /dev/null
no_tmp_files "$tmp/out"
test -s "$tmp/out/damage.png"
test "$(wc -l < "$tmp/out/history.csv")" -eq 7  # header, initial state, 5 rows
head -1 "$tmp/out/history.csv" | grep -q 'reaction_left_x'
head -1 "$tmp/out/history.csv" | grep -q 'damage_probe_0,damage_probe_1'
# the damage histogram: ten intervals of 0.1 whose shares add up to 100%, and its chart
test -s "$tmp/out/damage_histogram.png"
/usr/bin/python3 - "$tmp/out" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/damage_histogram.csv")))
assert len(rows) == 10 and rows[0]["damage_from"] == "0.0" and rows[-1]["damage_to"] == "1.0", rows
assert abs(sum(float(r["percent"]) for r in rows) - 100.0) < 1e-3
assert sum(int(r["particles"]) for r in rows) == 40 * 20, "every particle in one interval"
# the probe at the crack tip is damaged by the end, the far corner is not
last = list(csv.DictReader(open(sys.argv[1] + "/history.csv")))[-1]
assert float(last["damage_probe_0"]) > 0.0 and float(last["damage_probe_1"]) == 0.0, last
PY
/usr/bin/python3 - "$tmp/out" <<'PY'
import sys, xml.etree.ElementTree as ET
out = sys.argv[1]
root = ET.parse(out + "/fields.xdmf").getroot()
grids = root.findall(".//Grid[@GridType='Uniform']")
assert len(grids) == 4, len(grids)  # initial state + 3 snapshots
names = {a.get("Name") for a in grids[-1].findall("Attribute")}
assert {"displacement", "velocity", "damage", "dilatation"} <= names, names
PY
# in-situ stresses more than the rock holds: plane strain, E = 10 GPa, nu = 0.25 under -10 / -2 MPa
# stretches it by 1.25e-4 along sigma_h (Hooke), past its critical stretch of 1e-4: the in-situ
# stage holds every bond, and the run warns that they broke at its start
cat > "$tmp/in_situ.toml" <<'SCENE'
[scene]
dimension = 2
plane = "strain"
thickness = 0.001
[materials.rock]
model = "lps"
density = 2500.0
youngs_modulus = 10e9
poisson_ratio = 0.25
critical_stretch = 1e-4
[regions.block]
shape = "box"
min = [-0.01, -0.01]
max = [0.01, 0.01]
[bodies.block]
material = "rock"
region = "block"
spacing = 0.001
horizon = 3.015
[in_situ_stress]
sigma_H = -10e6
sigma_h = -2e6
start = "uniform_strain"
[solver]
end_time = 1e-8
SCENE
"$rift" run "$tmp/in_situ.toml" -o "$tmp/in_situ_out" --threads 1 > "$tmp/in_situ.log" 2> "$tmp/in_situ.err"
grep -q "in-situ stage: equilibrium in" "$tmp/in_situ.log"
grep -q "are past their limit at the in-situ equilibrium and broke at the start" "$tmp/in_situ.err"
# `rift run ARGUMENTS` exits with status 2 and this text in its message
exits_2() {  # expected text of the message, then the arguments of rift run
  local text="$1"
  shift
  set +e
  "$rift" run "$@" 2> "$tmp/err.txt"
  local status=$?
  set -e
  test "$status" -eq 2
  grep -q "$text" "$tmp/err.txt"
}
# SIGTERM (a batch system's notice): the run ends its step, writes a checkpoint and exits with
# 128 + 15; `--restart` continues it to the history of a run never stopped, byte for byte
sed 's/end_time = 4e-6/end_time = 4e-4/; s/history_rows = 5/history_rows = 500/' "$tmp/plate.toml" > "$tmp/long.toml"
"$rift" run "$tmp/long.toml" -o "$tmp/long_whole" --threads 1 -q > /dev/null
set +e
"$rift" run "$tmp/long.toml" -o "$tmp/long" --threads 1 -q > "$tmp/long.log" &
pid=$!
# a tenth of the way in (50 of its 500 history rows)
until [ "$(cat "$tmp/long/history.csv" 2> /dev/null | wc -l)" -gt 50 ]; do sleep 0.02; done
kill -TERM "$pid"
wait "$pid"
status=$?
set -e
test "$status" -eq 143
grep -q "rift: stopped by signal 15 after step" "$tmp/long.log"
test -s "$tmp/long/checkpoint.rift"
"$rift" run "$tmp/long.toml" -o "$tmp/long" --threads 1 --restart "$tmp/long/checkpoint.rift" > "$tmp/long2.log"
grep -q "rift: continued from $tmp/long/checkpoint.rift at step" "$tmp/long2.log"
cmp "$tmp/long/history.csv" "$tmp/long_whole/history.csv"
# SIGTERM inside a relaxation solve (issue 81): the run stops at the iteration it is in, even with a
# second SIGTERM on the heels of the first, writes a checkpoint of the unfinished load step, and the
# restart goes on from that iteration to the bytes of a run never stopped. Its log has progress lines.
cp "$(dirname "$0")/relax_under_traction.toml" "$tmp/relax.toml"
"$rift" run "$tmp/relax.toml" -o "$tmp/relax_whole" --threads 1 > /dev/null 2> "$tmp/relax_whole.err"
grep -q "rift: load step 1/1, iteration 1 (at most 8000), residual" "$tmp/relax_whole.err"
set +e
"$rift" run "$tmp/relax.toml" -o "$tmp/relax" --threads 1 -q > "$tmp/relax.log" &
pid=$!
until [ -e "$tmp/relax/fields_000000.h5" ]; do sleep 0.02; done  # written before the solve
sleep 0.3
kill -TERM "$pid"
sleep 0.05
kill -TERM "$pid" 2> /dev/null
wait "$pid"
status=$?
set -e
test "$status" -eq 143
grep -q "rift: stopped by signal 15 in load step 1 at iteration" "$tmp/relax.log"
"$rift" run "$tmp/relax.toml" -o "$tmp/relax" --threads 1 -q --restart "$tmp/relax/checkpoint.rift" > /dev/null
cmp "$tmp/relax/history.csv" "$tmp/relax_whole/history.csv"
cmp "$tmp/relax/fields_000001.h5" "$tmp/relax_whole/fields_000001.h5"
# a checkpoint of another scene is refused (exit status 2), the run's files unchanged
cp "$tmp/long/history.csv" "$tmp/history_before.csv"
exits_2 "cannot restart from this checkpoint: it was written for another scene" \
  "$tmp/plate.toml" -o "$tmp/long" --restart "$tmp/long/checkpoint.rift"
cmp "$tmp/long/history.csv" "$tmp/history_before.csv"
# a restart into another output directory (without the stopped run's files): exit status 2, nothing written
exits_2 "restart with the output directory of the run that wrote the checkpoint" \
  "$tmp/long.toml" -o "$tmp/elsewhere" --restart "$tmp/long/checkpoint.rift"
test ! -e "$tmp/elsewhere"
# a processor grid whose boxes are not the ranks (one, without mpirun), or not a grid: exit status 2, nothing written
exits_2 "a grid of 4 boxes for 1 rank; its numbers' product must be the ranks' number" "$tmp/plate.toml" -o "$tmp/grid" --processor-grid 2x2
exits_2 "a processor grid is 2 or 3 positive whole numbers joined by x" "$tmp/plate.toml" -o "$tmp/grid" --processor-grid 2x0
test ! -e "$tmp/grid"
# a mistake: exit status 2, the message (file:line:column, key), nothing written
refused() {  # scene, expected text of the message
  exits_2 "$2" "$1" -o "$1.out"
  test ! -e "$1.out"
}
sed 's/spacing = 0.0005/spacing = -0.0005/' "$tmp/plate.toml" > "$tmp/bad.toml"
refused "$tmp/bad.toml" "bad.toml:22:11: error: 'bodies.plate.spacing': must be > 0"
# a probe outside the body is a scene error too
sed 's/probes = .*/probes = [[0.5, 0.5]]/' "$tmp/plate.toml" > "$tmp/bad_probe.toml"
refused "$tmp/bad_probe.toml" "'output.probes': probe 0 lies"
echo "command line: all checks passed"
