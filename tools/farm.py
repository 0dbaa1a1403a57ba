#!/usr/bin/python3
"""Runs the render jobs of `rtdr eval --plan` on a Dask cluster, into the frame cache the plan names.

  /usr/bin/python3 tools/farm.py PLAN --local N                    a LocalCluster of N worker processes here
  /usr/bin/python3 tools/farm.py PLAN --scheduler tcp://host:8786  a running cluster (dask scheduler, dask worker)
  /usr/bin/python3 tools/farm.py PLAN --job K                      job K alone, here, without Dask: what a batch
                                                                   scheduler's task runs (docs/scaling.md, Slurm)

Then the same `rtdr eval`, without --plan, finds every frame in its cache and renders none. docs/scaling.md says
how to set up a cluster, and what every machine must share.

A job (eval/render_plan.h) is one `rtdr render` argument vector and the cache entries its frames fill. A worker runs
it by argument vector (never a shell), with `--out` a fresh staging folder inside the cache, made on the cache's own
protocol (core/atomic_file.h StagingFolder: .rtdr-cache-staging-<16 hex digits>, and beside it a .lock file the
worker holds an flock on while the job lives). Then it renames each frame to its entry: one file system, so each
entry appears whole or not at all. A worker killed in the middle of a job leaves only that hidden folder, whose lock
the kernel frees; the next rtdr eval on the cache removes it. A dependent job (a run of gradient frames continuing
frame A-1) gets the cached frame A-1 linked into its staging folder first, where rtdr render --gradients reads it
and checks its render key.

A job that fails is tried again, up to --retries more times (with --job too). Dask itself reruns, on another
worker, the job of a worker that died, and gives up with KilledWorker after distributed.scheduler.allowed-failures
deaths (3), which then counts as a failed try here. A job that fails on every try ends the run with that job's own
one-line error.
Progress, with an ETA from the jobs' cost estimates, goes to stderr; so does the summary: jobs, retries (tries
after a job's first, the ones Dask made after a worker died included) and worker-seconds (of every try that ran to
its end).

Exit status: 0 when every job is done; 1 when a job failed on every try, or the plan cannot be read; 2 for a bad
command line. Needs Debian's python3-distributed (tools/setup.sh installs it).
"""
import argparse
import ctypes
import fcntl
import json
import logging
import os
import secrets
import shutil
import signal
import subprocess
import sys
import time

STAGING_PREFIX = ".rtdr-cache-staging-"  # eval/frame_cache.cpp kStagingPrefix: the cache removes stale ones
EVENTS = "rtdr-farm"  # the Dask event topic each try of a job logs its start on


class FarmError(Exception):
    """A failure that ends the run: printed as one line, `farm: error: ...`."""


class JobFailed(Exception):
    """One try of a job failed: `message` is its one line (rtdr's own error, when rtdr printed one)."""

    def __init__(self, message, seconds):
        super().__init__(message, seconds)
        self.message = message
        self.seconds = seconds

    def __str__(self):
        return self.message


def read_plan(path):
    """The jobs of a plan file, one JSON object a line, each checked for what a worker reads."""
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise FarmError(f"cannot read the plan '{path}': {e.strerror}")
    jobs = []
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        try:
            job = json.loads(line)
            first, last = job["frames"]
            ok = (isinstance(job["argv"], list) and all(isinstance(a, str) for a in job["argv"]) and job["argv"]
                  and isinstance(job["entries"], list) and len(job["entries"]) == last - first + 1
                  and isinstance(job["cache"], str) and isinstance(job["cost"], (int, float)))
        except (ValueError, KeyError, TypeError) as e:
            raise FarmError(f"{path}:{number}: not a job of rtdr eval --plan ({e})")
        if not ok:
            raise FarmError(f"{path}:{number}: not a job of rtdr eval --plan (argv, entries, cache or cost)")
        jobs.append(job)
    return jobs


