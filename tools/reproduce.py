#!/usr/bin/python3
"""Regenerates the results tables of the docs from one declaration, eval/experiments.toml.

Usage (from the repository root, with Debian's Python):
  tools/reproduce.py NAME...         run each experiment's commands (rtdr eval, rtdr bench, ctest), keep its
                                     results in eval/results/<name>.csv and rewrite its tables in their READMEs
  tools/reproduce.py --list          the experiments, what each costs and where its tables are
  tools/reproduce.py --check         every marked table is exactly what its kept CSV makes (renders nothing)
  tools/reproduce.py --from-csv NAME DIR   a GPU experiment: its tables from the CSVs tools/gpu_device.sh wrote
Options: --build DIR (default build: rtdr and the stability test), --cache DIR (the frame cache of the
evaluations, default out/cache; share one between worktrees), --threads N (passed on), --experiments FILE and
--root DIR (another declaration and the folder its READMEs are in; the tests use them).

A table lives in its README between `<!-- experiment: MARKER -->` and `<!-- /experiment -->`: the commands that
made it, the table, and a footer with the command, the date, the commit and the machine's core count. Nothing
between the markers is typed by hand. A table whose experiment has no kept CSV keeps its hand-typed values
under a footer that says so ("Last hand-typed values ..., pending a run"). How cells are declared:
tools/reproduce_declarations.py; how the tables are made from the kept CSVs: tools/reproduce_tables.py.

Every command runs as an argument vector, never through a shell. `rtdr eval` reuses the frame cache, so a rerun
with the same seed only filters: its table comes back identical but for the timing columns
(tests/reproduce_test.py checks that).
"""
import argparse
import csv
import datetime
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import reproduce_declarations as declarations  # noqa: E402  (both beside this script)
import reproduce_tables as tables  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STABILITY_LINE = re.compile(r"stability: (?P<claim>.+): (?P<value>[^\s:]+)(?: \(threshold (?P<threshold>[^)]*)\))?$")


def fail(message):
    sys.exit(f"reproduce: error: {message}")


# ---- The machine's facts -----------------------------------------------------------------------------------

def commit_of(root):
    """The short commit of `root`, with "+changes" when a file differs from it that is not a doc (*.md), the
    declaration or a kept result."""
    head = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    if head.returncode != 0:
        return "none"
    status = subprocess.run(["git", "-C", root, "status", "--porcelain", "--untracked-files=no"],
                            capture_output=True, text=True).stdout.split("\n")
    changed = [line[3:] for line in status if line[3:] and not line[3:].endswith(".md")
               and not line[3:].startswith("eval/results/") and line[3:] != "eval/experiments.toml"]
    return head.stdout.strip() + ("+changes" if changed else "")


def facts(root):
    return {"date": datetime.date.today().isoformat(), "commit": commit_of(root),
            "cores": str(len(os.sched_getaffinity(0))), "load": f"{os.getloadavg()[0]:.1f}"}


# ---- Cost ---------------------------------------------------------------------------------------------------

def run_seconds(experiment, run, calibration):
    """A run's estimated wall time on the reference machine (2 cores), from the declaration's calibration."""
    if experiment.tool != "eval":  # ctest has no runs: its one command takes `seconds`
        return float(experiment.seconds or 0.0) / max(1, len(experiment.runs))
    w, h = (int(v) for v in experiment.size.split("x"))
    first, last = declarations.frame_range(run["frames"])
    frames = last - first + 1
    gradients = "--gradients" in experiment.flags or any(s.startswith("asvgf") or "gradient_" in s
                                                         for s in experiment.methods.values())
    inputs = 1 + sum("gradient_" in s for s in experiment.methods.values())
    input_frames = (last + 1 if gradients else frames) * inputs
    shading = any(s.startswith("trmv") for s in experiment.methods.values())
    filter_us = calibration.get("filter_pixel_us", {})
    us = (1e6 * calibration.get("run_overhead_s", 0.0)
          + w * h * experiment.ref_spp * frames * calibration.get("reference_sample_us", 1.0)
          + w * h * input_frames * calibration.get("shading_pixel_us" if shading else "input_pixel_us", 1.0)
          + sum(w * h * frames * filter_us.get(s.split(":")[0], filter_us.get("svgf", 1.0))
                for s in experiment.methods.values()))
    return us * 1e-6


def samples(experiment):
    """pixels x reference spp x frames of the references an eval experiment renders."""
    if experiment.tool != "eval":
        return 0
    w, h = (int(v) for v in experiment.size.split("x"))
    ranges = [declarations.frame_range(r["frames"]) for r in experiment.runs]
    return sum(w * h * experiment.ref_spp * (last - first + 1) for first, last in ranges)


