#!/usr/bin/python3
"""Hertz contact of a cylinder on a rigid plane (parameters/hertz_cylinder.prm)
on the meshes N = 16, 32, 64 of meshes/make_hertz_meshes.py, in plane stress
and in plane strain, against the closed form: with P = twice the reaction
of the half model's top,

    a = sqrt(4 P R / (pi E*)),   p0 = 2 P / (pi a),
    E* = E (plane stress),  E* = E / (1 - nu^2) (plane strain).

The numerical half-width is the zero of the pressure extrapolated from the
last two nodes in contact with the Hertz shape (p^2 linear in x^2), not the
last node in contact (whose error is a cell); the numerical peak pressure is
the pressure of the node at x = 0. The L2 error of all nodal pressures
against Hertz's profile p0 sqrt(1 - x^2/a^2) for the computed load (lumped
weights) is printed with its observed order. Prints the markdown table of
doc/benchmarks.md and, with --figure FILE, draws the errors against the
mesh size and against the run time (the program's own wall clock: mesh,
set-up with the factorisation, one step at the full load; not the start of
the process). With --check (the ctest) it fails
unless every error is below 1.5 times its observed value on its mesh
(BOUNDS) and the error in a falls from mesh to mesh, and unless on meshes
fitted to a = 0.1 (N = 16, 32, 64, plane stress) the L2 error of the
pressure against Hertz and its difference to the finite body on N = 256
fall with at least 0.8 times their observed orders (FITTED_ORDERS). --meshes runs other N (generated if not
shipped); --fitted A uses meshes fitted to the half-width A
(meshes/make_hertz_meshes.py); --reference N also runs the finite body on
mesh N and prints the L2 difference of each pressure profile to that one.

    benchmarks/run_hertz_cylinder.py [--executable build/viscoplastic_contact]
        [--figure doc/figures/hertz_cylinder.png] [--check]
        [--model "plane stress"|"plane strain"|both] [--meshes 16,32,64]
        [--fitted 0.1] [--reference 256]
"""

import argparse
import csv
import glob
import math
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..")
E, NU, R = 1000.0, 0.3, 1.0
MODELS = ("plane stress", "plane strain")
# The bounds of --check, per mesh N: 1.5 times the largest error observed
# over both models (a: 3.12e-2, 1.82e-2, 1.25e-2; p0: 1.64e-2, 2.23e-3,
# 2.22e-3 on N = 16, 32, 64).
BOUNDS = {"a": {16: 0.047, 32: 0.028, 64: 0.019},
          "p0": {16: 0.025, 32: 0.0034, 64: 0.0034}}
# On the fitted meshes N = 16 -> 32 -> 64: the observed orders of the
# pressure's L2 error against Hertz (1.41, 2.02) and of its difference to
# N = 256 (1.06, 1.09); --check requires 0.8 times each.
FITTED_ORDERS = {"L2 error": (1.41, 2.02), "L2": (1.06, 1.09)}
# The half-width the fitted meshes of --check are fitted to.
FITTED_A = 0.1


def set_entry(text, entry, value):
    return re.sub(r"(?m)^(\s*set %s\s*=)[^#\n]*" % re.escape(entry),
                  r"\g<1> %s " % value, text)


def mesh_file(n, folder, fitted=None):
    """The shipped mesh of N = n, or one written into folder (fitted to the
    half-width fitted, if given)."""
    shipped = os.path.join(TOP, "meshes", "hertz_cylinder_%d.msh" % n)
    if os.path.exists(shipped) and not fitted:
        return os.path.abspath(shipped)
    sys.path.insert(0, os.path.join(TOP, "meshes"))
    from make_hertz_meshes import quarter_disk
    written = os.path.join(folder, "hertz_cylinder_%d.msh" % n)
    with open(written, "w") as f:
        f.write(quarter_disk(n, fitted))
    return written


def run(executable, n, model, folder, fitted=None):
    with open(os.path.join(TOP, "parameters", "hertz_cylinder.prm")) as f:
        text = f.read()
    text = re.sub(r"(?m)^(set Dimension = 2)$",
                  r"\g<1>\nset Plane model = %s" % model, text)
    text = set_entry(text, "Mesh file", mesh_file(n, folder, fitted))
    text = set_entry(text, "Output directory", os.path.join(folder, "output"))
    text = set_entry(text, "Time step", 1)
    text = set_entry(text, "Profile times", 1)
    text = set_entry(text, "Write vtu", "false")
    prm = os.path.join(folder, "hertz.prm")
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("The run on N = %d failed:\n%s" % (n, result.stderr))
    loop = re.search(r"Total wallclock time elapsed since start *\| *([0-9.eE+-]+)s",
                     result.stdout)
    return os.path.join(folder, "output"), float(loop.group(1)) if loop else 0.


def analyse(output, model):
    e_star = E if model == "plane stress" else E / (1 - NU ** 2)
    return analyse_hertz(output, e_star, R)


