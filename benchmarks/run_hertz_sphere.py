#!/usr/bin/python3
"""Hertz contact of a sphere (parameters/hertz_sphere.prm): a rigid sphere of
radius R = 1 pressed into an elastic block by a moving obstacle, the
indentation d(t) = 0.01 t, on the quarter model [0, 1]^3 of
meshes/make_hertz_sphere_meshes.py (hexahedra and tetrahedra, N cells per
edge, graded toward the contact point), against the closed form of a rigid
sphere on an elastic half-space, E* = E / (1 - nu^2):

    F(d) = 4/3 E* sqrt(R) d^(3/2),
    a = (3 F R / (4 E*))^(1/3),   p0 = 3 F / (2 pi a^2),

F = 4 times the quarter model's contact force. a and p0 are compared with
the values of Hertz for the computed force F (the shape of the contact is
local; the block's finite size changes mostly the approach d), F(d) with
Hertz's curve (there the finite block is the modelling error). The
numerical contact radius is the zero of the pressure along the x axis
extrapolated from the last two nodes in contact with the Hertz shape (p^2
linear in x^2); the numerical peak pressure is that of the node at the
contact point. The L2 error of all nodal pressures against Hertz's profile
p0 sqrt(1 - r^2/a^2) for the computed force (lumped weights) is the
measure that converges. Prints the markdown tables of doc/benchmarks.md;
--figure
FILE draws the force-indentation curves and the errors against the mesh
size and the run time (the program's wall clock). --check (the ctest):
N = 8, 12, 16, 24 on both cell types, each error in a, p0 and F(d) within
1.5 times its observed value (OBSERVED), the L2 error of the pressure
falling from N = 8 to 16 to 24 with 0.8 times its observed orders on both
cell types, F(d) on a block of edge 40 a (hexahedra, N = 24) within 1.5
times its observed 0.73%, and 2-rank runs on N = 8 (full space back end)
equal to the 1-rank ones (condensed) to 1e-6.

--cost N,M,... --methods "full space,condensed" --ranks 1
--condensed-up-to 48 (the largest N for the condensed back end, counted
after refinement) --cells hexahedron,tetrahedron [--global-refinements
R,S,...: the graded mesh of N cells per edge refined globally R times,
where the matrix-free back end and the initial cycles find coarser
meshes]: the cost of the
moving obstacle at N cells per edge (N = 68: 985k dofs), from
the program's own cost report: active-set iterations and Krylov iterations
per step, the time of a step against one elastic solve with the operator
of the step (no contact, the same preconditioner, from a zero start), how
often the back end set up its operator, peak memory. Prints a markdown
table (doc/benchmarks.md, "Cost of a moving-obstacle step").

    benchmarks/run_hertz_sphere.py [--executable build/viscoplastic_contact]
        [--meshes 8,16,24,32] [--cells hexahedron,tetrahedron]
        [--figure doc/figures/hertz_sphere.png] [--check]
        [--cost 68 [--methods "full space,condensed"] [--ranks 1]
         [--condensed-up-to 48] [--cells hexahedron,tetrahedron]]
        [--recovery 16,24,32,48]

--recovery N,M,...: the nodal pressure along the symmetry axes as the
program writes it (lumped, z_i / w_i), averaged over each node's
neighbours, and recovered consistently (M p = z), on hexahedra and on
tetrahedra of both splits of the cubes, against Hertz (recovery_study()).
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
sys.path.insert(0, os.path.join(TOP, "scripts"))
sys.path.insert(0, os.path.join(TOP, "meshes"))
from vc_scripts import set_prm_entries  # noqa: E402
from make_hertz_sphere_meshes import hertz_sphere_block  # noqa: E402
E, NU, R, D = 1000.0, 0.3, 1.0, 0.01
E_STAR = E / (1 - NU ** 2)
# --check: the errors observed on N = 8, 12, 16, 24 (doc/benchmarks.md),
# each bound 1.5 times its observed error; the errors in a and p0 do not
# fall monotonically (which nodes are in contact changes with N), that of
# F(d) is the finite block's (10 a).
OBSERVED = {
    "hexahedron": {
        8: {"F": 9.07e-2, "a": 1.946e-1, "p0": 8.37e-3},
        12: {"F": 4.25e-2, "a": 1.031e-1, "p0": 3.21e-2},
        16: {"F": 7.08e-2, "a": 1.51e-3, "p0": 5.61e-3},
        24: {"F": 6.61e-2, "a": 3.06e-2, "p0": 3.98e-3}},
    "tetrahedron": {
        8: {"F": 3.061e-1, "a": 1.457e-1, "p0": 3.27e-2},
        12: {"F": 1.463e-1, "a": 3.04e-2, "p0": 5.56e-2},
        16: {"F": 1.275e-1, "a": 2.40e-2, "p0": 3.53e-2},
        24: {"F": 9.75e-2, "a": 2.33e-2, "p0": 2.15e-2}}}
# The observed orders of the pressure's L2 error against Hertz from N = 8
# to 16 and from 16 to 24; --check requires 0.8 times each.
OBSERVED_ORDERS = {"hexahedron": (1.06, 1.65), "tetrahedron": (1.93, 1.18)}
# F(d) on a block of edge 40 a (length 4, hexahedra, N = 24), where the
# finite block's error is small: observed 7.34e-3.
LARGE_BLOCK = {"length": 4.0, "N": 24, "F": 7.34e-3}


def hertz_force(d):
    return 4.0 / 3.0 * E_STAR * math.sqrt(R) * d ** 1.5


def run(executable, n, cells, ranks, folder, method=None, report=None,
        length=1.0, mirrored=False, refinements=0):
    """Runs the scene on N (a block of edge length; tetrahedra split around
    the other diagonal if mirrored; refined globally refinements times),
    returns the output folder and the wall time; report (a dict) receives
    the program's standard output."""
    mesh = os.path.join(folder, "hertz_sphere.msh")
    with open(mesh, "w") as f:
        f.write(hertz_sphere_block(n, cells == "tetrahedron", length,
                                   mirrored))
    entries = {(("Geometry",), "Mesh file"): mesh,
               (("Geometry",), "Cell type"):
                   "simplex" if cells == "tetrahedron" else "hypercube",
               (("Output",), "Output directory"): os.path.join(folder, "output"),
               (("Output",), "Profile times"): "1",
               (("Output",), "Write vtu"): "false",
               (("Output",), "Measure cost ratios"): "true"}
    if method:
        entries[(("Linear solver",), "Method")] = method
    if refinements:
        entries[(("Geometry",), "Global refinements")] = str(refinements)
    with open(os.path.join(TOP, "parameters", "hertz_sphere.prm")) as f:
        text = set_prm_entries(f.read(), entries)
    prm = os.path.join(folder, "hertz.prm")
    with open(prm, "w") as f:
        f.write(text)
    command = [os.path.join(TOP, "tests", "run_mpi.sh"), str(ranks),
               executable, prm]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("The run on %s, N = %d, %d rank(s) failed:\n%s"
                 % (cells, n, ranks, result.stderr))
    loop = re.search(r"Total wallclock time elapsed since start *\| *([0-9.eE+-]+)s",
                     result.stdout)
    if report is not None:
        report["stdout"] = result.stdout
    return os.path.join(folder, "output"), float(loop.group(1)) if loop else 0.


