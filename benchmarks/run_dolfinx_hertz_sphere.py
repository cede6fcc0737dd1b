#!/usr/bin/python3
"""The program against an independent dolfinx implementation in 3D: the
Hertz sphere at its final indentation.

The scene is parameters/hertz_sphere.prm (a rigid sphere of radius 1
pressed by d = 0.01 into an elastic block, the quarter model [0, 1]^3 with
symmetry planes) on the graded hexahedral mesh of
meshes/make_hertz_sphere_meshes.py with N cells per edge (N = 68: 985k
dofs), solved as one static problem: one time step to t = 1. For each N in
--subdivisions and each rank count in --ranks the script runs, back to
back:
- the program with its defaults (Method = auto; no VTU, no timing summary,
  the contact profile at t = 1 written), generating the mesh itself: the
  unit box of N cubes per edge moved by the grading as its Box map
  (graded_box()), the same vertices and cells as the Gmsh file of
  meshes/make_hertz_sphere_meshes.py, with the coarser meshes that its
  initial cycles (nested iteration) start from;
- benchmarks/dolfinx_hertz_sphere.py (dolfinx 0.5, PETSc SNES
  vinewtonrsls with the obstacle as the bounds u_y <= s at the top face's
  vertices; see its docstring) once per linear solver of --solvers: "gamg"
  (CG with smoothed-aggregation AMG and the rigid-body modes, the best
  iterative set-up) and "mumps" (LU in every Newton iteration). dolfinx
  creates the same mesh in memory (a box with its vertices moved).
Both solve the same discretisation (Q1, nodal contact), so the forces
agree to the solvers' tolerances. The runs of a row are repeated --repeat
times, interleaved; the fastest run of each counts.

Per run: the whole process's wall time, the peak resident memory of the
largest rank, the vertices at the obstacle, the quarter model's contact
force sum_i z_i and the contact radius a from the nodal pressures along the
x axis (profile_measures() of benchmarks/run_hertz_sphere.py, the measure
of doc/benchmarks.md). Per row: dolfinx time / program time, memory ratio
and the relative differences of F and a.

MUMPS runs up to N = --mumps-up-to only: at N = 48 (353k dofs) it took 22 GB
and 8 minutes on one rank.

Before the timed runs each dolfinx set-up runs once, untimed, at N = 4, so
that FFCx's JIT cache holds the compiled forms.

Writes <output-dir>/dolfinx_hertz_sphere.csv and dolfinx_hertz_sphere.md.

    benchmarks/run_dolfinx_hertz_sphere.py [--executable build/viscoplastic_contact]
        [--subdivisions 24,48,68] [--ranks 1,2] [--repeat 1]
        [--solvers gamg,mumps] [--mumps-up-to 32] [--python /usr/bin/python3]
        [--timeout 1800] [--output-dir doc/performance]

Needs Debian's python3-dolfinx; build the program in Release mode.
"""

import argparse
import csv
import os
import re
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scripts"))
sys.path.insert(0, os.path.join(HERE, "..", "meshes"))
from vc_scripts import (REPO_ROOT, add_executable_argument,  # noqa: E402
                        resolve_executable, set_prm_entries)
from run_dolfinx_comparison import (checked_run, fastest,  # noqa: E402
                                    provenance)
from run_hertz_sphere import E_STAR, R, profile_measures  # noqa: E402

DOLFINX_SCRIPT = os.path.join(HERE, "dolfinx_hertz_sphere.py")


