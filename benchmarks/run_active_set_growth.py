#!/usr/bin/python3
"""Where the active-set iterations per step grow with the mesh, and why.
Writes doc/performance/active_set_growth.md (read in doc/performance.md).

The scene is the 3D cube (parameters/cube_3d.prm on hexahedra,
parameters/cube_3d_tetrahedra.prm on tetrahedra) with Method = full space
(--method), the explicit update and no uniqueness check, up to
--end-time (0.25 by default: the first quarter of the run, where the rigid
zone forms and the iterations are highest). Each mesh of N subdivisions runs
twice:

  fixed k    the shipped step k = 1/32 on every mesh, so that the front of
             the rigid zone crosses more rows of nodes per step on a finer
             mesh;
  k ~ h      k = 1/(2N), refined with the mesh as a convergence study does
             (the same run as "fixed k" at N = 16), so that the front crosses
             about as many rows per step on every mesh.

and the hexahedra a third time:

  step cycles  the shipped k with Step cycles = 1: every step after the
             first is solved on the mesh coarsened once first, whose contact
             zone starts the iteration on the mesh (the two runs above have
             Step cycles = 0; a box of tetrahedra is not the refinement of a coarser
             box, so these have none).

The first step is solved on 2 coarser meshes first (Initial cycles; the
hexahedra refine theirs, the tetrahedra are built anew; none where N is not
a multiple of 4). The uniqueness check (a Lanczos iteration at set-up) is
off; the cube's step problem has one solution, so the pieces are
predicted either way. The runs print their iteration history (Output/Print iteration history), from
which the table takes, besides the iterations per step: the iterations of
step 2, the first step in which the zone forms (it starts from the pieces of
step 1, in which no node is at the rigid limit), and the largest number of
nodes at the rigid limit during that step against the number at its end
(the overshoot that the iteration then releases from the edge of the zone).

--friction MU runs every scene with Coulomb friction of coefficient MU
(the step cycles then start the stick/slip states from the coarser mesh
too); its page is doc/performance/active_set_growth_friction.md.

Usage:
    benchmarks/run_active_set_growth.py [--executable build/viscoplastic_contact]
        [--hexahedra 16,32,48] [--tetrahedra 16,32,48] [--end-time 0.25]
        [--method "full space"] [--friction MU]
        [--output doc/performance/active_set_growth.md]

Counts of iterations do not depend on the machine; the wall times in the
table do (compare them within one invocation).
"""

import argparse
import datetime
import os
import platform
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import (REPO_ROOT, add_executable_argument,  # noqa: E402
                        resolve_executable, set_prm_entries)

SCENES = {"hexahedra": "cube_3d.prm", "tetrahedra": "cube_3d_tetrahedra.prm"}
SHIPPED_STEP = 1 / 32