def analyse(output):
    with open(os.path.join(output, "time_series.csv")) as f:
        series = list(csv.DictReader(f))
    curve = [(D * float(r["time"]), 4 * float(r["total_contact_force"]))
             for r in series]
    force = curve[-1][1]
    profile = sorted(glob.glob(os.path.join(output, "contact_profile_*.csv")))[-1]
    with open(profile) as f:
        rows = list(csv.DictReader(f))
    result = profile_measures(rows, force, E_STAR, R)
    result.update({"F": force, "F Hertz": hertz_force(D), "curve": curve,
                   "F error": abs(force - hertz_force(D)) / hertz_force(D)})
    return result


def profile_measures(rows, force, e_star, radius):
    """a, p0 and the L2 error of a quarter model's contact profile (rows of
    the program's CSV) against Hertz's values for the force F (4 times the
    quarter's): the zero of the pressure along the x axis extrapolated from
    the last two nodes in contact (p^2 linear in x^2), the pressure at the
    contact point, all nodal pressures against p0 sqrt(1 - r^2/a^2) in the
    norm of the lumped weights."""
    axis = sorted((float(r["x"]), float(r["contact_pressure"]))
                  for r in rows if abs(float(r["z"])) < 1e-12)
    k = max(i for i, (_, p) in enumerate(axis) if p > 0)
    (x1, p1), (x2, p2) = axis[k - 1], axis[k]
    a = math.sqrt(x2 ** 2 + p2 ** 2 * (x2 ** 2 - x1 ** 2) / (p1 ** 2 - p2 ** 2))
    a_hertz = (3 * force * radius / (4 * e_star)) ** (1 / 3)
    p0_hertz = 3 * force / (2 * math.pi * a_hertz ** 2)
    p0 = axis[0][1]
    difference = norm = 0.0
    for r in rows:
        radius2 = float(r["x"]) ** 2 + float(r["z"]) ** 2
        exact = p0_hertz * math.sqrt(max(0.0, 1 - radius2 / a_hertz ** 2))
        weight = float(r["weight"])
        difference += weight * (float(r["contact_pressure"]) - exact) ** 2
        norm += weight * exact ** 2
    return {"a": a, "L2 error": math.sqrt(difference / norm),
            "a Hertz": a_hertz, "p0": p0, "p0 Hertz": p0_hertz,
            "nodes": sum(1 for r in rows if float(r["contact_pressure"]) > 0),
            "a error": abs(a - a_hertz) / a_hertz,
            "p0 error": abs(p0 - p0_hertz) / p0_hertz}


