#!/usr/bin/python3
"""Work and precision of uniform, graded and adaptive meshes.

The 2D benchmark (parameters/default.prm) on quadrilaterals, k = 1/64 for
every run, so that the time discretisation is the same everywhere and only
the mesh differs:

* uniform meshes with Subdivisions = 8, 16, 32, 64, 128;
* graded meshes (Contact refinement levels = 2): Subdivisions = 4, ..., 64;
* adaptive meshes (subsection Mesh adaptation) from the uniform mesh with
  Subdivisions = 16, adapted every 4 steps and every step (fractions 0.3 and
  0.03), with Maximum cells = 1000, ..., 8000; and from Subdivisions = 8
  (every 4 steps, fractions 0.3/0.03 and 0.15/0.1, 2000 cells);
* the same adaptive runs from Subdivisions = 16 with Initial cycles = 4,
  Initial refinement = adaptive: the mesh is adapted four times on step 1
  before the step is recorded (kind "adaptive+cycles", 2D only);
* the reference: a uniform mesh with Subdivisions = 256 (--reference).

With --dimension 3, the cube of parameters/cube_3d.prm (hexahedra, the full
space back end, its own k = 1/32): uniform Subdivisions = 4, 8, 16; graded
(Contact refinement levels = 1) 4, 8; adaptive from Subdivisions = 8, every
2 steps and every step, Maximum cells = 1000, 2000, 4000; the reference
Subdivisions = 32 (about 5 minutes). u_nu is not compared in 3D.

Errors against the reference, all quantities the program writes:
* u_nu: the relative L2(Gamma_3) error of the normal displacement at t = 1
  (the contact profile; the reference profile interpolated linearly in x,
  the nodal weights of the run);
* force history: max over the steps of |F_h(t_n) - F(t_n)| / F(1), with the
  total contact force F of time_series.csv;
* strain norm: the relative error of ||eps(u)||_L2 at t = 1 (run summary), a
  quantity of the whole body.
Work: the whole process's wall time (start-up included) and the dofs (for
adaptive runs, the mean over the steps of the dofs each step was computed
with, and the final count).

Writes <output-dir>/work_precision_mesh{,_3d}.{csv,md,png}.

    benchmarks/run_adaptive_meshes.py [--executable build/viscoplastic_contact]
                                      [--output-dir doc/adaptivity]
                                      [--reference N] [--dimension 2|3]
"""

import argparse
import csv
import math
import os
import re
import sys

import numpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "scripts"))
from vc_scripts import (REPO_ROOT, resolve_executable,  # noqa: E402
                        run_in_temporary_directory, set_prm_entries)
# parameters/cube_3d.prm with its own k = 1/32.
SCENES = {2: ("default.prm", 1.0 / 64), 3: ("cube_3d.prm", 1.0 / 32)}


def run(executable, subdivisions, levels=0, adaptive=None, dimension=2):
    """One run; adaptive = (refine fraction, coarsen fraction, max cells,
    refinement interval[, initial cycles])."""
    scene, time_step = SCENES[dimension]
    with open(os.path.join(REPO_ROOT, "parameters", scene)) as f:
        text = f.read()
    entries = {
        (("Geometry",), "Subdivisions"): str(subdivisions),
        (("Geometry",), "Cell type"): "hypercube",
        (("Geometry",), "Contact refinement levels"): str(levels),
        (("Time",), "Time step"): repr(time_step),
        (("Output",), "Output directory"): "results",
        (("Output",), "Write vtu"): "false",
        (("Output",), "Profile times"): "1",
        (("Output",), "Verbose"): "true",
        (("Output",), "Print timing summary"): "false",
    }
    if dimension == 3:
        # One rank: the full space back end with AMG (auto chooses it above
        # 1500 contact nodes anyway), so that all runs use the same solver.
        entries[(("Linear solver",), "Method")] = "full space"
    if adaptive:
        entries.update({
            (("Mesh adaptation",), "Adaptive refinement"): "true",
            (("Mesh adaptation",), "Refinement interval"): str(adaptive[3]),
            (("Mesh adaptation",), "Refine fraction"): repr(adaptive[0]),
            (("Mesh adaptation",), "Coarsen fraction"): repr(adaptive[1]),
            (("Mesh adaptation",), "Maximum cells"): str(adaptive[2]),
            (("Mesh adaptation",), "Maximum refinement level"): "8",
        })
    cycles = adaptive[4] if adaptive and len(adaptive) > 4 else 0
    if cycles:
        entries.update({
            (("Mesh adaptation",), "Initial cycles"): str(cycles),
            (("Mesh adaptation",), "Initial refinement"): "adaptive",
        })
    text = set_prm_entries(text, entries)
    with run_in_temporary_directory(executable, text) as (workdir, out, wall):
        dofs = int(re.search(r"^Mesh: \d+ \S+ cells, (\d+) displacement dofs",
                             out, re.M).group(1))
        # The dofs of each step: the initial count until the first
        # adaptation, then the count after each.
        step_dofs, current = [], dofs
        for line in out.splitlines():
            m = re.match(r"Mesh adapted at .* -> (\d+) dofs", line)
            if m:
                current = int(m.group(1))
            # The initial cycles refine before step 1: its mesh is that of
            # the summary of the last cycle's refinement.
            m = re.match(r"Initial cycles done: (\d+) cells, (\d+) dofs", line)
            if m:
                current = int(m.group(2))
            elif re.match(r"Step +\d+ ", line):
                step_dofs.append(current)
        cells = [re.search(r"^Mesh: (\d+) ", out, re.M).group(1)]
        # With initial cycles the first mesh printed is their coarsest; the
        # run's own mesh is the one they end on.
        cycled = re.search(r"^Initial cycles done: (\d+) cells, (\d+) dofs",
                           out, re.M)
        if cycled:
            cells[0], dofs = cycled.group(1), int(cycled.group(2))
        cells += re.findall(r"-> (\d+) cells", out)
        strain = float(re.search(r"\|\|eps\(u\)\|\|_L2 = ([0-9.eE+-]+)", out).group(1))
        results = os.path.join(workdir, "results")
        profile = [f for f in os.listdir(results) if f.startswith("contact_profile_")]
        with open(os.path.join(results, sorted(profile)[-1])) as f:
            nodes = sorted(csv.DictReader(f),
                           key=lambda r: (float(r["x"]), float(r.get("y", 0))))
        with open(os.path.join(results, "time_series.csv")) as f:
            series = list(csv.DictReader(f))
    kind = "adaptive+cycles" if cycles else "adaptive"
    return {"kind": kind if adaptive else ("graded" if levels else "uniform"),
            "subdivisions": subdivisions, "levels": levels,
            "fractions": "%g/%g" % adaptive[:2] if adaptive else "",
            "interval": adaptive[3] if adaptive else "",
            "max_cells": adaptive[2] if adaptive else "",
            "dofs": dofs, "final_dofs": step_dofs[-1],
            "mean_dofs": sum(step_dofs) / len(step_dofs),
            "final_cells": int(cells[-1]),
            "wall_time": wall, "strain_norm": strain,
            "force": [float(r["total_contact_force"]) for r in series],
            "x": [float(r["x"]) for r in nodes],
            "u_nu": [float(r["u_nu"]) for r in nodes],
            "weight": [float(r["weight"]) for r in nodes]}


