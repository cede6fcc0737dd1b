#!/usr/bin/python3
"""Cold starts with and without nested iteration (Initial cycles).

The 2D static scene of doc/performance.md: parameters/elastic.prm with one
step of k = 1/64 from rest, on quadrilaterals (Cell type = hypercube), at
N = 128, 256, 512 cells per edge (Subdivisions = 32, Global refinements =
log2(N/32)), on both back ends (condensed, full space), without initial
cycles (the cold start) and with Initial cycles = L, Initial refinement =
global, for L = 1 ... log2(N/32): step 1 is solved on N/2^L first, then on
each finer mesh from the previous solution, the last on N.

Per run: the active-set iterations of step 1 on the finest mesh, those of
each cycle and their total, the Krylov iterations of step 1 on the finest
mesh (full space), the time of step 1 (the time series' wall time: the
cycles, their set-ups and the last solve) and of the whole process.

Writes <output-dir>/cold_start.{csv,md,png}; with --from-csv only the
table and the figure, from the csv of an earlier invocation.

    benchmarks/run_cold_start.py [--executable build/viscoplastic_contact]
                                 [--output-dir doc/performance]
                                 [--sizes 128,256,512] [--from-csv]
                                 [--methods condensed,full space]
"""

import argparse
import csv
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "scripts"))
from vc_scripts import (REPO_ROOT, resolve_executable,  # noqa: E402
                        run_in_temporary_directory, set_prm_entries)
COARSEST = 32  # cells per edge of the first mesh of the longest nested iteration


