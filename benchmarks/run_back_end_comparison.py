#!/usr/bin/env python3
"""Compare the two back ends of the program on the same scenes.

For each scene and size, the scene is run once with Method = condensed and
once with Method = full space (one MPI rank, one run at a time), and the
script records from the program's own output: the dofs and contact nodes,
the set-up time of the back end for K, the average time step, the active-set
and Krylov iterations, and the total wall time of the run. It writes

  doc/back_ends/back_ends.csv   every measurement,
  doc/back_ends/back_ends.md    the table, with the ratio full space /
                                condensed of the total run time,

which is where the limits of Method = auto (source/back_ends/contact_solver.cc) come
from. Both methods of a row run back to back in the same invocation, so
their ratio is meaningful even on a shared machine; the absolute times are
not. The scenes:

  * benchmark: parameters/default.prm (2D triangles, "/" pattern), k = 1/64,
    Subdivisions from --subdivisions-2d;
  * cube hexahedra / cube tetrahedra: parameters/cube_3d.prm with Cell
    type = hypercube / simplex, k = 1/32, Subdivisions from
    --subdivisions-3d.

Every run takes --steps steps from t = 0 (the first steps, where the
contact zone forms, are the most expensive ones).

Usage: benchmarks/run_back_end_comparison.py [--executable PATH]
           [--steps 8] [--subdivisions-2d 32,64,128,256]
           [--subdivisions-3d 8,16,24,32] [--output doc/back_ends]
"""

import argparse
import csv
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import REPO_ROOT, resolve_executable, set_prm_entries  # noqa: E402

METHODS = ["condensed", "full space"]


def scene_prm(scene, subdivisions, method, steps, directory):
    if scene == "benchmark":
        base, k, cell = "default.prm", 1. / 64, "simplex"
    else:
        base, k = "cube_3d.prm", 1. / 32
        cell = "hypercube" if scene == "cube hexahedra" else "simplex"
    with open(os.path.join(REPO_ROOT, "parameters", base)) as f:
        text = f.read()
    return set_prm_entries(text, {
        (("Geometry",), "Subdivisions"): str(subdivisions),
        (("Geometry",), "Cell type"): cell,
        (("Time",), "Time step"): repr(k),
        (("Time",), "End time"): repr(steps * k),
        (("Linear solver",), "Method"): method,
        (("Output",), "Output directory"): directory,
        (("Output",), "Overwrite"): "true",
        (("Output",), "Write vtu"): "false",
        (("Output",), "Profile times"): "",
        (("Output",), "Verbose"): "false",
        (("Output",), "Print timing summary"): "true",
        (("Output",), "Measure cost ratios"): "true",
    })


def number(pattern, text, default=float("nan")):
    match = re.search(pattern, text)
    return float(match.group(1)) if match else default


def mesh_of_run(out):
    """Dofs and contact nodes of the run's mesh: with initial cycles the
    "Mesh:" line is the coarsest mesh's, and the run's comes after them."""
    match = (re.search(r"Initial cycles done: \d+ cells, (\d+) dofs, (\d+) "
                       r"contact nodes", out)
             or re.search(r"Mesh: \d+ \w+ cells, (\d+) displacement dofs, "
                          r"(\d+) contact nodes", out))
    if match is None:
        sys.exit("error: the program printed no mesh line; its output "
                 "format has changed")
    return int(match.group(1)), int(match.group(2))