def cost(executable, n, method, ranks, cells="hexahedron", refinements=0):
    """The cost of the moving-obstacle steps on N cells per edge (cells:
    hexahedron or tetrahedron; the graded mesh refined globally refinements
    times), from the program's report (see the top of the file)."""
    report = {}
    with tempfile.TemporaryDirectory() as folder:
        output, wall = run(executable, n, cells, ranks, folder, method,
                           report, refinements=refinements)
        with open(os.path.join(output, "time_series.csv")) as f:
            series = list(csv.DictReader(f))
        result = analyse(output)
    text = report["stdout"]

    def find(pattern):
        match = re.search(pattern, text)
        if not match:
            sys.exit("No '%s' in the report of N = %d, %s, %s."
                     % (pattern, n, cells, method))
        return match.group(1)
    steps = len(series)
    # The run's mesh: after Initial cycles that of the last cycle.
    mesh = (re.search(r"^Initial cycles done: \d+ cells, (\d+) dofs, (\d+) "
                      r"contact nodes", text, re.M)
            or re.search(r"(?:Hex|Tet) cells, (\d+) displacement dofs, (\d+) "
                         r"contact nodes", text))
    if not mesh:
        sys.exit("No mesh line in the report of N = %d, %s, %s."
                 % (n, cells, method))
    return {
        "N": n, "refinements": refinements, "method": method,
        "ranks": ranks, "wall": wall,
        "cells": cells,
        "dofs": int(mesh.group(1)), "contact nodes": int(mesh.group(2)),
        "in contact": result["nodes"], "F error": result["F error"],
        "iterations": [int(r["active_set_iterations"]) for r in series],
        "krylov": [int(r["krylov_iterations"]) for r in series],
        "step": float(find(r"average time step \(without output\): ([0-9.eE+-]+) ms")),
        "solve": float(find(r"one solve with the step operator, no contact: "
                            r"([0-9.eE+-]+) ms")),
        "solve krylov": int(find(r"no contact: [0-9.eE+-]+ ms \((\d+) Krylov")),
        "ratio": float(find(r"ratio step / solve: ([0-9.eE+-]+)")),
        "setups": int(find(r"set up by the back end (\d+)x")),
        "memory": float(find(r"peak memory over the run \[MB\]: sum over ranks ([0-9.eE+-]+)")),
        "steps": steps}