def analyse_hertz(output, e_star, radius):
    """The load P (twice the reaction of the half model's top), the
    half-width a and the peak pressure p0 of the last profile against
    Hertz's a = sqrt(4 P radius / (pi e_star)), p0 = 2 P / (pi a), and the
    L2 error of all nodal pressures against Hertz's profile."""
    with open(os.path.join(output, "time_series.csv")) as f:
        last = list(csv.DictReader(f))[-1]
    load = 2 * abs(float(last["reaction_prescribed_1_y"]))
    profile = sorted(glob.glob(os.path.join(output, "contact_profile_*.csv")))[-1]
    with open(profile) as f:
        rows = sorted((float(r["x"]), float(r["contact_pressure"]),
                       float(r["weight"])) for r in csv.DictReader(f))
    return profile_measures(rows, load, e_star, radius)


def profile_measures(rows, load, e_star, radius, in_contact=0.0):
    """analyse_hertz() of a profile of nodes (x, p, w) sorted in x and a
    load; a node is in contact where p > in_contact."""
    nodes = [(x, p) for x, p, _ in rows]
    k = max(i for i, (_, p) in enumerate(nodes) if p > in_contact)
    (x1, p1), (x2, p2) = nodes[k - 1], nodes[k]
    a = math.sqrt(x2 ** 2 + p2 ** 2 * (x2 ** 2 - x1 ** 2) / (p1 ** 2 - p2 ** 2))
    a_exact = math.sqrt(4 * load * radius / (math.pi * e_star))
    p0_exact = 2 * load / (math.pi * a_exact)
    # All nodal pressures against Hertz's profile p0 sqrt(1 - x^2/a^2) for
    # the computed load, in the norm of the lumped weights.
    difference = norm = 0.0
    for x, p, w in rows:
        exact = p0_exact * math.sqrt(max(0.0, 1 - x ** 2 / a_exact ** 2))
        difference += w * (p - exact) ** 2
        norm += w * exact ** 2
    return {"P": load, "a": a, "a exact": a_exact, "p0": nodes[0][1],
            "L2 error": math.sqrt(difference / norm),
            "p0 exact": p0_exact, "nodes": k + 1, "profile": rows,
            "a error": abs(a - a_exact) / a_exact,
            "p0 error": abs(nodes[0][1] - p0_exact) / p0_exact}


def pressure_difference(coarse, fine):
    """|p_coarse - p_fine| / |p_fine| in the lumped L2 norm of the fine arc:
    the coarse nodal pressures interpolated linearly in x at the fine
    nodes (the arc nodes of N are among those of 2N)."""
    xs = [x for x, _, _ in coarse]
    difference = norm = 0.0
    for x, p, w in fine:
        j = min(max(1, sum(1 for c in xs if c <= x)), len(xs) - 1)
        (x0, p0, _), (x1, p1, _) = coarse[j - 1], coarse[j]
        interpolated = p0 + (p1 - p0) * (x - x0) / (x1 - x0)
        difference += w * (interpolated - p) ** 2
        norm += w * p ** 2
    return math.sqrt(difference / norm)


def run_series(executable, model, meshes, fitted=None):
    """The runs on the meshes N, analysed, with N and the run time."""
    results = []
    for n in meshes:
        with tempfile.TemporaryDirectory() as folder:
            output, wall = run(executable, n, model, folder, fitted)
            result = analyse(output, model)
        result["N"], result["wall"] = n, wall
        results.append(result)
    return results


def add_reference_differences(executable, model, results, n, fitted=None):
    """r["L2"]: the L2 difference of each run's pressure to that of the
    finite body on mesh n."""
    with tempfile.TemporaryDirectory() as folder:
        output, _ = run(executable, n, model, folder, fitted)
        reference = analyse(output, model)["profile"]
    for r in results:
        r["L2"] = pressure_difference(r["profile"], reference)


