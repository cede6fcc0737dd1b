#!/usr/bin/env python3
"""Plot the time series and contact profiles of one run's output folder.

Usage: scripts/plot_run.py OUTPUT_FOLDER [--out DIR]

Reads OUTPUT_FOLDER/time_series.csv and OUTPUT_FOLDER/contact_profile_NNNN.csv
(by column name; columns added later are ignored) and writes

  forces.png             total_contact_force, every contact_force_zone_* and
                         every reaction_* column against time;
  contact.png            contact_area and peak_pressure against time, or,
                         for runs without these columns, the numbers of
                         unilateral, compliance and no-contact nodes;
  iterations.png         active-set (and Krylov, if any) iterations and the
                         time step against time;
  pressure_profiles.png  contact_pressure of the profiles (at most 8, evenly
                         picked) along x in 2D, against the distance from the
                         profile's point of largest pressure in 3D;

into OUTPUT_FOLDER/plots/ (created if missing), or into DIR with --out.
Without --out nothing is written anywhere else: a plots/ that is a link is
refused. Only these four names are ever written, and an existing file under
one of them is replaced only if this script wrote it (its PNG text chunk
says so): anything else there is refused, before any file is written.
Prints the paths written. Exit status 1, with a message naming the file, if
the folder or its time_series.csv is missing or a CSV file is malformed.
"""

import argparse
import csv
import math
import os
import re
import struct
import sys
import tempfile

if "matplotlib" not in sys.modules and sys.executable != "/usr/bin/python3":
    try:
        import matplotlib  # noqa: F401
    except ImportError:  # Debian's matplotlib lives with /usr/bin/python3
        if os.path.exists("/usr/bin/python3"):
            os.execv("/usr/bin/python3",
                     ["/usr/bin/python3", os.path.abspath(__file__)]
                     + sys.argv[1:])

try:
    import matplotlib  # noqa: E402

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: E402
except ImportError:
    sys.exit("plot_run.py: matplotlib is not installed for %s "
             "(apt-get install python3-matplotlib)" % sys.executable)

PLOT_NAMES = ("forces.png", "contact.png", "iterations.png",
              "pressure_profiles.png")
# The PNG text chunk that marks a file as one of this script's plots.
MARK_KEY = "Software"
MARK_VALUE = "viscoplastic_contact scripts/plot_run.py"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
MAX_PROFILES = 8
PROFILE_NAME = re.compile(r"contact_profile_([0-9]+)\.csv$")


class PlotError(Exception):
    """A problem the user has to fix; the message names the file."""


# ---------------------------------------------------------------- reading

class Table:
    """The rows of a CSV file with a header line, kept as text; columns are
    converted to numbers on demand, so unused (later) columns may hold
    anything."""

    def __init__(self, path):
        self.path = path
        try:
            with open(path, newline="", encoding="utf-8") as f:
                lines = [row for row in csv.reader(f, strict=True)]
        except FileNotFoundError:
            raise PlotError("%s: no such file" % path)
        except OSError as e:
            raise PlotError("%s: cannot read: %s" % (path, e.strerror or e))
        except UnicodeDecodeError:
            raise PlotError("%s: malformed CSV: not UTF-8 text" % path)
        except csv.Error as e:
            raise PlotError("%s: malformed CSV: %s" % (path, e))
        # (line number, fields), blank lines skipped.
        numbered = [(i + 1, row) for i, row in enumerate(lines) if row]
        if not numbered:
            raise PlotError("%s: malformed CSV: no header line" % path)
        line, header = numbered[0]
        self.header = [name.strip() for name in header]
        if any(not name for name in self.header):
            raise PlotError("%s: malformed CSV: empty column name in the "
                            "header (line %d)" % (path, line))
        if len(set(self.header)) != len(self.header):
            raise PlotError("%s: malformed CSV: repeated column name in the "
                            "header (line %d)" % (path, line))
        self.rows = numbered[1:]
        for line, row in self.rows:
            if len(row) != len(self.header):
                raise PlotError(
                    "%s: malformed CSV: line %d has %d fields, the header %d"
                    % (path, line, len(row), len(self.header)))
        self.index = {name: i for i, name in enumerate(self.header)}

    def __len__(self):
        return len(self.rows)

    def has(self, name):
        return name in self.index

    def column(self, name):
        """The column as floats (an empty field is NaN)."""
        if name not in self.index:
            raise PlotError("%s: malformed CSV: no column '%s' (columns: %s)"
                            % (self.path, name, ",".join(self.header)))
        i = self.index[name]
        values = []
        for line, row in self.rows:
            text = row[i].strip()
            if not text:
                values.append(float("nan"))
                continue
            try:
                values.append(float(text))
            except ValueError:
                raise PlotError("%s: malformed CSV: line %d, column '%s': "
                                "'%s' is not a number"
                                % (self.path, line, name, row[i]))
        return values