def print_cost(results):
    print("| cells | back end | ranks | N | dofs | contact nodes (in contact) "
          "| active-set iterations per step | Krylov iterations per step (one "
          "elastic solve) | step [s] | elastic solve [s] | step / solve | "
          "operator set-ups in the run | peak memory [GB] | run [s] |")
    print("| --- " * 14 + "|")
    for r in results:
        n = str(r["N"]) + (" refined %d times" % r["refinements"]
                           if r["refinements"] else "")
        print("| %s | %s | %d | %s | %d | %d (%d) | %s | %s (%d) | %.2f | %.2f "
              "| %.2f | %d | %.1f | %.0f |" % (
                  r["cells"], r["method"], r["ranks"], n, r["dofs"],
                  r["contact nodes"], r["in contact"],
                  ", ".join(str(i) for i in r["iterations"]),
                  ", ".join(str(i) for i in r["krylov"]), r["solve krylov"],
                  r["step"] / 1000, r["solve"] / 1000, r["ratio"],
                  r["setups"], r["memory"] / 1000, r["wall"]))


def recovered_pressures(rows, n, simplex, mirrored):
    """The nodal pressure of the top face three ways, by (x index, z
    index) of the graded grid: lumped, z_i / w_i (the program's
    contact_pressure); averaged, the force of the node and its neighbours
    in the grid over their weights; consistent, M p = z with the mass
    matrix of the top face's triangles (P1: the diagonal of each square as
    the mesh cuts it) or squares (Q1)."""
    import numpy as np
    graded = [(k / n) ** 2 for k in range(n + 1)]
    index = lambda x: min(range(n + 1), key=lambda i: abs(graded[i] - x))
    force, weight = {}, {}
    for r in rows:
        key = (index(float(r["x"])), index(float(r["z"])))
        force[key] = float(r["nodal_force"])
        weight[key] = float(r["weight"])
    lumped = {key: force[key] / weight[key] for key in force}
    averaged = {}
    for (i, k) in force:
        patch = [(i + a, k + b) for a in (-1, 0, 1) for b in (-1, 0, 1)
                 if (i + a, k + b) in force]
        averaged[(i, k)] = (sum(force[q] for q in patch)
                            / sum(weight[q] for q in patch))
    number = lambda i, k: k * (n + 1) + i
    mass = np.zeros(((n + 1) ** 2, (n + 1) ** 2))
    for k in range(n):
        for i in range(n):
            dx, dz = graded[i + 1] - graded[i], graded[k + 1] - graded[k]
            corners = [(i, k), (i + 1, k), (i + 1, k + 1), (i, k + 1)]
            if not simplex:
                # Q1 on a rectangle: (dx dz / 36) (1 + [a, b adjacent]) (1 +
                # [same x]) ... as the tensor product of 1D mass matrices.
                for a in corners:
                    for b in corners:
                        mx = dx / 6 * (2 if a[0] == b[0] else 1)
                        mz = dz / 6 * (2 if a[1] == b[1] else 1)
                        mass[number(*a), number(*b)] += mx * mz
                continue
            triangles = ([(corners[1], corners[0], corners[3]),
                          (corners[1], corners[2], corners[3])] if mirrored
                         else [(corners[0], corners[1], corners[2]),
                               (corners[0], corners[3], corners[2])])
            for triangle in triangles:
                area = dx * dz / 2
                for a in triangle:
                    for b in triangle:
                        mass[number(*a), number(*b)] += area / 12 * (2 if a == b else 1)
    loads = np.zeros((n + 1) ** 2)
    for (i, k), f in force.items():
        loads[number(i, k)] = f
    solution = np.linalg.solve(mass, loads)
    consistent = {key: solution[number(*key)] for key in force}
    return {"lumped": lumped, "averaged": averaged, "consistent": consistent}


