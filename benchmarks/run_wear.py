#!/usr/bin/python3
"""Archard's wear: the worn block and the worn tracks, drawn.

--figure runs parameters/wear_block.prm (an elastic block on a support
that moves under it, Coulomb friction, k_w = 1e-3: the worn depth of every
node at a few times, and the contact force as the block wears under its
held top), parameters/worn_track.prm and worn_track_3d.prm (a rigid
cylinder, a sphere in 3D, dragged across a block: the worn depth along the
track, in 3D along z = 0), and draws doc/figures/wear.png. The recurrence
the worn block satisfies node by node is checked by tests/run_wear_block.sh.

    benchmarks/run_wear.py [--executable build/viscoplastic_contact] --figure
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
TOP = os.path.join(HERE, "..")


def run(executable, scene, folder):
    with open(os.path.join(TOP, "parameters", scene)) as f:
        text = f.read()
    text = re.sub(r"(?m)^(\s*set Output directory\s*=)[^#\n]*",
                  r"\g<1> %s" % os.path.join(folder, "output"), text)
    text = re.sub(r"(?m)^(subsection Output)$",
                  r"\g<1>\n  set Write vtu = false\n  set Overwrite = true", text)
    prm = os.path.join(folder, "scene.prm")
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("%s failed:\n%s" % (scene, result.stderr))
    profiles = {}
    for name in sorted(glob.glob(os.path.join(folder, "output", "contact_profile_*.csv"))):
        with open(name) as f:
            rows = list(csv.DictReader(f))
        if "z" in rows[0]:
            rows = [r for r in rows if abs(float(r["z"])) < 1e-12]
        rows.sort(key=lambda r: float(r["x"]))
        profiles[float(rows[0]["time"])] = ([float(r["x"]) for r in rows],
                                            [float(r["wear"]) for r in rows])
    with open(os.path.join(folder, "output", "time_series.csv")) as f:
        series = list(csv.DictReader(f))
    return profiles, series


def figure(executable):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (block_axis, force_axis, track_axis) = plt.subplots(1, 3, figsize=(14, 4))
    with tempfile.TemporaryDirectory() as folder:
        profiles, series = run(executable, "wear_block.prm", folder)
    for t in (0.5, 1, 1.5, 2):
        x, w = profiles[t]
        block_axis.plot(x, w, "o-", markersize=3, label="t = %g" % t)
    force_axis.plot([float(r["time"]) for r in series],
                    [float(r["total_contact_force"]) for r in series], "o-",
                    markersize=3, label="normal force N")
    force_axis.plot([float(r["time"]) for r in series],
                    [-float(r["tangential_force_zone_1_x"]) for r in series], "s-",
                    markersize=3, label="tangential force (mu N)")
    for scene, style in (("worn_track.prm", "-"), ("worn_track_3d.prm", "--")):
        with tempfile.TemporaryDirectory() as folder:
            profiles, _ = run(executable, scene, folder)
        for t in sorted(profiles)[1:]:
            x, w = profiles[t]
            track_axis.plot(x, w, style, label="%s, t = %g"
                            % ("3D (z = 0)" if "3d" in scene else "2D", t))
    block_axis.set_xlabel("x")
    block_axis.set_ylabel("worn depth w")
    block_axis.set_title("worn block (k_w = 1e-3, V = 0.5)")
    force_axis.set_xlabel("t")
    force_axis.set_ylabel("force")
    force_axis.set_title("the block wears under its held top")
    track_axis.set_xlabel("x")
    track_axis.set_ylabel("worn depth w")
    track_axis.set_title("worn tracks (k_w = 2e-4)")
    for axis in (block_axis, force_axis, track_axis):
        axis.legend(fontsize=7)
        axis.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(TOP, "doc", "figures", "wear.png"), dpi=100)
    print("wrote doc/figures/wear.png")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--executable",
                        default=os.path.join(TOP, "build", "viscoplastic_contact"))
    parser.add_argument("--figure", action="store_true")
    arguments = parser.parse_args()
    if arguments.figure:
        figure(arguments.executable)


if __name__ == "__main__":
    main()
