#!/usr/bin/python3
"""Weak scaling of memory: the cube on tetrahedra (parameters/
cube_3d_tetrahedra.prm, Kuhn's six tetrahedra per cube, full space back
end, one time step) with about the same number of cells and dofs per rank, on 1, 2, 4
and 8 ranks (oversubscribed on a small machine: memory and iteration
counts do not depend on the cores).

For each rank count three runs:
  * generated, groups: the generated box, `Mesh group size = 0` (the
    default: one rank per node builds the whole mesh and hands out the
    parts; on one machine that is one group root);
  * generated, every rank: `Mesh group size = 1`, every rank builds the
    whole mesh itself (what the program did before groups);
  * Gmsh, groups: the same mesh written to a Gmsh file by this script and
    read by the group root.

and, to check that the results do not depend on the rank count, the
generated box of the one-rank run on every rank count ("same mesh").

It prints, per run, the peak resident memory (VmHWM) after the mesh and
over the whole run, of the group roots and of the other ranks (the
program's "peak memory" lines of Print timing summary), the active-set
iterations per step, the CG iterations per solve and the final
displacement norms, and then the checks of doc/scaling.md: the members' peak within +8% of the one-rank
figure, iteration counts within +-10% of one rank's, results identical
across the rank counts (relative 1e-6).

    benchmarks/run_mesh_memory_scaling.py [--executable build/viscoplastic_contact]
        [--ranks 1,2,4,8] [--dofs-per-rank 100000] [--markdown FILE]
"""

import argparse
import csv
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..")
sys.path.insert(0, os.path.join(TOP, "meshes"))
from gmsh_format import gmsh_elements_text  # noqa: E402

NUMBER = r"([0-9.eE+-]+)"


def set_entry(text, entry, value):
    """The entry replaced, or added at the top of its subsection."""
    pattern = r"(?m)^(\s*set %s\s*=)[^#\n]*" % re.escape(entry)
    if re.search(pattern, text):
        return re.sub(pattern, r"\g<1> %s " % value, text)
    subsection = {"Mesh group size": "Geometry", "Mesh file": "Geometry",
                  "Profile times": "Output",
                  "Initial cycles": "Mesh adaptation"}[entry]
    if "subsection %s\n" % subsection not in text:
        text += "\nsubsection %s\nend\n" % subsection
    return text.replace("subsection %s\n" % subsection,
                        "subsection %s\n  set %s = %s\n"
                        % (subsection, entry, value), 1)


def kuhn_cube_gmsh(n, path):
    """The unit cube of n^3 cubes, each cut into Kuhn's six tetrahedra (as
    the program's generated box), as a Gmsh file: boundary triangles of
    x = 0, z = 0 and z = 1 tagged 1, 5 and 6."""
    def index(i, j, k):
        return (k * (n + 1) + j) * (n + 1) + i + 1
    nodes = [(index(i, j, k), i / n, j / n, k / n)
             for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)]
    position = {node[0]: node[1:] for node in nodes}

    def positive(tet):
        a, b, c, d = (position[v] for v in tet)
        e = [[b[x] - a[x] for x in range(3)], [c[x] - a[x] for x in range(3)],
             [d[x] - a[x] for x in range(3)]]
        det = (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1])
               - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0])
               + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]))
        return tet if det > 0 else (tet[0], tet[1], tet[3], tet[2])

    orders = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    cells, boundary = [], []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                for order in orders:
                    corner = [i, j, k]
                    tet = [index(*corner)]
                    for axis in order:
                        corner[axis] += 1
                        tet.append(index(*corner))
                    cells.append((4, 10) + positive(tuple(tet)))
                    if i > 0 and 0 < k < n - 1:
                        continue
                    # A cube on a tagged plane: the faces of its
                    # tetrahedra that lie on the plane.
                    for skip in range(4):
                        face = [v for m, v in enumerate(tet) if m != skip]
                        points = [position[v] for v in face]
                        for axis, value, tag in ((0, 0., 1), (2, 0., 5),
                                                 (2, 1., 6)):
                            if all(abs(p[axis] - value) < 1e-12
                                   for p in points):
                                boundary.append((2, tag) + tuple(face))
    with open(path, "w") as f:
        f.write(gmsh_elements_text(nodes, boundary, cells,
                                   ((1, "clamped"), (5, "contact"),
                                    (6, "loaded")), ((10, "body"),)))


