// rtdr view: a probed pixel's terms (the JSON of /api/probe, which is `rtdr probe --json`'s), each with the
// equation it cites typeset by KaTeX, the paper's key and the golden function's file and line; and a tap list's
// weights drawn over the image around the pixel (docs/view.md, "Probe").
"use strict";

const RtdrProbe = (() => {
  const typesetCache = new Map();  // equation key -> KaTeX's HTML

  function typeset(key, equations) {
    if (!typesetCache.has(key)) {
      const tex = equations[key];
      typesetCache.set(key, tex === undefined || typeof katex === "undefined"
        ? null : katex.renderToString(tex, { throwOnError: true, displayMode: false }));
    }
    return typesetCache.get(key);
  }

  function element(tag, className, text) {
    const e = document.createElement(tag);
    if (className) e.className = className;
    if (text !== undefined) e.textContent = text;
    return e;
  }

  // A number as C's printf("%.9g") writes it, which `rtdr probe` prints: 9 significant digits, trailing zeros off,
  // exponential form below 1e-4 and from 1e9 on.
  function g9(v) {
    if (Number.isNaN(v)) return "nan";
    if (!Number.isFinite(v)) return v > 0 ? "inf" : "-inf";
    if (v === 0) return Object.is(v, -0) ? "-0" : "0";
    const [mantissa, exponent] = v.toExponential(8).split("e");
    const e = +exponent;
    const trim = (s) => (s.includes(".") ? s.replace(/0+$/, "").replace(/\.$/, "") : s);
    if (e < -4 || e >= 9) return `${trim(mantissa)}e${e < 0 ? "-" : "+"}${String(Math.abs(e)).padStart(2, "0")}`;
    return trim(v.toFixed(8 - e));
  }

  // A term's value as the probe's text prints it: a tuple in parentheses.
  function formatValue(value) {
    const parts = value.map(g9);
    return parts.length > 1 ? "(" + parts.join(", ") + ")" : parts[0];
  }

  // Fills `container` with the document's terms, grouped as the golden function grouped them.
  function show(container, doc, equations) {
    container.replaceChildren();
    const head = element("p", "probe-head",
      `${doc.method} ${doc.pass}, frame ${doc.frame}, pixel (${doc.pixel[0]}, ${doc.pixel[1]}), ` +
      `stream ${doc.stream}, level ${doc.level}: ${doc.terms.length} terms`);
    container.appendChild(head);
    const table = element("table", "terms");
    const columns = element("colgroup");
    for (const name of ["name", "value", "equation", "source"]) columns.appendChild(element("col", name));
    table.appendChild(columns);
    let group = null;
    for (const [index, term] of doc.terms.entries()) {
      if (term.group !== group) {
        group = term.group;
        const row = table.insertRow();
        row.className = "group";
        const cell = row.insertCell();
        cell.colSpan = 4;
        cell.textContent = group || "-";
      }
      const row = table.insertRow();
      row.className = "term";
      row.dataset.index = index;
      row.dataset.value = JSON.stringify(term.value);
      row.insertCell().textContent = term.name;
      const value = row.insertCell();
      value.className = "value";
      value.textContent = formatValue(term.value);
      const eq = row.insertCell();
      eq.className = "equation";
      for (const key of term.equations) {
        const box = element("div", "eq");
        box.appendChild(element("span", "key", key));
        const html = typeset(key, equations);
        if (html) {
          const math = element("span", "tex");
          math.innerHTML = html;  // KaTeX's own markup, from our own TeX table (filters/equations.cpp)
          box.appendChild(math);
        }
        eq.appendChild(box);
      }
      if (term.cite && term.equations.length === 0) eq.appendChild(element("span", "cite", term.cite));
      else if (term.cite) eq.title = term.cite;
      row.insertCell().appendChild(element("code", "source", `${term.file}:${term.line}`));
    }
    container.appendChild(table);
  }

  // The taps of a probe whose groups are labelled "tap (dx, dy)" (a-trous, EAW, the reconstruction), "7x7 tap
  // (dx, dy)" (the variance's bilateral) or "g3x3 tap (dx, dy)" (the prefilter): for each, its offset from the pixel
  // and its weight, the group's "h w", else its "w ..." or "g". Offsets are in strata where the probe says so
  // (a term named "... (strata)"): they are then multiplied by the stratum size. Returns each tap's top-left pixel,
  // its size in pixels and its weight.
  function taps(doc, stratumSize) {
    const label = /^(?:7x7 |g3x3 )?tap \((-?\d+), (-?\d+)\)$/;
    const strata = doc.terms.some((t) => t.name.includes("(strata)"));
    const scale = strata && stratumSize > 0 ? stratumSize : 1;
    // The pixel's own tap: the pixel, or the top-left pixel of its stratum.
    const [ox, oy] = doc.pixel.map((p) => Math.floor(p / scale) * scale);
    const byGroup = new Map();
    for (const t of doc.terms) {
      const m = label.exec(t.group);
      if (!m) continue;
      if (!byGroup.has(t.group)) byGroup.set(t.group, { x: ox + +m[1] * scale, y: oy + +m[2] * scale, size: scale, weight: null, rank: 9 });
      const tap = byGroup.get(t.group);
      const rank = t.name === "h w" ? 0 : (t.name === "w" || t.name.startsWith("w = ")) ? 1 : t.name === "g" ? 2 : 9;
      if (rank < tap.rank) { tap.rank = rank; tap.weight = t.value[0]; }
    }
    return [...byGroup.values()].filter((t) => t.weight !== null);
  }

  // Draws the taps' weights on the overlay, in viridis relative to the largest.
  function drawTaps(ctx, list, zoom) {
    const max = Math.max(...list.map((t) => t.weight), 0);
    for (const t of list) {
      const [r, g, b] = RtdrDisplay.viridis(max > 0 ? t.weight / max : 0);
      ctx.fillStyle = `rgba(${r}, ${g}, ${b}, 0.8)`;
      ctx.fillRect(t.x * zoom, t.y * zoom, t.size * zoom, t.size * zoom);
      ctx.strokeStyle = "rgba(255, 255, 255, 0.9)";  // outlined, to stand out on any image
      ctx.lineWidth = 1;
      ctx.strokeRect(t.x * zoom + 0.5, t.y * zoom + 0.5, t.size * zoom - 1, t.size * zoom - 1);
    }
  }

  return { show, taps, drawTaps, formatValue };
})();
