#!/usr/bin/python3
"""tools/farm.py runs the jobs of `rtdr eval --plan` into the frame cache, so that the eval then renders nothing
(ctest: `tools_farm_<case>`). Everything runs on 127.0.0.1, on pillars at 32x18, a few frames.

Usage: tools_farm_test.py SOURCE_DIR RTDR CASE

  plan           By construction, without Dask: for two runs (svgf and trmv on plain inputs with TRMV's shading
                 term and seed 5; asvgf and Fig. 5's 2x2 strata on two gradient sequences, frames 2-4, which
                 reach back to frame 0), each planned job is run alone, one after the other, by
                 `farm.py PLAN --job K` (what a batch scheduler's task runs; a Dask worker runs the same code).
                 Then a plan lists no job, and the eval renders nothing (no entry new or written again, no
                 warning, no staging folder left).
  local          farm.py --local 2 --threads 1 (a LocalCluster of 2 processes) runs a plan; the eval then renders
                 nothing, and its metrics.csv equals that of a plain `rtdr --threads 2 eval` in another cache,
                 every column but ms_*; every entry the farm wrote is the same file, byte for byte, as the plain
                 run's: bit-identical across processes and thread counts. Progress has an ETA; the summary counts.
  scheduler      The same with a real `dask scheduler` and two `dask worker` processes, started and stopped here.
  killed_worker  A worker is killed (SIGKILL) while its `rtdr render` runs a 4096-spp reference: the job runs again
                 (the summary counts the retry), the farm succeeds, and no partial entry is left or used: a new
                 plan lists no job, the eval renders nothing and warns of nothing, and no staging folder survives it.
  failing_job    A job whose scene does not exist fails on both its tries (--retries 1): the farm exits 1, its last
                 line is `farm: error: job K (...) failed on all 2 tries: rtdr: error: ...` with rtdr's own line,
                 no traceback, and that job's entry is not in the cache.

Prints one line per failed check and exits 1 when there is any.
"""
import csv
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SOURCE_DIR, RTDR, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
try:
    import distributed  # noqa: F401
except ImportError:
    print("tools_farm_test: needs Debian's python3-distributed (tools/setup.sh installs it)")
    sys.exit(1)
FARM = os.path.join(SOURCE_DIR, "tools", "farm.py")
PYTHON = "/usr/bin/python3"
DASK = shutil.which("dask", path="/usr/bin:" + os.environ.get("PATH", "")) or "/usr/bin/dask"
RUN = ["--scene", "pillars", "--size", "32x18", "--frames", "0-2", "--ref-spp", "4", "--methods", "svgf,asvgf"]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
    return condition


def run(argv, **kw):
    return subprocess.run(argv, capture_output=True, text=True, **kw)


def eval_args(args, cache, out, threads=None):
    threads = ["--threads", str(threads)] if threads else []
    return [RTDR] + threads + ["eval"] + args + ["--cache", cache, "--out", out]


def plan(args, cache, path):
    """The jobs of `rtdr eval --plan`, as farm.py reads them."""
    r = run(eval_args(args, cache, os.path.join(os.path.dirname(path), "unused")) + ["--plan", path])
    if not check(r.returncode == 0, f"rtdr eval --plan failed: {r.stderr.strip()}"):
        return []
    with open(path) as f:
        return [json.loads(line) for line in f]


def entries(cache):
    """{path relative to the cache: (device, inode)} of every frame file but those in hidden staging folders."""
    found = {}
    for root, dirs, files in os.walk(cache):
        dirs[:] = [d for d in dirs if not d.startswith(".")]
        for name in files:
            if name.endswith(".exr"):
                st = os.stat(os.path.join(root, name))
                found[os.path.relpath(os.path.join(root, name), cache)] = (st.st_dev, st.st_ino)
    return found


def metrics(out):
    """metrics.csv without its timing columns."""
    with open(os.path.join(out, "metrics.csv")) as f:
        return [{k: v for k, v in row.items() if not k.startswith("ms_")} for row in csv.DictReader(f)]


def eval_renders_nothing(args, cache, out, what):
    """Runs the eval on a cache the farm filled: it must store no entry, new or again, and warn of nothing."""
    before = entries(cache)
    r = run(eval_args(args, cache, out))
    check(r.returncode == 0, f"{what}: the eval failed: {r.stderr.strip()}")
    check(entries(cache) == before, f"{what}: the eval rendered frames: "
          f"{sorted(set(entries(cache).items()) ^ set(before.items()))[:4]}")
    check("warning" not in r.stderr, f"{what}: the eval warned: {r.stderr.strip()}")
    check(not [n for n in os.listdir(cache) if n.startswith(".rtdr-cache-staging-")],
          f"{what}: a staging folder is left in the cache after the eval: {os.listdir(cache)}")


