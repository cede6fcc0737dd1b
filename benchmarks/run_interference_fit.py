#!/usr/bin/python3
"""The interference fit (parameters/interference_fit.prm): a ring of inner
radius B = 1 and outer radius C = 2 shrunk onto a solid shaft with the
radial interference delta = 0.01, one material (E = 1000, nu = 0.3, plane
stress), the quarter model, on the meshes n = 8, 16, 32, 64 of
meshes/make_interference_meshes.py (2n segments on the shaft's arc, 3n on
the ring's: non-matching), against the closed form of thick-walled
cylinders (Lame):

    p = E delta (C^2 - B^2) / (2 B C^2) = 3.75.

Run with Geometric gap = measured (the distance of the two polygons counts
in the gap) and = ignored (Initial gap alone: both arcs discretise one
circle). Measured on the contact nodes (the ring's inner arc): the error of the mean
pressure (the contact force over the arc's length pi B / 2), the weighted
L2 error of the nodal pressures, sqrt(sum w (p_i - p)^2 / sum w) / p, and
the largest nodal error, each relative to p, with their observed orders.
Both arcs are polygons whose nodes lie on the circle; their chords lie up
to h^2 / (8 B) inside it, a gap that varies along the interface with the
nodes of the other side and that the pressure follows where it is measured
(nodal errors of 10 to 100 percent, falling like h); ignored, the nodal
errors are below 0.3 percent and the mean pressure's falls like h^2
(doc/benchmarks.md). Prints the markdown table of
doc/benchmarks.md and, with --figure FILE, draws the errors against the
number of contact nodes. With --check (the ctest) it fails unless every
error is below 1.5 times its observed value (BOUNDS) and falls from mesh
to mesh with at least 0.8 times its observed order (ORDERS).

Then the assembly of a shaft (r < 1, E = 1000, nu = 0.3) and two rings
(1 < r < 1.5, E = 500, nu = 0.25; 1.5 < r < 2, E = 2000, nu = 0.35), each
ring shrunk onto the body inside it (delta = 0.01 and 0.005), two contact
pairs with Geometric gap = ignored, in plane stress and in plane strain:
the two contact pressures against the closed form of compound cylinders
(lame_pressures()), the errors of the mean pressure and the nodal L2 error
of each interface with their orders, bounded in --check as above
(ASSEMBLY_BOUNDS, ASSEMBLY_ORDERS).

Then the relaxation of the fit with a viscoplastic ring (Perzyna,
lambda = 100, sigma_Y = 2; the interference grown in t < 0.1 and held to
T = 1; n = 8): the contact force at T with the time steps of
RELAXATION_STEPS, which has no closed form; --check requires the force at
T below 0.8 times the elastic one (the fit relaxes) and the differences
between successive steps to fall with at least 0.8 times their observed
orders (RELAXATION_ORDERS, about 1: the scheme is of first order in k).

    benchmarks/run_interference_fit.py [--executable build/viscoplastic_contact]
        [--figure doc/figures/interference_fit.png] [--check] [--meshes 8,16,32,64]
"""

import argparse
import csv
import glob
import math
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..")
E, NU, B, C, DELTA = 1000.0, 0.3, 1.0, 2.0, 0.01
P = E * DELTA * (C * C - B * B) / (2 * B * C * C)
KEYS = ("mean", "L2", "max")
GAPS = ("measured", "ignored")
MODELS = ("plane stress", "plane strain")
ASSEMBLY_KEYS = ("mean 1", "L2 1", "mean 2", "L2 2")
# The bounds and orders of --check for the assembly (Geometric gap =
# ignored), 1.5 and 0.8 times the observed ones.
ASSEMBLY_BOUNDS = {
    "plane stress": {"mean 1": {8: 1.9e-4, 16: 4.8e-5, 32: 1.2e-5, 64: 3.0e-6},
                     "L2 1": {8: 1.8e-3, 16: 8.7e-4, 32: 4.4e-4, 64: 2.2e-4},
                     "mean 2": {8: 1.1e-3, 16: 2.6e-4, 32: 6.6e-5, 64: 1.7e-5},
                     "L2 2": {8: 1.8e-3, 16: 7.1e-4, 32: 3.1e-4, 64: 1.5e-4}},
    "plane strain": {"mean 1": {8: 3.2e-5, 16: 8.8e-6, 32: 2.3e-6, 64: 5.7e-7},
                     "L2 1": {8: 1.4e-3, 16: 6.9e-4, 32: 3.5e-4, 64: 1.7e-4},
                     "mean 2": {8: 8.1e-4, 16: 2.0e-4, 32: 5.0e-5, 64: 1.3e-5},
                     "L2 2": {8: 1.6e-3, 16: 6.0e-4, 32: 2.6e-4, 64: 1.2e-4}}}