def observed_order(coarse, fine, key):
    return math.log(coarse[key] / fine[key]) / math.log(fine["N"] / coarse["N"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--executable", default=os.path.join(
        TOP, "build", "viscoplastic_contact"))
    parser.add_argument("--figure")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--model", choices=MODELS + ("both",), default="both")
    parser.add_argument("--meshes", default="16,32,64",
                        help="the N to run; those not in meshes/ are "
                             "generated by meshes/make_hertz_meshes.py")
    parser.add_argument("--fitted", type=float,
                        help="meshes fitted to this contact half-width "
                             "(meshes/make_hertz_meshes.py), N a multiple of 4")
    parser.add_argument("--reference", type=int,
                        help="also the finite body's reference on this N: the "
                             "L2 difference of each pressure profile to it")
    arguments = parser.parse_args()
    models = MODELS if arguments.model == "both" else (arguments.model,)
    runs = {model: run_series(arguments.executable, model,
                              [int(n) for n in arguments.meshes.split(",")],
                              arguments.fitted) for model in models}
    print("| model | N | nodes in contact | P | a | Hertz a | error | p0 "
          "| Hertz p0 | error | run time |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for model, results in runs.items():
        for r in results:
            print("| %s | %d | %d | %.5f | %.5f | %.5f | %.2e | %.3f | %.3f | "
                  "%.2e | %.3f s |" % (model, r["N"], r["nodes"], r["P"],
                                       r["a"], r["a exact"], r["a error"],
                                       r["p0"], r["p0 exact"], r["p0 error"],
                                       r["wall"]))
    print()
    print("| model | N | L2 error of the pressure against Hertz | observed "
          "order |")
    print("| --- | --- | --- | --- |")
    for model, results in runs.items():
        for i, r in enumerate(results):
            order = ("%.2f" % math.log(results[i - 1]["L2 error"]
                                       / r["L2 error"], r["N"]
                                       / results[i - 1]["N"])
                     if i > 0 else "")
            print("| %s | %d | %.3e | %s |" % (model, r["N"], r["L2 error"],
                                              order))
    print()
    for model, results in runs.items():
        for i in range(1, len(results)):
            print("%s, observed order N = %d -> %d: a %.2f, p0 %.2f" % (
                model, results[i - 1]["N"], results[i]["N"],
                math.log(results[i - 1]["a error"] / results[i]["a error"], 2),
                math.log(results[i - 1]["p0 error"] / results[i]["p0 error"],
                         2)))
    if arguments.reference:
        print("| model | N | L2 difference of the pressure to N = %d | "
              "observed order |" % arguments.reference)
        print("| --- | --- | --- | --- |")
        for model, results in runs.items():
            add_reference_differences(arguments.executable, model, results,
                                      arguments.reference, arguments.fitted)
            for i, r in enumerate(results):
                print("| %s | %d | %.2e | %s |" % (
                    model, r["N"], r["L2"],
                    "%.2f" % observed_order(results[i - 1], r, "L2") if i else ""))
    if arguments.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        figure, axes = plt.subplots(1, 2, figsize=(10, 4))
        for model, results in runs.items():
            style = "o-" if model == "plane stress" else "s--"
            for key, label in (("a error", "half-width a"),
                               ("p0 error", "peak pressure p0")):
                label = "%s, %s" % (label, model)
                axes[0].loglog([1 / r["N"] for r in results],
                               [r[key] for r in results], style, label=label)
                axes[1].loglog([r["wall"] for r in results],
                               [r[key] for r in results], style, label=label)
        axes[0].set_xlabel("mesh parameter 1/N")
        axes[1].set_xlabel("run time [s] (set-up and one step)")
        for axis in axes:
            axis.set_ylabel("relative error against Hertz")
            axis.grid(True, which="both", alpha=0.3)
            axis.legend()
        figure.suptitle("Hertz contact of a cylinder on a plane (2D, a = 0.1 R)")
        figure.tight_layout()
        figure.savefig(arguments.figure, dpi=100)
    if arguments.check:
        for model, results in runs.items():
            for r in results:
                for key in ("a", "p0"):
                    if r[key + " error"] > BOUNDS[key][r["N"]]:
                        sys.exit("%s, N = %d: the error in %s is %.2e, above "
                                 "%.2e." % (model, r["N"], key,
                                            r[key + " error"],
                                            BOUNDS[key][r["N"]]))
            for i in range(1, len(results)):
                if results[i]["a error"] >= results[i - 1]["a error"]:
                    sys.exit("%s: the error in a does not fall from N = %d to "
                             "%d." % (model, results[i - 1]["N"],
                                      results[i]["N"]))
        # On meshes fitted to a = 0.1 (plane stress): the L2 error of the
        # pressure against Hertz (from N = 64 on it is the finite body's
        # modelling error) and the L2 difference to the finite body's
        # solution on N = 256 fall with 0.8 times their observed orders.
        fitted = run_series(arguments.executable, "plane stress",
                            [16, 32, 64], FITTED_A)
        add_reference_differences(arguments.executable, "plane stress",
                                  fitted, 256, FITTED_A)
        for i, (coarse, fine) in enumerate(zip(fitted, fitted[1:])):
            for key in ("L2 error", "L2"):
                bound = 0.8 * FITTED_ORDERS[key][i]
                print("Fitted meshes, N = %d -> %d: the %s falls with order "
                      "%.2f (bound %.2f)." % (
                          coarse["N"], fine["N"],
                          "error against Hertz" if key == "L2 error"
                          else "difference to N = 256",
                          observed_order(coarse, fine, key), bound))
                if observed_order(coarse, fine, key) < bound:
                    sys.exit("Fitted meshes, N = %d -> %d: the %s of the "
                             "pressure falls with order %.2f (%.3e, %.3e), "
                             "below %.1f." % (
                                 coarse["N"], fine["N"],
                                 "error against Hertz" if key == "L2 error"
                                 else "difference to N = 256",
                                 observed_order(coarse, fine, key), coarse[key],
                                 fine[key], bound))
        print("Hertz (%s): a and p0 within 1.5 times their observed errors "
              "on N = 16, 32, 64 (a: 4.7%%, 2.8%%, 1.9%%; p0: 2.5%%, 0.34%%, "
              "0.34%%), the error in a falling; on fitted meshes the "
              "pressure's L2 error against Hertz and its difference to "
              "N = 256 fall with 0.8 times their observed orders." % (
                  ", ".join(models)))


if __name__ == "__main__":
    main()