def read_profiles(folder):
    """[(step, Table)] of the folder's contact_profile_NNNN.csv, by step."""
    profiles = []
    try:
        names = os.listdir(folder)
    except OSError as e:
        raise PlotError("%s: cannot list the folder: %s" % (folder, e))
    for name in names:
        match = PROFILE_NAME.match(name)
        path = os.path.join(folder, name)
        if match and os.path.isfile(path):
            profiles.append((int(match.group(1)), path))
    tables = []
    for step, path in sorted(profiles):
        table = Table(path)
        for name in ("x", "y", "contact_pressure") + (
                ("z",) if table.has("z") else ()):
            table.column(name)  # checks presence and numbers
        tables.append((step, table))
    return tables


def pick_evenly(items, most):
    """At most `most` items, the first and last included, evenly spaced."""
    if len(items) <= most:
        return list(items)
    chosen = sorted({round(i * (len(items) - 1) / (most - 1))
                     for i in range(most)})
    return [items[i] for i in chosen]


# ---------------------------------------------------------------- writing

def is_own_plot(path):
    """True if path is a PNG file whose text chunks carry this script's
    mark (the chunks before the image data)."""
    try:
        with open(path, "rb") as f:
            if f.read(8) != PNG_SIGNATURE:
                return False
            while True:
                head = f.read(8)
                if len(head) < 8:
                    return False
                length, kind = struct.unpack(">I4s", head)
                if kind in (b"IDAT", b"IEND") or length > 1 << 20:
                    return False
                data = f.read(length)
                f.read(4)  # CRC
                if kind == b"tEXt":
                    key, _, value = data.partition(b"\0")
                    if (key == MARK_KEY.encode("latin-1")
                            and value == MARK_VALUE.encode("latin-1")):
                        return True
    except OSError:
        return False


def check_target(path):
    """Refuses a path this script must not write over."""
    if os.path.islink(path):
        raise PlotError("%s is a symbolic link: not replaced (remove it "
                        "or use --out DIR)" % path)
    if os.path.lexists(path):
        if not os.path.isfile(path):
            raise PlotError("%s exists and is not a file: not replaced "
                            "(remove it or use --out DIR)" % path)
        if not is_own_plot(path):
            raise PlotError("%s exists and was not written by plot_run.py: "
                            "not replaced (remove it or use --out DIR)"
                            % path)


def plots_folder(folder, out):
    """The folder to write into, created if missing."""
    if out is not None:
        if os.path.lexists(out) and not os.path.isdir(out):
            raise PlotError("%s: --out exists and is not a folder" % out)
        try:
            os.makedirs(out, exist_ok=True)
        except OSError as e:
            raise PlotError("%s: cannot create the folder: %s" % (out, e))
        return out
    target = os.path.join(folder, "plots")
    if os.path.islink(target):
        raise PlotError("%s is a symbolic link: not written into (plots go "
                        "only into the output folder; use --out DIR)"
                        % target)
    if os.path.lexists(target) and not os.path.isdir(target):
        raise PlotError("%s exists and is not a folder: not written into "
                        "(use --out DIR)" % target)
    try:
        os.makedirs(target, exist_ok=True)
    except OSError as e:
        raise PlotError("%s: cannot create the folder: %s" % (target, e))
    if (os.path.dirname(os.path.realpath(target))
            != os.path.realpath(folder)):
        raise PlotError("%s is not inside %s: not written into (use --out "
                        "DIR)" % (target, folder))
    return target


