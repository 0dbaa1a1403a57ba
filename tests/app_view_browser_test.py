#!/usr/bin/python3
"""rtdr view's page in a real browser (ctest: `app_view_browser`): Debian's chromium, headless, driven by
python3-selenium through chromium-driver. The sequence and the server are tests/app_view_test.py's (pillars with
gradient samples, 64x36, 3 frames, asvgf); here with --ref (4-spp renders of the same frames) and --port-dumps (the
golden dump of `rtdr filter --dump-passes`, with filter.direct.alpha halved in frame 2: a port with one known error).

Checks, each against numbers computed here, not read from the page:
  - choosing a pass and a layer draws it: the canvas's bytes at a few pixels are within 1 of the layer's values
    (/api/layer) through the display mapping of docs/view.md: a scalar in viridis over its range (the nine colours
    read from docs/view.md), the radiance through exposure, the project's tone map and sRGB;
  - clicking a pixel shows the terms of `rtdr probe` for it: the same names and the same numbers as its text output,
    in order; each equation a term cites is typeset by KaTeX, and every equation of /api/equations typesets;
  - the frame slider, moved with the keyboard, draws the other frame's values;
  - against the port: the difference map is viridis of |golden - port| = alpha / 2, and the swipe shows the golden
    bytes left of the split and the port's right of it;
  - the metrics shown are /api/metrics's for the frame;
  - the browser logged no error.
The screenshot goes to BUILD_DIR/test-artifacts/view.png.

Usage: app_view_browser_test.py SOURCE_DIR RTDR BUILD_DIR
Prints one line per failed check and exits 1 when there is any.
"""
import json
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import app_view_test as v  # noqa: E402

from selenium import webdriver  # noqa: E402
from selenium.webdriver.chrome.service import Service  # noqa: E402
from selenium.webdriver.common.action_chains import ActionChains  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.common.keys import Keys  # noqa: E402
from selenium.webdriver.support.ui import Select, WebDriverWait  # noqa: E402

check = v.check
# How Chromium runs here: headless, without a sandbox (we run as root in a container), and with every network
# service of its own off, so that it talks to nothing but the server on 127.0.0.1.
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--window-size=1500,950"]


# ---- the display mapping of docs/view.md, computed independently of the page -----------------------------------
def viridis_anchors():
    with open(os.path.join(v.SOURCE_DIR, "docs", "view.md")) as f:
        doc = f.read()
    paragraph = doc[doc.index("Viridis's nine colours:"):].split("\n\n")[0]
    return [tuple(map(int, m)) for m in re.findall(r"\((\d+), (\d+), (\d+)\)", paragraph)]


def viridis(t, anchors):
    t = min(max(t, 0.0), 1.0) if t == t else 0.0
    s = t * (len(anchors) - 1)
    i = min(int(s), len(anchors) - 2)
    f = s - i
    return [int(a + f * (b - a) + 0.5) for a, b in zip(anchors[i], anchors[i + 1])]


def srgb_byte(x):
    e = 12.92 * x if x <= 0.0031308 else 1.055 * x ** (1 / 2.4) - 0.055
    return 0 if not e > 0 else 255 if e >= 1 else int(e * 255 + 0.5)


def tonemapped(r, g, b, exposure=1.0):
    lw = 0.2126 * r + 0.7152 * g + 0.0722 * b
    if not lw > 0:
        return [0, 0, 0]
    L = exposure * lw
    return [srgb_byte(min(max(c * (L / (1 + L)) / lw, 0.0), 1.0)) for c in (r, g, b)]


# ---- the page --------------------------------------------------------------------------------------------------
class Page:
    def __init__(self, driver, view):
        self.d, self.view = driver, view

    def wait(self, script, expected, what):
        try:
            WebDriverWait(self.d, 30).until(lambda d: d.execute_script(script) == expected)
            return True
        except Exception:
            return check(False, f"{what}: waited for {expected!r}, have {self.d.execute_script(script)!r}")

    def choose(self, group, layer, frame, mode, compare="golden", source="golden"):
        self.d.find_element(By.CSS_SELECTOR, f'#passes button[data-group="{group}"][data-layer="{layer}"]').click()
        return self.wait("return document.body.dataset.drawn", f"{frame}|{source}|{layer}|{mode}|{compare}",
                         f"drawing {group} {layer}")

    def pixels(self, points):
        return self.d.execute_script(
            "const ctx = document.getElementById('image').getContext('2d');"
            "return arguments[0].map(([x, y]) => Array.from(ctx.getImageData(x, y, 1, 1).data.slice(0, 3)));", points)

    def click_pixel(self, x, y):
        """A real click on the overlay, at the centre of pixel (x, y); Selenium's offsets are from the centre."""
        overlay = self.d.find_element(By.ID, "overlay")
        zoom = int(Select(self.d.find_element(By.ID, "zoom")).first_selected_option.text)
        w, h = overlay.size["width"], overlay.size["height"]
        ActionChains(self.d).move_to_element_with_offset(overlay, int((x + 0.5) * zoom - w / 2),
                                                         int((y + 0.5) * zoom - h / 2)).click().perform()