def recovery_study(executable, meshes):
    """--recovery: the nodal pressure on the symmetry axes (x and z, within
    a / 2 of the contact point) against Hertz for the computed force, for
    each recovery of recovered_pressures(), on hexahedra and on tetrahedra
    of both splits (meshes/make_hertz_sphere_meshes.py): the largest error
    relative to p0 (signed) on each axis for the lumped pressure and its
    observed order, the largest on either axis for the others, and the L2
    error of the lumped pressure over the face. Prints the markdown table of
    doc/benchmarks.md."""
    print("| cells | N | lumped, x axis | lumped, z axis | order | averaged | "
          "consistent | L2 over the face (lumped) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for cells, mirrored in (("hexahedron", False), ("tetrahedron", False),
                            ("tetrahedron", True)):
        previous = None
        for n in meshes:
            with tempfile.TemporaryDirectory() as folder:
                output, _ = run(executable, n, cells, 1, folder,
                                mirrored=mirrored)
                result = analyse(output)
                profile = sorted(glob.glob(os.path.join(
                    output, "contact_profile_*.csv")))[-1]
                with open(profile) as f:
                    rows = list(csv.DictReader(f))
            pressures = recovered_pressures(rows, n, cells == "tetrahedron",
                                            mirrored)
            a, p0 = result["a Hertz"], result["p0 Hertz"]
            graded = [(k / n) ** 2 for k in range(n + 1)]

            def worst(name, on_axis):
                errors = [(p - p0 * math.sqrt(1 - (graded[i] ** 2
                                                   + graded[k] ** 2) / a ** 2))
                          / p0
                          for (i, k), p in pressures[name].items()
                          if on_axis(i, k)
                          and graded[i] ** 2 + graded[k] ** 2 <= (a / 2) ** 2]
                return max(errors, key=abs)
            x_axis = worst("lumped", lambda i, k: k == 0)
            z_axis = worst("lumped", lambda i, k: i == 0)
            largest = max(abs(x_axis), abs(z_axis))
            order = ("%.2f" % (math.log(previous[0] / largest)
                               / math.log(n / previous[1]))
                     if previous else "")
            axes = lambda i, k: i == 0 or k == 0
            print("| %s | %d | %+.2e | %+.2e | %s | %+.2e | %+.2e | %.2e |" % (
                cells + (", other split" if mirrored else ""), n, x_axis,
                z_axis, order, worst("averaged", axes),
                worst("consistent", axes), result["L2 error"]))
            previous = (largest, n)


