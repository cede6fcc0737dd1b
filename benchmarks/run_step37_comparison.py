#!/usr/bin/python3
"""The matrix-free elastic solve against deal.II's step-37, side by side in
one run: the time of a CG iteration (one operator application, one
multigrid V-cycle, the vector updates) per degree of freedom, on the same
hexahedral meshes. Writes doc/performance/step37.md (read in
doc/performance.md).

step-37 (the Poisson equation with a variable coefficient, matrix-free
operator evaluation with sum factorisation, vectorised over cells; CG
preconditioned by a geometric multigrid V-cycle with a Chebyshev smoother
of degree 5 and float levels) is built from the deal.II 9.4 sources of the
tutorial (deal_ii_tutorial.py), edited to Q1 elements (as this program
uses) and to time, after its solve, 10 operator applications and 10
V-cycles on its solution. It runs its own scene: the unit cube refined
globally, one cycle per refinement, here up to 2^r cells per edge.

This program runs parameters/cube_3d.prm (the unit cube, hexahedra, Q1,
three components) with Method = matrix free on the cube of 2^r cells per
edge and reports the time of one elastic solve (K u = b without contact:
CG preconditioned by its multigrid V-cycle), its CG iterations and the
time of one operator application. All times are wall times of one rank; a
dof is one component of a node, so *per dof* is per component and dof.

Usage:
    benchmarks/run_step37_comparison.py [--executable build/viscoplastic_contact]
        [--refinements 4,5,6] [--work-dir build-step-37]
        [--output doc/performance/step37.md]
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
from run_performance import number, run, scene  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import resolve_executable  # noqa: E402

# What the edit inserts after step-37's solve: 10 operator applications and
# 10 V-cycles on copies of the solution, timed.
TIMING = """
    {
      LinearAlgebra::distributed::Vector<double> x(solution), y(solution);
      const unsigned int repetitions = 10;
      Timer              timer;
      for (unsigned int r = 0; r < repetitions; ++r)
        system_matrix.vmult(y, x);
      pcout << "Time operator application (wall) "
            << timer.wall_time() / repetitions << "s\\n";
      timer.restart();
      for (unsigned int r = 0; r < repetitions; ++r)
        preconditioner.vmult(y, x);
      pcout << "Time V-cycle (wall) " << timer.wall_time() / repetitions
            << "s\\n";
    }