def describe(job):
    first, last = job["frames"]
    frames = f"frame {first}" if first == last else f"frames {first}-{last}"
    return f"job {job['job']} ({job['what']}, {frames})"


def frame_name(index):
    return f"frame_{index:04d}.exr"  # app/sequence.h frame_name


def last_line(text):
    """The last non-empty line (a progress bar's carriage returns end lines too)."""
    lines = [s.strip() for s in text.replace("\r", "\n").split("\n") if s.strip()]
    return lines[-1] if lines else ""


class StagingFolder:
    """<parent>/.rtdr-cache-staging-<16 hex digits>, with <that>.lock flock'ed by this process while it lives: the
    protocol of core/atomic_file.h StagingFolder, so a folder whose process died is known stale and removed by the
    next rtdr that stages in the cache."""

    def __init__(self, parent):
        os.makedirs(parent, exist_ok=True)
        for _ in range(8):
            path = os.path.join(parent, STAGING_PREFIX + secrets.token_hex(8))
            try:
                fd = os.open(path + ".lock", os.O_RDWR | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, 0o644)
            except FileExistsError:
                continue
            fcntl.flock(fd, fcntl.LOCK_EX)
            # Between our open and our lock a cleaner may have removed the file: then it is not ours, try again.
            try:
                mine, now = os.fstat(fd), os.stat(path + ".lock")
                ours = (mine.st_dev, mine.st_ino) == (now.st_dev, now.st_ino)
            except FileNotFoundError:
                ours = False
            if not ours:
                os.close(fd)
                continue
            os.mkdir(path)
            self.path, self.fd = path, fd
            return
        raise OSError(f"no free staging name in '{parent}' after 8 tries")

    def remove(self):
        shutil.rmtree(self.path, ignore_errors=True)  # still locked: no cleaner touches it meanwhile
        os.unlink(self.path + ".lock")
        os.close(self.fd)


def log_try_start(run, job):
    """Tells the scheduler a try of `job` in farm run `run` starts (a retry when not its first); outside Dask,
    nothing."""
    try:
        from distributed import get_worker
        get_worker().log_event(EVENTS, {"run": run, "job": job["job"]})
    except (ImportError, ValueError):
        pass


def render(argv):
    """Runs `argv` (rtdr render), by argument vector, as a child that dies with this process (PR_SET_PDEATHSIG):
    a worker killed takes its rtdr with it. Returns "" when it succeeds, else its one line."""
    prctl, parent = ctypes.CDLL(None, use_errno=True).prctl, os.getpid()

    def die_with_worker():  # in the child, before exec
        prctl(1, int(signal.SIGKILL))  # 1: PR_SET_PDEATHSIG
        if os.getppid() != parent:  # the worker died before the line above
            os._exit(127)

    try:
        result = subprocess.run(argv, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                preexec_fn=die_with_worker)
    except OSError as e:
        return f"cannot run {argv[0]}: {e.strerror}"
    why = last_line(result.stderr.decode("utf-8", "replace"))
    if result.returncode < 0:
        return f"rtdr render was killed by signal {-result.returncode}" + (f" ({why})" if why else "")
    if result.returncode > 0:
        return why or f"rtdr render exited with status {result.returncode}"
    return ""