def graded_box(n):
    """The entries that make the program generate the mesh of
    hertz_sphere_block(n): the unit box of n cubes per edge moved by the
    grading (x, y, z) -> (x^2, 1 - (1 - y)^2, z^2), with the colorized
    box's boundary ids (0, 2, 4 at x, y, z = 0; 3 at y = 1)."""
    return {(("Geometry",), "Mesh file"): "",
            (("Geometry",), "Lengths"): "1, 1, 1",
            (("Geometry",), "Subdivisions"): str(n),
            (("Geometry",), "Box map"): "x^2; 1 - (1 - y)^2; z^2",
            (("Geometry",), "Box map inverse"):
                "sqrt(x); 1 - sqrt(1 - y); sqrt(z)",
            (("Boundary",), "Contact boundary ids"): "3",
            (("Boundary",), "Symmetry boundary ids"): "0, 4, 2"}


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def run_program(executable, n, ranks, timeout):
    with tempfile.TemporaryDirectory() as workdir:
        with open(os.path.join(REPO_ROOT, "parameters", "hertz_sphere.prm")) as f:
            prm = set_prm_entries(f.read(), {
                **graded_box(n),
                (("Time",), "Time step"): "1",
                (("Output",), "Write vtu"): "false",
                (("Output",), "Profile times"): "1",
                (("Output",), "Print timing summary"): "false",
                (("Output",), "Verbose"): "false",
                (("Output",), "Output directory"): "out"})
        with open(os.path.join(workdir, "run.prm"), "w") as f:
            f.write(prm)
        wall, memory, out = checked_run([executable, "run.prm"], ranks, workdir,
                                        timeout)
        if out is None or out == "failed":
            return {"time": wall, "memory": memory,
                    "status": "timeout" if out is None else "failed"}
        last = read_rows(os.path.join(workdir, "out", "time_series.csv"))[-1]
        profile = read_rows(os.path.join(workdir, "out",
                                         "contact_profile_0001.csv"))
    force = float(last["total_contact_force"])
    mesh = re.search(r"(\d+) displacement dofs, (\d+) contact nodes", out)
    back_end = re.search(r"^Back end: ([a-z ]+):", out, re.M)
    dofs, nodes = mesh.groups()
    back_end = back_end.group(1) if back_end else "?"
    # With initial cycles the header shows the first, coarsest mesh; the
    # line that ends the cycles shows the run's mesh and its back end.
    cycles = re.search(r"^Initial cycles done: \d+ cells, (\d+) dofs, (\d+) "
                       r"contact nodes for step 1; back end: ([a-z ]+):", out,
                       re.M)
    if cycles:
        dofs, nodes, back_end = cycles.groups()
    return {"time": wall, "memory": memory, "status": "ok", "force": force,
            "at_obstacle": int(last["unilateral_nodes"]),
            "a": profile_measures(profile, 4 * force, E_STAR, R)["a"],
            "iterations": last["active_set_iterations"],
            "dofs": dofs, "contact_nodes": nodes, "back_end": back_end}