def same_as_plain_run(args, cache, out, tmp, what):
    """The eval's metrics equal a plain run's (rtdr --threads 2, its own cache) but for ms_*; with the farm's frames
    byte for byte the plain run's."""
    plain_cache, plain_out = os.path.join(tmp, "plain_cache"), os.path.join(tmp, "plain_out")
    r = run(eval_args(args, plain_cache, plain_out, threads=2))
    if not check(r.returncode == 0, f"{what}: the plain run failed: {r.stderr.strip()}"):
        return
    a, b = metrics(out), metrics(plain_out)
    check(len(a) > 0 and a == b, f"{what}: metrics.csv differs from the plain run's:\n{a[:2]}\n{b[:2]}")
    farm_entries, plain_entries = entries(cache), entries(plain_cache)
    check(sorted(farm_entries) == sorted(plain_entries), f"{what}: the caches hold different entries")
    for rel in sorted(set(farm_entries) & set(plain_entries)):
        with open(os.path.join(cache, rel), "rb") as f, open(os.path.join(plain_cache, rel), "rb") as g:
            check(f.read() == g.read(), f"{what}: {rel} differs between the farm (--threads 1) and the plain run")


def farm(plan_path, *where, expect=0):
    r = run([PYTHON, FARM, plan_path, *where])
    check(r.returncode == expect, f"farm.py {' '.join(where)} exited {r.returncode}, not {expect}: {r.stderr}")
    check("Traceback" not in r.stderr, f"farm.py printed a traceback:\n{r.stderr}")
    return r


def summary_counts(stderr):
    m = re.search(r"farm: done: (\d+) jobs in [\d.]+ s, (\d+) retr(?:y|ies), ([\d.]+) worker-seconds", stderr)
    return (int(m.group(1)), int(m.group(2)), float(m.group(3))) if m else None


def case_plan(tmp):
    runs = [["--scene", "pillars", "--size", "32x18", "--frames", "1-3", "--ref-spp", "4", "--seed", "5",
             "--methods", "svgf,trmv"],
            ["--scene", "pillars", "--size", "32x18", "--frames", "2-4", "--ref-spp", "4",
             "--methods", "asvgf,asvgf:gradient_stratum_size=2"]]
    for k, args in enumerate(runs):
        cache, out = os.path.join(tmp, f"cache{k}"), os.path.join(tmp, f"out{k}")
        jobs = plan(args, cache, os.path.join(tmp, f"plan{k}.jsonl"))
        dependent = [j for j in jobs if j["dependent"]]
        check(len(jobs) == (6 if k == 0 else 5), f"run {k}: {len(jobs)} jobs planned")
        check(len(dependent) == (0 if k == 0 else 2), f"run {k}: {len(dependent)} dependent jobs")
        for job in jobs:
            farm(os.path.join(tmp, f"plan{k}.jsonl"), "--job", str(job["job"]), "--threads", "1")
        again = plan(args, cache, os.path.join(tmp, f"again{k}.jsonl"))
        check(again == [], f"run {k}: a plan after the jobs lists jobs: {again}")
        eval_renders_nothing(args, cache, out, f"run {k}")


def case_local(tmp):
    cache, out = os.path.join(tmp, "cache"), os.path.join(tmp, "out")
    jobs = plan(RUN, cache, os.path.join(tmp, "plan.jsonl"))
    check(len(jobs) == 4, f"{len(jobs)} jobs planned, not 3 references and a run of gradient frames")
    r = farm(os.path.join(tmp, "plan.jsonl"), "--local", "2", "--threads", "1")
    check(summary_counts(r.stderr) is not None and summary_counts(r.stderr)[:2] == (4, 0),
          f"the summary is not 4 jobs, 0 retries: {r.stderr}")
    check(re.search(r"farm: 4/4 jobs, 100% of the cost, [\d.]+ s elapsed, ETA 0 s", r.stderr),
          f"no progress with an ETA: {r.stderr}")
    eval_renders_nothing(RUN, cache, out, "local")
    same_as_plain_run(RUN, cache, out, tmp, "local")


class Cluster:
    """A `dask scheduler` and two `dask worker` processes on 127.0.0.1. The workers run without a nanny, so each
    worker is the process started here, and the parent of the `rtdr render` it runs."""

    def __init__(self, tmp):
        self.file = os.path.join(tmp, "scheduler.json")
        log = open(os.path.join(tmp, "dask.log"), "w")
        common = ["--no-dashboard", "--host", "127.0.0.1"]
        self.scheduler = subprocess.Popen([DASK, "scheduler", "--port", "0", "--scheduler-file", self.file] + common,
                                          stdout=log, stderr=log)
        worker = [DASK, "worker", "--scheduler-file", self.file, "--nthreads", "1", "--no-nanny"] + common
        self.workers = [subprocess.Popen(worker + ["--local-directory", os.path.join(tmp, f"worker{k}")],
                                         stdout=log, stderr=log) for k in range(2)]
        from distributed import Client
        with Client(scheduler_file=self.file, timeout=60) as client:
            client.wait_for_workers(2, timeout=60)
            self.address = client.scheduler.address

    def stop(self):
        for p in self.workers + [self.scheduler]:
            p.send_signal(signal.SIGINT)  # Ctrl-C: quicker to close than SIGTERM
        for p in self.workers + [self.scheduler]:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


