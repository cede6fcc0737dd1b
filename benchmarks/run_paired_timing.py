#!/usr/bin/python3
"""Two builds of the program on the same scene, side by side: each pair runs
the baseline and then the candidate (alternating which goes first), and the
ratio of their whole-process wall times is taken per pair, so that the
noise of a shared machine hits both alike. Both runs must print the same
run summary (the physical results); the script stops if they do not.

    benchmarks/run_paired_timing.py --baseline OLD/viscoplastic_contact \\
        --candidate build/viscoplastic_contact [--scene parameters/default.prm]
        [--pairs 5]

The scene runs without .vtu output (Write vtu = false) into a temporary
folder. Prints the wall times and the median and range of the ratio
candidate / baseline.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time


def run(executable, scene, folder):
    """Runs the scene once into folder; returns (wall time, run summary)."""
    prm = os.path.join(folder, "scene.prm")
    with open(prm, "w") as f:
        f.write("include %s\n" % os.path.abspath(scene))
        f.write("subsection Output\n  set Output directory = %s\n"
                "  set Write vtu = false\n  set Overwrite = true\n"
                "  set Print timing summary = false\nend\n"
                % os.path.join(folder, "output"))
    start = time.perf_counter()
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    wall = time.perf_counter() - start
    if result.returncode != 0:
        sys.exit("%s failed:\n%s%s" % (executable, result.stdout,
                                       result.stderr))
    summary = result.stdout[result.stdout.find("Run summary"):]
    # The counters of the run may differ between versions; the physical
    # results (norms, contact state, forces) must not.
    physical = "\n".join(line for line in summary.splitlines()
                         if re.search(r"final|Final", line))
    return wall, physical


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--baseline", required=True)
    parser.add_argument("--candidate", required=True)
    parser.add_argument("--scene", default="parameters/default.prm")
    parser.add_argument("--pairs", type=int, default=5)
    args = parser.parse_args()

    ratios = []
    with tempfile.TemporaryDirectory() as folder:
        for pair in range(args.pairs):
            order = [("baseline", args.baseline), ("candidate", args.candidate)]
            if pair % 2 == 1:
                order.reverse()
            times, summaries = {}, {}
            for name, executable in order:
                times[name], summaries[name] = run(executable, args.scene,
                                                   folder)
            if summaries["baseline"] != summaries["candidate"]:
                sys.exit("The two builds give different results:\n%s\n---\n%s"
                         % (summaries["baseline"], summaries["candidate"]))
            ratios.append(times["candidate"] / times["baseline"])
            print("pair %d: baseline %.3f s, candidate %.3f s, ratio %.3f"
                  % (pair + 1, times["baseline"], times["candidate"],
                     ratios[-1]), flush=True)
    print("ratio candidate / baseline: median %.3f, range %.3f .. %.3f "
          "(%d pairs, %s)" % (statistics.median(ratios), min(ratios),
                               max(ratios), len(ratios), args.scene))


if __name__ == "__main__":
    main()
