#!/usr/bin/python3
"""rtdr view (docs/view.md): its server (ctest: `app_view_<case>`); its page is tests/app_view_browser_test.py's,
which uses the helpers here. Each case renders pillars with
A-SVGF's gradient samples at 64x36, 3 frames, into a temporary folder, and starts `rtdr view --method asvgf --port 0`
on it; everything runs on 127.0.0.1.

Usage: app_view_test.py SOURCE_DIR RTDR BUILD_DIR CASE

  server   Paths: every traversal (`/../`, its percent-encoded and double-encoded forms, backslashes, `//`, an
           absolute-form target, `..` inside /katex/) gets 403 and no file; a path that is no route gets 404; a layer
           name is never a path. A symlink in --in that leads out of it stops rtdr view before it serves, with one
           line naming it; so does a missing --in, and a port that is taken. A missing layer gets 404 and the server
           answers the next request. It listens on
           127.0.0.1 only (/proc/net/tcp, and a connection to another address of this machine is refused). The data:
           /api/layer's bytes are the channels of `rtdr filter --dump-passes`'s EXR for the same frame, bit for bit;
           /api/probe's answer is `rtdr probe --json`'s output for the same question, byte for byte, for a pass of
           each scope; each term's file and line is a note() of that file.
  memory   The resident memory of rtdr view after 1,000 probe requests (every tenth followed by a layer request whose
           connection is closed before the answer is read, as a closed tab does) is within 10 MB of that after 100.
           Skipped under AddressSanitizer (tools/sanitize.sh), whose quarantine keeps freed memory on purpose.

Prints one line per failed check and exits 1 when there is any; 77 when the case is skipped.
"""
import http.client
import json
import os
import re
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

SOURCE_DIR = RTDR = BUILD_DIR = None  # from the command line (main), or set by tests/app_view_browser_test.py
SIZE, FRAMES, METHOD = "64x36", "0-2", "asvgf"
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
    return condition


def run(argv):
    # A view that should have stopped but serves instead fails here, not at ctest's timeout.
    return subprocess.run(argv, capture_output=True, text=True, timeout=240)


def render(out, *extra):
    r = run([RTDR, "render", "--scene", "pillars", "--frames", FRAMES, "--size", SIZE, "--gradients", "--out", out,
             *extra])
    if r.returncode != 0:
        sys.exit(f"rtdr render failed: {r.stderr.strip()}")