def duration(seconds):
    return f"{seconds / 60:.0f} min" if seconds >= 90 else f"{seconds:.0f} s"


def list_experiments(experiments, calibration):
    print(f"{'experiment':<22} {'tool':<6} {'ref. samples':>13} {'estimate':>9}  results  tables")
    total = 0.0
    for e in experiments.values():
        seconds = sum(run_seconds(e, r, calibration) for r in e.runs or [{}])
        total += seconds if not e.device_step else 0.0
        kept = tables.read_kept(e)
        state = f"kept {kept[0]['date']}" if kept else "pending"
        where = ", ".join(sorted({t.readme for t in e.tables}))
        cost = f"{samples(e) / 1e9:.2f} G" if e.tool == "eval" else "-"
        estimate = f"GPU: {e.device_step}" if e.device_step else duration(seconds)
        print(f"{e.name:<22} {e.tool:<6} {cost:>13} {estimate:>9}  {state:<15}  {where}")
    print(f"all CPU experiments: about {duration(total)} on 2 cores with an empty frame cache "
          f"(ref. samples: pixels x reference spp x frames; {calibration.get('note', '')})")


# ---- Running ------------------------------------------------------------------------------------------------

def run_eval(experiment, run, rtdr, options, out_dir):
    out = os.path.join(out_dir, run["id"])
    command = [rtdr] + options.rtdr_prefix + experiment.rtdr_args(run) + ["--cache", options.cache, "--out", out]
    subprocess.run(command, check=True)
    by_spec = {spec: alias for alias, spec in experiment.methods.items()}
    metrics = experiment.metrics()
    rows = {}
    with open(os.path.join(out, "metrics.csv"), encoding="utf-8") as f:
        for r in csv.DictReader(f):
            spec = r["method"] + (":" + r["params"] if r["params"] else "")
            if spec not in by_spec:
                fail(f"rtdr eval wrote method '{spec}', which {experiment.name} does not declare "
                     "(write specs as rtdr writes them back)")
            rows[(by_spec[spec], int(r["frame"]))] = [run["id"], by_spec[spec], spec, r["frame"]] + [
                r.get(m, "") for m in metrics]
    first, last = declarations.frame_range(run["frames"])
    return [rows[(alias, frame)] for alias in experiment.methods for frame in range(first, last + 1)]


def bench_rows(run_id, path):
    """rtdr bench's CSV as kept rows: the filter stage's metrics get their back end in front (cpu_ms_total), and
    each scene the threads it ran on as a metric of its own (`threads`)."""
    rows = []
    with open(path, encoding="utf-8") as f:
        for r in csv.DictReader(f):
            if not any(row[1] == r["scene"] and row[2] == "threads" for row in rows):
                rows.append([run_id, r["scene"], "threads", r["threads"]])
            metric = r["metric"]
            if r["stage"].startswith("filter:"):
                backend = r["stage"].rsplit(":", 1)[1]
                metric = metric if backend == "cpu/vulkan" else f"{backend}_{metric}"
            # A name a cell can read: ms_visibility+gbuffer is ms_visibility_gbuffer.
            rows.append([run_id, r["scene"], re.sub(r"\W", "_", metric), r["value"]])
    return rows


def run_bench(experiment, run, rtdr, options, out_dir):
    path = os.path.join(out_dir, run["id"] + ".csv")
    environment = dict(os.environ, **dict(v.split("=", 1) for v in run.get("env", [])))
    subprocess.run([rtdr] + options.rtdr_prefix + experiment.rtdr_args(run) + ["--csv", path], check=True,
                   env=environment)
    return bench_rows(run["id"], path)


def run_ctest(experiment, run, rtdr, options, out_dir):
    """ctest -L stability -V, its output passed through; the `stability:` lines it prints, as kept rows."""
    command = ["ctest", "--test-dir", options.build, "-L", "stability", "-V"]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    rows = []
    for line in process.stdout:
        sys.stdout.write(line)
        match = STABILITY_LINE.search(line.rstrip("\n"))
        if match:
            rows.append([match.group("claim"), match.group("value"), match.group("threshold") or ""])
    if process.wait() != 0:
        fail("ctest -L stability failed: its claims are not written into the READMEs")
    if not rows:
        fail("ctest -L stability printed no 'stability:' lines (is the build folder right?)")
    return rows


RUNNERS = {"eval": run_eval, "bench": run_bench, "ctest": run_ctest}


