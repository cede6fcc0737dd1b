#!/usr/bin/python3
"""Cost benchmark of the full space back end on the 3D scene (issue 4).

Runs parameters/cube_3d.prm (hexahedra, p4est) and
parameters/cube_3d_tetrahedra.prm (tetrahedra with the parameter file's
Simplex pattern, fully distributed mesh) at increasing resolution, each on 1
and on 2 MPI ranks, one run at a time, with file output off, Linear solver /
Method = full space (option --method, whatever the parameter files say), and a
fixed number of time steps (default 4 steps of
k = 1/32: the cost per step does not depend on how many steps follow). Per
run it records what the program prints:

* cells, displacement dofs, contact nodes, time steps (the "Mesh:" line);
* active-set iterations per step and Krylov iterations per solve (the run
  summary: "active-set iterations: A in S steps", "back end: N solves, K
  Krylov iterations");
* from the "Cost measurement" block: the average time step, the time of one
  solve with the step operator and no contact (CG with the run's
  preconditioner, timed in the same run after the time loop), the ratio
  step / solve (the figure of merit), one stress update with the history load
  and the ratio step / (solve + stress update), the time per dof and step,
  and the peak memory (VmHWM summed over the ranks);
* every section of the TimerOutput table (wall time, maximum over ranks);

and per resolution the speed-up of 2 ranks over 1 (time per step on one
rank / on two, measured in the same invocation of this script).

Writes <output-dir>/cube_benchmark.csv, cube_benchmark.md and
cube_benchmark.png (time per step and its phases against dofs).

    benchmarks/run_cube_benchmark.py [--executable build/viscoplastic_contact]
        [--subdivisions 8,16,32,48,64,72] [--cell-types hypercube,simplex]
        [--tet-subdivisions 8,16,32,48] [--steps 4] [--method "full space"]
        [--output-dir doc/benchmark_3d]

Subdivisions n gives 3 (n+1)^3 dofs on both cell types (n = 72: 1.20e6).
Build in Release mode. Runs as root need no flag: the script sets Open MPI's
OMPI_ALLOW_RUN_AS_ROOT variables.
"""

import argparse
import csv
import datetime
import os
import platform
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "scripts"))
from vc_scripts import REPO_ROOT, resolve_executable, set_prm_entries  # noqa

SCENES = {"hypercube": "parameters/cube_3d.prm",
          "simplex": "parameters/cube_3d_tetrahedra.prm"}
TIME_STEP = 1.0 / 32


def parse_output(text):
    """The numbers the program prints, as a dict (raises if one is missing)."""
    number = r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
    # Times of the Cost measurement block are printed in ms; converted to s.
    patterns = {
        "cells": (r"^Mesh: (\d+) ", 1),
        "dofs": (r" cells, (\d+) displacement dofs", 1),
        "contact_nodes": (r"dofs, (\d+) contact nodes", 1),
        "steps": (r"contact nodes, (\d+) time steps", 1),
        "active_set_iterations": (r"^\s*active-set iterations: (\d+) in \d+ steps", 1),
        "summary_steps": (r"^\s*active-set iterations: \d+ in (\d+) steps", 1),
        "solves": (r"^\s*back end: (\d+) solves, \d+ Krylov iterations", 1),
        "krylov_iterations": (r"^\s*back end: \d+ solves, (\d+) Krylov iterations", 1),
        "time_per_step": (r"average time step \(without output\): " + number + " ms", 1e-3),
        "elastic_solve": (r"one solve with the step operator, no contact: "
                          + number + " ms", 1e-3),
        "solve_krylov_iterations": (r"one solve with the step operator, no contact: "
                                    r".*\((\d+) Krylov iterations\)", 1),
        "stress_update": (r"one stress update with the history load: " + number + " ms",
                          1e-3),
        "figure_of_merit": (r"ratio step / solve: " + number, 1),
        "ratio_step_to_solve_and_update": (r"ratio step / \(solve \+ stress update\): "
                                           + number, 1),
        "us_per_dof_step": (r"per dof and step: " + number + " us", 1),
        "time_loop": (r"time loop \(without output\): " + number + " s", 1),
        "peak_memory_mb": (r"peak memory over the run \[MB\]: sum over ranks " + number, 1),
        "final_l2_norm": (r"^Final displacement: l2 norm " + number, 1),
    }
    values = {}
    for key, (pattern, scale) in patterns.items():
        match = re.search(pattern, text, re.M)
        if not match:
            raise RuntimeError("could not find %s in the program output:\n%s"
                               % (key, text[-3000:]))
        values[key] = float(match.group(1)) * scale
    # With initial cycles the "Mesh:" line is the first (coarsest) mesh; the
    # run's mesh is the one of the "Initial cycles done:" line.
    match = re.search(r"^Initial cycles done: (\d+) cells, (\d+) dofs, (\d+) "
                      r"contact nodes", text, re.M)
    if match:
        values["cells"], values["dofs"], values["contact_nodes"] = (
            float(g) for g in match.groups())
    values["active_set_per_step"] = (values["active_set_iterations"]
                                     / max(1.0, values["summary_steps"]))
    values["krylov_per_solve"] = (values["krylov_iterations"]
                                  / max(1.0, values["solves"]))
    match = re.search(r"^Back end: ([^:\n]+)", text, re.M)
    values["back_end"] = match.group(1).strip() if match else ""
    sections = {}
    for match in re.finditer(r"^\| ([A-Za-z][^|]*?)\s+\|\s+(\d+) \|\s+([\d.e+-]+)s \|",
                             text, re.M):
        sections[match.group(1).strip()] = float(match.group(3))
    values["sections"] = sections
    return values


