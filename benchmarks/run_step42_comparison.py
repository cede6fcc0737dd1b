#!/usr/bin/python3
"""This program against deal.II's step-42, side by side in one run: the time
per degree of freedom and nonlinear iteration at the same mesh sizes.
Writes doc/performance/step42.md (read in doc/performance.md).

step-42 (elastoplastic contact with a rigid obstacle in 3D: semismooth
Newton on a primal-dual active set, the matrix and its AMG rebuilt in every
Newton iteration, BiCGStab) is built from the deal.II 9.4 sources of the
tutorial: the script takes /usr/share/doc/libdeal.ii-doc/examples/step-42
if installed, otherwise it downloads Debian's libdeal.ii-doc package (which
ships the tutorial sources) with `apt-get download` and unpacks only
step-42, and builds it in Release against the installed library. step-42
runs its "box" scene: the unit cube, Q1, global refinements (one cycle
from zero on the cube of 2^r cells per edge, the cold start its results
page reports), a spherical obstacle pressed into the top.

This program runs parameters/cube_3d.prm on the same hexahedral meshes
(h = 1/2^r, the same number of dofs), the first 8 time steps of k = 1/32
(the contact zone forms: the most active-set iterations of a run), with
each back end. A nonlinear iteration is one active-set iteration here and
one Newton iteration of step-42; both times are wall times of the solve
phases measured by the programs' own TimerOutput: for step-42 its whole
cycle without set-up and graphical output, for this program its average
time step (right-hand side, active-set solve, stress update) times the
steps, divided by the iterations.

Usage:
    benchmarks/run_step42_comparison.py [--executable build/viscoplastic_contact]
        [--refinements 4,5] [--work-dir build-step-42]
        [--output doc/performance/step42.md]
"""

import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from deal_ii_tutorial import (build_tutorial, comparison_arguments,  # noqa: E402
                              write_page)
from run_performance import number, run, scene, section  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import resolve_executable  # noqa: E402

def run_step42(executable, refinements, work):
    """One cycle of step-42 from zero on the cube with 2^refinements cells
    per edge; returns dofs, Newton iterations, the solve phases' time, the
    wall time of the process and its peak memory."""
    directory = os.path.join(work, f"step42_r{refinements}")
    os.makedirs(directory, exist_ok=True)
    prm = os.path.join(directory, "run.prm")
    with open(prm, "w") as f:
        f.write("set polynomial degree             = 1\n"
                f"set number of initial refinements = {refinements}\n"
                "set number of cycles              = 1\n"
                "set refinement strategy           = global\n"
                "set obstacle                      = sphere\n"
                "set base mesh                     = box\n"
                f"set output directory              = {directory}/\n")
    start = time.perf_counter()
    child = subprocess.Popen([executable, prm], stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, text=True,
                             cwd=directory)
    out = child.stdout.read()
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - start
    if status != 0:
        print(out[-3000:])
        sys.exit(f"error: step-42 at {refinements} refinements failed")
    total = number(r"Total wallclock time elapsed since start\s*\|\s*([0-9.e+-]+)s",
                   out)
    newton = total - section("Setup", out) - section("Graphical output", out)
    dofs = int(number(r"Number of degrees of freedom: (\d+)", out))
    return {
        "dofs": dofs,
        "iterations": len(re.findall(r"Newton iteration \d+", out)),
        "solve_phases": newton,
        "assembly": section("Assembling", out),
        "amg_setup": section("Solve: setup preconditioner", out),
        "krylov": section("Solve: iterate", out),
        "linear_iterations": sum(int(n) for n in re.findall(
            r"in (\d+) Bicgstab iterations", out)),
        "wall": wall,
        "memory_mb": usage.ru_maxrss / 1024.,
    }


def run_ours(executable, refinements, method, work):
    """The first 8 steps of cube_3d.prm on hexahedra at h = 2^-refinements
    with the given back end."""
    subdivisions = 2**refinements
    prm = scene("cube_3d.prm", {
        (("Geometry",), "Subdivisions"): str(subdivisions),
        (("Time",), "End time"): "0.25",
        (("Linear solver",), "Method"): method,
        (("Contact",), "Check uniqueness"): "false",
    })
    row = run(executable, prm, work,
              f"ours_r{refinements}_{method.replace(' ', '_')}")
    row["solve_phases"] = row["step_ms"] * 1e-3 * row["steps"]
    return row


def main():
    args = comparison_arguments(
        __doc__, "step-42", "4,5",
        "mesh sizes as cells per edge 2^r (default 4,5: 15k and 108k dofs; "
        "6 is 823k)", "step42.md")
    executable = resolve_executable(args.executable)
    step42 = build_tutorial("step-42", os.path.abspath(args.work_dir))

    lines = [
        "# This program against step-42",
        "",
        "Written by `benchmarks/run_step42_comparison.py`: Release builds, "
        "one process at a time, one rank, on a shared 2-core machine; the "
        "ratios within a size were measured in one invocation. *per dof and "
        "iteration* is the time of the solve phases (step-42: its cycle "
        "without set-up and output; this program: the average time step "
        "times the steps) divided by the dofs and the nonlinear iterations "
        "(step-42: Newton; this program: active-set). *ratio* is this "
        "program's time per dof and iteration over step-42's at the same "
        "size.",
        "",
        "The problems differ: step-42 is elastoplastic with isotropic "
        "hardening (a nonlinear material, a new tangent per Newton "
        "iteration) and Signorini contact with a sphere pressed into the top "
        "(37 active nodes at 108k dofs), solved once from rest. This program "
        "keeps its elastic operator for the whole run (the explicit update "
        "puts the viscoplasticity into the right-hand side) and solves, per "
        "time step, a contact problem with a nonmonotone normal compliance "
        "and a rigid limit on the whole bottom face (1056 contact nodes at "
        "108k dofs, 214 at the rigid limit after 8 steps); its iterations "
        "include the stress update of each step. Both take one nonlinear "
        "iteration as the unit of work: the comparison is what an iteration "
        "costs, not which problem is harder.",
        "",
        "| program | back end | dofs | nonlinear it. | linear it. | solve phases [s] | per dof and iteration [us] | ratio | whole process [s] | peak memory [MB] |",
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    with tempfile.TemporaryDirectory() as work:
        for r in [int(x) for x in args.refinements.split(",")]:
            reference = run_step42(step42, r, work)
            reference_cost = reference["solve_phases"] / (
                reference["dofs"] * reference["iterations"])
            rows = [("step-42", "AMG (rebuilt per iteration), BiCGStab",
                     reference)]
            for method in ["condensed", "full space"]:
                rows.append(("this program", method,
                             run_ours(executable, r, method, work)))
            for program, back_end, row in rows:
                cost = row["solve_phases"] / (row["dofs"] * row["iterations"])
                linear = row.get("linear_iterations", row.get("krylov", 0))
                cells = (f"| {program} | {back_end} | {row['dofs']} | "
                         f"{int(row['iterations'])} | {int(linear)} | "
                         f"{row['solve_phases']:.2f} | {cost * 1e6:.2f} | "
                         f"{cost / reference_cost:.2f} | {row['wall']:.2f} | "
                         f"{row['memory_mb']:.0f} |")
                lines.append(cells)
                print(cells, flush=True)
    lines.append("")
    write_page(args.output, lines)


if __name__ == "__main__":
    main()
