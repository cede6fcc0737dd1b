#!/usr/bin/python3
"""The contact patch test (parameters/patch_test.prm, patch_test_3d.prm) on
every cell type with both back ends, at two mesh sizes: the largest relative
error over all steps of the contact force, the peak pressure, the reaction
of the top and the pressure of every contact node at the profile times,
against the closed form p = E D(t) / H (D(t) = 0.01 min(t, 2 - t), E = 1000,
H = 1). Prints the markdown table of doc/benchmarks.md.

    benchmarks/run_patch_test_errors.py [--executable build/viscoplastic_contact]
"""

import argparse
import csv
import glob
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
PARAMETERS = os.path.join(HERE, "..", "parameters")


def set_entry(text, entry, value):
    return re.sub(r"(?m)^(\s*set %s\s*=).*$" % re.escape(entry),
                  r"\g<1> %s" % value, text)


def exact_pressure(t):
    return 10 * min(t, 2 - t)


def run(executable, prm_text, folder):
    prm = os.path.join(folder, "scene.prm")
    with open(prm, "w") as f:
        f.write(set_entry(prm_text, "Output directory",
                          os.path.join(folder, "output")))
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("The run failed:\n" + result.stderr)
    return os.path.join(folder, "output")


def errors(output, area):
    """Largest relative errors: force, peak pressure, reaction, nodal
    pressures."""
    worst = [0.0, 0.0, 0.0, 0.0]
    with open(os.path.join(output, "time_series.csv")) as f:
        rows = list(csv.reader(f))
    header = rows[0]
    col = {name: i for i, name in enumerate(header)}
    for row in rows[1:]:
        p = exact_pressure(float(row[col["time"]]))
        worst[0] = max(worst[0], abs(float(row[col["total_contact_force"]])
                                     - p * area) / (p * area))
        worst[1] = max(worst[1],
                       abs(float(row[col["peak_pressure"]]) - p) / p)
        worst[2] = max(worst[2], abs(float(row[-1]) + p * area) / (p * area))
    for profile in glob.glob(os.path.join(output, "contact_profile_*.csv")):
        with open(profile) as f:
            for node in csv.DictReader(f):
                p = exact_pressure(float(node["time"]))
                worst[3] = max(worst[3],
                               abs(float(node["contact_pressure"]) - p) / p)
    return worst


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--executable",
                        default=os.path.join(HERE, "..", "build",
                                             "viscoplastic_contact"))
    arguments = parser.parse_args()
    print("| scene | cells | back end | h | contact force | peak pressure "
          "| reaction | nodal pressures |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for dim, name, area, sizes in ((2, "patch_test.prm", 2, (4, 16)),
                                   (3, "patch_test_3d.prm", 3, (2, 8))):
        with open(os.path.join(PARAMETERS, name)) as f:
            base = f.read()
        for cells in ("simplex", "hypercube"):
            for method in ("condensed", "full space"):
                for n in sizes:
                    text = set_entry(base, "Cell type", cells)
                    text = set_entry(text, "Method", method)
                    text = set_entry(text, "Subdivisions", n)
                    with tempfile.TemporaryDirectory() as folder:
                        worst = errors(run(arguments.executable, text, folder),
                                       area)
                    label = {"simplex": ("triangles", "tetrahedra"),
                             "hypercube": ("quadrilaterals", "hexahedra")}
                    print("| %dD | %s | %s | 1/%d | %s |" % (
                        dim, label[cells][dim - 2], method, n,
                        " | ".join("%.1e" % e for e in worst)))


if __name__ == "__main__":
    main()