def errors(r, reference, dimension):
    r["error_force"] = max(abs(a - b) for a, b in zip(r["force"], reference["force"])) \
        / reference["force"][-1]
    r["error_strain"] = abs(r["strain_norm"] - reference["strain_norm"]) \
        / reference["strain_norm"]
    # u_nu along the contact edge needs a 1D profile: 2D only.
    if dimension != 2:
        r["error_u_nu"] = float("nan")
        return
    num = den = 0.0
    for x, value, w in zip(r["x"], r["u_nu"], r["weight"]):
        exact = numpy.interp(x, reference["x"], reference["u_nu"])
        num += w * (value - exact) ** 2
        den += w * exact ** 2
    r["error_u_nu"] = math.sqrt(num / den)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--executable")
    parser.add_argument("--output-dir",
                        default=os.path.join(REPO_ROOT, "doc", "adaptivity"))
    parser.add_argument("--reference", type=int)
    parser.add_argument("--dimension", type=int, default=2, choices=(2, 3))
    args = parser.parse_args()
    executable = resolve_executable(args.executable)
    d = args.dimension
    if args.reference is None:
        args.reference = 256 if d == 2 else 32

    print("reference: uniform, Subdivisions = %d ..." % args.reference, flush=True)
    reference = run(executable, args.reference, dimension=d)
    if d == 2:
        runs = [run(executable, n) for n in (8, 16, 32, 64, 128)]
        runs += [run(executable, n, levels=2) for n in (4, 8, 16, 32, 64)]
        for interval in (4, 1):
            for max_cells in (1000, 2000, 4000, 8000):
                runs.append(run(executable, 16,
                                adaptive=(0.3, 0.03, max_cells, interval)))
        for fractions in ((0.3, 0.03), (0.15, 0.1)):
            runs.append(run(executable, 8, adaptive=fractions + (2000, 4)))
        for interval in (4, 1):
            for max_cells in (1000, 2000, 4000, 8000):
                runs.append(run(executable, 16,
                                adaptive=(0.3, 0.03, max_cells, interval, 4)))
    else:
        runs = [run(executable, n, dimension=3) for n in (4, 8, 16)]
        runs += [run(executable, n, levels=1, dimension=3) for n in (4, 8)]
        for interval in (2, 1):
            for max_cells in (1000, 2000, 4000):
                runs.append(run(executable, 8, dimension=3,
                                adaptive=(0.3, 0.03, max_cells, interval)))
    suffix = "" if d == 2 else "_3d"
    for r in runs:
        errors(r, reference, d)
        print("%-8s n = %3d %-9s %5s: %6d dofs (mean %8.1f), %.2f s, errors u_nu "
              "%.3e force %.3e strain %.3e"
              % (r["kind"], r["subdivisions"], r["fractions"], r["max_cells"],
                 r["final_dofs"], r["mean_dofs"], r["wall_time"], r["error_u_nu"],
                 r["error_force"], r["error_strain"]), flush=True)

    os.makedirs(args.output_dir, exist_ok=True)
    keys = ["kind", "subdivisions", "levels", "fractions", "interval", "max_cells",
            "final_cells", "final_dofs", "mean_dofs", "wall_time",
            "error_u_nu", "error_force", "error_strain"]
    with open(os.path.join(args.output_dir, "work_precision_mesh%s.csv" % suffix), "w",
              newline="") as f:
        writer = csv.writer(f)
        writer.writerow(keys)
        for r in runs:
            writer.writerow([r[k] for k in keys])
    scene = ("The 2D benchmark on quadrilaterals, k = 1/64 in every run"
             if d == 2 else
             "The 3D cube (parameters/cube_3d.prm) on hexahedra, full space back "
             "end, k = 1/32 in every run")
    graded = "Contact refinement levels = %d" % (2 if d == 2 else 1)
    lines = ["# Work and precision: uniform, graded and adaptive meshes (%dD)" % d, "",
             "Generated by `benchmarks/run_adaptive_meshes.py%s`. %s; errors against "
             "a uniform mesh with Subdivisions = %d (%d dofs, the same k, %.1f s): "
             "u_nu = relative L2(Gamma_3) error of the normal displacement at t = 1 "
             "(2D only); force = max over the steps of the error of the total "
             "contact force, relative to F(1); strain = relative error of "
             "||eps(u)||_L2 at t = 1. Graded: %s. Adaptive: from the uniform mesh "
             "of the Subdivisions listed, adapted every *interval* steps with the "
             "Refine/Coarsen fractions and Maximum cells listed (Maximum "
             "refinement level 8); adaptive+cycles: the same, with Initial "
             "cycles = 4, Initial refinement = adaptive (step 1 solved on four "
             "meshes adapted by the indicator before it is recorded). dofs: "
             "final (mean over the steps). Wall time: "
             "the whole process, one rank, on a shared machine (+-20 %%)."
             % ("" if d == 2 else " --dimension 3", scene, args.reference,
                reference["dofs"], reference["wall_time"], graded), "",
             "| mesh | Subdivisions | fractions | interval | Maximum cells | final cells | "
             "dofs (mean) | wall time [s] | error u_nu | error force | error strain |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in runs:
        lines.append("| %s | %d | %s | %s | %s | %d | %d (%.0f) | %.2f | %.3e | %.3e | %.3e |" % (
            r["kind"], r["subdivisions"], r["fractions"], r["interval"], r["max_cells"],
            r["final_cells"], r["final_dofs"], r["mean_dofs"], r["wall_time"],
            r["error_u_nu"], r["error_force"], r["error_strain"]))
    with open(os.path.join(args.output_dir, "work_precision_mesh%s.md" % suffix), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 3, figsize=(15, 8.4))
    fig.suptitle("%dD: %s" % (d, scene))
    start = 16 if d == 2 else 8
    groups = [("uniform", lambda r: True, "o", "uniform"),
              ("graded", lambda r: True, "s", "graded (%s)" % graded),
              ("adaptive", lambda r: r["subdivisions"] == start and r["interval"] > 1,
               "^", "adaptive from 1/%d, every %d steps" % (start, 4 if d == 2 else 2)),
              ("adaptive", lambda r: r["subdivisions"] == start and r["interval"] == 1,
               "v", "adaptive from 1/%d, every step" % start)]
    if d == 2:
        groups.append(("adaptive", lambda r: r["subdivisions"] == 8, "x",
                       "adaptive from 1/8 (0.3/0.03, 0.15/0.1)"))
        groups.append(("adaptive+cycles", lambda r: r["interval"] > 1, "<",
                       "adaptive from 1/16 + 4 initial cycles, every 4 steps"))
        groups.append(("adaptive+cycles", lambda r: r["interval"] == 1, ">",
                       "adaptive from 1/16 + 4 initial cycles, every step"))
    for row, (work, work_label) in enumerate((("mean_dofs", "dofs (mean over the steps)"),
                                              ("wall_time", "wall time [s], whole process"))):
        for ax, key, title in zip(axes[row], ["error_u_nu", "error_force", "error_strain"],
                                  ["u_nu on Gamma_3 at t = 1 (rel. L2%s)"
                                   % ("" if d == 2 else "; 2D only"),
                                   "total contact force, max over t (rel.)",
                                   "||eps(u)||_L2 at t = 1 (rel.)"]):
            for kind, select, marker, label in groups:
                sel = [r for r in runs if r["kind"] == kind and select(r)]
                ax.loglog([r[work] for r in sel], [r[key] for r in sel],
                          marker=marker, label=label)
            ax.set_xlabel(work_label)
            ax.set_title(title)
            ax.grid(True, which="both", alpha=0.3)
        axes[row][0].set_ylabel("error against Subdivisions = %d" % args.reference)
    axes[0][0].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.output_dir, "work_precision_mesh%s.png" % suffix), dpi=100)


if __name__ == "__main__":
    main()