ASSEMBLY_ORDERS = {
    "plane stress": {"mean 1": (2.09, 2.04, 2.02), "L2 1": (1.04, 1.02, 1.01),
                     "mean 2": (2.07, 2.04, 2.02), "L2 2": (1.38, 1.22, 1.11)},
    "plane strain": {"mean 1": (1.94, 2.00, 2.00), "L2 1": (1.07, 1.03, 1.01),
                     "mean 2": (2.08, 2.04, 2.02), "L2 2": (1.42, 1.25, 1.14)}}
# The bounds of --check: 1.5 times the errors observed on n = 8, 16, 32, 64
# (measured: mean 4.37e-2, 1.09e-2, 2.73e-3, 6.81e-4; L2 0.878, 0.446,
# 0.225, 0.113; max 1.61, 0.854, 0.439, 0.222; ignored: mean 1.02e-3,
# 2.57e-4, 6.43e-5, 1.61e-5; L2 2.63e-3, 1.22e-3, 5.99e-4, 2.99e-4; max
# 3.31e-3, 1.98e-3, 1.09e-3, 5.68e-4).
BOUNDS = {
    "measured": {"mean": {8: 0.066, 16: 0.016, 32: 0.0041, 64: 0.0010},
                 "L2": {8: 1.32, 16: 0.67, 32: 0.34, 64: 0.17},
                 "max": {8: 2.4, 16: 1.28, 32: 0.66, 64: 0.33}},
    "ignored": {"mean": {8: 1.5e-3, 16: 3.9e-4, 32: 9.6e-5, 64: 2.4e-5},
                "L2": {8: 3.9e-3, 16: 1.8e-3, 32: 9.0e-4, 64: 4.5e-4},
                "max": {8: 5.0e-3, 16: 3.0e-3, 32: 1.6e-3, 64: 8.5e-4}}}
# The observed orders between successive meshes (in the number of contact
# nodes); --check requires 0.8 times each.
ORDERS = {
    "measured": {"mean": (2.06, 2.03, 2.02), "L2": (1.01, 1.00, 1.00),
                 "max": (0.94, 0.98, 0.99)},
    "ignored": {"mean": (2.05, 2.03, 2.01), "L2": (1.14, 1.04, 1.01),
                "max": (0.77, 0.88, 0.94)}}


def set_entry(text, entry, value):
    return re.sub(r"(?m)^(\s*set %s\s*=)[^#\n]*" % re.escape(entry),
                  r"\g<1> %s " % value, text)


def run(executable, n, folder, gap):
    sys.path.insert(0, os.path.join(TOP, "meshes"))
    from make_interference_meshes import shaft_and_ring
    mesh = os.path.join(folder, "interference_fit_%d.msh" % n)
    with open(mesh, "w") as f:
        f.write(shaft_and_ring(n))
    with open(os.path.join(TOP, "parameters", "interference_fit.prm")) as f:
        text = f.read()
    text = set_entry(text, "Mesh file", mesh)
    text = set_entry(text, "Write vtu", "false")
    text = set_entry(text, "Geometric gap", gap)
    text = set_entry(text, "Output directory", os.path.join(folder, "output_%s_%d" % (gap, n)))
    prm = os.path.join(folder, "interference_fit_%s_%d.prm" % (gap, n))
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("The run on n = %d failed:\n%s" % (n, result.stderr))
    return os.path.join(folder, "output_%s_%d" % (gap, n))


def analyse(output):
    (profile,) = glob.glob(os.path.join(output, "contact_profile_*.csv"))
    with open(profile) as f:
        rows = list(csv.DictReader(f))
    weights = [float(row["weight"]) for row in rows]
    pressures = [float(row["contact_pressure"]) for row in rows]
    force = sum(w * p for w, p in zip(weights, pressures))
    return {"nodes": len(rows),
            "mean": abs(force / (math.pi * B / 2) - P) / P,
            "L2": math.sqrt(sum(w * (p - P) ** 2 for w, p in zip(weights, pressures))
                            / sum(weights)) / P,
            "max": max(abs(p - P) for p in pressures) / P}


# The three-body assembly: a shaft and two rings of different materials,
# each ring shrunk onto the body inside it.
ASSEMBLY_RADII = (1.0, 1.5, 2.0)
ASSEMBLY_MATERIALS = ((1000.0, 0.3), (500.0, 0.25), (2000.0, 0.35))
ASSEMBLY_DELTAS = (0.01, 0.005)