"""


def edit_step37(refinements):
    """The edit of step-37.cc: Q1, cycles up to the given refinement, the
    timing above after the solve."""
    def edit(text):
        replacements = [
            ("const unsigned int degree_finite_element = 2;",
             "const unsigned int degree_finite_element = 1;"),
            ("cycle < 9 - dim;", f"cycle < {refinements};"),
            ("          << time.cpu_time() << \"s/\" << time.wall_time() << \"s\\n\";\n",
             "          << time.cpu_time() << \"s/\" << time.wall_time() << \"s\\n\";\n"
             + TIMING),
            # No graphical output: only the solves are measured.
            ("        output_results(cycle);\n", ""),
        ]
        for old, new in replacements:
            if old not in text:
                sys.exit(f"error: step-37.cc has no line {old.strip()!r} to edit")
            text = text.replace(old, new)
        return text
    return edit


def run_step37(executable, work):
    """All cycles of the edited step-37; per cycle the dofs, CG
    iterations, solve time, and the times of one operator application and
    one V-cycle."""
    directory = os.path.join(work, "step37_run")
    os.makedirs(directory, exist_ok=True)
    out = subprocess.run([executable], cwd=directory, check=True,
                         capture_output=True, text=True).stdout
    rows = []
    for cycle in re.split(r"^Cycle \d+\n", out, flags=re.M)[1:]:
        solve = re.search(r"Time solve \((\d+) iterations\)\s+\(CPU/wall\) "
                          r"[0-9.e+-]+s/([0-9.e+-]+)s", cycle)
        rows.append({
            "dofs": int(number(r"Number of degrees of freedom: (\d+)", cycle)),
            "iterations": int(solve.group(1)),
            "solve": float(solve.group(2)),
            "operator": number(r"Time operator application \(wall\) ([0-9.e+-]+)s",
                               cycle),
            "v_cycle": number(r"Time V-cycle \(wall\) ([0-9.e+-]+)s", cycle),
        })
    vectorisation = re.search(r"^Vectorization over .*$", out, re.M)
    return rows, vectorisation.group(0) if vectorisation else ""


def run_ours(executable, refinements, work):
    """One step of cube_3d.prm on the cube of 2^refinements cells per edge,
    matrix free: the time and CG iterations of one elastic solve."""
    prm = scene("cube_3d.prm", {
        (("Geometry",), "Subdivisions"): str(2**refinements),
        (("Time",), "End time"): "0.03125",
        (("Linear solver",), "Method"): "matrix free",
        (("Contact",), "Check uniqueness"): "false",
    })
    return run(executable, prm, work, f"ours_r{refinements}")


def main():
    args = comparison_arguments(
        __doc__, "step-37", "4,5,6",
        "mesh sizes as cells per edge 2^r (default 4,5,6: this program's "
        "15k, 108k and 824k dofs)", "step37.md")
    executable = resolve_executable(args.executable)
    refinements = [int(x) for x in args.refinements.split(",")]
    work_dir = os.path.abspath(args.work_dir)
    # A build for another largest refinement is built anew.
    step37 = build_tutorial("step-37", os.path.join(work_dir, f"r{max(refinements)}"),
                            edit_step37(max(refinements)))

    with tempfile.TemporaryDirectory() as work:
        start = time.perf_counter()
        theirs, vectorisation = run_step37(step37, work)
        step37_wall = time.perf_counter() - start
        ours = {r: run_ours(executable, r, work) for r in refinements}

    lines = [
        "# The matrix-free elastic solve against step-37",
        "",
        "Written by `benchmarks/run_step37_comparison.py`: Release builds, "
        "one process at a time, one rank, on a shared 2-core machine, all "
        "runs in one invocation. step-37 (Q1, the Poisson equation, CG with "
        "its geometric multigrid V-cycle: Chebyshev smoother of degree 5, "
        "float levels) as deal.II 9.4 ships it but for the degree and the "
        "timing of 10 operator applications and 10 V-cycles after its "
        f"solve; {vectorisation or 'its vectorisation not printed'}. This "
        "program: one elastic solve of `cube_3d.prm` with `Method = matrix "
        "free` (CG with its multigrid V-cycle, three components per node). "
        "*per dof* divides by the degrees of freedom (one per node for "
        "step-37, three for this program: per component and dof). The "
        "program times its operator application apart (the run summary's "
        "cost measurement); in brackets, its CG iteration less the "
        "operator application: the V-cycle with the vector updates.",
        "",
        "| program | cells per edge | dofs | CG iterations | solve [s] | per CG iteration and dof [ns] | operator application per dof [ns] | V-cycle per dof [ns] |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for r in refinements:
        # step-37's cycle c is the cube refined c + 1 times.
        row = theirs[r - 1] if r - 1 < len(theirs) else None
        if row:
            per_iteration = row["solve"] / row["iterations"] / row["dofs"]
            lines.append(f"| step-37 | {2**r} | {row['dofs']} | {row['iterations']} | "
                         f"{row['solve']:.4g} | {per_iteration * 1e9:.1f} | "
                         f"{row['operator'] / row['dofs'] * 1e9:.1f} | "
                         f"{row['v_cycle'] / row['dofs'] * 1e9:.1f} |")
        mine = ours[r]
        solve = mine["solve_ms"] * 1e-3
        iterations = int(mine["solve_iterations"])
        per_iteration = solve / iterations / mine["dofs"]
        product = mine["operator_ms"] * 1e-3 / mine["dofs"]
        lines.append(f"| this program | {2**r} | {mine['dofs']} | {iterations} | "
                     f"{solve:.4g} | {per_iteration * 1e9:.1f} | {product * 1e9:.1f} | "
                     f"({(per_iteration - product) * 1e9:.1f}) |")
        print(lines[-2] if row else "", lines[-1], sep="\n", flush=True)
    lines += [
        "",
        f"step-37's whole run (all its cycles up to {2**max(refinements)} cells "
        f"per edge): {step37_wall:.1f} s.",
        "",
    ]
    write_page(args.output, lines)


if __name__ == "__main__":
    main()
