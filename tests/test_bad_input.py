#!/usr/bin/env python3
"""Bad input through the command line, one table row per mistake (issue 81): each exits with status
2 before any work, names the key (and file:line:column where the scene has a line) and leaves the
output directory empty or absent. Classes: non-finite numbers, integers past what the code holds,
impossible sizes, nonsense geometry, unusable outputs; and the warnings for what is legitimate but
likely not meant (exit status 0). Usage: test_bad_input.py RIFT"""
import os
import re
import subprocess
import sys
import tempfile

RIFT = sys.argv[1]

PD = """[scene]
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
pressure = 1e6
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
"""

STATIC = """[scene]
dimension = 2
plane = "strain"
thickness = 0.001
[materials.rock]
model = "lps"
density = 2500.0
youngs_modulus = 10e9
poisson_ratio = 0.25
fracture_energy = 10.0
[regions.block]
shape = "box"
min = [-0.01, -0.01]
max = [0.01, 0.01]
[regions.bottom]
shape = "box"
min = [-0.01, -0.01]
max = [0.01, -0.009]
[bodies.block]
material = "rock"
region = "block"
spacing = 0.001
horizon = 3.015
[[boundaries]]
region = "bottom"
type = "fixed"
[in_situ_stress]
sigma_H = -10e6
sigma_h = -5e6
[solver]
type = "dynamic_relaxation"
load_steps = 2
breaking = "at_equilibrium"
"""

BAR = """[scene]
dimension = 3
[materials.steel]
model = "pmb"
density = 7800.0
youngs_modulus = 200e9
poisson_ratio = 0.25
critical_stretch = 0.01
[regions.bar]
shape = "box"
min = [0.0, 0.0, 0.0]
max = [0.02, 0.002, 0.002]
[bodies.bar]
material = "steel"
region = "bar"
spacing = 0.0005
horizon = 3.015
[solver]
end_time = 1e-6
"""

MPM = """[scene]
method = "mpm"
dimension = 2
plane = "strain"
thickness = 0.001
[materials.steel]
model = "linear_elastic"
density = 7800.0
youngs_modulus = 200e9
poisson_ratio = 0.3
[regions.plate]
shape = "box"
min = [0.0, 0.0]
max = [0.02, 0.01]
[bodies.plate]
material = "steel"
region = "plate"
particles_per_cell = 2
[[cracks]]
points = [[0.0, 0.0055], [0.008, 0.0055]]
[[boundaries]]
region = "plate"
type = "velocity"
y = 1.0
[mpm]
cell_size = 0.001
[solver]
end_time = 1e-6
"""

BASES = {"pd": PD, "static": STATIC, "bar": BAR, "mpm": MPM}