# The relaxation of the fit with a viscoplastic ring (Perzyna, lambda =
# 100, sigma_Y = 2; the shaft elastic): the interference grown in t < 0.1,
# then held to T = 1, on the mesh n = 8, with these time steps.
RELAXATION_STEPS = (0.1, 0.05, 0.025, 0.0125, 0.00625)
# The observed orders of the differences of the final contact force
# between successive steps; --check requires 0.8 times each.
RELAXATION_ORDERS = (1.27, 1.17, 1.07)


def run_relaxation(executable, k, folder):
    """The final contact force of the viscoplastic fit with the step k and
    the force at the end of the first step."""
    sys.path.insert(0, os.path.join(TOP, "meshes"))
    from make_interference_meshes import shaft_and_ring
    mesh = os.path.join(folder, "relaxation.msh")
    if not os.path.exists(mesh):
        with open(mesh, "w") as f:
            f.write(shaft_and_ring(8))
    with open(os.path.join(TOP, "parameters", "interference_fit.prm")) as f:
        text = f.read()
    text = set_entry(text, "Mesh file", mesh)
    text = set_entry(text, "Write vtu", "false")
    text = set_entry(text, "Initial gap", "-%g * min(10 * t, 1)" % DELTA)
    text = set_entry(text, "Time step", k)
    text = re.sub(r"(?ms)^subsection Material\b.*?^end\n",
                  lambda _: "subsection Material\n  set Material ids = 1\n"
                  "  set Young's modulus = %g\n  set Poisson ratio = %g\n"
                  "  set Plasticity = false\nend\nsubsection Material 2\n"
                  "  set Material ids = 2\n  set Young's modulus = %g\n"
                  "  set Poisson ratio = %g\n  set Plasticity = true\n"
                  "  set Viscosity = 100\n  set Yield stress = 2\nend\n" % (E, NU, E, NU),
                  text, count=1)
    output = os.path.join(folder, "relaxation_%g" % k)
    text = set_entry(text, "Output directory", output)
    prm = output + ".prm"
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("The relaxation with k = %g failed:\n%s" % (k, result.stderr))
    with open(os.path.join(output, "time_series.csv")) as f:
        rows = list(csv.DictReader(f))
    return float(rows[-1]["total_contact_force"])


def lame_pressures(radii, materials, deltas, plane_strain=False):
    """The contact pressures of a shaft and rings shrunk onto each other
    (thick-walled cylinders): the radial displacement of a ring a < r < b
    under the pressures p_a inside and p_b outside is
      u(r) = [(1 - nu) (p_a a^2 - p_b b^2) r / (b^2 - a^2)
              + (1 + nu) (p_a - p_b) a^2 b^2 / ((b^2 - a^2) r)] / E,
    that of the solid shaft u(r) = -(1 - nu) p r / E (plane stress; plane
    strain with E / (1 - nu^2) and nu / (1 - nu)); the interference of
    interface k is u_k(r_k) - u_{k-1}(r_k) = delta_k."""
    def constants(k):
        E, nu = materials[k]
        return (E / (1 - nu * nu), nu / (1 - nu)) if plane_strain else (E, nu)

    def displacement(k, r, pressures):
        E, nu = constants(k)
        if k == 0:
            return -(1 - nu) * pressures[0] * r / E
        a, b = radii[k - 1], radii[k]
        p_a = pressures[k - 1]
        p_b = pressures[k] if k < len(pressures) else 0.0
        return ((1 - nu) * (p_a * a * a - p_b * b * b) * r / (b * b - a * a)
                + (1 + nu) * (p_a - p_b) * a * a * b * b / ((b * b - a * a) * r)) / E

    m = len(deltas)
    def interferences(pressures):
        return [displacement(k, radii[k - 1], pressures)
                - displacement(k - 1, radii[k - 1], pressures) for k in range(1, m + 1)]
    # The map from the pressures to the interferences is linear: its
    # columns, then Gauss elimination.
    matrix = [interferences([1.0 if j == i else 0.0 for j in range(m)]) for i in range(m)]
    rows = [[matrix[j][i] for j in range(m)] + [deltas[i]] for i in range(m)]
    for i in range(m):
        pivot = max(range(i, m), key=lambda r: abs(rows[r][i]))
        rows[i], rows[pivot] = rows[pivot], rows[i]
        for r in range(m):
            if r != i:
                factor = rows[r][i] / rows[i][i]
                rows[r] = [x - factor * y for x, y in zip(rows[r], rows[i])]
    return [rows[i][m] / rows[i][i] for i in range(m)]