def run_job(job, threads=0, run=""):
    """Runs one job where this is called (a Dask worker): rtdr render into a staging folder inside the cache, then
    each frame renamed to its entry. Returns the seconds it took; raises JobFailed with one line otherwise."""
    log_try_start(run, job)
    start = time.monotonic()
    argv = list(job["argv"])
    if threads:
        argv[1:1] = ["--threads", str(threads)]  # rtdr's global option: the frames are the same for any count
    first, last = job["frames"]
    try:
        staging = StagingFolder(job["cache"])
    except OSError as e:
        raise JobFailed(f"cannot stage in the cache '{job['cache']}': {e}", time.monotonic() - start)
    try:
        if job.get("previous"):  # frame first-1, which the run continues (its key is checked by rtdr render)
            target = os.path.join(staging.path, frame_name(first - 1))
            try:
                try:
                    os.link(job["previous"], target)
                except OSError:
                    shutil.copyfile(job["previous"], target)
            except OSError as e:
                raise JobFailed(f"cannot read the frame it continues, '{job['previous']}': {e.strerror}",
                                time.monotonic() - start)
        why = render(argv + ["--out", staging.path])
        if why:
            raise JobFailed(why, time.monotonic() - start)
        staged = [os.path.join(staging.path, frame_name(f)) for f in range(first, last + 1)]
        for path in staged:
            if not os.path.isfile(path):
                raise JobFailed(f"rtdr render wrote no {os.path.basename(path)}", time.monotonic() - start)
        for path, entry in zip(staged, job["entries"]):  # each rename is atomic: an entry is whole or absent
            os.makedirs(os.path.dirname(entry), exist_ok=True)
            os.replace(path, entry)
    except OSError as e:
        raise JobFailed(f"cannot move a frame into the cache: {e}", time.monotonic() - start)
    finally:
        staging.remove()
    return time.monotonic() - start


class Progress:
    """Lines on stderr: jobs done, share of the cost done, elapsed time and the ETA the cost done so far gives."""

    def __init__(self, jobs, out):
        self.total, self.cost_total, self.out = len(jobs), sum(j["cost"] for j in jobs) or 1, out
        self.done = self.cost_done = 0
        self.start = time.monotonic()

    def finished(self, job):
        self.done += 1
        self.cost_done += job["cost"]
        elapsed = time.monotonic() - self.start
        eta = elapsed * (self.cost_total - self.cost_done) / self.cost_done if self.cost_done else 0.0
        print(f"farm: {self.done}/{self.total} jobs, {100.0 * self.cost_done / self.cost_total:.0f}% of the cost, "
              f"{elapsed:.1f} s elapsed, ETA {eta:.0f} s", file=self.out, flush=True)


def run_plan(client, jobs, retries, threads, out=sys.stderr):
    """Runs every job on `client`'s cluster, each failed one tried again up to `retries` times. Returns the summary
    (jobs, retries, worker_seconds, seconds); raises FarmError with the job's own line when one fails every try."""
    from distributed import as_completed
    progress = Progress(jobs, out)
    tries = {j["job"]: 1 for j in jobs}
    by_key, outstanding, worker_seconds = {}, set(), 0.0
    run = secrets.token_hex(8)  # this run's tries among the scheduler's events, which outlive runs

    def submit(job):
        key = f"rtdr-farm-{run}-job-{job['job']}-try-{tries[job['job']]}"
        future = client.submit(run_job, job, threads, run, key=key, pure=False)
        by_key[future.key] = job
        outstanding.add(future)
        return future

    pending = as_completed([submit(j) for j in jobs])
    for future in pending:
        outstanding.discard(future)
        job = by_key[future.key]
        if future.status == "finished":
            worker_seconds += future.result()
            progress.finished(job)
            continue
        try:
            error = future.exception()  # JobFailed, KilledWorker (its workers died), ...
        except Exception as e:  # noqa: BLE001  (cancelled: the scheduler lost it)
            error = e
        worker_seconds += getattr(error, "seconds", 0.0)
        line = last_line(str(error)) or type(error).__name__
        if tries[job["job"]] > retries:
            client.cancel(list(outstanding))
            raise FarmError(f"{describe(job)} failed on all {tries[job['job']]} tries: {line}")
        print(f"farm: {describe(job)} failed (try {tries[job['job']]} of {retries + 1}): {line}; trying again",
              file=out, flush=True)
        tries[job["job"]] += 1
        pending.add(submit(job))
    # Every try that began, the reruns Dask made after a worker died included.
    started = sum(1 for _, msg in client.get_events(EVENTS) if isinstance(msg, dict) and msg.get("run") == run)
    return {"jobs": len(jobs), "retries": max(started, sum(tries.values())) - len(jobs),
            "worker_seconds": worker_seconds, "seconds": time.monotonic() - progress.start}


