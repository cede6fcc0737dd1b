#!/usr/bin/python3
"""What a contact pair costs: the 3D two-body patch test
(parameters/two_block_patch_test_3d.prm, hexahedra 6:8, Global refinements
R) with the pad pressed onto the deformable base along the pair, against
the same mesh with the pad pressed onto a rigid plane (the zone without
Opposite boundary ids, Initial gap 0; the base then carries no load): the
same operator, dofs and contact nodes, the pair's coupling the only
difference. In both the base lies 0.1 below the pad (a mesh whose bodies
touch is a mesh error without a pair), which the pair's Initial gap -0.1
closes. Runs in pairs one after the other (the
machine is shared and noisy: only ratios measured side by side mean
anything) and prints per back end and mesh the time per step of the time
loop (without output, the program's own measurement; the first step sets
up the back end on the run's mesh, after Initial cycles) and of the steps
after the first, the active-set and Krylov iterations per step, the elastic solves per step (the program's
"ratio step / solve": a step against one solve with the step's operator,
no contact) and the median over the pairs of the ratio two bodies / rigid
plane.

--large R [--ranks 1,2]: the two-body scene alone on Global refinements R
(R = 4: 1.2M dofs), on each rank count: dofs, time per step, elastic
solves per step, set-ups of the operator, peak memory (sum over ranks).

    benchmarks/run_two_body_cost.py [--executable build/viscoplastic_contact]
        [--refinements 2,3] [--pairs 3] [--methods "full space,condensed"]
        [--large 4 --ranks 1,2 --methods "full space"]
"""

import argparse
import csv
import os
import re
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..")
sys.path.insert(0, os.path.join(TOP, "scripts"))
sys.path.insert(0, os.path.join(TOP, "meshes"))
from vc_scripts import set_prm_entries  # noqa: E402
from make_two_body_meshes import blocks_3d  # noqa: E402

SEPARATION = 0.1


def run(executable, refinements, method, rigid, folder, ranks=1):
    output = os.path.join(folder, "output_%d" % len(os.listdir(folder)))
    mesh = os.path.join(folder, "blocks.msh")
    if not os.path.exists(mesh):
        with open(mesh, "w") as f:
            f.write(blocks_3d(6, 8, False, SEPARATION))
    entries = {(("Geometry",), "Mesh file"): mesh,
               (("Contact",), "Initial gap"): "0" if rigid else str(-SEPARATION),
               (("Contact",), "Search distance"): str(2 * SEPARATION),
               (("Geometry",), "Global refinements"): str(refinements),
               (("Linear solver",), "Method"): method,
               (("Time",), "End time"): "1",
               (("Output",), "Output directory"): output,
               (("Output",), "Write vtu"): "false",
               (("Output",), "Profile times"): "",
               (("Output",), "Measure cost ratios"): "true"}
    if rigid:
        entries[(("Contact",), "Opposite boundary ids")] = ""
        del entries[(("Contact",), "Search distance")]
    with open(os.path.join(TOP, "parameters", "two_block_patch_test_3d.prm")) as f:
        text = set_prm_entries(f.read(), entries)
    prm = os.path.join(folder, "scene_%d.prm" % len(os.listdir(folder)))
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([os.path.join(TOP, "tests", "run_mpi.sh"), str(ranks),
                             executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("The run (%s, R = %d, %s) failed:\n%s%s"
                 % ("rigid plane" if rigid else "two bodies", refinements, method,
                    result.stdout[-3000:], result.stderr))
    number = lambda pattern: float(re.search(pattern, result.stdout).group(1))
    with open(os.path.join(output, "time_series.csv")) as f:
        steps = list(csv.DictReader(f))
    return {"time per step": number(r"time loop \(without output\): *([0-9.eE+-]+) s")
                             / len(steps),
            # The finest mesh (Initial cycles start on coarser ones).
            "dofs": max(int(n) for n in re.findall(
                r"(?:^Mesh: |^Initial cycles done: ).*?([0-9]+) (?:displacement )?dofs",
                result.stdout, re.MULTILINE)),
            # The steps after the first (wall_time is cumulative), which
            # set up the back end on the run's mesh.
            "later steps": (float(steps[-1]["wall_time"]) - float(steps[0]["wall_time"]))
                           / max(1, len(steps) - 1),
            "solves per step": number(r"ratio step / solve: *([0-9.eE+-]+)"),
            "set-ups": int(number(r"set up by the back end ([0-9]+)x")),
            "memory": number(r"peak memory over the run \[MB\]: sum over ranks ([0-9.]+)"),
            "iterations": sum(int(s["active_set_iterations"]) for s in steps) / len(steps),
            "krylov": sum(int(s["krylov_iterations"]) for s in steps) / len(steps)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--executable", default=os.path.join(
        TOP, "build", "viscoplastic_contact"))
    parser.add_argument("--refinements", default="2,3")
    parser.add_argument("--pairs", type=int, default=3)
    parser.add_argument("--methods", default="full space,condensed")
    parser.add_argument("--large", type=int)
    parser.add_argument("--ranks", default="1,2")
    arguments = parser.parse_args()

    if arguments.large is not None:
        print("| back end | ranks | dofs | time per step | the steps after the first "
              "| elastic solves per step | active-set iterations per step "
              "| Krylov iterations per step | operator set-ups "
              "| peak memory (sum over ranks) |")
        print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
        for method in arguments.methods.split(","):
            for ranks in (int(r) for r in arguments.ranks.split(",")):
                with tempfile.TemporaryDirectory() as folder:
                    r = run(arguments.executable, arguments.large, method, False,
                            folder, ranks)
                print("| %s | %d | %d | %.3g s | %.3g s | %.2f | %.2f | %.1f | %d | %.2f GB |"
                      % (method, ranks, r["dofs"], r["time per step"], r["later steps"],
                         r["solves per step"], r["iterations"], r["krylov"],
                         r["set-ups"], r["memory"] / 1024))
                sys.stdout.flush()
        return

    print("| back end | R | dofs | time per step: rigid plane, two bodies "
          "| the steps after the first | elastic solves per step "
          "| active-set iterations per step | Krylov iterations per step "
          "| ratio two bodies / rigid plane, all steps and after the first "
          "(median of %d pairs) |" % arguments.pairs)
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for method in arguments.methods.split(","):
        for refinements in (int(v) for v in arguments.refinements.split(",")):
            ratios, later, pairs = [], [], []
            with tempfile.TemporaryDirectory() as folder:
                for _ in range(arguments.pairs):
                    rigid = run(arguments.executable, refinements, method, True, folder)
                    pair = run(arguments.executable, refinements, method, False, folder)
                    ratios.append(pair["time per step"] / rigid["time per step"])
                    later.append(pair["later steps"] / rigid["later steps"])
                    pairs.append((rigid, pair))
            rigid, pair = pairs[len(pairs) // 2]
            print("| %s | %d | %d | %.3g s, %.3g s | %.3g s, %.3g s | %.2f, %.2f | %.2f, %.2f "
                  "| %.1f, %.1f | %.2f, %.2f |"
                  % (method, refinements, pair["dofs"], rigid["time per step"],
                     pair["time per step"], rigid["later steps"], pair["later steps"],
                     rigid["solves per step"], pair["solves per step"], rigid["iterations"],
                     pair["iterations"], rigid["krylov"], pair["krylov"],
                     statistics.median(ratios), statistics.median(later)))
            sys.stdout.flush()


if __name__ == "__main__":
    main()