# (name, base, text to find, its replacement, key named, the line's text ('' = no line: an option))
CASES = [
    # non-finite numbers
    ("density inf", "pd", "density = 2440.0", "density = inf", "materials.glass.density", "density = inf"),
    ("youngs modulus inf", "pd", "youngs_modulus = 72e9", "youngs_modulus = inf", "materials.glass.youngs_modulus", "youngs_modulus = inf"),
    ("youngs modulus nan", "pd", "youngs_modulus = 72e9", "youngs_modulus = nan", "materials.glass.youngs_modulus", "youngs_modulus = nan"),
    ("boundary velocity nan", "pd", "x = -5.0", "x = nan", "boundaries[0].x", "x = nan"),
    ("boundary velocity inf", "pd", "x = -5.0", "x = -inf", "boundaries[0].x", "x = -inf"),
    ("end time inf", "pd", "end_time = 4e-6", "end_time = inf", "solver.end_time", "end_time = inf"),
    ("crack pressure inf", "pd", "pressure = 1e6", "pressure = inf", "cracks[0].pressure", "pressure = inf"),
    ("region corner inf", "pd", "max = [0.02, 0.01]", "max = [inf, 0.01]", "regions.plate.max", "max = [inf, 0.01]"),
    ("ramp end nan", "pd", "end = 1e-6 }", "end = nan }", "boundaries[0].time.end", "time = {"),
    ("spacing nan", "pd", "spacing = 0.0005", "spacing = nan", "bodies.plate.spacing", "spacing = nan"),
    ("in-situ stress -inf", "static", "sigma_H = -10e6", "sigma_H = -inf", "in_situ_stress.sigma_H", "sigma_H = -inf"),
    ("mpm cell size inf", "mpm", "cell_size = 0.001", "cell_size = inf", "mpm.cell_size", "cell_size = inf"),
    ("mpm crack point nan", "mpm", "[0.008, 0.0055]", "[nan, 0.0055]", "cracks[0].points", "points = "),
    # loads no solid holds, speeds no wave reaches (finite, but a unit or an exponent is wrong)
    ("crack pressure 1e30", "pd", "pressure = 1e6", "pressure = 1e30", "cracks[0].pressure", "pressure = 1e30"),
    ("boundary velocity 1e300", "pd", "x = -5.0", "x = -1e300", "boundaries[0].x", "x = -1e300"),
    ("in-situ stress 1e20", "static", "sigma_h = -5e6", "sigma_h = -1e20", "in_situ_stress.sigma_h", "sigma_h = -1e20"),
    # integers past what the code holds
    ("snapshots 2^32", "pd", "snapshots = 3", "snapshots = 4294967296", "output.snapshots", "snapshots = 4294967296"),
    ("snapshots 2^31", "pd", "snapshots = 3", "snapshots = 2147483648", "output.snapshots", "snapshots = 2147483648"),
    ("snapshots a billion", "pd", "snapshots = 3", "snapshots = 1000000000", "output.snapshots", "snapshots = 1000000000"),
    ("history rows 1e12", "pd", "history_rows = 5", "history_rows = 1000000000000", "output.history_rows", "history_rows = 1000000000000"),
    ("load steps 2^32", "static", "load_steps = 2", "load_steps = 4294967296", "solver.load_steps", "load_steps = 4294967296"),
    ("max iterations 2^32", "static", "load_steps = 2", "load_steps = 2\nmax_iterations = 4294967296", "solver.max_iterations", "max_iterations ="),
    ("breaking passes 2^32", "static", "load_steps = 2", "load_steps = 2\nmax_breaking_passes = 4294967296", "solver.max_breaking_passes", "max_breaking_passes ="),
    ("in-situ iterations 2^32", "static", "sigma_h = -5e6", "sigma_h = -5e6\nmax_iterations = 4294967296", "in_situ_stress.max_iterations", "max_iterations ="),
    ("checkpoint every 2^62", "pd", "history_rows = 5", "history_rows = 5\n[checkpoint]\nevery_steps = 4611686018427387904", "checkpoint.every_steps", "every_steps ="),
    ("pd end time 1e30", "pd", "end_time = 4e-6", "end_time = 1e30", "solver.end_time", "end_time = 1e30"),
    ("pd end time 1e12", "pd", "end_time = 4e-6", "end_time = 1e12", "solver.end_time", "end_time = 1e12"),
    ("mpm end time 1e30", "mpm", "end_time = 1e-6", "end_time = 1e30", "solver.end_time", "end_time = 1e30"),
    ("time step 1e-300", "pd", "end_time = 4e-6", "end_time = 4e-6\ntime_step = 1e-300", "solver.time_step", "time_step = 1e-300"),
    ("mpm time step 1e-300", "mpm", "end_time = 1e-6", "end_time = 1e-6\ntime_step = 1e-300", "solver.time_step", "time_step = 1e-300"),
    # impossible sizes
    ("horizon a million spacings", "pd", "horizon = 3.015", "horizon = 1e6", "bodies.plate.horizon", "[bodies.plate]"),
    ("3d horizon 2500 spacings", "bar", "horizon = 3.015", "horizon = 2500", "bodies.bar.horizon", "[bodies.bar]"),
    ("box corner -1e308", "pd", "min = [0.0, 0.0]\nmax = [0.02", "min = [-1e308, 0.0]\nmax = [0.02", "bodies.plate.spacing", "[bodies.plate]"),
    ("3d spacing 2e-6", "bar", "spacing = 0.0005", "spacing = 2e-6", "bodies.bar.spacing", "[bodies.bar]"),
    ("2d spacing 1e-7", "pd", "spacing = 0.0005", "spacing = 1e-7", "bodies.plate.spacing", "[bodies.plate]"),
    ("2d spacing 5e-7 past the memory", "pd", "spacing = 0.0005", "spacing = 5e-7", "bodies.plate.spacing", "[bodies.plate]"),
    ("mpm cell size 1e-9", "mpm", "cell_size = 0.001", "cell_size = 1e-9", "mpm.cell_size", "cell_size = 1e-9"),
    # nonsense
    ("pre-crack 100 m away", "pd", "points = [[0.01, 0.0], [0.01, 0.004]]", "points = [[100.0, 0.0], [100.0, 0.004]]", "cracks[0].points", "points = [[100.0"),
    ("pre-crack of zero length", "pd", "points = [[0.01, 0.0], [0.01, 0.004]]", "points = [[0.01, 0.0], [0.01, 0.0]]", "cracks[0].points", "points = [[0.01, 0.0], [0.01, 0.0]]"),
    ("mpm crack outside the plate", "mpm", "points = [[0.0, 0.0055], [0.008, 0.0055]]", "points = [[0.5, 0.5], [0.6, 0.5]]", "cracks[0].points", "points = [[0.5"),
    ("two bodies on one region", "pd", "[[cracks]]", "[bodies.twin]\nmaterial = \"glass\"\nregion = \"plate\"\nspacing = 0.0005\nhorizon = 3.015\n[[cracks]]", "bodies.twin.region", "[bodies.twin]"),
    ("two bodies overlap", "pd", "[[cracks]]", "[regions.right]\nshape = \"box\"\nmin = [0.015, 0.0]\nmax = [0.03, 0.01]\n[bodies.right]\nmaterial = \"glass\"\nregion = \"right\"\nspacing = 0.0005\nhorizon = 3.015\n[[cracks]]", "bodies.right.region", "[bodies.right]"),
    ("empty union", "pd", "[bodies.plate]", "[regions.none]\nshape = \"union\"\nof = []\n[bodies.plate]", "regions.none.of", "of = []"),
    ("3d crack without area", "bar", "[solver]", "[[cracks]]\npoints = [[0.01, 0.0, 0.0], [0.01, 0.001, 0.0], [0.01, 0.002, 0.0]]\n[solver]", "cracks[0].points", "points = [[0.01, 0.0, 0.0]"),
]