def run_one(jobs, index, retries, threads):
    """--job K: job K of the plan, here, tried up to 1 + retries times. Returns the seconds of its last try."""
    job = next((j for j in jobs if j["job"] == index), None)
    if job is None:
        raise FarmError(f"the plan has no job {index}" + (f" (its jobs are {jobs[0]['job']} to {jobs[-1]['job']})"
                                                          if jobs else " (it holds none)"))
    for attempt in range(1, retries + 2):
        try:
            return run_job(job, threads)
        except JobFailed as e:
            if attempt > retries:
                raise FarmError(f"{describe(job)} failed on all {attempt} tries: {e}")
            print(f"farm: {describe(job)} failed (try {attempt} of {retries + 1}): {e}; trying again",
                  file=sys.stderr, flush=True)


def parse_args(argv):
    p = argparse.ArgumentParser(prog="farm.py", description="Runs the render jobs of rtdr eval --plan on Dask.")
    p.add_argument("plan", help="the file rtdr eval --plan wrote")
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--local", type=int, metavar="N", help="a LocalCluster of N worker processes on this machine")
    where.add_argument("--scheduler", metavar="URL", help="a running Dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--job", type=int, metavar="K", help="run job K of the plan here, without Dask")
    p.add_argument("--retries", type=int, default=2, help="tries of a failed job after its first (default 2)")
    p.add_argument("--threads", type=int, metavar="T",
                   help="rtdr --threads of every job (default: the cores shared among --local's workers; with "
                        "--scheduler or --job, every core of the machine the job runs on)")
    args = p.parse_args(argv)
    if args.local is not None and args.local < 1:
        p.error("--local needs at least 1 worker")
    if args.retries < 0 or (args.threads is not None and args.threads < 0):
        p.error("--retries and --threads must be at least 0")
    return args


def main(argv):
    args = parse_args(argv)
    try:
        jobs = read_plan(args.plan)
        if args.job is not None:
            seconds = run_one(jobs, args.job, args.retries, args.threads or 0)
            print(f"farm: done: job {args.job} in {seconds:.1f} s", file=sys.stderr)
            return 0
        if not jobs:
            print(f"farm: {args.plan} holds no job: the cache has every frame", file=sys.stderr)
            return 0
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            raise FarmError("needs Debian's python3-distributed (tools/setup.sh installs it)")
        threads = args.threads
        if args.local:
            if threads is None:
                threads = max(1, (os.cpu_count() or 1) // args.local)
            cluster = LocalCluster(n_workers=args.local, threads_per_worker=1, processes=True, host="127.0.0.1",
                                   dashboard_address=None, silence_logs=logging.ERROR)
        else:
            cluster = None
        try:
            with Client(cluster if cluster else args.scheduler) as client:
                workers = len(client.scheduler_info()["workers"])
                print(f"farm: {len(jobs)} jobs, {sum(j['cost'] for j in jobs):.4g} pixel samples, on "
                      f"{args.scheduler or 'a LocalCluster'} ({workers} workers now)", file=sys.stderr, flush=True)
                s = run_plan(client, jobs, args.retries, threads or 0)
        finally:
            if cluster:
                cluster.close()
    except FarmError as e:
        print(f"farm: error: {e}", file=sys.stderr)
        return 1
    except OSError as e:  # the scheduler cannot be reached, say
        print(f"farm: error: {last_line(str(e))}", file=sys.stderr)
        return 1
    retries = f"{s['retries']} retr{'y' if s['retries'] == 1 else 'ies'}"
    print(f"farm: done: {s['jobs']} jobs in {s['seconds']:.1f} s, {retries}, "
          f"{s['worker_seconds']:.1f} worker-seconds", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