def expect_pixels(page, points, expected, what):
    got = page.pixels(points)
    for p, g, e in zip(points, got, expected):
        check(max(abs(a - b) for a, b in zip(g, e)) <= 1, f"{what}: pixel {p} is {g}, expected {e}")


def check_layers(page, view, anchors):
    points = [(3, 4), (20, 10), (31, 18), (50, 30), (63, 35)]
    # A scalar: viridis over the layer's finite range.
    if page.choose("adaptive_alpha", "filter.direct.alpha", 2, "false colour"):
        _, w, _, (alpha,) = v.layer_values(view, 2, "golden", "filter.direct.alpha")
        lo, hi = min(alpha), max(alpha)
        check(hi > lo, "alpha is constant: pick another layer")
        expect_pixels(page, points, [viridis((alpha[y * w + x] - lo) / (hi - lo), anchors) for x, y in points],
                      "filter.direct.alpha in viridis")
    # Radiance: exposure 1, the project's tone map, sRGB.
    if page.choose("modulate", "color", 2, "tonemap"):
        _, w, _, (r, g, b) = v.layer_values(view, 2, "golden", "color")
        expect_pixels(page, points, [tonemapped(r[y * w + x], g[y * w + x], b[y * w + x]) for x, y in points],
                      "color, tone mapped")
    # The frame slider, with the keyboard: frame 1's values.
    page.d.find_element(By.ID, "frame").send_keys(Keys.ARROW_LEFT)
    if page.wait("return document.body.dataset.drawn", "1|golden|color|tonemap|golden", "the slider to frame 1"):
        _, w, _, (r, g, b) = v.layer_values(view, 1, "golden", "color")
        expect_pixels(page, points, [tonemapped(r[y * w + x], g[y * w + x], b[y * w + x]) for x, y in points],
                      "color of frame 1 after the slider")
    page.d.find_element(By.ID, "frame").send_keys(Keys.ARROW_RIGHT)
    page.wait("return document.body.dataset.drawn", "2|golden|color|tonemap|golden", "the slider back to frame 2")


def check_probe(page, seq):
    """A click on pixel (30, 20) of a-trous level 1 shows rtdr probe's terms: names and numbers, in order."""
    x, y = 30, 20
    page.choose("atrous", "filter.direct.level1", 2, "tonemap")
    page.click_pixel(x, y)
    if not page.wait("return document.body.dataset.probed", f"2|{x}|{y}|atrous|direct|1|200", "the probe's answer"):
        return
    rows = page.d.execute_script(
        "return [...document.querySelectorAll('#probe-terms tr.term')].map((r) => ({"
        "name: r.cells[0].textContent, value: r.cells[1].textContent,"
        "keys: [...r.querySelectorAll('.eq .key')].map((k) => k.textContent),"
        "typeset: r.querySelectorAll('.eq .tex .katex').length,"
        "errors: r.querySelectorAll('.katex-error').length}))")
    text = v.probe_cli(seq, 2, x, y, "atrous", "direct", 1, as_json=False)
    lines = [l for l in text.splitlines() if l and not l.startswith("#")]
    terms = json.loads(v.probe_cli(seq, 2, x, y, "atrous", "direct", 1))["terms"]
    check(len(rows) == len(lines) == len(terms) and len(rows) > 25, f"{len(rows)} rows, rtdr probe {len(lines)} terms")
    for row, line, term in zip(rows, lines, terms):
        name_value = line.split(" | ")[1]  # "name = value"
        if not check(f"{row['name']} = {row['value']}" == name_value, f"row {row} is not rtdr probe's {line!r}"):
            break
        check(row["keys"] == term["equations"] and row["typeset"] == len(term["equations"]) and not row["errors"],
              f"row {row['name']}: equations {row['keys']} typeset {row['typeset']}, cited {term['equations']}")
    broken = page.d.execute_script(
        "const bad = []; for (const [k, tex] of Object.entries(rtdrView.state.equations))"
        " try { katex.renderToString(tex, {throwOnError: true}); } catch (e) { bad.push(k + ': ' + e.message); }"
        " return bad;")
    check(not broken, f"equations KaTeX cannot typeset: {broken}")