def cube(cells, n, end_time, step, method, directory, step_cycles,
         friction):
    # The first step on 2 coarser meshes: refined from N/4 subdivisions on
    # hexahedra, built anew on tetrahedra (Subdivisions = N).
    cycles = 2 if n % 4 == 0 else 0
    refinements = cycles if cells == "hexahedra" else 0
    with open(os.path.join(REPO_ROOT, "parameters", SCENES[cells])) as f:
        text = f.read()
    if friction:
        text = set_prm_entries(text, {
            (("Contact",), "Tangential law"): "Coulomb",
            (("Contact",), "Friction coefficient"): repr(friction)})
    return set_prm_entries(text, {
        (("Geometry",), "Subdivisions"): str(n // 2 ** refinements),
        (("Geometry",), "Global refinements"): str(refinements),
        (("Mesh adaptation",), "Initial cycles"): str(cycles),
        (("Mesh adaptation",), "Step cycles"): str(step_cycles),
        (("Time",), "End time"): repr(end_time),
        (("Time",), "Time step"): repr(step),
        (("Linear solver",), "Method"): method,
        (("Contact",), "Check uniqueness"): "false",
        (("Output",), "Output directory"): directory,
        (("Output",), "Write vtu"): "false",
        (("Output",), "Profile times"): "",
        (("Output",), "Verbose"): "true",
        (("Output",), "Print timing summary"): "false",
        (("Output",), "Print iteration history"): "true",
    })


STEP_LINE = re.compile(r"^Step +(\d+) .*active-set iterations +(\d+) "
                       r"+unilateral +(\d+)")
ITERATION_LINE = re.compile(r"^ +iteration (\d+): (\d+) nodes changed their "
                            r"piece, (\d+) nodes at the rigid limit.*?"
                            r"(?:after (\d+) Krylov iterations)?$")


def parse_steps(out):
    """The steps of a run: per step its iterations, as the history lines
    that follow its step line give them."""
    steps, current = [], None
    for line in out.splitlines():
        match = STEP_LINE.match(line)
        if match:
            current = {"step": int(match.group(1)),
                       "iterations": int(match.group(2)),
                       "rigid": int(match.group(3)), "history": []}
            steps.append(current)
            continue
        match = ITERATION_LINE.match(line)
        # History lines before the first step line are the initial cycles'.
        if match and current is not None:
            current["history"].append(
                {"changed": int(match.group(2)), "rigid": int(match.group(3)),
                 "krylov": int(match.group(4) or 0)})
    for step in steps:
        if len(step["history"]) != step["iterations"]:
            sys.exit(f"error: step {step['step']} has {step['iterations']} "
                     f"iterations but {len(step['history'])} history lines")
    return steps


def measure(executable, cells, n, step, step_cycles, args, work):
    name = f"{cells}_{n}_k{round(1 / step)}_c{step_cycles}"
    directory = os.path.join(work, name)
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as f:
        f.write(cube(cells, n, args.end_time, step, args.method, directory,
                     step_cycles, args.friction))
    start = time.perf_counter()
    done = subprocess.run([executable, prm], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        print(done.stdout[-3000:])
        sys.exit(f"error: run {name} failed")
    out = done.stdout
    steps = parse_steps(out)
    dofs = re.findall(r"(?:Mesh: \d+ \w+ cells, (\d+) displacement dofs"
                      r"|Initial cycles done: \d+ cells, (\d+) dofs)", out)
    dofs = int(next(g for g in dofs[-1] if g))
    coarser = re.search(r"^  step cycles: (\d+) active-set iterations", out,
                        re.M)
    second = steps[1] if len(steps) > 1 else None
    later = steps[2:]
    return {
        "cells": cells, "n": n, "k": step, "dofs": dofs, "wall": wall,
        "steps": len(steps),
        "per_step": sum(s["iterations"] for s in steps) / len(steps),
        "coarser_per_step": (int(coarser.group(1)) / len(steps)
                             if coarser else None),
        "krylov_per_step": sum(h["krylov"] for s in steps
                               for h in s["history"]) / len(steps),
        "step1": steps[0]["iterations"],
        "step2": second["iterations"] if second else float("nan"),
        "step2_peak": max(h["rigid"] for h in second["history"])
        if second else 0,
        "step2_rigid": second["rigid"] if second else 0,
        "later_per_step": (sum(s["iterations"] for s in later) / len(later)
                           if later else float("nan")),
    }


def page(rows, args, command):
    lines = [
        "# Active-set iterations per step against the mesh"
        + (f", Coulomb friction mu = {args.friction}" if args.friction
           else ""),
        "",
        f"Generated by `benchmarks/run_active_set_growth.py` on "
        f"{datetime.date.today().isoformat()} ({platform.node()}, "
        f"{os.cpu_count()} cores); command: `{command}`.",
        "",
        f"`cube_3d.prm` (hexahedra) and `cube_3d_tetrahedra.prm` "
        f"(tetrahedra)"
        + (f" with Coulomb friction, mu = {args.friction}" if args.friction
           else "")
        + ", the first step solved on 2 coarser meshes first "
        f"(Initial cycles = 2; none where N is not a multiple of 4), "
        f"without the uniqueness check, Method = "
        f"{args.method}, up to t = {args.end_time}, one rank. *fixed k*: "
        f"the shipped k = 1/32 on every mesh; *k ~ h*: k = 1/(2N). "
        f"*its/step*: active-set iterations per step over the run; *step 1*: "
        f"those of step 1 (on the fine mesh); *step 2*: "
        f"those of step 2, where the rigid zone forms from the pieces of "
        f"step 1; *rigid: peak / end*: the most nodes at the rigid limit "
        f"during step 2 against the number at its end; *steps 3-*: the "
        f"iterations per step after step 2; *Krylov/step*: the CG "
        f"iterations per step on the mesh. *step cycles*: the shipped k "
        f"with Step cycles = 1 (the other runs have 0): each step after "
        f"the first solved on the mesh coarsened once first; *coarser "
        f"its/step*: the active-set iterations there, per step of the run. "
        f"The wall times of one mesh ran one after the other.",
        "",
        "| cells | N | dofs | k | steps | its/step | step 1 | step 2 | rigid in step 2: "
        "peak / end | steps 3-: its/step | Krylov/step | coarser its/step "
        "| wall [s] |",
        "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        k = ("1/32 (fixed, = 1/(2N))" if r["n"] == 16 and r["mode"] == "fixed"
             else "1/32 (fixed)" if r["mode"] == "fixed"
             else "1/32, step cycles" if r["mode"] == "cycles"
             else f"1/{round(1 / r['k'])} (~ h)")
        coarser = ("" if r["coarser_per_step"] is None
                   else f"{r['coarser_per_step']:.2f}")
        lines.append(
            f"| {r['cells']} | {r['n']} | {r['dofs']} | {k} | {r['steps']} "
            f"| {r['per_step']:.2f} | {r['step1']} | {r['step2']} "
            f"| {r['step2_peak']} / {r['step2_rigid']} "
            f"| {r['later_per_step']:.2f} | {r['krylov_per_step']:.1f} "
            f"| {coarser} | {r['wall']:.1f} |")
    lines.append("")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    add_executable_argument(parser)
    parser.add_argument("--hexahedra", default="16,32,48")
    parser.add_argument("--tetrahedra", default="16,32,48")
    parser.add_argument("--end-time", type=float, default=0.25)
    parser.add_argument("--method", default="full space")
    parser.add_argument("--friction", type=float, default=0)
    parser.add_argument("--output")
    args = parser.parse_args()
    if args.output is None:
        args.output = os.path.join(
            REPO_ROOT, "doc", "performance",
            "active_set_growth%s.md" % ("_friction" if args.friction else ""))
    executable = resolve_executable(args.executable)
    command = "benchmarks/run_active_set_growth.py " + " ".join(
        a if " " not in a else f'"{a}"' for a in sys.argv[1:])
    rows = []
    with tempfile.TemporaryDirectory(prefix="vc_active_set_") as work:
        for cells, sizes in (("hexahedra", args.hexahedra),
                             ("tetrahedra", args.tetrahedra)):
            for n in [int(s) for s in sizes.split(",") if s]:
                for mode, step, step_cycles in (
                        ("fixed", SHIPPED_STEP, 0), ("h", 1 / (2 * n), 0),
                        ("cycles", SHIPPED_STEP, 1)):
                    if mode == "h" and abs(step - SHIPPED_STEP) < 1e-15:
                        continue  # the same run as fixed k
                    if mode == "cycles" and cells != "hexahedra":
                        continue  # a box of tetrahedra refines no coarser box
                    row = measure(executable, cells, n, step, step_cycles,
                                  args, work)
                    row["mode"] = mode
                    rows.append(row)
                    print(f"{cells} N = {n} k = 1/{round(1 / step)}: "
                          f"{row['per_step']:.2f} its/step, step 2 "
                          f"{row['step2']}, {row['wall']:.1f} s", flush=True)
    text = page(rows, args, command)
    with open(args.output, "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
