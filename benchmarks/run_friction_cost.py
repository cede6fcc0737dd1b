#!/usr/bin/python3
"""What friction costs: the 3D sliding block (parameters/sliding_block_3d.prm,
hexahedra, Subdivisions N) with Coulomb friction against the same scene
frictionless, in pairs run one after the other (the machine is shared and
noisy: only ratios measured side by side mean anything).

For each N and back end it prints the time per step of the time loop
(without output, the program's own measurement), the active-set
iterations and the Krylov iterations per step of both, and the median
over the pairs of the ratio frictional / frictionless. The frictionless
block slides on the support without resistance; its top, held in all
components, keeps it in place, so both scenes have the same operator, the
same mesh and the same steps. --compare picks other pairs of scenes: a
static coefficient 0.5 against the same one weakening to 0.3 with the
slip (static,weakening), or the sliding block against the block held on
a support that moves under it (Coulomb,moving).

--scene hertz_sphere: the Hertz sphere's ramp instead (parameters/
hertz_sphere.prm, the rigid sphere pressed into the quarter block by
0.01 t in 4 steps, hexahedra graded toward the contact point, N cells per
edge, meshes/make_hertz_sphere_meshes.py), frictionless against Coulomb
friction mu = 0.3 (frictionless,Coulomb only). Unlike the sliding block,
whose frictionless steps repeat the last one (its extrapolated start is
the solution), both ramps grow their contact zone in every step, and with
friction the surface under the sphere, which moves inward on the
frictionless block (nu = 0.3), sticks at the centre and slips in a ring
at the edge of the zone.

    benchmarks/run_friction_cost.py [--executable build/viscoplastic_contact]
        [--scene sliding_block | hertz_sphere]
        [--meshes 8,16,24] [--pairs 3] [--methods "full space,condensed"]
        [--compare frictionless,Coulomb | static,weakening | Coulomb,moving]
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
from make_hertz_sphere_meshes import hertz_sphere_block  # noqa: E402


def set_entry(text, entry, value):
    """The entry replaced; Write vtu, which the shipped file leaves at its
    default, added to subsection Output."""
    if entry == "Write vtu" and "set Write vtu" not in text:
        return text.replace("subsection Output\n",
                            "subsection Output\n  set Write vtu = %s\n" % value)
    return re.sub(r"(?m)^(\s*set %s\s*=)[^#\n]*" % re.escape(entry),
                  r"\g<1> %s " % value, text)


# The scenes compared: the block frictionless, with Coulomb friction
# (mu = 0.3), with a static coefficient 0.5 and with 0.5 weakening to 0.3
# over a slip of 0.005 (the same scene without and with slip weakening),
# and with mu = 0.3 on a support that moves under the block held at its top
# (the Coulomb scene seen from the block: the same relative motion).
SCENES = {"frictionless": ("frictionless", 0, ""),
          "Coulomb": ("Coulomb", 0.3, ""),
          "static": ("Coulomb", 0.5, ""),
          "weakening": ("Coulomb", 0.5,
                        "\n  set Weakening slips = 0, 0.005"
                        "\n  set Weakening factors = 1, 0.6"),
          "moving": ("Coulomb", 0.3,
                     "\n  set Obstacle motion = -0.02 * max(t - 1, 0); 0; 0")}


def hertz_sphere_prm(n, method, scene, folder):
    """The Hertz sphere's ramp on N graded hexahedra per edge, frictionless
    or with Coulomb friction (mu = 0.3)."""
    law, coefficient, _ = SCENES[scene]
    mesh = os.path.join(folder, "hertz_sphere_%d.msh" % n)
    if not os.path.exists(mesh):
        with open(mesh, "w") as f:
            f.write(hertz_sphere_block(n, False, 1.0, False))
    entries = {(("Geometry",), "Mesh file"): mesh,
               (("Linear solver",), "Method"): method,
               (("Contact",), "Tangential law"): law,
               (("Output",), "Output directory"): os.path.join(
                   folder, "%s_%d" % (scene, len(os.listdir(folder)))),
               (("Output",), "Profile times"): "",
               (("Output",), "Write vtu"): "false",
               (("Output",), "Measure cost ratios"): "true"}
    if coefficient:
        entries[(("Contact",), "Friction coefficient")] = coefficient
    with open(os.path.join(TOP, "parameters", "hertz_sphere.prm")) as f:
        return set_prm_entries(f.read(), entries)


def sliding_block_prm(n, method, scene, folder):
    """The sliding block on N hexahedra per edge of its height."""
    law, coefficient, extra = SCENES[scene]
    with open(os.path.join(TOP, "parameters", "sliding_block_3d.prm")) as f:
        text = f.read()
    for entry, value in (("Subdivisions", n), ("Method", method),
                         ("Tangential law", law),
                         ("Friction coefficient", coefficient),
                         ("Output directory", os.path.join(
                             folder, "%s_%d" % (scene, len(os.listdir(folder))))),
                         ("Write vtu", "false"), ("Profile times", "")):
        text = set_entry(text, entry, value)
    text = re.sub(r"(?m)^(\s*set Friction coefficient\s*=[^\n]*)",
                  lambda m: m.group(1) + extra, text)
    if scene == "moving":
        text = set_entry(text, "Displacement", "0; 0; -0.01 * min(t, 1)")
    # The time loop comes with the Cost measurement block.
    return text.replace("subsection Output\n",
                        "subsection Output\n  set Measure cost ratios = true\n")


def run(executable, n, method, scene, folder, geometry):
    text = (hertz_sphere_prm if geometry == "hertz_sphere"
            else sliding_block_prm)(n, method, scene, folder)
    law = scene
    prm = os.path.join(folder, "%s.prm" % law)
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("The %s run on N = %d (%s) failed:\n%s"
                 % (law, n, method, result.stderr))
    loop = float(re.search(r"time loop \(without output\): *([0-9.eE+-]+) s",
                           result.stdout).group(1))
    output = re.search(r"(?m)^\s*set Output directory\s*=\s*(\S+)", text).group(1)
    with open(os.path.join(output, "time_series.csv")) as f:
        steps = list(csv.DictReader(f))
    # The mesh of the run: the last of the initial cycles if it takes them
    # (its header names the coarsest).
    found = (re.search(r"Initial cycles done: [0-9]+ cells, ([0-9]+) dofs",
                       result.stdout)
             or re.search(r"([0-9]+) displacement dofs", result.stdout))
    dofs = int(found.group(1)) if found else 0
    return {"time per step": loop / len(steps), "dofs": dofs,
            "iterations": sum(int(s["active_set_iterations"])
                              for s in steps) / len(steps),
            "krylov": sum(int(s["krylov_iterations"])
                          for s in steps) / len(steps)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--executable", default=os.path.join(
        TOP, "build", "viscoplastic_contact"))
    parser.add_argument("--scene", default="sliding_block",
                        choices=("sliding_block", "hertz_sphere"))
    parser.add_argument("--meshes", default="8,16,24")
    parser.add_argument("--pairs", type=int, default=3)
    parser.add_argument("--methods", default="full space,condensed")
    parser.add_argument("--compare", default="frictionless,Coulomb",
                        help="baseline,candidate among " + ", ".join(SCENES))
    arguments = parser.parse_args()
    baseline, candidate = arguments.compare.split(",")
    if (arguments.scene == "hertz_sphere"
            and (baseline, candidate) != ("frictionless", "Coulomb")):
        parser.error("--scene hertz_sphere compares frictionless,Coulomb only")
    print("| back end | N | dofs | time per step: %s, %s | "
          "active-set iterations per step | Krylov iterations per step | "
          "ratio %s / %s (median of %d pairs) |"
          % (baseline, candidate, candidate, baseline, arguments.pairs))
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for method in arguments.methods.split(","):
        for n in (int(v) for v in arguments.meshes.split(",")):
            ratios, pairs = [], []
            with tempfile.TemporaryDirectory() as folder:
                for _ in range(arguments.pairs):
                    plain = run(arguments.executable, n, method, baseline,
                                folder, arguments.scene)
                    coulomb = run(arguments.executable, n, method, candidate,
                                  folder, arguments.scene)
                    ratios.append(coulomb["time per step"]
                                  / plain["time per step"])
                    pairs.append((plain, coulomb))
            plain, coulomb = pairs[len(pairs) // 2]
            print("| %s | %d | %d | %.3g s, %.3g s | %.2f, %.2f | %.1f, %.1f "
                  "| %.2f |" % (method, n, plain["dofs"],
                                plain["time per step"],
                                coulomb["time per step"], plain["iterations"],
                                coulomb["iterations"], plain["krylov"],
                                coulomb["krylov"], statistics.median(ratios)))
            sys.stdout.flush()


if __name__ == "__main__":
    main()
