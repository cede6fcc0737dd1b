#!/usr/bin/python3
"""Hertz contact of two elastic cylinders: an upper cylinder of radius
R1 = 1 (E1 = 1000) pressed by its flat top onto a lower one of radius
R2 = 2 (E2 = 2000), both nu = 0.3, plane stress, the half model x >= 0
with the symmetry line x = 0 (meshes/make_hertz_meshes.py, two_cylinders:
arcs of 2N and 3N segments, graded toward the contact point, non-matching),
the lower cylinder on rollers along its flat bottom, the upper one's top
pushed down by 0.024. Two bodies in contact along a pair (Opposite
boundary ids, the gap measured between the arcs). With P = twice the
reaction of the half model's top, Hertz's closed form for two cylinders is

    a = sqrt(4 P R* / (pi E*)),   p0 = 2 P / (pi a),
    1 / R* = 1 / R1 + 1 / R2,     1 / E* = 1 / E1 + 1 / E2 (plane stress).

The half-width a is the zero of the pressure extrapolated from the last two
nodes in contact (benchmarks/run_hertz_cylinder.py, analyse_hertz()), p0
the pressure at x = 0, and the L2 error of all nodal pressures is taken
against Hertz's profile for the computed load; the L2 difference of the
pressures to those on N = 128 (the arcs' nodes of N are among those of
128) shows the discretisation converging, while the errors against Hertz
level off where the finite bodies differ from Hertz's half-spaces.
Prints the markdown table of doc/benchmarks.md; with --check (the ctest)
it fails unless every error is below 1.5 times its observed value on
N = 16, 32, 64 (BOUNDS) and the difference to N = 128 falls with at least
0.8 times its observed order (ORDERS). --method runs another back end.

    benchmarks/run_hertz_two_cylinders.py [--executable build/viscoplastic_contact]
        [--check] [--meshes 16,32,64] [--reference 128]
        [--method condensed|"full space"]
"""

import argparse
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..")
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(TOP, "meshes"))
from run_hertz_cylinder import analyse_hertz, pressure_difference  # noqa: E402
from make_hertz_meshes import two_cylinders  # noqa: E402

R1, R2, E1, E2, NU, DISPLACEMENT = 1.0, 2.0, 1000.0, 2000.0, 0.3, 0.024
R_STAR = R1 * R2 / (R1 + R2)
E_STAR = 1 / (1 / E1 + 1 / E2)
# The bounds of --check, per mesh N: 1.5 times the errors observed (a:
# 3.92%, 1.51%, 1.72%; p0: 1.43%, 0.93%, 0.94%; L2 against Hertz: 3.45%,
# 3.47%, 2.84%; L2 difference to N = 128: 8.54e-2, 5.53e-2, 2.65e-2 on
# N = 16, 32, 64). Against Hertz the errors level off at about 1.7% in a
# and 0.9% in p0: the bodies are finite (Hertz's are half-spaces).
BOUNDS = {"a error": {16: 0.059, 32: 0.023, 64: 0.026},
          "p0 error": {16: 0.021, 32: 0.014, 64: 0.014},
          "L2 error": {16: 0.052, 32: 0.052, 64: 0.043},
          "L2": {16: 0.128, 32: 0.083, 64: 0.040}}
# The observed orders of the difference to N = 128 (16 -> 32 -> 64).
ORDERS = (0.63, 1.06)