# options: (name, base, extra arguments, key, text in the message); the output path may be made by setup
OPTION_CASES = [
    ("output path is a file", "pd", "file", "-o", "is a file"),
    ("output path below a file", "pd", "below", "-o", "lies below a file"),
    ("max memory too small", "pd", "memory", "bodies.plate.spacing", "more than --max-memory"),
    ("zero threads", "pd", "threads", "", "a whole number of threads from 1 to 9999"),
    ("scene is a directory", "pd", "directory", "", "is a directory"),
    ("scene missing", "pd", "missing", "", "No such file or directory"),
]

# runtime guards: scenes that pass every check but whose loads are unbounded; `run` stops with status 1
# and says where (a particle flown off, a non-finite energy), never a signal
RUNTIME = [
    ("boundary displacement 1e30 m", "pd", "type = \"velocity\"\nx = -5.0", "type = \"displacement\"\nx = -1e30"),
]

# warnings: (name, base, find, replace, key, text in the message, the line's text); `check` exits with 0
WARNINGS = [
    ("pmb poisson ratio ignored", "pd", "model = \"lps\"\ndensity = 2440.0\nyoungs_modulus = 72e9\npoisson_ratio = 0.25",
     "model = \"pmb\"\ndensity = 2440.0\nyoungs_modulus = 72e9\npoisson_ratio = 0.2", "materials.glass.poisson_ratio",
     "PMB's Poisson ratio is 1/3 in plane stress", "poisson_ratio = 0.2"),
    ("more snapshots than steps", "pd", "snapshots = 3", "snapshots = 500", "output.snapshots", "one each step", "snapshots = 500"),
]


def line_of(text, needle):
    at = text.index(needle)
    return text.count("\n", 0, at) + 1


def run(args):
    return subprocess.run([RIFT] + args, capture_output=True, text=True, timeout=120, env=dict(os.environ, OMP_NUM_THREADS="1"))