def run(executable, ranks, n, variant, folder):
    with open(os.path.join(TOP, "parameters", "cube_3d_tetrahedra.prm")) as f:
        text = f.read()
    name = "%s_%d_%d" % (variant, ranks, n)
    entries = [("Subdivisions", n), ("Method", "full space"),
               ("End time", 0.03125), ("Profile times", ""),
               ("Write vtu", "false"), ("Print timing summary", "true"),
               ("Output directory", os.path.join(folder, name)),
               ("Mesh group size", 1 if variant == "every_rank" else 0),
               # One mesh per run: no coarser meshes first for step 1 (a
               # generated box would take them, a Gmsh file cannot).
               ("Initial cycles", 0)]
    # (variant same_mesh: the generated box with groups.)
    if variant == "gmsh":
        mesh = os.path.join(folder, "cube_%d.msh" % n)
        if not os.path.exists(mesh):
            kuhn_cube_gmsh(n, mesh)
        entries += [("Mesh file", mesh), ("Clamped boundary ids", 1),
                    ("Contact boundary ids", 5), ("Loaded boundary ids", 6)]
    for entry, value in entries:
        text = set_entry(text, entry, value)
    prm = os.path.join(folder, name + ".prm")
    with open(prm, "w") as f:
        f.write(text)
    command = [executable, prm]
    if ranks > 1:
        command = ["mpirun", "--oversubscribe", "-np", str(ranks)] + command
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    result = subprocess.run(command, capture_output=True, text=True, env=env)
    if result.returncode != 0:
        sys.exit("The run %s failed:\n%s" % (name, result.stderr))
    out = result.stdout

    def memory(when):
        line = re.search(r"peak memory %s \[MB\]: sum over ranks %s, largest "
                         r"rank %s, largest group root %s, largest member "
                         r"(\S+)" % (when, NUMBER, NUMBER, NUMBER), out)
        member = None if line.group(4) == "none" else float(line.group(4))
        return float(line.group(3)), member

    steps = re.search(r"active-set iterations: (\d+) in (\d+) steps", out)
    solves = re.search(r"back end: (\d+) solves, (\d+) Krylov", out)
    dofs = re.search(r"Mesh: (\d+) Tet cells, (\d+) displacement dofs", out)
    with open(os.path.join(folder, name, "time_series.csv")) as f:
        series = list(csv.DictReader(f))
    return {"ranks": ranks, "variant": variant, "n": n, "series": series,
            "cells": int(dofs.group(1)), "dofs": int(dofs.group(2)),
            "mesh_root": memory("after the mesh")[0],
            "mesh_member": memory("after the mesh")[1],
            "run_root": memory("over the run")[0],
            "run_member": memory("over the run")[1],
            "active_set": int(steps.group(1)) / int(steps.group(2)),
            "mesh_time": float(re.search(r"Mesh built in %s s" % NUMBER,
                                         out).group(1)),
            "cg": int(solves.group(2)) / int(solves.group(1)),
            "final": re.search(r"^Final displacement: .*$", out,
                               re.M).group(0)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--executable",
                        default=os.path.join(TOP, "build",
                                             "viscoplastic_contact"))
    parser.add_argument("--ranks", default="1,2,4,8")
    parser.add_argument("--dofs-per-rank", type=float, default=1e5)
    parser.add_argument("--markdown", help="write the tables to this file")
    args = parser.parse_args()

    rows = []
    rank_counts = [int(r) for r in args.ranks.split(",")]
    with tempfile.TemporaryDirectory() as folder:
        # 3 (n + 1)^3 dofs, about dofs-per-rank of them per rank on the
        # first rank count; then the same number of cells (6 n^3) per rank.
        n_first = round((rank_counts[0] * args.dofs_per_rank / 3)
                        ** (1 / 3)) - 1
        for ranks in rank_counts:
            n = round(n_first * (ranks / rank_counts[0]) ** (1 / 3))
            for variant in ("groups", "every_rank", "gmsh"):
                rows.append(run(args.executable, ranks, n, variant, folder))
                r = rows[-1]
                print("%-10s %d ranks, N = %d, %d dofs: after the mesh root "
                      "%.0f member %s MB; over the run root %.0f member %s "
                      "MB; %.2f active-set its/step, %.1f CG its/solve"
                      % (variant, ranks, n, r["dofs"], r["mesh_root"],
                         r["mesh_member"], r["run_root"], r["run_member"],
                         r["active_set"], r["cg"]), flush=True)
        # The mesh of the first rank count on all the others.
        same_mesh = [run(args.executable, ranks, n_first, "same_mesh",
                         folder) for ranks in rank_counts[1:]]


    def fmt(value):
        return "-" if value is None else "%.0f" % value
    lines = ["| mesh | ranks | N | cells per rank | dofs per rank | mesh "
             "built in [s] | after the mesh: root / largest member [MB] | "
             "whole run: root / largest member [MB] | active-set its per "
             "step | CG its per solve |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    label = {"groups": "generated, groups", "every_rank":
             "generated, every rank builds", "gmsh": "Gmsh file, groups"}
    for r in rows:
        lines.append("| %s | %d | %d | %.0f | %.0f | %.1f | %s / %s | %s / %s "
                     "| %.2f | %.1f |"
                     % (label[r["variant"]], r["ranks"], r["n"],
                        r["cells"] / r["ranks"], r["dofs"] / r["ranks"],
                        r["mesh_time"], fmt(r["mesh_root"]),
                        fmt(r["mesh_member"]), fmt(r["run_root"]),
                        fmt(r["run_member"]), r["active_set"], r["cg"]))
    # The checks, against the one-rank run of the same variant.
    checks = []
    for variant in ("groups", "gmsh", "every_rank"):
        own = [r for r in rows if r["variant"] == variant]
        one = [r for r in own if r["ranks"] == 1]
        if not one:
            continue
        one = one[0]
        for r in own[1:]:
            # Every rank is a root when every rank builds the mesh.
            member = r["run_member"] or r["run_root"]
            growth = member / one["run_root"] - 1
            checks.append("%s, %d ranks: members' peak %+.1f%% of one rank's "
                          "(after the mesh %+.1f%%), roots' %+.1f%%; active-set "
                          "its %+.1f%%, CG its %+.1f%% (on a finer mesh)"
                          % (label[variant], r["ranks"], 100 * growth,
                             100 * ((r["mesh_member"] or r["mesh_root"])
                                    / one["mesh_root"] - 1),
                             100 * (r["run_root"] / one["run_root"] - 1),
                             100 * (r["active_set"] / one["active_set"] - 1),
                             100 * (r["cg"] / one["cg"] - 1)))
    # The same mesh on every rank count: every column of time_series.csv
    # but the timings and the Krylov iterations, relative 1e-6 with an
    # absolute floor of 1e-9 (the tolerances of the ctest rank comparisons).
    reference = rows[0]
    for r in same_mesh:
        worst = 0.
        for a, b in zip(reference["series"], r["series"]):
            for column, value in a.items():
                if column in ("wall_time", "krylov_iterations"):
                    continue
                x, y = float(value), float(b[column])
                worst = max(worst, abs(x - y) / max(abs(x), 1e-9 / 1e-6))
        checks.append("the %d-rank mesh (N = %d) on %d ranks: largest "
                      "relative difference in time_series.csv %.1e (bound "
                      "1e-6)%s; active-set its %+.1f%%, CG its %+.1f%% "
                      "(bound +-10%%)"
                      % (reference["ranks"], reference["n"], r["ranks"],
                         worst, "" if worst <= 1e-6 else ": FAILED",
                         100 * (r["active_set"] / reference["active_set"] - 1),
                         100 * (r["cg"] / reference["cg"] - 1)))
    # The generated and the Gmsh mesh of one rank count are the same mesh.
    for ranks in rank_counts:
        finals = {r["variant"]: r["final"] for r in rows
                  if r["ranks"] == ranks}
        checks.append("%d ranks, generated and Gmsh mesh: %s" % (
            ranks, "the same final norms" if len(set(finals.values())) == 1
            else "DIFFERENT final norms %s" % finals))
    table = "\n".join(lines) + "\n\n" + "\n".join("* " + c for c in checks)
    print(table)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(table + "\n")


if __name__ == "__main__":
    main()