def save(figure, path):
    """Writes the figure to a temporary file next to path and renames it
    over path (checked again just before)."""
    directory = os.path.dirname(path) or "."
    descriptor, temporary = tempfile.mkstemp(prefix=".plot_run.",
                                             suffix=".png", dir=directory)
    try:
        with os.fdopen(descriptor, "wb") as f:
            figure.savefig(f, format="png", dpi=110,
                           metadata={MARK_KEY: MARK_VALUE})
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)  # mkstemp makes it 0600
        check_target(path)
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise
    finally:
        plt.close(figure)


def note(axes, text):
    axes.text(0.5, 0.5, text, transform=axes.transAxes, ha="center",
              va="center", wrap=True)


# ---------------------------------------------------------------- figures

def forces_figure(series):
    figure, axes = plt.subplots(figsize=(8, 4.5))
    time = series.column("time")
    names = [n for n in ("total_contact_force",) if series.has(n)]
    names += [n for n in series.header
              if n.startswith("contact_force_zone_") or n.startswith("reaction_")]
    for name in names:
        axes.plot(time, series.column(name), ".-", markersize=3, label=name)
    if names:
        axes.legend(fontsize="small")
    else:
        note(axes, "no total_contact_force or reaction_* column in\n%s"
             % series.path)
    axes.axhline(0, color="0.7", linewidth=0.8)
    axes.set_xlabel("time")
    axes.set_ylabel("force (N, per unit thickness in 2D)")
    axes.set_title("Contact force and reactions")
    axes.grid(alpha=0.3)
    figure.tight_layout()
    return figure


def contact_figure(series):
    time = series.column("time")
    measures = [(n, label) for n, label in
                (("contact_area", "contact area (width in 2D)"),
                 ("peak_pressure", "peak pressure"))
                if series.has(n)]
    if measures:
        figure, axes = plt.subplots(len(measures), 1, sharex=True,
                                    figsize=(8, 3 + 2 * len(measures)),
                                    squeeze=False)
        for row, (name, label) in zip(axes[:, 0], measures):
            row.plot(time, series.column(name), ".-", markersize=3)
            row.set_ylabel(label)
            row.set_title(name)
            row.grid(alpha=0.3)
        axes[-1, 0].set_xlabel("time")
    else:
        figure, axes = plt.subplots(figsize=(8, 4.5))
        counts = [n for n in ("unilateral_nodes", "compliance_nodes",
                              "no_contact_nodes") if series.has(n)]
        for name in counts:
            axes.plot(time, series.column(name), ".-", markersize=3,
                      label=name, drawstyle="steps-post")
        if counts:
            axes.legend(fontsize="small")
        else:
            note(axes, "no contact columns in\n%s" % series.path)
        axes.set_xlabel("time")
        axes.set_ylabel("nodes")
        axes.set_title("Contact nodes by state")
        axes.grid(alpha=0.3)
    figure.tight_layout()
    return figure


def iterations_figure(series):
    time = series.column("time")
    figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    lines = []
    if series.has("active_set_iterations"):
        lines += top.plot(time, series.column("active_set_iterations"), ".-",
                          markersize=3, label="active_set_iterations")
    top.set_ylabel("active-set iterations")
    if series.has("krylov_iterations"):
        krylov = series.column("krylov_iterations")
        if any(v != 0 and not math.isnan(v) for v in krylov):
            right = top.twinx()
            lines += right.plot(time, krylov, ".-", markersize=3,
                                color="tab:orange", label="krylov_iterations")
            right.set_ylabel("Krylov iterations")
    if lines:
        top.legend(lines, [line.get_label() for line in lines],
                   fontsize="small")
    else:
        note(top, "no iteration columns in\n%s" % series.path)
    top.set_title("Iterations per step")
    top.grid(alpha=0.3)
    if series.has("time_step"):
        bottom.plot(time, series.column("time_step"), ".-", markersize=3)
    else:
        note(bottom, "no time_step column in\n%s" % series.path)
    bottom.set_ylabel("time step")
    bottom.set_xlabel("time")
    bottom.grid(alpha=0.3)
    figure.tight_layout()
    return figure