def run_assembly(executable, n, folder, model):
    sys.path.insert(0, os.path.join(TOP, "meshes"))
    from make_interference_meshes import shaft_and_ring
    mesh = os.path.join(folder, "assembly_%d.msh" % n)
    with open(mesh, "w") as f:
        f.write(shaft_and_ring(n, radii=ASSEMBLY_RADII))
    with open(os.path.join(TOP, "parameters", "interference_fit.prm")) as f:
        text = f.read()
    text = re.sub(r"(?m)^(set Dimension = 2)$", r"\g<1>\nset Plane model = %s" % model, text)
    text = set_entry(text, "Mesh file", mesh)
    text = set_entry(text, "Write vtu", "false")
    text = set_entry(text, "Initial gap", "-%g * t" % ASSEMBLY_DELTAS[0])
    name = "assembly_%s_%d" % (model.replace(" ", "_"), n)
    text = set_entry(text, "Output directory", os.path.join(folder, name))
    materials = "".join(
        "subsection Material%s\n  set Material ids = %d\n  set Young's modulus = %g\n"
        "  set Poisson ratio = %g\n  set Plasticity = false\nend\n"
        % ("" if k == 0 else " %d" % (k + 1), k + 1, E, nu)
        for k, (E, nu) in enumerate(ASSEMBLY_MATERIALS))
    text = re.sub(r"(?ms)^subsection Material\b.*?^end\n", lambda _: materials, text, count=1)
    text += ("subsection Contact zone 2\n  set Boundary ids = 6\n"
             "  set Opposite boundary ids = 5\n  set Unilateral constraint = true\n"
             "  set Normal compliance = false\n  set Layer thickness = 0\n"
             "  set Initial gap = -%g * t\n  set Geometric gap = ignored\nend\n"
             % ASSEMBLY_DELTAS[1])
    prm = os.path.join(folder, name + ".prm")
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("The assembly on n = %d failed:\n%s" % (n, result.stderr))
    return os.path.join(folder, name)


def analyse_assembly(output, pressures):
    """Per interface k: the mean pressure's error (the zone's force over
    the arc's length) and the weighted L2 error of its nodal pressures."""
    with open(os.path.join(output, "time_series.csv")) as f:
        last = list(csv.DictReader(f))[-1]
    (profile,) = glob.glob(os.path.join(output, "contact_profile_*.csv"))
    with open(profile) as f:
        rows = list(csv.DictReader(f))
    result = {"nodes": len(rows)}
    for k, p in enumerate(pressures, 1):
        force = float(last["contact_force_zone_%d" % k])
        result["mean %d" % k] = abs(force / (math.pi * ASSEMBLY_RADII[k - 1] / 2) - p) / p
        zone = [row for row in rows if int(row["zone"]) == k]
        weights = [float(row["weight"]) for row in zone]
        result["L2 %d" % k] = math.sqrt(
            sum(w * (float(row["contact_pressure"]) - p) ** 2 for w, row in zip(weights, zone))
            / sum(weights)) / p
    return result


def observed_order(coarse, fine, key):
    return math.log(coarse[key] / fine[key]) / math.log(fine["nodes"] / coarse["nodes"])


def print_table(results, keys, headers):
    print("| n | contact nodes | " + " | ".join(h + " | order" for h in headers) + " |")
    print("|---|---|" + "---|---|" * len(keys))
    for k, r in enumerate(results):
        cells = ["%d" % r["n"], "%d" % r["nodes"]]
        for key in keys:
            cells.append("%.2e" % r[key])
            cells.append("%.2f" % observed_order(results[k - 1], r, key) if k > 0 else "")
        print("| " + " | ".join(cells) + " |")