def case_scheduler(tmp):
    cache, out = os.path.join(tmp, "cache"), os.path.join(tmp, "out")
    plan(RUN, cache, os.path.join(tmp, "plan.jsonl"))
    cluster = Cluster(tmp)
    try:
        r = farm(os.path.join(tmp, "plan.jsonl"), "--scheduler", cluster.address, "--threads", "1")
    finally:
        cluster.stop()
    check(summary_counts(r.stderr) is not None and summary_counts(r.stderr)[:2] == (4, 0),
          f"the summary is not 4 jobs, 0 retries: {r.stderr}")
    eval_renders_nothing(RUN, cache, out, "scheduler")
    same_as_plain_run(RUN, cache, out, tmp, "scheduler")


def processes():
    """{pid: (parent pid, argument vector)} of every process."""
    found = {}
    for name in os.listdir("/proc"):
        try:
            with open(f"/proc/{name}/stat") as f:
                parent = int(f.read().rsplit(")", 1)[1].split()[1])
            with open(f"/proc/{name}/cmdline", "rb") as f:
                found[int(name)] = (parent, f.read().decode("utf-8", "replace").split("\0"))
        except (ValueError, OSError, IndexError):
            continue
    return found


def running(pid):
    """Whether process `pid` lives (a zombie, dead but not yet reaped, does not)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def case_killed_worker(tmp):
    cache, out = os.path.join(tmp, "cache"), os.path.join(tmp, "out")
    args = ["--scene", "pillars", "--size", "32x18", "--frames", "0-1", "--ref-spp", "4096", "--methods", "svgf"]
    plan(args, cache, os.path.join(tmp, "plan.jsonl"))
    cluster = Cluster(tmp)
    try:
        farm_run = subprocess.Popen([PYTHON, FARM, os.path.join(tmp, "plan.jsonl"), "--scheduler", cluster.address,
                                     "--threads", "1"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        killed = None
        deadline = time.monotonic() + 60
        while killed is None and farm_run.poll() is None and time.monotonic() < deadline:
            procs = processes()
            for pid, (parent, argv) in procs.items():
                # A reference's rtdr render, staging in our cache, run by one of our workers.
                if (argv[0] == RTDR and "render" in argv and "4096" in argv and any(a.startswith(cache) for a in argv)
                        and parent in [w.pid for w in cluster.workers]):
                    time.sleep(0.05)  # inside its render (half a second or more), its start logged with the scheduler
                    os.kill(parent, signal.SIGKILL)
                    killed = (parent, pid)
                    break
            time.sleep(0.01)
        stdout, stderr = farm_run.communicate(timeout=120)
    finally:
        cluster.stop()
    if not check(killed is not None, "no worker was caught running a reference"):
        return
    check(farm_run.returncode == 0, f"the farm failed after a worker was killed: {stderr}")
    counts = summary_counts(stderr)
    check(counts is not None and counts[0] == 4 and counts[1] >= 1, f"the summary counts no retry: {stderr}")
    check(not running(killed[1]), "the killed worker's rtdr render lives on")
    check(plan(args, cache, os.path.join(tmp, "again.jsonl")) == [], "a plan after the farm lists jobs")
    eval_renders_nothing(args, cache, out, "killed worker")


def case_failing_job(tmp):
    cache = os.path.join(tmp, "cache")
    jobs = plan(RUN, cache, os.path.join(tmp, "plan.jsonl"))
    missing = os.path.join(tmp, "no such folder", "pillars.gltf")
    bad = jobs[1]
    bad["argv"][bad["argv"].index("--scene") + 1] = missing
    with open(os.path.join(tmp, "plan.jsonl"), "w") as f:
        f.writelines(json.dumps(j) + "\n" for j in jobs)
    r = farm(os.path.join(tmp, "plan.jsonl"), "--local", "1", "--retries", "1", expect=1)
    last = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else ""
    check(re.fullmatch(rf"farm: error: job 1 \(reference, frame 1\) failed on all 2 tries: rtdr: error: "
                       rf"{re.escape(missing)}: no such scene file.*", last), f"not the job's own error: {last!r}")
    check(r.stderr.count("job 1 (reference, frame 1) failed (try 1 of 2)") == 1, f"no retry announced: {r.stderr}")
    check(not os.path.exists(bad["entries"][0]), "the failed job's entry exists")


def main():
    tmp = tempfile.mkdtemp(prefix=f"rtdr_farm_test_{CASE}_")
    try:
        {"plan": case_plan, "local": case_local, "scheduler": case_scheduler, "killed_worker": case_killed_worker,
         "failing_job": case_failing_job}[CASE](tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    for f in failures:
        print(f"tools_farm_test {CASE}: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