def profile_curve(table, three_d):
    """(coordinate, pressure) of one profile, sorted by the coordinate."""
    pressure = table.column("contact_pressure")
    x = table.column("x")
    if three_d:
        y, z = table.column("y"), table.column("z")
        finite = [i for i, p in enumerate(pressure) if not math.isnan(p)]
        centre = max(finite, key=lambda i: pressure[i]) if finite else 0
        coordinate = [math.sqrt((x[i] - x[centre]) ** 2
                                + (y[i] - y[centre]) ** 2
                                + (z[i] - z[centre]) ** 2)
                      for i in range(len(x))]
    else:
        coordinate = x
    order = sorted(range(len(coordinate)), key=lambda i: coordinate[i])
    return ([coordinate[i] for i in order], [pressure[i] for i in order])


def profiles_figure(profiles, folder):
    figure, axes = plt.subplots(figsize=(8, 4.5))
    shown = pick_evenly([p for p in profiles if len(p[1])], MAX_PROFILES)
    three_d = any(table.has("z") for _, table in profiles)
    colours = plt.cm.viridis([0.85 * i / max(len(shown) - 1, 1)
                              for i in range(len(shown))])
    for (step, table), colour in zip(shown, colours):
        coordinate, pressure = profile_curve(table, table.has("z"))
        times = table.column("time") if table.has("time") else []
        label = ("t = %.6g" % times[0] if times and not math.isnan(times[0])
                 else "step %d" % step)
        if three_d:
            axes.plot(coordinate, pressure, ".", markersize=4, color=colour,
                      label=label)
        else:
            axes.plot(coordinate, pressure, ".-", markersize=3, color=colour,
                      label=label)
    if shown:
        axes.legend(fontsize="small", markerscale=2 if three_d else 1)
        if len(shown) < len(profiles):
            axes.set_title("Contact pressure (%d of %d profiles)"
                           % (len(shown), len(profiles)))
        else:
            axes.set_title("Contact pressure")
    else:
        axes.set_title("Contact pressure")
        note(axes, "no contact_profile_NNNN.csv with contact nodes in\n%s"
             % folder)
    axes.set_xlabel("distance from the point of largest pressure" if three_d
                    else "x")
    axes.set_ylabel("contact pressure")
    axes.grid(alpha=0.3)
    figure.tight_layout()
    return figure


# ---------------------------------------------------------------- main

def plot_run(folder, out):
    if not os.path.exists(folder):
        raise PlotError("%s: no such output folder" % folder)
    if not os.path.isdir(folder):
        raise PlotError("%s: not a folder" % folder)
    series = Table(os.path.join(folder, "time_series.csv"))
    series.column("time")  # required
    profiles = read_profiles(folder)

    target = plots_folder(folder, out)
    paths = [os.path.join(target, name) for name in PLOT_NAMES]
    for path in paths:  # refuse before writing anything
        check_target(path)
    figures = (lambda: forces_figure(series),
               lambda: contact_figure(series),
               lambda: iterations_figure(series),
               lambda: profiles_figure(profiles, folder))
    for path, make in zip(paths, figures):
        figure = make()
        if not len(series) and make is not figures[-1]:
            figure.text(0.5, 0.5, "no steps in %s" % series.path,
                        ha="center", va="center", color="tab:red")
        try:
            save(figure, path)
        except OSError as e:
            raise PlotError("%s: cannot write: %s" % (path, e))
        print(path)
    if not len(series):
        print("note: %s has no steps" % series.path, file=sys.stderr)
    if not profiles:
        print("note: no contact_profile_NNNN.csv in %s" % folder,
              file=sys.stderr)


def main():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="Writes " + ", ".join(PLOT_NAMES)
        + " into OUTPUT_FOLDER/plots/ or DIR.")
    parser.add_argument("folder", metavar="OUTPUT_FOLDER",
                        help="the Output directory of a run")
    parser.add_argument("--out", metavar="DIR",
                        help="write the plots into DIR instead")
    args = parser.parse_args()
    try:
        plot_run(args.folder, args.out)
    except PlotError as e:
        print("plot_run.py: error: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