def check_port_and_reference(page, view, anchors):
    points = [(3, 4), (20, 10), (31, 18), (50, 30), (63, 35)]
    page.choose("adaptive_alpha", "filter.direct.alpha", 2, "false colour")
    Select(page.d.find_element(By.ID, "compare")).select_by_value("difference")
    if page.wait("return document.body.dataset.drawn", "2|golden|filter.direct.alpha|false colour|difference",
                 "the difference map"):
        _, w, _, (alpha,) = v.layer_values(view, 2, "golden", "filter.direct.alpha")
        _, _, _, (port,) = v.layer_values(view, 2, "port", "filter.direct.alpha")
        diff = [abs(a - p) for a, p in zip(alpha, port)]
        check(max(diff) > 0 and all(abs(d - a / 2) <= 1e-6 for d, a in zip(diff, alpha)), "port alpha is not alpha / 2")
        expect_pixels(page, points, [viridis(diff[y * w + x] / max(diff), anchors) for x, y in points],
                      "the difference map")
    Select(page.d.find_element(By.ID, "compare")).select_by_value("golden")
    page.wait("return document.body.dataset.drawn", "2|golden|filter.direct.alpha|false colour|golden", "golden")
    golden = page.pixels([(10, 5), (50, 5)])
    Select(page.d.find_element(By.ID, "compare")).select_by_value("port")
    page.wait("return document.body.dataset.drawn", "2|golden|filter.direct.alpha|false colour|port", "port")
    port = page.pixels([(10, 5), (50, 5)])
    Select(page.d.find_element(By.ID, "compare")).select_by_value("swipe")  # split at 0.5: x < 32 golden
    page.wait("return document.body.dataset.drawn", "2|golden|filter.direct.alpha|false colour|swipe", "swipe")
    check(page.pixels([(10, 5), (50, 5)]) == [golden[0], port[1]], "swipe: not golden left and port right")
    Select(page.d.find_element(By.ID, "compare")).select_by_value("golden")
    page.wait("return document.body.dataset.drawn", "2|golden|filter.direct.alpha|false colour|golden", "golden")
    # The metrics of frame 2 against --ref.
    metrics = json.loads(view.get("/api/metrics?frame=2")[2])
    shown = page.d.find_element(By.ID, "metrics").text
    for key, label in [("rmse", "RMSE"), ("relmse", "relMSE"), ("ssim", "SSIM"), ("flip", "FLIP")]:
        m = re.search(label + r" (\S+)", shown)
        check(m and abs(float(m.group(1)) - metrics[key]) <= 1e-3 * abs(metrics[key]), f"{label}: {shown!r} {metrics}")


def run(tmp):
    seq, ref, dumps = (os.path.join(tmp, n) for n in ("seq", "ref", "dumps"))
    v.render(seq)
    r = v.run([v.RTDR, "render", "--scene", "pillars", "--frames", v.FRAMES, "--size", v.SIZE, "--spp", "4",
               "--seed", "9", "--out", ref])
    check(r.returncode == 0, f"reference render: {r.stderr.strip()}")
    r = v.run([v.RTDR, "filter", "--method", v.METHOD, "--in", seq, "--out", dumps, "--dump-passes"])
    check(r.returncode == 0, f"rtdr filter --dump-passes: {r.stderr.strip()}")
    make_port_error(os.path.join(dumps, "frame_0002.exr"))
    anchors = viridis_anchors()
    check(len(anchors) == 9, f"docs/view.md lists {len(anchors)} viridis colours")
    with v.View("--in", seq, "--ref", ref, "--port-dumps", dumps) as view:
        options = webdriver.ChromeOptions()
        options.binary_location = "/usr/bin/chromium"
        for flag in CHROMIUM_FLAGS + [f"--user-data-dir={os.path.join(tmp, 'chromium')}"]:
            options.add_argument(flag)
        options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
        driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
        try:
            driver.get(view.url("/"))
            page = Page(driver, view)
            page.wait("return document.body.dataset.ready", "1", "the page to start")
            # The last frame, 2, with the keyboard on the slider; the page starts on the first.
            driver.find_element(By.ID, "frame").send_keys(Keys.END)
            page.wait("return document.body.dataset.drawn.split('|')[0]", "2", "the slider to the last frame")
            check_layers(page, view, anchors)
            check_port_and_reference(page, view, anchors)
            check_probe(page, seq)
            artifacts = os.path.join(v.BUILD_DIR, "test-artifacts")
            os.makedirs(artifacts, exist_ok=True)
            driver.save_screenshot(os.path.join(artifacts, "view.png"))
            errors = [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]
            check(not errors, f"console errors: {errors}")
        finally:
            driver.quit()


def make_port_error(path):
    """Halves filter.direct.alpha in one dump frame, in place: a port whose error this test knows."""
    import OpenImageIO as oiio
    image = oiio.ImageInput.open(path)
    spec = image.spec()
    pixels = image.read_image(format="float")
    image.close()
    names = list(spec.channelnames)
    pixels[:, :, names.index("filter.direct.alpha")] *= 0.5
    out_spec = oiio.ImageSpec(spec.width, spec.height, spec.nchannels, "float")
    out_spec.channelnames = names
    out = oiio.ImageOutput.create(path)
    out.open(path, out_spec)
    out.write_image(pixels)
    out.close()


def main():
    v.SOURCE_DIR, v.RTDR, v.BUILD_DIR = sys.argv[1:4]
    with tempfile.TemporaryDirectory(prefix="rtdr_view_browser_") as tmp:
        run(tmp)
    v.finish()


if __name__ == "__main__":
    main()