class View:
    """A running `rtdr view`, stopped (SIGINT, as Ctrl-C) when the block ends."""

    def __init__(self, *args):
        self.proc = subprocess.Popen([RTDR, "view", "--method", METHOD, "--port", "0", *args],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.lines = []
        for line in self.proc.stdout:
            self.lines.append(line)
            m = re.match(r"RTDR view of (\S+) on (.+): http://127\.0\.0\.1:(\d+)/  \(Ctrl-C to stop\)$", line.rstrip("\n"))
            if m:
                self.port = int(m.group(3))
                return
        sys.exit(f"rtdr view did not start: {''.join(self.lines)}{self.proc.stderr.read()}")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.proc.send_signal(signal.SIGINT)
        self.proc.wait(timeout=30)

    def url(self, path):
        return f"http://127.0.0.1:{self.port}{path}"

    def get(self, path):
        """(status, headers, body bytes); urllib raises on 4xx, so read those from the error."""
        try:
            with urllib.request.urlopen(self.url(path), timeout=30) as r:
                return r.status, r.headers, r.read()
        except urllib.error.HTTPError as e:
            return e.code, e.headers, e.read()

    def raw(self, target):
        """The status and body for a request line sent as it is, with no client normalising its target."""
        with socket.create_connection(("127.0.0.1", self.port), timeout=30) as s:
            s.sendall(f"GET {target} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n".encode("latin-1"))
            data = b""
            while chunk := s.recv(65536):
                data += chunk
        head, _, body = data.partition(b"\r\n\r\n")
        return int(head.split()[1]), body

    def resident_kb(self):
        with open(f"/proc/{self.proc.pid}/status") as f:
            return int(re.search(r"VmRSS:\s+(\d+) kB", f.read()).group(1))


def layer_values(view, frame, source, name):
    """The planes of a layer as /api/layer sends them: (channels, width, height, [list of floats per channel])."""
    status, headers, body = view.get(f"/api/layer?frame={frame}&source={source}&name={name}")
    if not check(status == 200, f"/api/layer {source} {name} frame {frame}: {status}"):
        return None
    w, h = int(headers["X-RTDR-Width"]), int(headers["X-RTDR-Height"])
    channels = headers["X-RTDR-Channels"].split(",")
    values = struct.unpack(f"<{len(body) // 4}f", body)
    return channels, w, h, [values[c * w * h:(c + 1) * w * h] for c in range(len(channels))]


def probe_cli(seq, frame, x, y, pass_, stream, level, as_json=True):
    r = run([RTDR, "probe", "--method", METHOD, "--in", seq, "--frame", str(frame), "--pixel", f"{x},{y}",
             "--pass", pass_, "--stream", stream, "--level", str(level)] + (["--json"] if as_json else []))
    check(r.returncode == 0, f"rtdr probe failed: {r.stderr.strip()}")
    return r.stdout


# ---- server ---------------------------------------------------------------------------------------------------
def case_server(tmp):
    seq, dumps = os.path.join(tmp, "seq"), os.path.join(tmp, "dumps")
    render(seq)
    r = run([RTDR, "filter", "--method", METHOD, "--in", seq, "--out", dumps, "--dump-passes"])
    check(r.returncode == 0, f"rtdr filter --dump-passes failed: {r.stderr.strip()}")
    with View("--in", seq) as view:
        for target in ["/../etc/passwd", "/..%2f..%2fetc%2fpasswd", "/%2e%2e/%2e%2e/etc/passwd", "/%2E%2E/etc/passwd",
                       "/%252e%252e/%252e%252e/etc/passwd", "/katex/../../../../../etc/passwd",
                       "/katex/fonts/..%2f..%2f..%2f..%2f..%2fetc%2fpasswd", "/..\\..\\etc\\passwd",
                       "/%5c..%5c..%5cetc%5cpasswd", "//etc/passwd", f"http://127.0.0.1:{view.port}/../etc/passwd",
                       "/view.js/..", "/.%2e/etc/passwd"]:
            status, body = view.raw(target)
            check(status == 403 and b"root:" not in body, f"{target!r}: {status}, expected 403")
        for target in ["/etc/passwd", "/usr/share/javascript/katex/katex.min.js", "/api/layer/../info",
                       "/api/layer?frame=0&source=golden&name=../../../../etc/passwd", "/katex/contrib/copy-tex.js"]:
            status, body = view.raw(target)
            check(status in (403, 404) and b"root:" not in body, f"{target!r}: {status}, expected 404 or 403")
        for path in ["/", "/view.js", "/katex/katex.min.js", "/katex/fonts/KaTeX_Main-Regular.woff2"]:
            check(view.get(path)[0] == 200, f"{path}: not served")

        # A missing layer: 404, and the server goes on.
        status, _, body = view.get("/api/layer?frame=1&source=golden&name=filter.direct.no_such_layer")
        check(status == 404 and "no_such_layer" in json.loads(body)["error"], f"missing layer: {status} {body!r}")
        check(view.get("/api/layer?frame=9&source=golden&name=color")[0] == 404, "a frame not viewed is not 404")
        check(view.get("/api/info")[0] == 200, "no answer after a 404")

        check_loopback(view)
        check_layers_are_the_dump(view, dumps)
        check_probe_is_the_cli(view, seq)

        # A port that is taken: one line, before any filtering, and no URL printed.
        r = run([RTDR, "view", "--method", METHOD, "--in", seq, "--port", str(view.port)])
        err = r.stderr.strip().splitlines()
        check(r.returncode == 1 and err == [f"rtdr: error: cannot listen on 127.0.0.1:{view.port} (in use? --port 0 "
                                            "takes any free port)"] and "RTDR view of" not in r.stdout
              and "filtering" not in r.stdout, f"a port in use: exit {r.returncode}, {r.stderr!r}")
    r = run([RTDR, "view", "--method", METHOD, "--in", os.path.join(tmp, "no_such_folder")])
    check(r.returncode == 1 and len(r.stderr.strip().splitlines()) == 1 and r.stderr.startswith("rtdr: error: "),
          f"a missing --in: exit {r.returncode}, {r.stderr!r}")

    # A frame of --in that is a symlink out of it: refused before anything is served.
    outside = os.path.join(tmp, "outside")
    os.makedirs(outside)
    os.rename(os.path.join(seq, "frame_0001.exr"), os.path.join(outside, "frame_0001.exr"))
    os.symlink(os.path.join(outside, "frame_0001.exr"), os.path.join(seq, "frame_0001.exr"))
    r = run([RTDR, "view", "--method", METHOD, "--in", seq, "--port", "0"])
    err = r.stderr.strip().splitlines()
    check(r.returncode == 1 and len(err) == 1 and err[0].startswith("rtdr: error: --in:") and "leads out of" in err[0]
          and "RTDR view of" not in r.stdout, f"a symlink out of --in: exit {r.returncode}, {r.stderr!r}")


def check_loopback(view):
    """Listening on 127.0.0.1 only: the kernel's table of listening sockets, and a connection to another address."""
    listening = []
    for table in ["/proc/net/tcp", "/proc/net/tcp6"]:
        with open(table) as f:
            for row in f.readlines()[1:]:
                local, state = row.split()[1], row.split()[3]
                if state == "0A" and int(local.split(":")[1], 16) == view.port:
                    listening.append((table, local.split(":")[0]))
    check(listening == [("/proc/net/tcp", "0100007F")], f"listening sockets on the port: {listening}")
    others = run(["hostname", "-I"]).stdout.split()
    for address in [a for a in others if ":" not in a and not a.startswith("127.")][:1]:
        try:
            socket.create_connection((address, view.port), timeout=5).close()
            check(False, f"a connection to {address}:{view.port} was accepted")
        except OSError:
            pass


def check_layers_are_the_dump(view, dumps):
    import OpenImageIO as oiio
    for frame in [0, 2]:
        image = oiio.ImageInput.open(os.path.join(dumps, f"frame_{frame:04d}.exr"))
        spec = image.spec()
        pixels = image.read_image(format="float")
        image.close()
        names = list(spec.channelnames)
        for name in ["color", "filter.direct.alpha", "filter.indirect.level0", "filter.direct.gradient.level1.delta"]:
            got = layer_values(view, frame, "golden", name)
            if not got:
                continue
            channels, w, h, planes = got
            for c, channel in enumerate(channels):
                full = name + ("." + channel if channel else "")
                expected = pixels[:, :, names.index(full)].reshape(-1).tolist()
                check(list(planes[c]) == expected, f"/api/layer {full} frame {frame} differs from the dump")


def check_probe_is_the_cli(view, seq):
    for frame, x, y, pass_, stream, level in [(2, 30, 20, "atrous", "direct", 1), (1, 10, 30, "temporal", "indirect", 0),
                                              (2, 40, 12, "gradient_atrous", "direct", 2), (2, 5, 5, "taa", "direct", 0)]:
        query = f"frame={frame}&x={x}&y={y}&pass={pass_}&level={level}&stream={stream}"
        status, _, body = view.get("/api/probe?" + query)
        cli = probe_cli(seq, frame, x, y, pass_, stream, level)
        check(status == 200 and body.decode() == cli, f"/api/probe?{query} is not rtdr probe --json's output")
        for term in json.loads(cli)["terms"]:
            path = os.path.join(SOURCE_DIR, term["file"])
            if not check(term["file"].startswith("filters/") and os.path.isfile(path), f"term file {term['file']}"):
                break
            with open(path) as f:
                line = f.read().splitlines()[term["line"] - 1]
            if not check("note(" in line, f"{term['file']}:{term['line']} is not a note(): {line.strip()}"):
                break
    status, _, body = view.get("/api/probe?frame=2&x=999&y=0&pass=atrous")
    check(status == 400 and "outside" in json.loads(body)["error"], f"a pixel outside: {status} {body!r}")


# ---- memory ---------------------------------------------------------------------------------------------------
def case_memory(tmp):
    if os.environ.get("ASAN_OPTIONS"):
        print("app_view_memory: skipped under AddressSanitizer (its quarantine holds freed memory)")
        sys.exit(77)
    seq = os.path.join(tmp, "seq")
    render(seq)
    with View("--in", seq) as view:
        passes = ["atrous", "temporal", "variance", "gradient_atrous", "adaptive_alpha", "tonemap"]
        resident = {}
        for i in range(1000):
            status, _, _ = view.get(f"/api/probe?frame={i % 3}&x={(7 * i) % 64}&y={(5 * i) % 36}"
                                    f"&pass={passes[i % len(passes)]}&level={i % 2}&stream={['direct', 'indirect'][i % 2]}")
            check(status == 200 or i % len(passes) == 5 and status == 400, f"probe {i}: {status}")
            if i % 10 == 0:  # a layer asked for, then the connection closed unread: a tab closed mid-answer
                with socket.create_connection(("127.0.0.1", view.port)) as s:
                    s.sendall(b"GET /api/layer?frame=1&source=golden&name=filter.direct.level0 HTTP/1.1\r\n"
                              b"Host: x\r\n\r\n")
            if i + 1 in (100, 1000):
                time.sleep(0.5)
                resident[i + 1] = view.resident_kb()
        growth = (resident[1000] - resident[100]) / 1024
        print(f"resident memory: {resident[100] / 1024:.1f} MB after 100 probes, {resident[1000] / 1024:.1f} MB after 1000")
        check(growth <= 10, f"resident memory grew by {growth:.1f} MB from 100 to 1000 probes")


def finish():
    for f in failures:
        print(f)
    sys.exit(1 if failures else 0)


def main():
    global SOURCE_DIR, RTDR, BUILD_DIR
    SOURCE_DIR, RTDR, BUILD_DIR, case = sys.argv[1:5]
    with tempfile.TemporaryDirectory(prefix="rtdr_view_test_") as tmp:
        {"server": case_server, "memory": case_memory}[case](tmp)
    finish()


if __name__ == "__main__":
    main()
