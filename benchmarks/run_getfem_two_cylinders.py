#!/usr/bin/python3
"""Side by side with GetFEM: Hertz contact of two elastic cylinders
(benchmarks/run_hertz_two_cylinders.py: R1 = 1, E1 = 1000 above, R2 = 2,
E2 = 2000 below, nu = 0.3, plane stress, the half model x >= 0, the top
pushed down by 0.024) on the same meshes (meshes/make_hertz_meshes.py,
two_cylinders(N, 3N/2): non-matching arcs graded toward the contact point)
in this program (mortar with the dual basis, the condensed back end) and in
GetFEM 5.4 (Debian's python3-getfem: one mesh and one displacement field
per body, Q1 elements, the nodal contact brick between non-matching meshes,
node-to-segment with either arc as the slave side, Alart and Curnier's
augmented Lagrangian solved by Newton's method, the model's default direct
solver). GetFEM imports a Gmsh file with its coincident points merged, so
each body goes in a file of its own (the arcs touch at the origin).

Per N: the load P (twice the half model's contact force), the half-width
a (the zero of the pressure extrapolated from the last two nodes in
contact), the peak pressure p0 (the node at x = 0) and the L2 error of the
nodal pressures against Hertz's profile for the computed load, for both;
GetFEM's nodal pressure is its contact force at a node of the slave arc
(K u there, along the arc's normal) over the node's lumped weight (half
its two segments). Node-to-segment contact does not pass the patch test:
its pressure near the contact point depends on which side is the slave,
which the two GetFEM rows show. The
time of each: the program's whole run (its own clock, from reading the
parameters to the last output) and GetFEM's model set-up and solve (in this
process; reading the meshes included).

    benchmarks/run_getfem_two_cylinders.py [--executable build/viscoplastic_contact]
        [--meshes 16,32,64,128]
"""

import argparse
import contextlib
import math
import os
import re
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..")
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(TOP, "meshes"))
from run_hertz_cylinder import analyse_hertz, profile_measures  # noqa: E402
from run_hertz_two_cylinders import (DISPLACEMENT, E1, E2, E_STAR, NU, R1,  # noqa: E402
                                     R2, R_STAR, run)
from make_hertz_meshes import two_cylinders  # noqa: E402


def split_bodies(text):
    """The Gmsh text of each body of two_cylinders (material ids 1, 2), its
    cells' tag 100 + id so that GetFEM's regions of cells and of faces
    differ."""
    lines = text.splitlines()
    nodes = {int(l.split()[0]): l
             for l in lines[lines.index("$Nodes") + 2:lines.index("$EndNodes")]}
    elements = [l.split() for l in
                lines[lines.index("$Elements") + 2:lines.index("$EndElements")]]
    body_of = {int(v): int(f[3]) for f in elements if f[1] == "3" for v in f[5:]}
    bodies = []
    for body in (1, 2):
        own = [f for f in elements if body_of[int(f[5])] == body]
        used = sorted({int(v) for f in own for v in f[5:]})
        out = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$Nodes", str(len(used))]
        out += [nodes[v] for v in used] + ["$EndNodes", "$Elements", str(len(own))]
        for k, f in enumerate(own, 1):
            tags = [str(100 + body)] * 2 if f[1] == "3" else f[3:5]
            out.append(" ".join([str(k)] + f[1:3] + tags + f[5:]))
        out.append("$EndElements")
        bodies.append("\n".join(out) + "\n")
    return bodies


@contextlib.contextmanager
def quiet():
    """GetFEM's solver prints to the standard output of the process."""
    sys.stdout.flush()
    saved = os.dup(1)
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            os.dup2(saved, 1)
            os.close(saved)