def check_series(name, results, keys, bounds, orders):
    """The failures of one series: an error above its bound on a mesh, or
    an order below 0.8 times the observed one."""
    failures = []
    for k, r in enumerate(results):
        for key in keys:
            bound = bounds[key].get(r["n"])
            if bound is not None and r[key] > bound:
                failures.append("%s, n = %d: %s error %.3g above %.3g"
                                % (name, r["n"], key, r[key], bound))
            if k > 0:
                order = observed_order(results[k - 1], r, key)
                if order < 0.8 * orders[key][k - 1]:
                    failures.append("%s, n = %d: %s order %.2f below 0.8 x %.2f"
                                    % (name, r["n"], key, order, orders[key][k - 1]))
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--executable",
                        default=os.path.join(TOP, "build", "viscoplastic_contact"))
    parser.add_argument("--figure")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--meshes", default="8,16,32,64")
    arguments = parser.parse_args()
    meshes = [int(n) for n in arguments.meshes.split(",")]
    series, assembly = {}, {}
    with tempfile.TemporaryDirectory() as folder:
        for gap in GAPS:
            series[gap] = [dict(analyse(run(arguments.executable, n, folder, gap)), n=n)
                           for n in meshes]
        relaxation = [run_relaxation(arguments.executable, k, folder)
                      for k in RELAXATION_STEPS]
        for model in MODELS:
            pressures = lame_pressures(ASSEMBLY_RADII, ASSEMBLY_MATERIALS, ASSEMBLY_DELTAS,
                                       model == "plane strain")
            assembly[model] = [
                dict(analyse_assembly(run_assembly(arguments.executable, n, folder, model),
                                      pressures), n=n) for n in meshes]

    print("Lame pressure p = %.6g" % P)
    for gap in GAPS:
        results = series[gap]
        print("\nGeometric gap = %s:\n" % gap)
        print_table(results, KEYS, ("mean pressure", "L2", "max"))

    for model in MODELS:
        results = assembly[model]
        pressures = lame_pressures(ASSEMBLY_RADII, ASSEMBLY_MATERIALS, ASSEMBLY_DELTAS,
                                   model == "plane strain")
        print("\nThe assembly, %s (Lame: p1 = %.6g, p2 = %.6g):\n" % ((model,) + tuple(pressures)))
        print_table(results, ASSEMBLY_KEYS, ("mean p1", "L2 p1", "mean p2", "L2 p2"))

    # The elastic fit's force, Lame's p pi B / 2: the relaxed force is
    # below it.
    elastic_force = P * math.pi * B / 2
    differences = [abs(a - b) for a, b in zip(relaxation, relaxation[1:])]
    relaxation_orders = [math.log(a / b) / math.log(2)
                         for a, b in zip(differences, differences[1:])]
    print("\nRelaxation with a viscoplastic ring (n = 8), the contact force at "
          "T = 1 (elastic, Lame: %.4g):\n" % elastic_force)
    print("| k | force at T | difference to k/2 | order |")
    print("|---|---|---|---|")
    for j, k in enumerate(RELAXATION_STEPS):
        print("| %g | %.6g | %s | %s |"
              % (k, relaxation[j], "%.2e" % differences[j] if j < len(differences) else "",
                 "%.2f" % relaxation_orders[j - 1] if 0 < j < len(differences) else ""))

    if arguments.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        figure, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
        for axis, gap in zip(axes, GAPS):
            results = series[gap]
            nodes = [r["nodes"] for r in results]
            for key, label in zip(KEYS, ("mean pressure", "L2 of the nodal pressures",
                                         "largest nodal error")):
                axis.loglog(nodes, [r[key] for r in results], "o-", label=label)
            axis.loglog(nodes, [results[0]["L2"] * (nodes[0] / m) for m in nodes], "k:",
                        label="order 1")
            axis.loglog(nodes, [results[0]["mean"] * (nodes[0] / m) ** 2 for m in nodes],
                        "k--", label="order 2")
            axis.set_xlabel("contact nodes")
            axis.set_title("Geometric gap = %s" % gap)
        axes[0].set_ylabel("error relative to Lame's pressure")
        axes[1].legend()
        figure.suptitle("Interference fit, non-matching arcs (2n and 3n segments)")
        figure.tight_layout()
        figure.savefig(arguments.figure, dpi=100)

    if arguments.check:
        failures = []
        for gap in GAPS:
            failures += check_series(gap, series[gap], KEYS, BOUNDS[gap], ORDERS[gap])
        for model in MODELS:
            failures += check_series("assembly, " + model, assembly[model], ASSEMBLY_KEYS,
                                     ASSEMBLY_BOUNDS[model], ASSEMBLY_ORDERS[model])
        if relaxation[-1] > 0.8 * elastic_force:
            failures.append("relaxation: the force at T = 1, %.4g, is not below 0.8 times "
                            "the elastic %.4g" % (relaxation[-1], elastic_force))
        for j, order in enumerate(relaxation_orders):
            if order < 0.8 * RELAXATION_ORDERS[j]:
                failures.append("relaxation: order %.2f below 0.8 x %.2f"
                                % (order, RELAXATION_ORDERS[j]))
        if failures:
            sys.exit("\n".join(failures))
        print("Every error within its bound, every order at least 0.8 times the observed one.")


if __name__ == "__main__":
    main()