def run_all(executable, meshes, cell_types, ranks):
    runs = {}
    for cells in cell_types:
        runs[cells] = []
        for n in meshes:
            with tempfile.TemporaryDirectory() as folder:
                output, wall = run(executable, n, cells, ranks, folder)
                result = analyse(output)
            result["N"], result["wall"] = n, wall
            runs[cells].append(result)
    return runs


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--executable", default=os.path.join(
        TOP, "build", "viscoplastic_contact"))
    parser.add_argument("--meshes", default="8,16,24,32")
    parser.add_argument("--cells", default="hexahedron,tetrahedron")
    parser.add_argument("--figure")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--cost")
    parser.add_argument("--methods", default="full space,condensed")
    # The condensed factor at N = 68 needs more than this machine's 24 GB.
    parser.add_argument("--condensed-up-to", type=int, default=48)
    parser.add_argument("--ranks", type=int, default=1)
    # With --cost: the graded mesh of N cells per edge refined globally
    # this many times (a list: each in turn), where the matrix-free back
    # end and the cycles of Initial and Step cycles find coarser meshes.
    parser.add_argument("--global-refinements", default="0")
    parser.add_argument("--recovery")
    arguments = parser.parse_args()
    if arguments.recovery:
        recovery_study(arguments.executable,
                       [int(n) for n in arguments.recovery.split(",")])
        return
    if arguments.cost:
        results = []
        for cells in arguments.cells.split(","):
            for n in arguments.cost.split(","):
                for refinements in arguments.global_refinements.split(","):
                    for method in arguments.methods.split(","):
                        if (method == "condensed" and int(n) * 2 ** int(
                                refinements) > arguments.condensed_up_to):
                            print(f"N = {n}: condensed skipped (above "
                                  f"--condensed-up-to "
                                  f"{arguments.condensed_up_to})")
                            continue
                        results.append(cost(arguments.executable, int(n),
                                            method, arguments.ranks, cells,
                                            int(refinements)))
                        print_cost(results[-1:])
        print()
        print_cost(results)
        return
    meshes = [8, 12, 16, 24] if arguments.check else [
        int(n) for n in arguments.meshes.split(",")]
    cell_types = arguments.cells.split(",")
    runs = run_all(arguments.executable, meshes, cell_types, 1)

    print("| cells | N | nodes in contact | F | Hertz F(d) | error | a | Hertz a(F) "
          "| error | p0 | Hertz p0(F) | error | run time |")
    print("| --- " * 13 + "|")
    for cells, results in runs.items():
        for r in results:
            print("| %s | %d | %d | %.4f | %.4f | %.2e | %.4f | %.4f | %.2e | "
                  "%.2f | %.2f | %.2e | %.2f s |" % (
                      cells, r["N"], r["nodes"], r["F"], r["F Hertz"],
                      r["F error"], r["a"], r["a Hertz"], r["a error"],
                      r["p0"], r["p0 Hertz"], r["p0 error"], r["wall"]))
    print()
    print("| cells | N | L2 error of the pressure | observed order |")
    print("| --- | --- | --- | --- |")
    for cells, results in runs.items():
        for i, r in enumerate(results):
            order = ""
            if i > 0:
                order = "%.2f" % (
                    math.log(results[i - 1]["L2 error"] / r["L2 error"])
                    / math.log(r["N"] / results[i - 1]["N"]))
            print("| %s | %d | %.3e | %s |" % (cells, r["N"], r["L2 error"],
                                              order))
    print()
    for cells, results in runs.items():
        for i in range(1, len(results)):
            print("%s, observed order in h (h ~ 1/N), N = %d -> %d: a %.2f, "
                  "p0 %.2f" % (cells, results[i - 1]["N"], results[i]["N"],
                  math.log(results[i - 1]["a error"] / results[i]["a error"])
                  / math.log(results[i]["N"] / results[i - 1]["N"]),
                  math.log(results[i - 1]["p0 error"] / results[i]["p0 error"])
                  / math.log(results[i]["N"] / results[i - 1]["N"])))

    if arguments.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        figure, axes = plt.subplots(1, 3, figsize=(15, 4.2))
        d = [D * k / 100 for k in range(101)]
        axes[0].plot(d, [hertz_force(x) for x in d], "k-", label="Hertz")
        for cells, results in runs.items():
            style = "o" if cells == "hexahedron" else "s"
            r = results[-1]
            axes[0].plot([c[0] for c in r["curve"]], [c[1] for c in r["curve"]],
                         style, label="%s, N = %d" % (cells, r["N"]))
            for key, label in (("a error", "contact radius a"),
                               ("p0 error", "peak pressure p0"),
                               ("F error", "force F(d)")):
                line = "%s-" % style if key != "F error" else "%s:" % style
                axes[1].loglog([1 / r["N"] for r in results],
                               [r[key] for r in results], line,
                               label="%s, %s" % (label, cells))
                axes[2].loglog([r["wall"] for r in results],
                               [r[key] for r in results], line,
                               label="%s, %s" % (label, cells))
        axes[0].set_xlabel("indentation d")
        axes[0].set_ylabel("force F (whole sphere)")
        axes[0].legend()
        axes[1].set_xlabel("mesh parameter 1/N")
        axes[2].set_xlabel("run time [s] (set-up and 4 steps)")
        for axis in axes[1:]:
            axis.set_ylabel("relative error against Hertz")
            axis.grid(True, which="both", alpha=0.3)
            axis.legend(fontsize="x-small")
        axes[0].grid(alpha=0.3)
        figure.suptitle("Hertz contact of a sphere (3D quarter model, a = 0.1 R, "
                        "block of edge 10 a)")
        figure.tight_layout()
        figure.savefig(arguments.figure, dpi=100)

    if arguments.check:
        for cells, results in runs.items():
            for r in results:
                for key in ("a", "p0", "F"):
                    bound = 1.5 * OBSERVED[cells][r["N"]][key]
                    if r[key + " error"] > bound:
                        sys.exit("%s, N = %d: the error in %s is %.2e, above "
                                 "%.2e (1.5 times the observed %.2e)." % (
                                     cells, r["N"], key, r[key + " error"],
                                     bound, OBSERVED[cells][r["N"]][key]))
            # The L2 error of the pressure profile from N = 8 to 16 and from
            # 16 to 24.
            ladder = [r for r in results if r["N"] in (8, 16, 24)]
            for i, (coarse, fine) in enumerate(zip(ladder, ladder[1:])):
                order = (math.log(coarse["L2 error"] / fine["L2 error"])
                         / math.log(fine["N"] / coarse["N"]))
                bound = 0.8 * OBSERVED_ORDERS[cells][i]
                if order < bound:
                    sys.exit("%s: the L2 error of the pressure falls with "
                             "order %.2f from N = %d to %d (%.3e, %.3e), below "
                             "%.2f (0.8 times the observed %.2f)." % (
                                 cells, order, coarse["N"], fine["N"],
                                 coarse["L2 error"], fine["L2 error"], bound,
                                 OBSERVED_ORDERS[cells][i]))
        # F(d) on a large block.
        with tempfile.TemporaryDirectory() as folder:
            output, _ = run(arguments.executable, LARGE_BLOCK["N"],
                            "hexahedron", 1, folder,
                            length=LARGE_BLOCK["length"])
            large = analyse(output)
        print("Block of edge %g (hexahedra, N = %d): F(d) error %.2e." % (
            LARGE_BLOCK["length"], LARGE_BLOCK["N"], large["F error"]))
        if large["F error"] > 1.5 * LARGE_BLOCK["F"]:
            sys.exit("On the block of edge %g, F(d) is %.2e off Hertz, above "
                     "%.2e (1.5 times the observed %.2e)." % (
                         LARGE_BLOCK["length"], large["F error"],
                         1.5 * LARGE_BLOCK["F"], LARGE_BLOCK["F"]))
        # Two ranks (the full space back end) against one (condensed).
        serial = run_all(arguments.executable, [8], cell_types, 1)
        parallel = run_all(arguments.executable, [8], cell_types, 2)
        for cells in cell_types:
            one, two = serial[cells][0], parallel[cells][0]
            for (d1, f1), (d2, f2) in zip(one["curve"], two["curve"]):
                if abs(f1 - f2) > 1e-6 * abs(f1):
                    sys.exit("%s, N = 8: the force at d = %g is %.10g on 1 "
                             "rank, %.10g on 2." % (cells, d1, f1, f2))
            if abs(one["p0"] - two["p0"]) > 1e-6 * one["p0"]:
                sys.exit("%s, N = 8: p0 %.10g on 1 rank, %.10g on 2."
                         % (cells, one["p0"], two["p0"]))
        print("Hertz sphere (%s): a, p0 and F(d) within 1.5 times their "
              "observed errors on N = 8, 12, 16, 24, the L2 error of the "
              "pressure falling with 0.8 times its observed orders from N = 8 "
              "to 16 to 24, F(d) within %.1f%% of Hertz on a block of edge "
              "40 a; 2 ranks agree with 1." % (
                  ", ".join(cell_types), 150 * LARGE_BLOCK["F"]))


if __name__ == "__main__":
    main()