def run(executable, scene, subdivisions, method, steps, work):
    name = f"{scene.replace(' ', '_')}_{subdivisions}_{method.replace(' ', '_')}"
    directory = os.path.join(work, name)
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as f:
        f.write(scene_prm(scene, subdivisions, method, steps, directory))
    start = time.time()
    proc = subprocess.run([executable, prm], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    wall = time.time() - start
    out = proc.stdout
    if proc.returncode != 0:
        print(out[-2000:])
        sys.exit(f"error: {name} failed")
    krylov = 0
    iterations = 0
    with open(os.path.join(directory, "time_series.csv")) as f:
        for row in csv.DictReader(f):
            krylov += int(row["krylov_iterations"])
            iterations += int(row["active_set_iterations"])
    dofs, contact_nodes = mesh_of_run(out)
    return {
        "scene": scene, "subdivisions": subdivisions, "method": method,
        "dofs": dofs,
        "contact_nodes": contact_nodes,
        "steps": steps,
        "setup_back_end_s": number(r"Setup: back end for K\s*\|\s*\d+\s*\|\s*([0-9.e+-]+)s", out),
        "step_ms": number(r"average time step \(without output\): ([0-9.e+-]+) ms", out),
        "active_set_per_step": iterations / steps,
        "krylov_per_step": krylov / steps,
        "total_s": wall,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--executable")
    parser.add_argument("--steps", type=int, default=8)
    parser.add_argument("--subdivisions-2d", default="32,64,128,256")
    parser.add_argument("--subdivisions-3d", default="8,16,24,32")
    parser.add_argument("--output", default=os.path.join(REPO_ROOT, "doc", "back_ends"))
    args = parser.parse_args()
    executable = resolve_executable(args.executable)
    work = os.path.join(REPO_ROOT, "output", "back_end_comparison")
    os.makedirs(work, exist_ok=True)
    os.makedirs(args.output, exist_ok=True)

    cases = [("benchmark", int(n)) for n in args.subdivisions_2d.split(",") if n]
    for scene in ["cube hexahedra", "cube tetrahedra"]:
        cases += [(scene, int(n)) for n in args.subdivisions_3d.split(",") if n]
    rows = []
    for scene, n in cases:
        for method in METHODS:
            row = run(executable, scene, n, method, args.steps, work)
            print(f"{scene:16s} N = {n:4d} {method:10s} {row['dofs']:8d} dofs "
                  f"{row['total_s']:8.2f} s total, {row['step_ms']:9.1f} ms per step",
                  flush=True)
            rows.append(row)

    with open(os.path.join(args.output, "back_ends.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)

    lines = ["# The two back ends on the same scenes", "",
             "Written by `benchmarks/run_back_end_comparison.py " +
             f"--steps {args.steps} --subdivisions-2d {args.subdivisions_2d} "
             f"--subdivisions-3d {args.subdivisions_3d}` (one MPI rank, "
             "Release build, one run at a time, both methods of a row back "
             "to back). Each run takes the first "
             f"{args.steps} steps from t = 0, where the contact zone forms, "
             "with the scene's other defaults: where `Initial cycles = auto` "
             "takes coarser meshes (the full space back end), the first step "
             "is solved on them first; the dofs, contact nodes and iterations "
             "are those of the run's mesh. "
             "Times are wall times on a shared 2-core machine: compare the "
             "ratios within a row, not absolute times across invocations.", "",
             "| scene | N | dofs | contact nodes | method | set-up of the back end [s] "
             "| time step [ms] | active-set it./step | Krylov it./step | total run [s] "
             "| full space / condensed (total) |",
             "| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for i in range(0, len(rows), 2):
        condensed, full = rows[i], rows[i + 1]
        ratio = full["total_s"] / condensed["total_s"]
        for row, r in [(condensed, ""), (full, f"{ratio:.2f}")]:
            lines.append(
                f"| {row['scene']} | {row['subdivisions']} | {row['dofs']} | "
                f"{row['contact_nodes']} | {row['method']} | {row['setup_back_end_s']:.3g} | "
                f"{row['step_ms']:.4g} | {row['active_set_per_step']:.2f} | "
                f"{row['krylov_per_step']:.1f} | {row['total_s']:.3g} | {r} |")
    lines += ["", "The total includes mesh, set-up (with the uniqueness check, "
              "which costs one Krylov solve per Lanczos iteration on the full "
              "space back end and a dense product on the condensed one) and the "
              "final cost measurement of the run summary.", ""]
    with open(os.path.join(args.output, "back_ends.md"), "w") as f:
        f.write("\n".join(lines))
    print("wrote", os.path.join(args.output, "back_ends.md"))


if __name__ == "__main__":
    main()