SCENE = """set Dimension = 2
subsection Geometry
  set Cell type = hypercube
  set Mesh file = {mesh}
end
subsection Boundary
  set Clamped boundary ids  =
  set Contact boundary ids  = 3      # the upper arc
  set Loaded boundary ids   =
  set Symmetry boundary ids = 1, 4   # x = 0; rollers under the lower one
  subsection Prescribed displacement 1
    set Boundary ids = 2             # the upper cylinder's flat top
    set Components   = y
    set Displacement = -{displacement} * t
  end
end
subsection Material
  set Material ids    = 1
  set Young's modulus = {e1}
  set Poisson ratio   = {nu}
  set Plasticity      = false
end
subsection Material 2
  set Material ids    = 2
  set Young's modulus = {e2}
  set Poisson ratio   = {nu}
  set Plasticity      = false
end
subsection Loads
  set Body force       = 0; 0
  set Surface traction = 0; 0
end
subsection Contact
  set Opposite boundary ids = 5      # the lower arc
  set Unilateral constraint = true
  set Normal compliance     = false
  set Layer thickness       = 0
end
subsection Time
  set End time  = 1
  set Time step = 1
end
subsection Linear solver
  set Method = {method}
end
subsection Output
  set Output directory = {output}
  set Profile times    = 1
  set Write vtu        = false
end
"""


def run(executable, n, method, folder):
    mesh = os.path.join(folder, "two_cylinders_%d.msh" % n)
    with open(mesh, "w") as f:
        f.write(two_cylinders(n, 3 * n // 2, R1, R2))
    output = os.path.join(folder, "output_%d" % n)
    prm = os.path.join(folder, "two_cylinders_%d.prm" % n)
    with open(prm, "w") as f:
        f.write(SCENE.format(mesh=mesh, displacement=DISPLACEMENT, e1=E1, e2=E2, nu=NU,
                             method=method, output=output))
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("The run on N = %d failed:\n%s" % (n, result.stderr))
    return output, result.stdout


def observed_order(coarse, fine):
    return math.log(coarse["L2"] / fine["L2"]) / math.log(fine["N"] / coarse["N"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--executable",
                        default=os.path.join(TOP, "build", "viscoplastic_contact"))
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--meshes", default="16,32,64")
    parser.add_argument("--method", default="condensed")
    parser.add_argument("--reference", type=int, default=128)
    arguments = parser.parse_args()
    results = []
    with tempfile.TemporaryDirectory() as folder:
        for n in [int(n) for n in arguments.meshes.split(",")] + [arguments.reference]:
            output, _ = run(arguments.executable, n, arguments.method, folder)
            result = analyse_hertz(output, E_STAR, R_STAR)
            result["N"] = n
            results.append(result)
    reference = results.pop()
    for r in results:
        r["L2"] = pressure_difference(r["profile"], reference["profile"])

    print("| N | P | nodes in contact | a | Hertz a | error | p0 | Hertz p0 | error "
          "| L2 error | L2 to N = %d | order |" % arguments.reference)
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for k, r in enumerate(results):
        order = ("%.2f" % observed_order(results[k - 1], r)) if k > 0 else ""
        print("| %d | %.4g | %d | %.4g | %.4g | %.2f%% | %.4g | %.4g | %.2f%% | %.2f%% "
              "| %.2e | %s |"
              % (r["N"], r["P"], r["nodes"], r["a"], r["a exact"], 100 * r["a error"],
                 r["p0"], r["p0 exact"], 100 * r["p0 error"], 100 * r["L2 error"],
                 r["L2"], order))

    if arguments.check:
        failures = []
        for k, r in enumerate(results):
            for key in ("a error", "p0 error", "L2 error", "L2"):
                bound = BOUNDS[key].get(r["N"])
                if bound is not None and r[key] > bound:
                    failures.append("N = %d: %s %.3g above %.3g" % (r["N"], key, r[key], bound))
            if k > 0 and observed_order(results[k - 1], r) < 0.8 * ORDERS[k - 1]:
                failures.append("N = %d: the difference to N = %d falls with order %.2f, "
                                "below 0.8 x %.2f" % (r["N"], arguments.reference,
                                                      observed_order(results[k - 1], r),
                                                      ORDERS[k - 1]))
        if failures:
            sys.exit("\n".join(failures))
        print("a, p0, the L2 error against Hertz and the difference to N = %d within 1.5 "
              "times their observed values; the difference falls with at least 0.8 "
              "times its observed order." % arguments.reference)


if __name__ == "__main__":
    main()