def make_prm(cell_type, subdivisions, steps, method="full space"):
    with open(os.path.join(REPO_ROOT, SCENES[cell_type])) as f:
        text = f.read()
    return set_prm_entries(text, {
        (("Geometry",), "Subdivisions"): str(subdivisions),
        (("Time",), "End time"): repr(steps * TIME_STEP),
        (("Time",), "Time step"): repr(TIME_STEP),
        (("Output",), "Output directory"): "results",
        (("Output",), "Write vtu"): "false",
        (("Output",), "Verbose"): "false",
        (("Output",), "Print timing summary"): "true",
        (("Output",), "Measure cost ratios"): "true",
        (("Output",), "Profile times"): "",
        (("Linear solver",), "Method"): method,
    })


def run_case(executable, cell_type, subdivisions, ranks, steps, method="full space"):
    with tempfile.TemporaryDirectory() as workdir:
        prm = os.path.join(workdir, "cube.prm")
        with open(prm, "w") as f:
            f.write(make_prm(cell_type, subdivisions, steps, method))
        command = [executable, prm]
        if ranks > 1:
            command = ["mpirun", "-np", str(ranks), "--oversubscribe"] + command
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                   OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
        result = subprocess.run(command, cwd=workdir, env=env,
                                capture_output=True, text=True)
        if result.returncode != 0:
            raise RuntimeError("run failed (%s, n = %d, %d ranks):\n%s%s"
                               % (cell_type, subdivisions, ranks,
                                  result.stdout[-2000:], result.stderr[-2000:]))
        return parse_output(result.stdout)


PHASES = ["Solve: contact problem", "Stress update", "Assemble right-hand side"]