def main():
    failures = []
    tmp = tempfile.mkdtemp()
    for n, (name, base, find, replace, key, line_text) in enumerate(CASES):
        text = BASES[base]
        assert find in text, f"{name}: '{find}' not in the {base} scene"
        text = text.replace(find, replace, 1)
        scene = os.path.join(tmp, f"case{n}.toml")
        out = os.path.join(tmp, f"out{n}")
        with open(scene, "w") as f:
            f.write(text)
        for command in (["check", scene], ["run", scene, "-o", out]):
            r = run(command)
            problems = []
            if r.returncode != 2:
                problems.append(f"exit status {r.returncode}, not 2")
            if f"'{key}'" not in r.stderr:
                problems.append(f"the key '{key}' is not named")
            if line_text:
                want = f"{scene}:{line_of(text, line_text)}:"
                if not re.search(re.escape(want) + r"\d+: error: ", r.stderr):
                    problems.append(f"no {want}COLUMN: error:")
            if os.path.exists(out) and os.listdir(out):
                problems.append(f"wrote {os.listdir(out)}")
            if problems:
                failures.append(f"{name} ({command[0]}): {'; '.join(problems)}\n    stderr: {r.stderr.strip()[:400]}")
    for n, (name, base, setup, key, message) in enumerate(OPTION_CASES):
        scene = os.path.join(tmp, f"option{n}.toml")
        with open(scene, "w") as f:
            f.write(BASES[base])
        out = os.path.join(tmp, f"option_out{n}")
        args = ["run", scene, "-o", out]
        if setup == "file":
            open(out, "w").close()
        elif setup == "below":
            open(out, "w").close()
            args = ["run", scene, "-o", os.path.join(out, "results")]
        elif setup == "memory":
            args += ["--max-memory", "100K"]
        elif setup == "threads":
            args += ["--threads", "0"]
        elif setup == "directory":
            args = ["run", tmp, "-o", out]
        elif setup == "missing":
            args = ["run", os.path.join(tmp, "no_such_scene.toml"), "-o", out]
        r = run(args)
        problems = []
        if r.returncode != 2:
            problems.append(f"exit status {r.returncode}, not 2")
        if key and f"'{key}'" not in r.stderr:
            problems.append(f"the key '{key}' is not named")
        if message not in r.stderr:
            problems.append(f"'{message}' is not in the message")
        if os.path.isdir(out) and os.listdir(out):
            problems.append(f"wrote {os.listdir(out)}")
        if problems:
            failures.append(f"{name}: {'; '.join(problems)}\n    stderr: {r.stderr.strip()[:400]}")
    for n, (name, base, find, replace, key, message, line_text) in enumerate(WARNINGS):
        text = BASES[base]
        assert find in text, name
        text = text.replace(find, replace, 1)
        scene = os.path.join(tmp, f"warning{n}.toml")
        with open(scene, "w") as f:
            f.write(text)
        r = run(["check", scene])
        want = f"{scene}:{line_of(text, line_text)}:"
        if r.returncode != 0 or f"'{key}'" not in r.stderr or message not in r.stderr or want not in r.stderr or ": warning: " not in r.stderr:
            failures.append(f"{name}: exit status {r.returncode}, stderr: {r.stderr.strip()[:400]}")
    for n, (name, base, find, replace) in enumerate(RUNTIME):
        scene = os.path.join(tmp, f"runtime{n}.toml")
        with open(scene, "w") as f:
            f.write(BASES[base].replace(find, replace, 1))
        r = run(["run", scene, "-o", os.path.join(tmp, f"runtime_out{n}")])
        if r.returncode != 1 or "rift: run stopped: " not in r.stderr:
            failures.append(f"{name}: exit status {r.returncode}, not 1; stderr: {r.stderr.strip()[-400:]}")
    total = len(CASES) + len(OPTION_CASES) + len(WARNINGS) + len(RUNTIME)
    assert len(CASES) + len(OPTION_CASES) >= 40, "at least 40 bad scenes (issue 81)"
    if failures:
        print("\n".join(failures))
        print(f"bad input: {len(failures)} of {total} cases failed")
        return 1
    print(f"bad input: all {total} cases exit with status 2 (or warn) as they should")
    return 0


if __name__ == "__main__":
    sys.exit(main())
