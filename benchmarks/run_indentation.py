#!/usr/bin/python3
"""An indentation with plasticity and unloading (parameters/indentation.prm):
a rigid cylinder pushed into a viscoplastic block (Perzyna) to the depth
0.02 and withdrawn, d(t) = 0.02 min(t/T, 2 - t/T), at the loading times
T = 0.1, 1, 10, 100, 1000 (the relaxation time of the law is 2 lambda / E = 0.1),
the same 40 steps each. Perzyna's overstress is of the order of lambda
times the strain rate, so as T grows the force history and the residual
imprint approach those of rate-independent plasticity (lambda -> 0), the
differences between successive T falling like 1/T once T is well above
the relaxation time. The rate-independent limit itself is the run with
T = 10^6 (10^7 relaxation times: the backward-Euler update with k far
above the relaxation time is the return to the yield surface, i.e.
rate-independent plasticity). Prints the table of doc/benchmarks.md (peak
force, residual imprint, their distances from the limit and the ratio of
successive distances); --figure FILE draws the force against the
indentation for every T and the limit, and the distances against T. --check (the ctest, on a coarser mesh): the peak force
falls and the imprint grows monotonically with T, each change is smaller
than the one before (by at least 3 in the last decade), the imprint is
positive; and the elastic
block (Plasticity = false) has the same force history for every T to 1e-9
and no imprint (below 1e-9).

    benchmarks/run_indentation.py [--executable build/viscoplastic_contact]
        [--figure doc/figures/indentation.png] [--check]
"""

import argparse
import csv
import glob
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "scripts"))
from vc_scripts import (REPO_ROOT, run_in_temporary_directory,  # noqa: E402
                        set_prm_entries)

DEPTH = 0.02
TIMES = (0.1, 1.0, 10.0, 100.0, 1000.0)
LIMIT = 1e6  # the rate-independent limit


def run(executable, loading_time, plastic=True, coarse=False):
    with open(os.path.join(REPO_ROOT, "parameters", "indentation.prm")) as f:
        text = f.read()
    T = loading_time
    entries = {
        (("Contact",), "Initial gap"):
            "x^2 - %g * min(t / %r, 2 - t / %r)" % (DEPTH, T, T),
        (("Time",), "End time"): repr(2 * T),
        (("Time",), "Time step"): repr(2 * T / 40),
        (("Output",), "Profile times"): repr(2 * T),
        (("Output",), "Write vtu"): "false",
        (("Output",), "Output directory"): "output",
    }
    if T == LIMIT:
        # The backward-Euler Newton iteration does not converge at the
        # first unloading step with k this far above the relaxation time
        # (doc/benchmarks.md): that step is cut until it does.
        entries[(("Time",), "On solver failure")] = "cut time step"
    if not plastic:
        entries[(("Material",), "Plasticity")] = "false"
    if coarse:
        entries[(("Geometry",), "Subdivisions")] = "16"
    try:
        with run_in_temporary_directory(
                executable, set_prm_entries(text, entries)) as (folder, _, _):
            return analyse(os.path.join(folder, "output"), T)
    except RuntimeError as error:
        sys.exit("The run with T = %g failed:\n%s" % (T, error))