def run_dolfinx(python, n, ranks, solver, timeout):
    with tempfile.TemporaryDirectory() as workdir:
        wall, memory, out = checked_run(
            [python, DOLFINX_SCRIPT, "--subdivisions", str(n), "--solver",
             solver, "--profile", "profile.csv"], ranks, workdir, timeout)
        if out is None or out == "failed":
            return {"time": wall, "memory": memory,
                    "status": "timeout" if out is None else "failed"}
        profile = read_rows(os.path.join(workdir, "profile.csv"))
    contact = re.search(r"final contact: (\d+) at the obstacle, total force = "
                        r"(\S+)", out)
    iterations = re.search(r"SNES iterations: (\d+), converged reason \S+, "
                           r"Krylov iterations (\d+)", out)
    times = re.search(r"set-up time: (\S+) s, solve time: (\S+) s", out)
    force = float(contact.group(2))
    return {"time": wall, "memory": memory, "status": "ok", "force": force,
            "at_obstacle": int(contact.group(1)),
            "a": profile_measures(profile, 4 * force, E_STAR, R)["a"],
            "iterations": f"{iterations.group(1)} ({iterations.group(2)})",
            "solve": float(times.group(2))}


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_executable_argument(parser)
    parser.add_argument("--subdivisions", default="24,48,68")
    parser.add_argument("--ranks", default="1,2")
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--python", default="/usr/bin/python3",
                        help="the Python that imports dolfinx")
    parser.add_argument("--solvers", default="gamg,mumps",
                        help="dolfinx's linear solvers (gamg, mumps)")
    parser.add_argument("--mumps-up-to", type=int, default=32,
                        help="the largest N for MUMPS (at N = 48 it took 22 GB)")
    parser.add_argument("--timeout", type=float, default=1800)
    parser.add_argument("--output-dir", default=os.path.join(REPO_ROOT, "doc",
                                                             "performance"))
    args = parser.parse_args()
    executable = resolve_executable(args.executable)
    solvers = [s for s in args.solvers.split(",") if s]

    for solver in solvers:  # untimed: fills the FFCx JIT cache
        run_dolfinx(args.python, 4, 1, solver, args.timeout)

    rows = []
    for n in [int(n) for n in args.subdivisions.split(",") if n]:
        for ranks in [int(r) for r in args.ranks.split(",") if r]:
            program, peers = None, {s: None for s in solvers}
            for _ in range(args.repeat):
                program = fastest(program, run_program(executable, n, ranks,
                                                       args.timeout))
                for s in solvers:
                    peers[s] = fastest(peers[s], run_dolfinx(
                        args.python, n, ranks, s, args.timeout)
                        if s != "mumps" or n <= args.mumps_up_to else
                        {"time": float("nan"), "memory": float("nan"),
                         "status": "not run"})
            row = {"N": n, "ranks": ranks, "dofs": program.get("dofs", ""),
                   "contact_nodes": program.get("contact_nodes", ""),
                   "program_back_end": program.get("back_end", "")}
            for name, r in [("program", program)] + [(f"dolfinx_{s}", peers[s])
                                                     for s in solvers]:
                ok = r["status"] == "ok"
                row[f"{name}_s"] = f"{r['time']:.2f}" if ok else r["status"]
                row[f"{name}_MB"] = (f"{r['memory']:.0f}"
                                     if r["memory"] == r["memory"] else "")
                row[f"{name}_iterations"] = r.get("iterations", "")
                row[f"{name}_at_obstacle"] = r.get("at_obstacle", "")
                row[f"{name}_force"] = f"{r['force']:.10g}" if ok else ""
                row[f"{name}_a"] = f"{r['a']:.6g}" if ok else ""
            summary = []
            for s in solvers:
                d = peers[s]
                both = program["status"] == "ok" and d["status"] == "ok"
                row[f"dolfinx_{s}_solve_s"] = (f"{d['solve']:.2f}"
                                               if "solve" in d else "")
                row[f"time_ratio_{s}"] = (f"{d['time'] / program['time']:.2f}"
                                          if both else "")
                row[f"memory_ratio_{s}"] = (
                    f"{d['memory'] / program['memory']:.2f}" if both else "")
                for q in ("force", "a"):
                    row[f"{q}_rel_diff_{s}"] = (
                        f"{abs(d[q] - program[q]) / abs(program[q]):.1e}"
                        if both else "")
                row[f"contact_agrees_{s}"] = (
                    ("yes" if d["at_obstacle"] == program["at_obstacle"]
                     else "NO") if both else "")
                summary.append(
                    f"dolfinx {s} {row[f'dolfinx_{s}_s']} s "
                    f"({row[f'dolfinx_{s}_MB']} MB, "
                    f"{row[f'dolfinx_{s}_iterations']} iterations), ratio "
                    f"{row[f'time_ratio_{s}']}, F diff "
                    f"{row[f'force_rel_diff_{s}']}, a diff "
                    f"{row[f'a_rel_diff_{s}']}")
            print(f"N = {n}, {ranks} rank(s), {row['dofs']} dofs: program "
                  f"{row['program_s']} s ({row['program_MB']} MB, "
                  f"{row['program_back_end']}); " + "; ".join(summary),
                  flush=True)
            rows.append(row)

    os.makedirs(args.output_dir, exist_ok=True)
    with open(os.path.join(args.output_dir, "dolfinx_hertz_sphere.csv"), "w",
              newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    write_markdown(args, rows, solvers)


def write_markdown(args, rows, solvers):
    generated, versions = provenance("run_dolfinx_hertz_sphere.py",
                                     args.python)
    lines = [
        "# The program against dolfinx on the Hertz sphere (3D)", "", generated,
        "",
        "The scene: parameters/hertz_sphere.prm at the final indentation "
        "d = 0.01 as one static problem, on the graded hexahedral mesh with N "
        "cells per edge (the quarter model). *program*: viscoplastic_contact "
        "with its defaults (Method = auto), generating the mesh as the box of N "
        "cubes per edge moved by the grading (Box map). "
        "*dolfinx*: benchmarks/dolfinx_hertz_sphere.py, an independent "
        "implementation of the same discretisation (Q1, nodal contact) in "
        "dolfinx " + (f"{versions[0]} with PETSc {versions[1]}"
                      if len(versions) == 2 else "")
        + ", creating the same mesh in memory: SNES vinewtonrsls with the "
        "obstacle as bounds, full Newton steps, and per Newton iteration "
        "*gamg* (CG, rtol 1e-8, smoothed-aggregation AMG with the rigid-body "
        "modes of the reduced system) or *mumps* (LU). The runs of a row ran "
        f"back to back, the fastest of {args.repeat} interleaved repeat(s) "
        "counting. Times are whole processes in seconds (dolfinx's forms "
        "precompiled by an untimed warm-up run); *solve* is dolfinx's own "
        "timer of the SNES solve. Memory is the peak resident memory of the "
        "largest rank in MB. *iterations*: the program's active-set "
        "iterations on the final mesh (after its initial cycles on coarser "
        "meshes, where auto runs them), dolfinx's Newton iterations (Krylov iterations in "
        "brackets). *at obstacle*: vertices at the sphere. *F*: the quarter "
        "model's contact force; *a*: the contact radius from the nodal "
        "pressures on the x axis (doc/benchmarks.md); *diff*: the largest "
        "relative difference of dolfinx from the program in the row.", ""]
    header = ("| N | ranks | dofs | program [s] | "
              + " | ".join(f"dolfinx {s} [s] | {s} / program | {s} solve [s]"
                           for s in solvers)
              + " | memory: program [MB] | "
              + " | ".join(f"dolfinx {s} [MB]" for s in solvers)
              + " | program back end | iterations: program | "
              + " | ".join(f"dolfinx {s}" for s in solvers)
              + " | at obstacle | F | F diff | a | a diff |")
    lines += [header, "|" + "|".join(["---:"] * (header.count("|") - 1)) + "|"]

    def largest(row, quantity):
        values = [float(row[f"{quantity}_rel_diff_{s}"]) for s in solvers
                  if row[f"{quantity}_rel_diff_{s}"]]
        return f"{max(values):.1e}" if values else ""
    for r in rows:
        differ = any(r[f"contact_agrees_{s}"] == "NO" for s in solvers)
        lines.append(
            f"| {r['N']} | {r['ranks']} | {r['dofs']} | {r['program_s']} | "
            + " | ".join(f"{r[f'dolfinx_{s}_s']} | {r[f'time_ratio_{s}']} | "
                         f"{r[f'dolfinx_{s}_solve_s']}" for s in solvers)
            + f" | {r['program_MB']} | "
            + " | ".join(r[f"dolfinx_{s}_MB"] for s in solvers)
            + f" | {r['program_back_end']} | {r['program_iterations']} | "
            + " | ".join(r[f"dolfinx_{s}_iterations"] for s in solvers)
            + f" | {r['program_at_obstacle']}{' (differ)' if differ else ''} | "
            f"{r['program_force']} | {largest(r, 'force')} | {r['program_a']} | "
            f"{largest(r, 'a')} |")
    with open(os.path.join(args.output_dir, "dolfinx_hertz_sphere.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