def write_tables(experiment, run_facts, root):
    kept = tables.read_kept(experiment)
    recs = tables.records(experiment, kept[1], kept[2])
    for t in experiment.tables:
        tables.replace_block(os.path.join(root, t.readme), t.marker, tables.block(t, run_facts, recs))
        print(f"reproduce: wrote the table {t.marker} in {t.readme}")


def reproduce(experiment, calibration, options):
    if experiment.device_step:
        fail(f"{experiment.name} runs on a GPU: bash tools/gpu_device.sh {experiment.device_step} there, then "
             f"tools/reproduce.py --from-csv {experiment.name} DIR here")
    rtdr = os.path.join(options.build, "app", "rtdr")
    if experiment.tool != "ctest" and not os.access(rtdr, os.X_OK):
        fail(f"no {rtdr}: build it first, or name the build folder with --build")
    run_facts = facts(options.root)
    runs = experiment.runs or [{"id": "ctest"}]
    estimates = [run_seconds(experiment, r, calibration) for r in runs]
    rows, start, scale = [], time.monotonic(), 1.0
    with tempfile.TemporaryDirectory(prefix="reproduce-") as out_dir:
        for k, run in enumerate(runs):
            left = scale * sum(estimates[k:])
            print(f"reproduce: {experiment.name} [{k + 1}/{len(runs)}] {run['id']}: about "
                  f"{duration(scale * estimates[k])}; the experiment about {duration(left)} left", flush=True)
            run_start = time.monotonic()
            rows += RUNNERS[experiment.tool](experiment, run, rtdr, options, out_dir)
            if estimates[k] > 0:  # the machine's pace so far rescales what is left
                scale = (time.monotonic() - start) / sum(estimates[:k + 1])
            print(f"reproduce: {run['id']} took {duration(time.monotonic() - run_start)}", flush=True)
    tables.write_kept(experiment, dict(experiment=experiment.name, **run_facts), tables.expected_header(experiment),
                      rows)
    write_tables(experiment, run_facts, options.root)
    print(f"reproduce: {experiment.name} took {duration(time.monotonic() - start)}")


def from_csv(experiment, folder, options):
    """A GPU experiment's tables from the CSVs tools/gpu_device.sh wrote on the device (its $LOGS, unpacked)."""
    if not experiment.device_step:
        fail(f"{experiment.name} is not a GPU experiment: run it here")
    rows, threads = [], set()
    for run in experiment.runs:
        path = os.path.join(folder, run["device_csv"])
        if not os.path.exists(path):
            fail(f"no {path}: did tools/gpu_device.sh {experiment.device_step} finish?")
        rows += bench_rows(run["id"], path)
        with open(path, encoding="utf-8") as f:
            threads |= {r["threads"] for r in csv.DictReader(f)}
    run_facts = facts(options.root)
    run_facts["cores"] = max(threads, key=int)
    run_facts.pop("load")
    run_facts["device"] = device_name(folder)
    tables.write_kept(experiment, dict(experiment=experiment.name, **run_facts), tables.expected_header(experiment),
                      rows)
    write_tables(experiment, run_facts, options.root)


def device_name(folder):
    """The GPU's name from tools/gpu_device.sh's info.txt (nvidia-smi's CSV), with spaces as the footer has them."""
    try:
        with open(os.path.join(folder, "info.txt"), encoding="utf-8") as f:
            return f.read().split("\n")[1].split(",")[0].strip().replace("=", "-") or "a GPU"
    except (OSError, IndexError):
        return "a GPU"


# ---- Checking -----------------------------------------------------------------------------------------------

def markdown_files(root):
    listed = subprocess.run(["git", "-C", root, "ls-files", "--cached", "--others", "--exclude-standard", "*.md"],
                            capture_output=True, text=True)
    if listed.returncode == 0 and listed.stdout:
        return [f for f in listed.stdout.split("\n") if f and os.path.exists(os.path.join(root, f))]
    found = []
    for folder, subfolders, names in os.walk(root):  # not a git checkout: all but build trees and outputs
        subfolders[:] = [d for d in subfolders if not d.startswith(("build", "out", "."))]
        found += [os.path.relpath(os.path.join(folder, n), root) for n in names if n.endswith(".md")]
    return found