def run_getfem(n, folder, slave=1):
    """slave: the body (1 upper, 2 lower) whose arc is GetFEM's slave side,
    on whose nodes the pressure is taken."""
    import getfem as gf
    import numpy as np
    gf.util("trace level", 0)
    start = time.perf_counter()
    files = []
    for k, text in enumerate(split_bodies(two_cylinders(n, 3 * n // 2, R1, R2)), 1):
        files.append(os.path.join(folder, "body_%d.msh" % k))
        with open(files[-1], "w") as f:
            f.write(text)
    model = gf.Model("real")
    meshes, fems, integrations, lames = [], [], [], []
    for k, (name, E) in enumerate(zip(files, (E1, E2)), 1):
        mesh = gf.Mesh("import", "gmsh", name)
        fem = gf.MeshFem(mesh, 2)
        fem.set_classical_fem(1)
        integration = gf.MeshIm(mesh, 2)
        lame = E * NU / ((1 + NU) * (1 - 2 * NU))
        mu = E / (2 * (1 + NU))
        lame = 2 * lame * mu / (lame + 2 * mu)  # plane stress
        model.add_fem_variable("u%d" % k, fem)
        model.add_initialized_data("lambda%d" % k, [lame])
        model.add_initialized_data("mu%d" % k, [mu])
        model.add_isotropic_linearized_elasticity_brick(integration, "u%d" % k,
                                                        "lambda%d" % k, "mu%d" % k)
        model.add_normal_Dirichlet_condition_with_multipliers(integration, "u%d" % k, 1, 1)
        meshes.append(mesh)
        fems.append(fem)
        integrations.append(integration)
        lames.append((lame, mu))
    model.add_initialized_data("top", [-DISPLACEMENT])
    model.add_normal_Dirichlet_condition_with_multipliers(integrations[0], "u1", 1, 2, "top")
    model.add_normal_Dirichlet_condition_with_multipliers(integrations[1], "u2", 1, 4)
    model.add_initialized_data("r", [E1])
    with quiet():
        model.add_nodal_contact_between_nonmatching_meshes_brick(
            integrations[0], integrations[1], "u1", "u2", "lambda_n", "r", 3, 5,
            int(slave == 1), int(slave == 2))
    # The residual's floor of round-off is near 2e-9 on N = 32 (of 1 at the
    # start): 1e-7 stops at it.
    with quiet():
        iterations, converged = model.solve("max_res", 1e-7, "max_iter", 50)
    elapsed = time.perf_counter() - start
    if not converged:
        sys.exit("GetFEM's Newton iteration did not converge on N = %d" % n)

    # The contact force at the slave arc's nodes: K u of its body.
    body = slave - 1
    data = gf.MeshFem(meshes[body], 1)
    data.set_classical_fem(0)
    ones = np.ones(data.nbdof())
    stiffness = gf.asm("linear elasticity", integrations[body], fems[body], data,
                       lames[body][0] * ones, lames[body][1] * ones)
    force = stiffness.mult(model.variable("u%d" % slave))
    arc = fems[body].basic_dof_on_region(3 if slave == 1 else 5)
    points = fems[body].basic_dof_nodes(arc)
    # The arc's centre and radius: its outward normal is (x - c) / R.
    centre, radius = (R1, R1) if slave == 1 else (-R2, R2)
    nodes = sorted({(points[0][k], points[1][k], int(arc[k]))
                    for k in range(0, len(arc), 2)})
    rows = []
    for j, (x, y, dof) in enumerate(nodes):
        weight = sum(math.hypot(x - nodes[i][0], y - nodes[i][1]) / 2
                     for i in (j - 1, j + 1) if 0 <= i < len(nodes))
        # The force along the arc's inward normal: the reactions of x = 0
        # and of the top or bottom are tangential to the arc where they act.
        pressure = -(force[dof] * x + force[dof + 1] * (y - centre)) / radius
        rows.append((x, max(pressure, 0.0) / weight, weight))
    return rows, elapsed, model.nbdof(), iterations


def run_program(executable, n, folder):
    output, stdout = run(executable, n, "condensed", folder)
    wall = float(re.search(r"Total wallclock time elapsed since start *\| *([0-9.eE+-]+)s",
                           stdout).group(1))
    dofs = int(re.search(r"([0-9]+) displacement dofs", stdout).group(1))
    measures = analyse_hertz(output, E_STAR, R_STAR)
    measures["iterations"] = int(re.search(r"active-set iterations: ([0-9]+)",
                                           stdout).group(1))
    return measures, wall, dofs


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--executable",
                        default=os.path.join(TOP, "build", "viscoplastic_contact"))
    parser.add_argument("--meshes", default="16,32,64,128")
    arguments = parser.parse_args()
    try:
        import getfem  # noqa: F401
    except ImportError:
        sys.exit("GetFEM's Python interface is missing: apt-get install python3-getfem")

    print("| N | code | dofs | P | a | error | p0 | error | L2 error | time [s] "
          "| iterations |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for n in (int(v) for v in arguments.meshes.split(",")):
        with tempfile.TemporaryDirectory() as folder:
            ours, wall, dofs = run_program(arguments.executable, n, folder)
            runs = [("this program", ours, wall, dofs, "%d active-set" % ours["iterations"])]
            for slave, name in ((1, "GetFEM, upper slave"), (2, "GetFEM, lower slave")):
                rows, seconds, count, newton = run_getfem(n, folder, slave)
                # The load of the half model twice; nodes out of contact
                # have a force of round-off.
                load = 2 * sum(p * w for _, p, w in rows)
                runs.append((name,
                             profile_measures(rows, load, E_STAR, R_STAR, 1e-6 * rows[0][1]),
                             seconds, count, "%d Newton" % newton))
        for name, r, seconds, count, steps in runs:
            print("| %d | %s | %d | %.4g | %.4g | %.2f%% | %.4g | %.2f%% | %.2f%% | %.3g "
                  "| %s |"
                  % (n, name, count, r["P"], r["a"],
                     100 * abs(r["a"] - r["a exact"]) / r["a exact"], r["p0"],
                     100 * abs(r["p0"] - r["p0 exact"]) / r["p0 exact"],
                     100 * r["L2 error"], seconds, steps))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
