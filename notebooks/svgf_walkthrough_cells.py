"""The cells of svgf_walkthrough.ipynb: each SVGF pass on a real frame, in the order of filters/svgf/README.md
(make_notebooks.py writes the notebook)."""
from nbformat.v4 import new_code_cell, new_markdown_cell

from common_cell import COMMON

WALKTHROUGH = [
    new_markdown_cell("""# SVGF, pass by pass

Spatiotemporal Variance-Guided Filtering (Schied et al. 2017) on a real frame rendered by RTDR. Each
section is one pass, in the order of `filters/svgf/README.md`: first the equation the pass computes, then
the image it produced. Every image is a layer that `rtdr filter --dump-passes` wrote (names in
`docs/buffers.md`). The last sections print every term of one pixel with `rtdr probe`, and end with an
exercise.

The data comes from `RTDR_WALKTHROUGH_IN` (the rendered 1-spp frames) and `RTDR_WALKTHROUGH_DUMP` (the
filtered frames with their dumps). To make them yourself:

```sh
build/app/rtdr render --scene pillars --frames 0-9 --size 320x180 --out out/walkthrough/in
build/app/rtdr filter --method svgf --in out/walkthrough/in --out out/walkthrough/svgf --dump-passes
```

To step through every pass of every frame yourself, and click any pixel to see every term of its equation,
open the same frames in the browser (docs/view.md):

```sh
build/app/rtdr view --in out/walkthrough/in --method svgf
```"""),
    new_code_cell(COMMON + """

IN = os.environ.get("RTDR_WALKTHROUGH_IN", "out/walkthrough/in")
DUMP = os.environ.get("RTDR_WALKTHROUGH_DUMP", "out/walkthrough/svgf")
RTDR = os.environ.get("RTDR_EXE", "build/app/rtdr")

frames = frame_files(DUMP)
last = frames[-1]
frame = frame_index(last)
inp, out = read_exr(os.path.join(IN, last)), read_exr(os.path.join(DUMP, last))
print(f"{len(frames)} frames; looking at frame {frame} ({last}), {inp['depth.Z'].shape[1]}x{inp['depth.Z'].shape[0]}")"""),
    new_markdown_cell(r"""## 0. The input: demodulated 1-spp illumination [SVGF17 Sec. 3]

The path tracer's radiance, direct and indirect apart, divided by the surface albedo $a$, so that a pixel's
colour is

$$c = e + \max(a, 10^{-3}) \odot (D + I)$$

with $e$ the emission and $D$, $I$ the layers `direct` and `indirect`. Texture is gone from $D$ and $I$, so
the filter never blurs it; the noise is what is left."""),
    new_code_cell("""show([display(rgb(inp, "direct")), display(rgb(inp, "indirect")), rgb(inp, "albedo")],
     ["direct D (demodulated)", "indirect I (demodulated)", "albedo a"])"""),
    new_markdown_cell(r"""## 1. Temporal accumulation [SVGF17 Sec. 4.1]

Each pixel $p$ is back-projected with its motion vector to $p'$ in the previous frame; where the history
there is consistent (same mesh, depth and normal), it is blended with this frame's sample:

$$C'_i(p) = \alpha\, C_i(p) + (1 - \alpha)\, C'_{i-1}(p'), \qquad \alpha = \max(0.2,\ 1/n)$$

The history length $n$ counts the frames blended so far; it is 1 after a disocclusion, where the history
is dropped: watch the trailing edges of the moving pillars."""),
    new_code_cell("""n = out["filter.direct.history_length"]
show([display(rgb(out, "filter.direct.temporal")), n],
     ["integrated colour C'", f"history length n (max {n.max():.0f})"])"""),
    new_markdown_cell(r"""## 2. Moments and variance [SVGF17 Sec. 4.2]

The first and second moments of the luminance $l$ are accumulated like the colour, and their difference is
the variance of one sample's luminance:

$$\mu'_{1,i} = \alpha\, l_i + (1 - \alpha)\, \mu'_{1,i-1}, \qquad
  \mu'_{2,i} = \alpha\, l_i^2 + (1 - \alpha)\, \mu'_{2,i-1}, \qquad
  \sigma'^2_i = \mu'_{2,i} - \mu'^2_{1,i}$$

Where $n < 4$ the history is too short for this, and the moments are averaged over a 7x7 neighbourhood
with the weights $w_z w_n$ of Eq. 3 and 4 instead. Bright means noisy: the filter will blur more there."""),
    new_code_cell("""var = out["filter.direct.variance"]
show([np.sqrt(var), out["filter.direct.moments.mu1"], (n < 4).astype(float)],
     ["standard deviation sqrt(sigma'^2)", "mu1' (mean luminance)", "n < 4: the 7x7 spatial estimate"], cmap="magma")"""),
    new_markdown_cell(r"""## 3. The variance prefilter [SVGF17 Sec. 4.4, the $g_{3\times3}$ of Eq. 5]

One noisy variance value would make the luminance weight of the next pass erratic, so before each a-trous
level the variance is blurred by a 3x3 Gaussian:

$$g_{3\times3}(\mathrm{Var})(p) = \sum_{dx, dy \in \{-1, 0, 1\}} g(dx)\, g(dy)\, \mathrm{Var}(p + (dx, dy)),
  \qquad g = \left(\tfrac14, \tfrac12, \tfrac14\right)$$

It only steers the luminance weight; the variance that the a-trous propagates to the next level is the
unblurred one. The cell below computes it again with numpy (edges clamped, as the golden pass does) and
compares it with the dump of level 0."""),
    new_code_cell("""prefiltered = out["filter.direct.level0.prefiltered_variance"]
g = np.array([0.25, 0.5, 0.25])
padded = np.pad(var, 1, mode="edge")  # a tap outside the image reads the nearest edge pixel
ours = sum(g[dy + 1] * g[dx + 1] * padded[1 + dy:1 + dy + var.shape[0], 1 + dx:1 + dx + var.shape[1]]
           for dy in (-1, 0, 1) for dx in (-1, 0, 1))
print(f"largest |numpy - dump| = {np.abs(ours - prefiltered).max():.3g} (variances up to {var.max():.3g})")
show([np.sqrt(var), np.sqrt(prefiltered)], ["sqrt(Var): level 0's input", "sqrt(g3x3(Var))"], cmap="magma")"""),
    new_markdown_cell(r"""## 4. The a-trous levels [SVGF17 Eq. 1-5, Sec. 4.3]

Five levels; level $i$ gathers 25 taps $q$ spaced $2^i$ pixels apart, weighted by the B3 kernel $h$ and by
how alike $p$ and $q$ are:

$$c_{i+1}(p) = \frac{\sum_q h(q)\, w(p, q)\, c_i(q)}{\sum_q h(q)\, w(p, q)} \quad \text{(Eq. 1)}, \qquad
  w(p, q) = w_z\, w_n\, w_l \quad \text{(Eq. 2)}$$

$$w_z = \exp\left(-\frac{|z(p) - z(q)|}{\sigma_z\, |\nabla z(p) \cdot (p - q)| + \epsilon}\right) \ \text{(Eq. 3)}, \qquad
  w_n = \max(0,\ n(p) \cdot n(q))^{\sigma_n} \ \text{(Eq. 4)}$$

$$w_l = \exp\left(-\frac{|l_i(p) - l_i(q)|}{\sigma_l \sqrt{g_{3\times3}(\mathrm{Var}(l_i(p)))} + \epsilon}\right) \quad \text{(Eq. 5)}$$

The variance is filtered with the squared weights, so it shrinks level by level and the luminance weight
grows stricter:

$$\mathrm{Var}(c_{i+1}(p)) = \frac{\sum_q h(q)^2\, w(p, q)^2\, \mathrm{Var}(c_i(q))}{\left(\sum_q h(q)\, w(p, q)\right)^2}
  \quad \text{(Sec. 4.3)}$$"""),
    new_code_cell("""levels = sorted({k.split(".")[2] for k in out if k.startswith("filter.direct.level") and k.endswith(".R")},
                key=lambda level: int(level[len("level"):]))
show([display(rgb(out, f"filter.direct.{level}")) for level in levels], levels)
print("mean variance per level:", [float(out[f"filter.direct.{level}.variance"].mean()) for level in levels])"""),
    new_markdown_cell(r"""## 5. Remodulated, recombined, tone mapped, antialiased [SVGF17 Sec. 3]

The filtered streams $\hat D$, $\hat I$ are multiplied by the albedo again and recombined,
$c = e + \max(a, 10^{-3}) \odot (\hat D + \hat I)$; the luminance is tone mapped with Reinhard's operator,
$L_d = L / (1 + L)$ [Reinhard02 Eq. 3]; and TAA blends each pixel with its clipped history,
$o = 0.1\, c + 0.9\, \mathrm{clip}(h)$ [Karis14]."""),
    new_code_cell("""noisy = rgb(inp, "emission") + np.maximum(rgb(inp, "albedo"), 1e-3) * (rgb(inp, "direct") + rgb(inp, "indirect"))
show([display(noisy), display(rgb(out, "color")), rgb(out, "display")], ["1-spp input", "SVGF colour c", "display o (TAA)"])"""),
    new_markdown_cell("""## 6. One pixel, every term: `rtdr probe`

The weights of every tap of a-trous level 1 at a pixel on the floor, as a shader port would compare them.
`rtdr probe` filters the frames up to this one, then runs the pass again at the pixel, recording every term
it computes."""),
    new_code_cell("""h, w = inp["depth.Z"].shape
x, y = w // 2, int(h * 0.8)

def probe_taps(*flags):
    \"\"\"Every term of every tap of a-trous level 1 at (x, y): {"tap (dx, dy)": {term: value}}, and the sums.\"\"\"
    command = [RTDR, "probe", "--in", IN, "--frame", str(frame), "--pixel", f"{x},{y}", "--pass", "atrous",
               "--level", "1", "--json", *flags]
    terms = json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)["terms"]
    taps = {}
    for t in terms:
        taps.setdefault(t["group"], {})[t["name"]] = t["value"][0]
    return taps

taps = probe_taps()
print(f"pixel ({x}, {y}), {sum(1 for g in taps if g.startswith('tap'))} taps")
print(f"{'tap':>14} {'h':>8} {'w_z':>8} {'w_n':>8} {'w_l':>8}")
for name, terms in taps.items():
    if name.startswith("tap"):
        print(f"{name:>14} {terms['h(q)']:8.4f} {terms.get('w_z', 1):8.4f} {terms.get('w_n', 1):8.4f} {terms.get('w_l', 1):8.4f}")"""),
    new_markdown_cell(r"""## Exercise: how strict should the luminance weight be?

$\sigma_l$ in Eq. 5 says how many standard deviations of noise a luminance difference may be before a tap
loses its weight; the paper uses $\sigma_l = 4$. The cell below probes the same pixel with three values
(`rtdr probe ... --json --sigma-l S`) and filters the whole sequence with each (`rtdr filter --method svgf
--sigma-l S`). Each heat map shows $w_l$ of the 25 taps, laid out as they lie around $p$.

1. Which taps lose weight first as $\sigma_l$ shrinks? Compare their $l(q)$ with $l(p)$ in the table above.
2. Take one tap and compute its $w_l$ by hand from $l(p)$, $l(q)$ and $g_{3\times3}(\mathrm{Var})(p)$, which
   the probe prints, with $\epsilon = 10^{-4}$. Does it match?
3. In the filtered images, where does $\sigma_l = 1$ leave noise, and what does $\sigma_l = 16$ blur that it
   should not? Which would you choose for this scene, and why?"""),
    new_code_cell("""import tempfile

sweep = [1.0, 4.0, 16.0]
work = tempfile.mkdtemp()
fig, axes = plt.subplots(1, len(sweep), figsize=(4 * len(sweep), 3.4), constrained_layout=True)
filtered = []
for ax, sigma_l in zip(axes, sweep):
    taps = probe_taps("--sigma-l", str(sigma_l))
    step = taps[""]["step 2^i"]
    grid = np.ones((5, 5))  # the centre tap's w_l is 1 by definition
    for name, terms in taps.items():
        match = re.fullmatch(r"tap \\((-?\\d+), (-?\\d+)\\)", name)
        if match and "w_l" in terms:
            dx, dy = int(match.group(1)) / step, int(match.group(2)) / step
            grid[int(dy) + 2, int(dx) + 2] = terms["w_l"]
    image = ax.imshow(grid, vmin=0, vmax=1, cmap="viridis", extent=[-2.5, 2.5, 2.5, -2.5])
    ax.set_title(f"w_l, sigma_l = {sigma_l:g}: sum h w = {taps['sum']['sum h w']:.3f}", fontsize=9)
    ax.set_xlabel("dx / 2^i")
    out_dir = os.path.join(work, f"sigma_l_{sigma_l:g}")
    subprocess.run([RTDR, "filter", "--method", "svgf", "--in", IN, "--out", out_dir, "--sigma-l", str(sigma_l)],
                   check=True, capture_output=True)
    filtered.append(read_exr(os.path.join(out_dir, last)))
axes[0].set_ylabel("dy / 2^i")
fig.colorbar(image, ax=axes, shrink=0.8)
plt.show()
show([display(rgb(f, "color")) for f in filtered], [f"SVGF colour, sigma_l = {s:g}" for s in sweep])"""),
]