def check(experiments, root, declaration):
    """Every marked table against what its kept CSV makes; every marker declared; no stray kept CSV. A folder with
    a declaration of its own (tests/data/reproduce/experiments.toml) is that declaration's, and is left out."""
    problems, checked, pending = [], 0, []
    declared = {t.marker: t for e in experiments.values() for t in e.tables}
    for md in markdown_files(root):
        other = os.path.join(root, os.path.dirname(md), "experiments.toml")
        if os.path.exists(other) and not os.path.samefile(other, declaration):
            continue
        with open(os.path.join(root, md), encoding="utf-8") as f:
            try:
                found = tables.find_blocks(f.read())
            except declarations.DeclarationError as error:
                problems.append(f"{md}: {error}")
                continue
        problems += [f"{md}: marker {m} is declared by no experiment" for m in found if m not in declared]
        problems += [f"{md}: marker {m} belongs in {declared[m].readme}" for m in found
                     if m in declared and declared[m].readme != md]
    for e in experiments.values():
        try:
            kept = tables.read_kept(e)
            recs = tables.records(e, kept[1], kept[2]) if kept else None
        except declarations.DeclarationError as error:
            problems.append(str(error))
            continue
        for t in e.tables:
            path = os.path.join(root, t.readme)
            found = tables.block_in(path, t.marker) if os.path.exists(path) else None
            if found is None:
                problems.append(f"{t.readme}: no <!-- experiment: {t.marker} --> block")
                continue
            if kept is None:
                match = tables.PENDING.match(found[-1]) if found else None
                if not match or match.group("command") != e.footer_command():
                    problems.append(f"{t.readme}: {t.marker} has no kept CSV ({os.path.relpath(e.results, root)}) "
                                    "and no 'Last hand-typed values ..., pending a run' footer")
                else:
                    pending.append(t.marker)
                continue
            try:
                wanted = tables.block(t, kept[0], recs)
            except declarations.DeclarationError as error:
                problems.append(str(error))
                continue
            if found == wanted:
                checked += 1
            else:
                k = next((k for k, (a, b) in enumerate(zip(found, wanted)) if a != b), min(len(found), len(wanted)))
                problems.append(f"{t.readme}: table {t.marker}, line {k + 1} inside the markers is\n    "
                                f"{found[k] if k < len(found) else '(nothing)'}\n  but its kept CSV makes\n    "
                                f"{wanted[k] if k < len(wanted) else '(nothing)'}")
    results = os.path.dirname(next(iter(experiments.values())).results) if experiments else ""
    if os.path.isdir(results):
        stray = [n for n in os.listdir(results) if n.endswith(".csv") and n[:-4] not in experiments]
        problems += [f"{os.path.relpath(results, root)}/{n}: no experiment of that name" for n in stray]
    for p in problems:
        print(p)
    print(f"reproduce --check: {checked} tables as their kept CSVs make them"
          + (f"; {len(pending)} hand-typed, pending a run: {', '.join(pending)}" if pending else "")
          + (f"; {len(problems)} problems" if problems else ""))
    return 1 if problems else 0


def main():
    parser = argparse.ArgumentParser(description="Regenerates the docs' results tables (eval/experiments.toml).")
    parser.add_argument("names", nargs="*", metavar="NAME", help="experiments to run")
    parser.add_argument("--list", action="store_true", help="list the experiments and their cost")
    parser.add_argument("--check", action="store_true", help="check every table against its kept CSV")
    parser.add_argument("--from-csv", metavar="DIR", help="a GPU experiment's tables from the device's CSVs in DIR")
    parser.add_argument("--experiments", default=os.path.join(ROOT, "eval", "experiments.toml"))
    parser.add_argument("--root", default=ROOT, help="the folder the declared READMEs are in")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--cache", default=os.path.join(ROOT, "out", "cache"))
    parser.add_argument("--threads", type=int, help="rtdr --threads N")
    options = parser.parse_args()
    options.rtdr_prefix = ["--threads", str(options.threads)] if options.threads is not None else []
    try:
        experiments, calibration = declarations.load(options.experiments)
        if options.list:
            list_experiments(experiments, calibration)
            return 0
        if options.check:
            return check(experiments, options.root, options.experiments)
        unknown = [n for n in options.names if n not in experiments]
        if unknown or not options.names:
            fail(f"no experiment {', '.join(unknown)}" if unknown else "name an experiment (--list shows them)")
        if options.from_csv:
            if len(options.names) != 1:
                fail("--from-csv takes one experiment")
            from_csv(experiments[options.names[0]], options.from_csv, options)
            return 0
        for name in options.names:
            reproduce(experiments[name], calibration, options)
    except declarations.DeclarationError as error:
        fail(str(error))
    except subprocess.CalledProcessError as error:
        fail(f"{os.path.basename(error.cmd[0])} failed (exit {error.returncode}): nothing was written")
    return 0


if __name__ == "__main__":
    sys.exit(main())
