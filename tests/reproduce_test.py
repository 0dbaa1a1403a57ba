#!/usr/bin/python3
"""tools/reproduce.py on a tiny experiment (ctest: reproduce): what a new user who reruns an experiment gets.

Usage: reproduce_test.py SOURCE_DIR BUILD_DIR

tests/data/reproduce holds a declaration of two experiments, `tiny` (pillars at 48x27, 4 frames, svgf, asvgf, the
3x3 box and the input against 4-spp references) and `tiny-gpu` (a GPU experiment, whose CSV device/ holds as
tools/gpu_device.sh would bring it back), and a README with their markers. In a temporary copy this test:
  1. runs it, with an empty frame cache, and checks the table against the kept CSV: --check passes, and one cell
     recomputed here from the CSV (svgf's mean RMSE over frames 1-3) is the table's;
  2. runs it again on one thread, with the references from the cache, as a new user would: every cell but the
     timing column, and every value of the kept CSV but the times, comes back identical;
  3. writes `tiny-gpu` from its device CSV (--from-csv): the cells are the CSV's values, the footer names the
     GPU from info.txt and the device's threads, and --check passes;
  4. breaks the README and the CSV in the ways --check must catch (a cell, the footer, a row of the CSV, a
     stray marker), and a declaration with a misspelt key, each of which must fail.
Prints what failed and exits 1.
"""
import os
import shutil
import subprocess
import sys
import tempfile

failures = []


def expect(condition, what):
    if not condition:
        failures.append(what)
        print(f"FAILED: {what}")


def reproduce(tmp, *args):
    return subprocess.run(["/usr/bin/python3", os.path.join(SOURCE, "tools", "reproduce.py"), "--experiments",
                           os.path.join(tmp, "experiments.toml"), "--root", tmp, "--build", BUILD, "--cache",
                           os.path.join(tmp, "cache")] + list(args), capture_output=True, text=True)


def block_lines(readme, marker):
    text = open(readme, encoding="utf-8").read()
    return text.split(f"<!-- experiment: {marker} -->\n")[1].split("<!-- /experiment -->")[0].split("\n")


def table_rows(readme, marker="tiny"):
    """The table's rows between the markers, each a list of cells, without the header."""
    lines = [line for line in block_lines(readme, marker) if line.startswith("| ")][1:]
    return [[c.strip() for c in line.strip("|").split("|")] for line in lines]


def csv_lines(tmp):
    with open(os.path.join(tmp, "results", "tiny.csv"), encoding="utf-8") as f:
        return f.read().split("\n")


def without_times(lines):
    """The kept CSV without its facts line and its ms_total column (the header names where it is)."""
    header = lines[1].split(",")
    keep = [k for k, name in enumerate(header) if not name.startswith("ms_")]
    return [[line.split(",")[k] for k in keep] for line in lines[1:] if line]


def check_fails(tmp, what, edit_file, old, new):
    """--check must fail once `old` is replaced by `new` in edit_file, and pass again when it is restored."""
    path = os.path.join(tmp, edit_file)
    original = open(path, encoding="utf-8").read()
    expect(old in original, f"the test's edit '{old}' is in {edit_file}")
    with open(path, "w", encoding="utf-8") as f:
        f.write(original.replace(old, new, 1))
    result = reproduce(tmp, "--check")
    expect(result.returncode != 0, f"--check fails on {what}")
    with open(path, "w", encoding="utf-8") as f:
        f.write(original)


def main():
    tmp = tempfile.mkdtemp(prefix="reproduce-test-")
    try:
        for name in ("experiments.toml", "README.md"):
            shutil.copy(os.path.join(SOURCE, "tests", "data", "reproduce", name), tmp)
        readme = os.path.join(tmp, "README.md")

        listed = reproduce(tmp, "--list")
        expect(listed.returncode == 0 and "tiny" in listed.stdout and "pending" in listed.stdout,
               "--list names the experiment, pending before its first run")

        first = reproduce(tmp, "tiny")
        expect(first.returncode == 0, f"the first run succeeds: {first.stderr[-500:]}")
        checked = reproduce(tmp, "--check")
        expect(checked.returncode == 0, f"--check passes after the run: {checked.stdout}")
        rows_first, csv_first = table_rows(readme), csv_lines(tmp)
        expect(len(rows_first) == 4, "the table has the four declared rows")

        # svgf's RMSE, recomputed from the kept CSV: the mean over frames 1-3 (the table's mean_over).
        header = csv_first[1].split(",")
        rmse = [float(line.split(",")[header.index("rmse")]) for line in csv_first[2:]
                if line.startswith("pillars,svgf,") and line.split(",")[3] in ("1", "2", "3")]
        expect(len(rmse) == 3 and rows_first[0][1].strip("*") == f"{sum(rmse) / 3:.5f}",
               f"svgf's RMSE cell is the mean of its CSV rows over frames 1-3 ({rows_first[0][1]})")

        second = reproduce(tmp, "--threads", "1", "tiny")
        expect(second.returncode == 0, f"the second run succeeds: {second.stderr[-500:]}")
        rows_second = table_rows(readme)
        timing = [k for k, row in enumerate(rows_first[0]) if row.endswith(" ms")]
        expect(timing == [6], "the timing column is the last")
        for a, b in zip(rows_first, rows_second):
            expect([c for k, c in enumerate(a) if k not in timing] == [c for k, c in enumerate(b) if k not in timing],
                   f"a rerun gives the same cells but the times: {a} against {b}")
        expect(without_times(csv_first) == without_times(csv_lines(tmp)),
               "a rerun keeps the same values in the CSV but the times")

        device = reproduce(tmp, "--from-csv", os.path.join(SOURCE, "tests", "data", "reproduce", "device"), "tiny-gpu")
        expect(device.returncode == 0, f"--from-csv writes the GPU experiment: {device.stderr[-500:]}")
        expect(table_rows(readme, "tiny-gpu") == [["temporal", "0.136 ms"], ["atrous", "1.007 ms"],
                                                   ["total", "1.340 ms"]],
               f"the GPU table holds the device CSV's values: {table_rows(readme, 'tiny-gpu')}")
        footer = [line for line in block_lines(readme, "tiny-gpu") if line.startswith("Made by")]
        expect(len(footer) == 1 and footer[0].startswith("Made by `bash tools/gpu_device.sh targets` on NVIDIA H100 "
                                                         "80GB HBM3, ") and "16 cores." in footer[0],
               f"the GPU table's footer names the step, the GPU and its cores: {footer}")
        expect(reproduce(tmp, "--check").returncode == 0, "--check passes with the GPU table written")

        check_fails(tmp, "a changed cell", "README.md", rows_second[1][2], rows_second[1][2] + "1")
        check_fails(tmp, "a changed footer", "README.md", "Made by `tools/reproduce.py tiny`",
                    "Made by `tools/reproduce.py other`")
        last_row = [line for line in csv_lines(tmp) if line.startswith("pillars,none,none,3,")][0]
        check_fails(tmp, "a row missing from the kept CSV", os.path.join("results", "tiny.csv"), last_row + "\n", "")
        check_fails(tmp, "a marker no experiment declares", "README.md", "More prose.",
                    "<!-- experiment: nothing -->\n<!-- /experiment -->")
        check_fails(tmp, "a misspelt key in the declaration", "experiments.toml", "mean_over =", "mean_ovr =")
        expect(reproduce(tmp, "--check").returncode == 0, "--check passes again once everything is restored")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"reproduce_test: {len(failures)} failures" if failures else "reproduce_test: all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    SOURCE, BUILD = sys.argv[1], sys.argv[2]
    sys.exit(main())
