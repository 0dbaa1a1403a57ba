// rtdr view: the page. It asks the server (app/view_server.cpp, docs/view.md) for the method's passes and their
// layers (/api/info), draws the chosen layer of the chosen frame from its float values (/api/layer, display.js),
// and explains a clicked pixel with the probe's terms (/api/probe, probe.js). No state lives on the server but the
// filtered sequence; everything here is the page's own.
"use strict";

(() => {
  const $ = (id) => document.getElementById(id);
  const state = {
    info: null, equations: {},
    frame: 0,                  // index into info.frames
    group: null, layer: null,  // the chosen pass (or input, reference) and layer, objects of info.groups
    mode: null, compare: "golden", flipPort: false, flipTimer: null,
    pixel: null, probeDoc: null, probeAbort: null, loadToken: 0,
    planes: null,              // what is drawn: { width, height, planes, other (port, for swipe) }
    cache: new Map(),          // "source|frame|name" -> loaded layer, the most recent 32 kept
  };

  // ---- data -------------------------------------------------------------------------------------------------
  async function loadLayer(source, frame, name) {
    const key = `${source}|${frame}|${name}`;
    if (state.cache.has(key)) {
      const hit = state.cache.get(key);
      state.cache.delete(key);
      state.cache.set(key, hit);
      return hit;
    }
    const url = `/api/layer?frame=${frame}&source=${source}&name=${encodeURIComponent(name)}`;
    const res = await fetch(url);
    if (!res.ok) throw new Error((await res.json()).error);
    const width = +res.headers.get("X-RTDR-Width"), height = +res.headers.get("X-RTDR-Height");
    const channels = res.headers.get("X-RTDR-Channels").split(",");
    const all = new Float32Array(await res.arrayBuffer());
    const planes = channels.map((_, c) => all.subarray(c * width * height, (c + 1) * width * height));
    planes.kind = channels[0] === "R" ? "rgb" : channels.length > 1 ? "vector" : "scalar";
    const layer = { width, height, channels, planes };
    state.cache.set(key, layer);
    while (state.cache.size > 32) state.cache.delete(state.cache.keys().next().value);
    return layer;
  }

  const frameIndex = () => state.info.frames[state.frame];

  // ---- the pass list ----------------------------------------------------------------------------------------
  function buildPassList() {
    const nav = $("passes");
    nav.replaceChildren();
    for (const group of state.info.groups) {
      if (group.layers.length === 0) continue;
      const box = document.createElement("section");
      box.className = "group";
      const title = document.createElement("h2");
      title.textContent = group.name;
      title.title = group.description || "";
      const cite = document.createElement("span");
      cite.className = "cite";
      cite.textContent = group.cite ? " " + group.cite : "";
      title.appendChild(cite);
      box.appendChild(title);
      for (const layer of group.layers) {
        const b = document.createElement("button");
        b.textContent = layer.name;
        b.title = layer.meaning ? `${layer.meaning} ${layer.cite || ""}` : "";
        b.dataset.group = group.name;
        b.dataset.layer = layer.name;
        b.addEventListener("click", () => selectLayer(group, layer));
        box.appendChild(b);
      }
      nav.appendChild(box);
    }
  }

  function selectLayer(group, layer) {
    state.group = group;
    state.layer = layer;
    state.mode = null;  // the layer's default, once loaded
    for (const b of document.querySelectorAll("#passes button"))
      b.classList.toggle("chosen", b.dataset.group === group.name && b.dataset.layer === layer.name);
    // The probe follows the pass, and the stream and level of the layer where it has them.
    if (group.probe) {
      $("probe-pass").value = group.name;
      const stream = layer.stream || state.info.streams.find((s) => layer.name.includes(`.${s}.`));
      if (stream) $("probe-stream").value = stream;
      $("probe-level").value = layer.level || 0;
    }
    $("compare").disabled = !(state.info.port && group.source === "golden");
    if ($("compare").disabled) setCompare("golden");
    redraw();
    if (state.pixel && group.probe) probe();
  }

  // ---- drawing ----------------------------------------------------------------------------------------------
  async function redraw() {
    const token = ++state.loadToken;
    const name = state.layer.name, frame = frameIndex();
    try {
      const golden = await loadLayer(state.group.source, frame, name);
      const port = state.compare !== "golden" ? await loadLayer("port", frame, name) : null;
      if (token !== state.loadToken) return;  // a newer choice came in while this one loaded
      state.planes = { golden, port };
      draw();
      document.body.dataset.drawn = `${frame}|${state.group.source}|${name}|${state.mode}|${state.compare}`;
      $("status").textContent = "";
    } catch (e) {
      if (token === state.loadToken) $("status").textContent = e.message;
    }
  }

  // The mode's controls as numbers; the range follows the values while "auto" is ticked.
  function controls(planes) {
    const c = { exposure: +$("exposure").value || 1, lo: +$("lo").value, hi: +$("hi").value, max: 1 };
    const scalars = Float32Array.from(planes[0], (_, i) => RtdrDisplay.scalarOf(planes, i));
    const [lo, hi] = RtdrDisplay.range(scalars);
    if ($("auto").checked) {
      // Lengths and differences start at 0.
      [c.lo, c.hi] = planes.kind === "vector" || state.compare === "difference" ? [0, hi] : [lo, hi];
      $("lo").value = +c.lo.toPrecision(6);
      $("hi").value = +c.hi.toPrecision(6);
    }
    c.max = planes.kind === "vector" ? (c.hi > 0 ? c.hi : 1) : 1;
    return c;
  }

  function updateModes(planes) {
    const layer = { kind: planes.kind, display_referred: !!state.layer.display_referred, channels: planes.length };
    const modes = RtdrDisplay.modes(layer);
    if (!modes.includes(state.mode)) state.mode = modes[0];
    const select = $("mode");
    select.replaceChildren(...modes.map((m) => new Option(m, m, false, m === state.mode)));
  }

  // One layer's RGBA bytes in the current mode.
  function rgbaOf(layer, ctl) {
    const rgba = new Uint8ClampedArray(layer.width * layer.height * 4);
    RtdrDisplay.render(layer.planes, state.mode, ctl, rgba);
    return rgba;
  }

  // |golden - port|, the largest over the channels, per pixel.
  function difference(golden, port) {
    const d = new Float32Array(golden.width * golden.height);
    for (let i = 0; i < d.length; ++i)
      d[i] = Math.max(...golden.planes.map((p, c) => Math.abs(p[i] - port.planes[c][i])));
    const planes = [d];
    planes.kind = "scalar";
    return { width: golden.width, height: golden.height, planes };
  }

  function draw() {
    const { golden, port } = state.planes;
    const shown = state.compare === "difference" ? difference(golden, port)
      : state.compare === "port" || (state.compare === "flip" && state.flipPort) ? port : golden;
    updateModes(shown.planes);
    if (state.compare === "difference") state.mode = "false colour";
    const ctl = controls(shown.planes);
    let rgba = rgbaOf(shown, ctl);
    if (state.compare === "swipe") {  // golden left of the split, the port right of it
      const right = rgbaOf(port, ctl), split = Math.round(+$("swipe").value * golden.width);
      for (let y = 0; y < golden.height; ++y)
        rgba.set(right.subarray((y * golden.width + split) * 4, (y + 1) * golden.width * 4), (y * golden.width + split) * 4);
    }
    const canvas = $("image");
    canvas.width = shown.width;
    canvas.height = shown.height;
    canvas.getContext("2d").putImageData(new ImageData(rgba, shown.width, shown.height), 0, 0);
    drawScale(ctl);
    showControls();
    applyZoom();
    $("shown").textContent = state.compare === "flip" ? (state.flipPort ? "port" : "golden") : state.compare;
  }

  // Only the controls that act on what is shown.
  function showControls() {
    $("exposure-control").hidden = !(state.mode === "tonemap" || state.mode === "linear");
    $("range-control").hidden = state.mode !== "false colour";
    $("port-control").hidden = $("compare").disabled;
    $("swipe").hidden = state.compare !== "swipe";
    $("shown").hidden = state.compare !== "flip";
  }

  function drawScale(ctl) {
    const falseColour = state.mode === "false colour" || state.mode === "arrows";
    $("scale").hidden = !falseColour;
    if (!falseColour) return;
    const bar = $("colorbar"), ctx = bar.getContext("2d");
    for (let x = 0; x < bar.width; ++x) {
      const [r, g, b] = RtdrDisplay.viridis(x / (bar.width - 1));
      ctx.fillStyle = `rgb(${r}, ${g}, ${b})`;
      ctx.fillRect(x, 0, 1, bar.height);
    }
    const [lo, hi] = state.mode === "arrows" ? [0, ctl.max] : [ctl.lo, ctl.hi];
    $("scale-lo").textContent = lo.toPrecision(4);
    $("scale-hi").textContent = hi.toPrecision(4);
  }

  function applyZoom() {
    const zoom = +$("zoom").value, canvas = $("image"), overlay = $("overlay");
    canvas.style.width = `${canvas.width * zoom}px`;
    canvas.style.height = `${canvas.height * zoom}px`;
    overlay.width = canvas.width * zoom;
    overlay.height = canvas.height * zoom;
    drawOverlay();
  }

  // Arrows for motion vectors, the probed taps' weights, and a square around the probed pixel.
  function drawOverlay() {
    const overlay = $("overlay"), ctx = overlay.getContext("2d"), zoom = +$("zoom").value;
    ctx.clearRect(0, 0, overlay.width, overlay.height);
    const shown = state.planes && state.planes.golden;
    if (shown && state.mode === "arrows") drawArrows(ctx, shown, zoom);
    if (state.probeDoc && $("taps").checked) RtdrProbe.drawTaps(ctx, RtdrProbe.taps(state.probeDoc, state.info.stratum_size), zoom);
    if (state.pixel) {
      ctx.strokeStyle = "#ff2a6d";
      ctx.lineWidth = 2;
      ctx.strokeRect(state.pixel[0] * zoom - 2, state.pixel[1] * zoom - 2, zoom + 4, zoom + 4);
    }
  }

  function drawArrows(ctx, layer, zoom) {
    const step = Math.max(4, Math.round(48 / zoom));  // one arrow every `step` pixels
    ctx.strokeStyle = "white";
    ctx.lineWidth = 1;
    for (let y = step >> 1; y < layer.height; y += step)
      for (let x = step >> 1; x < layer.width; x += step) {
        const i = y * layer.width + x, mx = layer.planes[0][i], my = layer.planes[1][i];
        if (!(Math.hypot(mx, my) > 0.05)) continue;
        const x0 = (x + 0.5) * zoom, y0 = (y + 0.5) * zoom, x1 = x0 + mx * zoom, y1 = y0 + my * zoom;
        const a = Math.atan2(y1 - y0, x1 - x0), head = Math.min(6, Math.hypot(x1 - x0, y1 - y0) / 2);
        ctx.beginPath();
        ctx.moveTo(x0, y0);
        ctx.lineTo(x1, y1);
        ctx.lineTo(x1 - head * Math.cos(a - 0.5), y1 - head * Math.sin(a - 0.5));
        ctx.moveTo(x1, y1);
        ctx.lineTo(x1 - head * Math.cos(a + 0.5), y1 - head * Math.sin(a + 0.5));
        ctx.stroke();
      }
  }

  function setCompare(mode) {
    state.compare = mode;
    $("compare").value = mode;
    clearInterval(state.flipTimer);
    state.flipTimer = null;
    if (mode === "flip")
      state.flipTimer = setInterval(() => { state.flipPort = !state.flipPort; if (state.planes) draw(); }, 700);
  }

  // ---- the probe --------------------------------------------------------------------------------------------
  async function probe() {
    if (state.probeAbort) state.probeAbort.abort();  // many quick clicks: only the last one is answered
    const abort = state.probeAbort = new AbortController();
    const [x, y] = state.pixel;
    const q = { frame: frameIndex(), x, y, pass: $("probe-pass").value, stream: $("probe-stream").value,
                level: +$("probe-level").value || 0 };
    const url = "/api/probe?" + new URLSearchParams(q).toString();
    $("probe-status").textContent = `probing (${x}, ${y}) ...`;
    try {
      const res = await fetch(url, { signal: abort.signal });
      const doc = await res.json();
      if (abort.signal.aborted) return;
      if (!res.ok) {
        state.probeDoc = null;
        $("probe-terms").replaceChildren();
        $("probe-status").textContent = doc.error;
      } else {
        state.probeDoc = doc;
        RtdrProbe.show($("probe-terms"), doc, state.equations);
        $("probe-status").textContent = "";
      }
      drawOverlay();
      document.body.dataset.probed = `${q.frame}|${x}|${y}|${q.pass}|${q.stream}|${q.level}|${res.status}`;
    } catch (e) {
      if (e.name !== "AbortError") $("probe-status").textContent = e.message;
    }
  }

  function pixelAt(event) {
    const zoom = +$("zoom").value, canvas = $("image");
    const x = Math.floor(event.offsetX / zoom), y = Math.floor(event.offsetY / zoom);
    return x >= 0 && y >= 0 && x < canvas.width && y < canvas.height ? [x, y] : null;
  }

  // The values under the mouse, as the layer holds them.
  function hover(event) {
    const p = pixelAt(event), shown = state.planes && state.planes.golden;
    if (!p || !shown) return;
    const i = p[1] * shown.width + p[0];
    const values = shown.planes.map((plane) => RtdrProbe.formatValue([plane[i]]));
    $("hover").textContent = `(${p[0]}, ${p[1]}) ${shown.channels.map((c, k) => (c ? c + " " : "") + values[k]).join("  ")}`;
  }

  // ---- the frame and the reference's metrics ---------------------------------------------------------------
  async function setFrame(k) {
    state.frame = k;
    $("frame").value = k;
    $("frame-label").textContent = `${frameIndex()} (${k + 1} of ${state.info.frames.length})`;
    if (state.layer) redraw();
    if (state.pixel) probe();
    if (state.info.reference) showMetrics();
  }

  async function showMetrics() {
    const frame = frameIndex();
    const res = await fetch(`/api/metrics?frame=${frame}`);
    const m = await res.json();
    if (frame !== frameIndex()) return;
    $("metrics").textContent = res.ok
      ? `against --ref, frame ${frame}: RMSE ${m.rmse.toPrecision(4)}  relMSE ${m.relmse.toPrecision(4)}  ` +
        `SSIM ${m.ssim.toPrecision(4)}  FLIP ${m.flip.toPrecision(4)}`
      : m.error;
  }

  // ---- start ------------------------------------------------------------------------------------------------
  function buildControls() {
    const info = state.info;
    document.title = `rtdr view: ${info.method} on ${info.in}`;
    $("title").textContent = `${info.method} on ${info.in}, ${info.width}x${info.height}`;
    $("frame").max = info.frames.length - 1;
    $("frame").addEventListener("input", () => setFrame(+$("frame").value));
    const passes = info.groups.filter((g) => g.probe).map((g) => g.name);
    $("probe-pass").replaceChildren(...passes.map((p) => new Option(p, p)));
    $("probe-stream").replaceChildren(...info.streams.map((s) => new Option(s, s)));
    for (const id of ["probe-pass", "probe-stream", "probe-level"])
      $(id).addEventListener("change", () => { if (state.pixel) probe(); });
    $("zoom").value = Math.max(1, Math.min(6, Math.floor((window.innerWidth * 0.5) / info.width)));
    $("zoom").addEventListener("change", applyZoom);
    $("mode").addEventListener("change", () => { state.mode = $("mode").value; draw(); });
    for (const id of ["exposure", "lo", "hi", "swipe"]) $(id).addEventListener("input", () => state.planes && draw());
    $("auto").addEventListener("change", () => state.planes && draw());
    $("taps").addEventListener("change", drawOverlay);
    $("compare").addEventListener("change", () => { setCompare($("compare").value); redraw(); });
    $("compare").disabled = true;
    $("overlay").addEventListener("click", (e) => {
      state.pixel = pixelAt(e);
      if (state.pixel) { drawOverlay(); probe(); }
    });
    $("overlay").addEventListener("mousemove", hover);
  }

  async function start() {
    const [info, equations] = await Promise.all([fetch("/api/info").then((r) => r.json()),
                                                 fetch("/api/equations").then((r) => r.json())]);
    state.info = info;
    state.equations = equations;
    buildControls();
    buildPassList();
    const first = info.groups.find((g) => g.probe && g.layers.length) || info.groups[0];
    await setFrame(0);
    selectLayer(first, first.layers[0]);
    document.body.dataset.ready = "1";
  }

  window.rtdrView = { state, selectLayer, setFrame };
  start();
})();