def analyse(output, T):
    with open(os.path.join(output, "time_series.csv")) as f:
        series = list(csv.DictReader(f))
    s = [float(r["time"]) / T for r in series]
    depth = [DEPTH * min(x, 2 - x) for x in s]
    force = [2 * float(r["total_contact_force"]) for r in series]
    profile = sorted(glob.glob(os.path.join(output, "contact_profile_*.csv")))[-1]
    with open(profile) as f:
        rows = sorted((float(r["x"]), float(r["u_nu"])) for r in csv.DictReader(f))
    # At the end the indenter is back at s = x^2: u_y(0) = r(0) + 0.
    imprint = -rows[0][1]
    return {"T": T, "depth": depth, "force": force, "peak": max(force),
            "imprint": imprint}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--executable", default=os.path.join(
        REPO_ROOT, "build", "viscoplastic_contact"))
    parser.add_argument("--figure")
    parser.add_argument("--check", action="store_true")
    arguments = parser.parse_args()
    executable = os.path.abspath(arguments.executable)
    runs = [run(executable, T, coarse=arguments.check) for T in TIMES]
    limit = run(executable, LIMIT, coarse=arguments.check)
    for r in runs:
        r["F distance"] = (r["peak"] - limit["peak"]) / limit["peak"]
        r["imprint distance"] = ((limit["imprint"] - r["imprint"])
                                 / limit["imprint"])
    print("| T | T / relaxation time | peak force F | F / limit - 1 | imprint "
          "| 1 - imprint / limit | distances shrink by (F, imprint) |")
    print("| --- " * 7 + "|")
    for i, r in enumerate(runs):
        ratio = ""
        if i >= 1:
            ratio = "%.1f, %.1f" % (
                runs[i - 1]["F distance"] / r["F distance"],
                runs[i - 1]["imprint distance"] / r["imprint distance"])
        print("| %g | %g | %.5f | %.2e | %.3e | %.2e | %s |" % (
            r["T"], r["T"] / 0.1, r["peak"], r["F distance"], r["imprint"],
            r["imprint distance"], ratio))
    print("| %g (the limit) | %g | %.5f | | %.3e | | |" % (
        LIMIT, LIMIT / 0.1, limit["peak"], limit["imprint"]))

    if arguments.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        figure, axes = plt.subplots(1, 2, figsize=(11, 4.2))
        for r in runs:
            axes[0].plot(r["depth"], r["force"], ".-", markersize=3,
                         label="T = %g" % r["T"])
        axes[0].plot(limit["depth"], limit["force"], "k--",
                     label="rate-independent limit (T = %g)" % LIMIT)
        axes[0].set_xlabel("indentation d")
        axes[0].set_ylabel("force F (whole cylinder, per unit length)")
        axes[0].legend()
        axes[0].grid(alpha=0.3)
        times = [r["T"] for r in runs]
        axes[1].loglog(times, [r["F distance"] for r in runs], "o-",
                       label="peak force: F / F_limit - 1")
        axes[1].loglog(times, [r["imprint distance"] for r in runs], "s-",
                       label="imprint: 1 - imprint / imprint_limit")
        axes[1].loglog(times[2:], [0.1 / T for T in times[2:]], "k:",
                       label="slope -1")
        axes[1].set_xlabel("loading time T (relaxation time 0.1)")
        axes[1].set_ylabel("relative distance from the rate-independent limit")
        axes[1].legend()
        axes[1].grid(True, which="both", alpha=0.3)
        figure.suptitle("Indentation with plasticity and unloading (Perzyna, "
                        "plane strain): toward the rate-independent limit")
        figure.tight_layout()
        figure.savefig(arguments.figure, dpi=100)

    if arguments.check:
        # Slower loading: less overstress, so a lower peak force and more
        # plastic flow, so a deeper imprint.
        for i in range(1, len(runs)):
            for key, sign in (("peak", 1), ("imprint", -1)):
                if not sign * (runs[i - 1][key] - runs[i][key]) > 0:
                    sys.exit("The %s does not %s from T = %g to %g: %g, %g."
                             % (key, "fall" if sign > 0 else "grow",
                                runs[i - 1]["T"], runs[i]["T"],
                                runs[i - 1][key], runs[i][key]))
        # Toward the limit: each change smaller than the one before, by at
        # least 3 in the last decade (T >> the relaxation time).
        for i in range(2, len(runs)):
            for key in ("peak", "imprint"):
                before = abs(runs[i - 2][key] - runs[i - 1][key])
                after = abs(runs[i - 1][key] - runs[i][key])
                factor = 3 if i == len(runs) - 1 else 1
                if not before > factor * after:
                    sys.exit("The change of the %s from T = %g to %g (%g) is "
                             "not below 1/%d of the one before (%g)."
                             % (key, runs[i - 1]["T"], runs[i]["T"], after,
                                factor, before))
        # The distances from the limit fall like 1/T in the last decade.
        for key in ("F distance", "imprint distance"):
            factor = runs[-2][key] / runs[-1][key]
            if not 5 < factor < 20:
                sys.exit("The %s from the rate-independent limit falls by %g "
                         "from T = %g to %g, not by about 10."
                         % (key, factor, runs[-2]["T"], runs[-1]["T"]))
        if not runs[-1]["imprint"] > 1e-4:
            sys.exit("No residual imprint: %g." % runs[-1]["imprint"])
        elastic = []
        for T in (TIMES[0], TIMES[-1]):
            elastic.append(run(executable, T, plastic=False, coarse=True))
        for a, b in zip(elastic[0]["force"], elastic[1]["force"]):
            if abs(a - b) > 1e-9 * max(abs(a), 1e-12) + 1e-12:
                sys.exit("The elastic force history depends on T: %.12g, "
                         "%.12g." % (a, b))
        if max(abs(e["imprint"]) for e in elastic) > 1e-9:
            sys.exit("The elastic block keeps an imprint: %g."
                     % elastic[0]["imprint"])
        print("Indentation: as the loading slows the peak force falls and "
              "the imprint grows toward the rate-independent limit (changes "
              "shrinking, the distances from the limit falling like 1/T in "
              "the last decade); the elastic block is rate independent and "
              "keeps no imprint.")


if __name__ == "__main__":
    main()
