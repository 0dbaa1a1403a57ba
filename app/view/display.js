// rtdr view: how a layer's float values become the 8-bit pixels of the canvas (docs/view.md, "Display"). Pure
// functions of the values and the controls, nothing else: tests/app_view_browser_test.py reads the canvas back and
// checks it against the same mapping, computed in Python from docs/view.md.
"use strict";

const RtdrDisplay = (() => {
  // Rec. 709 luminance weights (core/color.h, core/color_shared.h).
  const LUMA = [0.2126, 0.7152, 0.0722];

  // The sRGB encoding curve (core/color.h srgb_encode).
  function srgbEncode(v) {
    return v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055;
  }

  // An encoded value in [0, 1] to a byte, rounded to nearest; below 0 and NaN give 0 (core/color.h to_byte).
  function toByte(e) {
    if (!(e > 0)) return 0;
    if (e >= 1) return 255;
    return Math.floor(e * 255 + 0.5);
  }

  // The project's tone map (filters/svgf/tonemap.cpp tonemap_pixel): Reinhard on luminance, L = exposure L_w,
  // L_d = L / (1 + L), the colour scaled by L_d / L_w and clamped to [0, 1]. Returns display-referred linear RGB.
  function tonemap(r, g, b, exposure) {
    const Lw = LUMA[0] * r + LUMA[1] * g + LUMA[2] * b;
    if (!(Lw > 0)) return [0, 0, 0];
    const L = exposure * Lw;
    const scale = L / (1 + L) / Lw;
    return [r, g, b].map((c) => Math.min(Math.max(scale * c, 0), 1));
  }

  // Viridis, a perceptually uniform false-colour map: nine colours at t = 0, 1/8, ..., 1, linearly interpolated
  // in between, each channel then rounded to a byte. The same nine are listed in docs/view.md.
  const VIRIDIS = [
    [68, 1, 84], [71, 45, 123], [59, 82, 139], [44, 114, 142], [33, 144, 140],
    [39, 173, 129], [93, 200, 99], [170, 220, 50], [253, 231, 37],
  ];
  function viridis(t) {
    if (!(t > 0)) t = 0;  // NaN too
    if (t > 1) t = 1;
    const s = t * (VIRIDIS.length - 1);
    const i = Math.min(Math.floor(s), VIRIDIS.length - 2);
    const f = s - i;
    return VIRIDIS[i].map((a, c) => Math.floor(a + f * (VIRIDIS[i + 1][c] - a) + 0.5));
  }

  // A hue wheel for 2-D vectors: the direction (x right, y down on screen, as motion vectors are) sets the hue,
  // red pointing right, and the length over `max` the saturation; value 1.
  function wheel(x, y, max) {
    const hue = ((Math.atan2(y, x) / (2 * Math.PI)) + 1) % 1;
    const sat = max > 0 ? Math.min(Math.hypot(x, y) / max, 1) : 0;
    const h6 = hue * 6, k = Math.floor(h6) % 6, f = h6 - Math.floor(h6);
    const p = 1 - sat, q = 1 - sat * f, u = 1 - sat * (1 - f);
    const rgb = [[1, u, p], [q, 1, p], [p, 1, u], [p, q, 1], [u, p, 1], [1, p, q]][k];
    return rgb.map((c) => toByte(c));
  }

  // The finite minimum and maximum of one channel or of the length of a vector.
  function range(values) {
    let lo = Infinity, hi = -Infinity;
    for (const v of values) if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    return Number.isFinite(lo) ? [lo, hi] : [0, 1];
  }

  // The modes a layer of this kind can be shown in; the first is its default.
  function modes(layer) {
    if (layer.kind === "rgb") return layer.display_referred ? ["linear", "tonemap", "false colour"] : ["tonemap", "linear", "false colour"];
    if (layer.kind === "vector") return layer.channels === 2 ? ["wheel", "arrows"] : ["normal", "false colour"];
    return ["false colour"];
  }

  // The scalar a "false colour" pixel shows: the value, the luminance of an RGB value, the length of a vector.
  function scalarOf(planes, i) {
    if (planes.length === 1) return planes[0][i];
    if (planes.length === 3 && planes.kind === "rgb") return LUMA[0] * planes[0][i] + LUMA[1] * planes[1][i] + LUMA[2] * planes[2][i];
    return Math.hypot(...planes.map((p) => p[i]));
  }

  // Fills `rgba` (width * height * 4 bytes) with layer `planes` (an array of Float32Array, one per channel, with
  // .kind) in `mode`; `controls` holds exposure, lo and hi (the false-colour range) and max (the wheel's length).
  function render(planes, mode, controls, rgba) {
    const n = planes[0].length;
    for (let i = 0; i < n; ++i) {
      let rgb;
      if (mode === "tonemap") {
        rgb = tonemap(planes[0][i], planes[1][i], planes[2][i], controls.exposure).map((c) => toByte(srgbEncode(c)));
      } else if (mode === "linear") {
        rgb = [0, 1, 2].map((c) => toByte(srgbEncode(Math.min(Math.max(controls.exposure * planes[c][i], 0), 1))));
      } else if (mode === "wheel" || mode === "arrows") {
        rgb = mode === "wheel" ? wheel(planes[0][i], planes[1][i], controls.max)
                               : viridis(Math.hypot(planes[0][i], planes[1][i]) / (controls.max || 1));
      } else if (mode === "normal") {
        rgb = [0, 1, 2].map((c) => toByte(0.5 * planes[c][i] + 0.5));
      } else {
        const span = controls.hi - controls.lo;
        rgb = viridis(span > 0 ? (scalarOf(planes, i) - controls.lo) / span : 0.5);
      }
      rgba[4 * i] = rgb[0];
      rgba[4 * i + 1] = rgb[1];
      rgba[4 * i + 2] = rgb[2];
      rgba[4 * i + 3] = 255;
    }
  }

  return { srgbEncode, toByte, tonemap, viridis, wheel, range, modes, scalarOf, render, VIRIDIS };
})();