def run(executable, n, method, cycles):
    with open(os.path.join(REPO_ROOT, "parameters", "elastic.prm")) as f:
        text = f.read()
    refinements = int(round(math.log2(n / COARSEST)))
    entries = {
        (("Geometry",), "Subdivisions"): str(COARSEST),
        (("Geometry",), "Global refinements"): str(refinements),
        (("Geometry",), "Cell type"): "hypercube",
        (("Time",), "End time"): "0.015625",
        (("Time",), "Time step"): "0.015625",
        (("Linear solver",), "Method"): method,
        (("Mesh adaptation",), "Initial cycles"): str(cycles),
        (("Mesh adaptation",), "Initial refinement"): "global",
        # The step on the finest mesh from rest: Step cycles = auto would
        # solve it on a coarser mesh first (from 40k dofs there).
        (("Mesh adaptation",), "Step cycles"): "0",
        (("Output",), "Output directory"): "results",
        (("Output",), "Write vtu"): "false",
        (("Output",), "Profile times"): "0.015625",
        (("Output",), "Verbose"): "true",
        (("Output",), "Print timing summary"): "false",
    }
    text = set_prm_entries(text, entries)
    with run_in_temporary_directory(executable, text) as (workdir, out, wall):
        with open(os.path.join(workdir, "results", "time_series.csv")) as f:
            row = list(csv.DictReader(f))[0]
    cycle_iterations = [int(m) for m in
                        re.findall(r"^Initial cycle \d+: .*, (\d+) active-set iterations",
                                   out, re.M)]
    assert len(cycle_iterations) == cycles, out
    final = int(row["active_set_iterations"])
    force = float(row["total_contact_force"])
    # The dofs of step 1: of the mesh after the cycles (the header shows the
    # first one).
    last = re.search(r"^Initial cycles done: \d+ cells, (\d+) dofs", out, re.M)
    dofs = int(last.group(1) if last else
               re.search(r"(\d+) displacement dofs", out).group(1))
    return {"n": n, "method": method, "cycles": cycles,
            "first_mesh": n >> cycles, "dofs": dofs,
            "cycle_iterations": cycle_iterations,
            "final_iterations": final,
            "total_iterations": final + sum(cycle_iterations),
            "krylov": int(row["krylov_iterations"]),
            "step_time": float(row["wall_time"]), "wall_time": wall,
            "force": force}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--executable")
    parser.add_argument("--output-dir",
                        default=os.path.join(REPO_ROOT, "doc", "performance"))
    parser.add_argument("--sizes", default="128,256,512")
    parser.add_argument("--methods", default="condensed,full space",
                        help="the back ends to run, comma-separated")
    parser.add_argument("--from-csv", action="store_true")
    args = parser.parse_args()
    executable = resolve_executable(args.executable)
    sizes = [int(s) for s in args.sizes.split(",")]
    keys = ["method", "n", "cycles", "first_mesh", "dofs", "final_iterations",
            "total_iterations", "krylov", "step_time", "wall_time", "force"]
    csv_file = os.path.join(args.output_dir, "cold_start.csv")
    if args.from_csv:
        with open(csv_file) as f:
            runs = []
            for row in csv.DictReader(f):
                r = {k: (row[k] if k == "method" else float(row[k])) for k in keys}
                for k in ("n", "cycles", "first_mesh", "dofs", "final_iterations",
                          "total_iterations", "krylov"):
                    r[k] = int(r[k])
                r["cycle_iterations"] = [int(i) for i in row["cycle_iterations"].split()]
                runs.append(r)
        # With global cycles step 1 runs on the mesh of the cold start, whose
        # dofs every row gets (a csv of a version that printed only the first
        # mesh of the cycles is corrected so).
        for r in runs:
            r["dofs"] = next(c["dofs"] for c in runs
                             if c["n"] == r["n"] and c["cycles"] == 0)
        sizes = []

    runs = runs if args.from_csv else []
    for method in args.methods.split(",") if sizes else ():
        for n in sizes:
            for cycles in range(0, int(round(math.log2(n / COARSEST))) + 1):
                r = run(executable, n, method, cycles)
                runs.append(r)
                print("%-10s N = %3d L = %d: final %2d, cycles %s, total %2d, "
                      "krylov %4d, step %.2f s, process %.2f s, force %.10g"
                      % (method, n, cycles, r["final_iterations"],
                         r["cycle_iterations"], r["total_iterations"], r["krylov"],
                         r["step_time"], r["wall_time"], r["force"]), flush=True)

    os.makedirs(args.output_dir, exist_ok=True)
    with open(csv_file, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(keys + ["cycle_iterations"])
        for r in runs:
            writer.writerow([r[k] for k in keys]
                            + [" ".join(str(i) for i in r["cycle_iterations"])])
    lines = ["# Cold starts with and without nested iteration", "",
             "Generated by `benchmarks/run_cold_start.py`. The 2D static scene "
             "(`parameters/elastic.prm`, one step of k = 1/64 from rest) on "
             "quadrilaterals, N cells per edge (Subdivisions = %d, Global "
             "refinements = log2(N/%d)). L = 0: the cold start on N; L > 0: "
             "Initial cycles = L, Initial refinement = global, step 1 solved "
             "on N/2^L, ..., N/2 first, each solution the start of the next "
             "mesh. *final*: active-set iterations of step 1 on N; *per cycle*: "
             "those on N/2^L, ..., N/2; *total*: all of them. Krylov: CG "
             "iterations of step 1 on N (full space back end). Step 1: its "
             "wall time in the time series (cycles, their set-ups and the last "
             "solve); process: the whole process. One rank, a shared 2-core "
             "machine (+-20 %% on times). The contact force of step 1 is the "
             "same with and without cycles to the digits printed."
             % (COARSEST, COARSEST), "",
             "| back end | N | dofs | L | first mesh | final | per cycle | total | "
             "Krylov | step 1 [s] | process [s] | contact force |",
             "|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|"]
    for r in runs:
        lines.append("| %s | %d | %d | %d | %d | %d | %s | %d | %s | %.2f | %.2f | %.10g |" % (
            r["method"], r["n"], r["dofs"], r["cycles"], r["first_mesh"],
            r["final_iterations"],
            ", ".join(str(i) for i in r["cycle_iterations"]) or "-",
            r["total_iterations"],
            r["krylov"] if r["method"] == "full space" else "-",
            r["step_time"], r["wall_time"], r["force"]))
    with open(os.path.join(args.output_dir, "cold_start.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for method, marker in (("condensed", "o"), ("full space", "s")):
        cold = [r for r in runs if r["method"] == method and r["cycles"] == 0]
        nested = [max((r for r in runs if r["method"] == method and r["n"] == c["n"]),
                      key=lambda r: r["cycles"]) for c in cold]
        axes[0].plot([r["n"] for r in cold], [r["final_iterations"] for r in cold],
                     marker=marker, label="%s, cold" % method)
        axes[0].plot([r["n"] for r in nested], [r["final_iterations"] for r in nested],
                     marker=marker, linestyle="--",
                     label="%s, nested from %d" % (method, COARSEST))
        # The whole process: the step time of a run with cycles contains the
        # set-ups of the finer meshes, the cold run's does not.
        axes[1].plot([r["n"] for r in cold], [r["wall_time"] for r in cold],
                     marker=marker, label="%s, cold" % method)
        axes[1].plot([r["n"] for r in nested], [r["wall_time"] for r in nested],
                     marker=marker, linestyle="--",
                     label="%s, nested from %d" % (method, COARSEST))
    axes[0].set_ylabel("active-set iterations of step 1 on N")
    axes[1].set_ylabel("whole process [s]")
    for ax in axes:
        ax.set_xscale("log", base=2)
        ax.set_xlabel("N (cells per edge)")
        ax.grid(True, alpha=0.3)
    axes[1].set_yscale("log")
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.output_dir, "cold_start.png"), dpi=100)


if __name__ == "__main__":
    main()