def write_outputs(rows, output_dir, command_line, method="full space"):
    os.makedirs(output_dir, exist_ok=True)
    columns = ["cell_type", "subdivisions", "ranks", "cells", "dofs",
               "contact_nodes", "steps", "back_end", "active_set_per_step",
               "krylov_per_solve", "elastic_solve", "solve_krylov_iterations",
               "time_per_step", "figure_of_merit", "stress_update",
               "ratio_step_to_solve_and_update", "us_per_dof_step",
               "time_loop", "peak_memory_mb", "speedup_2_over_1",
               "final_l2_norm"] + ["section: " + p for p in
                                   ["Setup: mesh", "Setup: dofs and constraints",
                                    "Setup: assemble elastic operator",
                                    "Setup: back end for K",
                                    "Setup: contact nodes",
                                    "Setup: uniqueness margin"] + PHASES]
    with open(os.path.join(output_dir, "cube_benchmark.csv"), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(columns)
        for row in rows:
            writer.writerow([row.get(c, row["sections"].get(c[9:], "")
                                     if c.startswith("section: ") else "")
                             for c in columns])

    lines = ["# 3D benchmark: the %s back end on the cube scene" % method, "",
             "Generated by `benchmarks/run_cube_benchmark.py` on %s (%s, %d cores); "
             "command: `%s`." % (datetime.date.today(), platform.node(),
                                 os.cpu_count(), command_line), "",
             "Scene: `parameters/cube_3d.prm` (hexahedra, p4est) and "
             "`parameters/cube_3d_tetrahedra.prm` (tetrahedra with that file's "
             "Simplex pattern, fully distributed mesh), Method = %s, "
             "k = 1/32, %d time steps per run, no file output. One run at a "
             "time; all ratios come from this one invocation."
             % (method, rows[0]["steps"]),
             "",
             "* *solve*: one solve with the step operator and no contact (CG "
             "with the run's preconditioner on the full space back end, the "
             "factorisation on the condensed one), timed by the program in the "
             "same run after the time loop (its \"Cost measurement\" block).",
             "* *back end*: the one the run used (its \"Back end:\" line; in "
             "cube_benchmark.csv).",
             "* *figure of merit*: time per step / one solve (the program's "
             "\"ratio step / solve\").",
             "* *speed-up*: time per step on 1 rank / on 2 ranks.",
             "* *peak memory*: VmHWM summed over the ranks; *bytes per dof*: "
             "that sum over the displacement dofs.",
             "* *phases*: wall time per step of each TimerOutput section "
             "(maximum over ranks).", "",
             "| cells | type | dofs | ranks | active-set it./step | Krylov it./solve | "
             "solve [s] | time/step [s] | figure of merit | us per dof and step "
             "| contact problem /step [s] | stress update /step [s] | "
             "peak memory [MB] | bytes per dof | speed-up 2/1 |",
             "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for row in rows:
        steps = row["steps"]
        lines.append("| %d | %s | %d | %d | %.2f | %.1f | %.3g | %.3g | %.2f | %.3g | "
                     "%.3g | %.3g | %.0f | %.0f | %s |" % (
                         row["cells"], "hex" if row["cell_type"] == "hypercube" else "tet",
                         row["dofs"], row["ranks"], row["active_set_per_step"],
                         row["krylov_per_solve"], row["elastic_solve"],
                         row["time_per_step"], row["figure_of_merit"],
                         row["us_per_dof_step"],
                         row["sections"].get(PHASES[0], 0) / steps,
                         row["sections"].get(PHASES[1], 0) / steps,
                         row["peak_memory_mb"],
                         row["peak_memory_mb"] * 2**20 / row["dofs"],
                         ("%.2f" % row["speedup_2_over_1"])
                         if "speedup_2_over_1" in row else ""))
    with open(os.path.join(output_dir, "cube_benchmark.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no chart")
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for cell_type, marker in (("hypercube", "o"), ("simplex", "s")):
        for ranks, style in ((1, "-"), (2, "--")):
            sel = [r for r in rows if r["cell_type"] == cell_type and r["ranks"] == ranks]
            if not sel:
                continue
            label = "%s, %d rank%s" % ("hex" if cell_type == "hypercube" else "tet",
                                       ranks, "s" if ranks > 1 else "")
            axes[0].loglog([r["dofs"] for r in sel], [r["time_per_step"] for r in sel],
                           marker=marker, linestyle=style, label=label)
            axes[1].semilogx([r["dofs"] for r in sel], [r["figure_of_merit"] for r in sel],
                             marker=marker, linestyle=style, label=label)
    dofs = sorted({r["dofs"] for r in rows})
    scale = min(r["time_per_step"] for r in rows if r["dofs"] == dofs[0])
    axes[0].loglog(dofs, [scale * d / dofs[0] for d in dofs], "k:", label="O(dofs)")
    axes[0].set_xlabel("displacement dofs")
    axes[0].set_ylabel("wall time per step [s]")
    axes[0].legend()
    axes[0].grid(True, which="both", alpha=0.3)
    axes[1].set_xlabel("displacement dofs")
    axes[1].set_ylabel("time per step / one solve")
    axes[1].grid(True, which="both", alpha=0.3)
    axes[1].legend()
    fig.suptitle("3D cube scene, Method = %s (ML AMG), %d steps of k = 1/32"
                 % (method, rows[0]["steps"]))
    fig.tight_layout()
    fig.savefig(os.path.join(output_dir, "cube_benchmark.png"), dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--executable")
    parser.add_argument("--subdivisions", default="8,16,32,48,64,72",
                        help="for every cell type; --tet-subdivisions overrides it for tetrahedra")
    parser.add_argument("--tet-subdivisions", default=None)
    parser.add_argument("--cell-types", default="hypercube,simplex")
    parser.add_argument("--ranks", default="1,2")
    parser.add_argument("--steps", type=int, default=4)
    parser.add_argument("--method", default="full space",
                        help="Linear solver / Method of every run (default: "
                             "%(default)s, whatever the parameter files say)")
    parser.add_argument("--output-dir", default=os.path.join(REPO_ROOT, "doc", "benchmark_3d"))
    args = parser.parse_args()
    executable = resolve_executable(args.executable)
    rows = []
    for cell_type in args.cell_types.split(","):
        sizes = args.subdivisions
        if cell_type == "simplex" and args.tet_subdivisions:
            sizes = args.tet_subdivisions
        for n in [int(v) for v in sizes.split(",")]:
            by_ranks = {}
            for ranks in [int(v) for v in args.ranks.split(",")]:
                print("running %s n = %d on %d rank(s) ..." % (cell_type, n, ranks),
                      flush=True)
                row = run_case(executable, cell_type, n, ranks, args.steps,
                               args.method)
                row.update(cell_type=cell_type, subdivisions=n, ranks=ranks)
                by_ranks[ranks] = row
                rows.append(row)
            if 1 in by_ranks and 2 in by_ranks:
                by_ranks[2]["speedup_2_over_1"] = (by_ranks[1]["time_per_step"]
                                                   / by_ranks[2]["time_per_step"])
            # Written after every resolution, so that an interrupted
            # benchmark keeps what it measured.
            write_outputs(rows, args.output_dir, " ".join(sys.argv), args.method)


if __name__ == "__main__":
    main()
