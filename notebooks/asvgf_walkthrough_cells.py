"""The cells of asvgf_walkthrough.ipynb: A-SVGF's gradient samples, lambda and alpha_i on pillars' moving shadows,
beside SVGF's lagging history (make_notebooks.py writes the notebook)."""
from nbformat.v4 import new_code_cell, new_markdown_cell

from common_cell import COMMON

ASVGF_WALKTHROUGH = [
    new_markdown_cell("""# A-SVGF, pass by pass: gradient samples, lambda and the adaptive alpha

SVGF's temporal accumulation trusts the history wherever the surface was seen last frame. In the scene
`pillars`, eleven pillars move left to right in front of a fixed area light (scenes/README.md), so their
shadows sweep across a floor that does not move: every floor pixel passes SVGF's consistency tests, SVGF
keeps blending in where the shadow was, and the shadows lag. A-SVGF (Schied, Peters, Dachsbacher 2018)
measures how much the shading changed with *temporal gradient samples*, and drops the history where it did.

The sections follow filters/asvgf/README.md: the gradient samples and the gradient image [ASVGF18 Eq. 3, 13],
its reconstruction [ASVGF18 Eq. 7-12], the adaptive alpha [ASVGF18 Eq. 14, 15], then SVGF's temporal pass
with it, beside plain SVGF. Every image is a layer of the input (docs/buffers.md, "Gradient samples") or
one that `rtdr filter --dump-passes` wrote (docs/buffers.md, "Filter passes"). The last sections print
every term of one pixel with `rtdr probe`, and end with an exercise.

The data comes from `RTDR_ASVGF_IN` (1-spp frames with gradient samples), `RTDR_ASVGF_DUMP` (them filtered
by `asvgf`, with dumps), `RTDR_ASVGF_SVGF_DUMP` (filtered by `svgf`, with dumps) and `RTDR_ASVGF_REF`
(reference frames). To make them yourself:

```sh
build/app/rtdr render --scene pillars --frames 0-11 --size 320x180 --gradients --out out/asvgf-walkthrough/in
build/app/rtdr filter --method asvgf --in out/asvgf-walkthrough/in --out out/asvgf-walkthrough/asvgf --dump-passes
build/app/rtdr filter --method svgf --in out/asvgf-walkthrough/in --out out/asvgf-walkthrough/svgf --dump-passes
build/app/rtdr render --scene pillars --frames 0-11 --size 320x180 --spp 16 --out out/asvgf-walkthrough/ref
```

To step through every pass of every frame yourself, and click any pixel to see every term of its equation
(the gradient image, its reconstruction and alpha_i included), open the same frames in the browser
(docs/view.md): `build/app/rtdr view --in out/asvgf-walkthrough/in --method asvgf --ref out/asvgf-walkthrough/ref`.

The text describes this sequence. The test suite runs the notebook on a smaller one (tests/run_notebooks.sh),
where a pillar is about one stratum wide and lambda stays small: the exercise asks why."""),
    new_code_cell(COMMON + """

IN = os.environ.get("RTDR_ASVGF_IN", "out/asvgf-walkthrough/in")
DUMP = os.environ.get("RTDR_ASVGF_DUMP", "out/asvgf-walkthrough/asvgf")
SVGF_DUMP = os.environ.get("RTDR_ASVGF_SVGF_DUMP", "out/asvgf-walkthrough/svgf")
REF = os.environ.get("RTDR_ASVGF_REF", "out/asvgf-walkthrough/ref")
RTDR = os.environ.get("RTDR_EXE", "build/app/rtdr")
ALPHA = np.float32(0.1)  # asvgf's constant alpha [ASVGF18 Sec. 5]; rtdr filter --method asvgf prints it

def read_uint(path, name):
    \"\"\"One uint channel as stored (read_exr converts to float, which scales a uint to [0, 1]).\"\"\"
    inp = oiio.ImageInput.open(path)
    k = list(inp.spec().channelnames).index(name)
    values = inp.read_image(0, 0, k, k + 1, "uint")[..., 0]
    inp.close()
    return values

def header(path, name):
    \"\"\"A string attribute of an EXR's header (docs/buffers.md, "Gradient samples").\"\"\"
    inp = oiio.ImageInput.open(path)
    value = inp.spec().getattribute(name)
    inp.close()
    return value

def read_layers(path, *prefixes):
    \"\"\"The channels of read_exr whose names start with one of prefixes (a dump holds about 150).\"\"\"
    return {name: v for name, v in read_exr(path).items() if name.startswith(prefixes)}

def luminance(c):
    \"\"\"Rec. 709 Y in float32, as core/color.h computes it.\"\"\"
    return np.float32(0.2126) * c[..., 0] + np.float32(0.7152) * c[..., 1] + np.float32(0.0722) * c[..., 2]

def show_maps(images, titles, cmap="viridis", vmin=None, vmax=None):
    \"\"\"Like show, with one colour scale and a colour bar.\"\"\"
    fig, axes = plt.subplots(1, len(images), figsize=(4 * len(images), 2.6), constrained_layout=True)
    for ax, image, title in zip(np.atleast_1d(axes), images, titles):
        shown = ax.imshow(image, cmap=cmap, vmin=vmin, vmax=vmax)
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    fig.colorbar(shown, ax=axes, shrink=0.8)
    plt.show()

# The frames in order of their index, and the layers used below.
names = frame_files(DUMP)
indices = [frame_index(name) for name in names]
inputs = [read_layers(os.path.join(IN, n), "direct.", "gradient.prev_direct", "normal.") for n in names]
sources = [read_uint(os.path.join(IN, n), "gradient.source") for n in names]
asvgf = [read_layers(os.path.join(DUMP, n), "filter.direct.gradient.", "filter.direct.lambda", "filter.direct.alpha",
                     "filter.direct.temporal.", "filter.direct.history_length") for n in names]
svgf = [read_layers(os.path.join(SVGF_DUMP, n), "filter.direct.temporal.", "filter.direct.history_length") for n in names]
refs = [read_layers(os.path.join(REF, n), "direct.") for n in names]
s = int(header(os.path.join(IN, names[-1]), "rtdr.gradient.stratum_size"))
H, W = sources[-1].shape
last, frame = len(names) - 1, indices[-1]
inp, out = inputs[last], asvgf[last]
print(f"{len(names)} frames ({indices[0]}-{frame}), {W}x{H} pixels, strata of {s}x{s}; looking at frame {frame}")"""),
    new_markdown_cell(r"""## 1. Gradient samples [ASVGF18 Sec. 3.2, 3.3, Eq. 2-6]

A pixel's 1-spp sample is a function $f_i(G, \xi)$ of the surface sample $G$ it sees and of its random
numbers $\xi$ [ASVGF18 Sec. 3.2]. One pixel's samples in two frames differ by the change in lighting *and*
by the noise. So A-SVGF takes, in each stratum of $s \times s$ pixels, one pixel $j$ of the previous frame,
carries its surface sample $G_{i-1,j}$ to where that point is now, $\tilde G_{i-1,j}$ at pixel $\bar j$
(the forward projection [ASVGF18 Sec. 3.1]), and shades it there again with the *same* random numbers
$\xi_{i-1,j}$ [ASVGF18 Eq. 6]. The two samples' difference

$$\delta_{i,\bar j} = f_i(\tilde G_{i-1,j}, \xi_{i-1,j}) - f_{i-1}(G_{i-1,j}, \xi_{i-1,j}) \quad \text{(Eq. 3)}$$

is then the change in lighting alone: with new random numbers its variance would be twice a sample's
[ASVGF18 Eq. 4-5]; with the same ones it is exactly 0 where nothing changed [ASVGF18 Eq. 2, 6].

In the input, `gradient.source` holds at such a pixel $\bar j$ the linear index $y W + x$ of its source
pixel $j$ in the previous frame (4294967295 elsewhere), and `gradient.prev_direct` the luminance of
$f_{i-1}$. Below: which pixels are gradient samples, on a crop with the stratum grid drawn in. Where the
forward projection found no pixel (the surface point left the view or is hidden now) a stratum has none."""),
    new_code_cell("""NONE = np.uint32(4294967295)  # gradient.source where the pixel is not a gradient sample
strata_w, strata_h = -(-W // s), -(-H // s)  # partial strata at the right and bottom edges count
is_sample = sources[last] != NONE
per_stratum = np.zeros((strata_h, strata_w), int)
np.add.at(per_stratum, (np.nonzero(is_sample)[0] // s, np.nonzero(is_sample)[1] // s), 1)
print(f"frame {frame}: {is_sample.sum()} gradient samples in {strata_w * strata_h} strata "
      f"({(per_stratum == 0).sum()} strata without one)")
ys, xs = np.nonzero(is_sample)  # where the samples are now, and where they were (gradient.source = y W + x)
source_x, source_y = sources[last][is_sample] % W, sources[last][is_sample] // W
moved = (source_x != xs) | (source_y != ys)
print(f"{moved.sum()} of them moved since the previous frame (on the pillars); the floor's did not")

# The checks: at most one sample per stratum [ASVGF18 Sec. 3.3], so at most as many as strata, and some.
for k in range(1, len(names)):
    samples = sources[k] != NONE
    count = np.zeros((strata_h, strata_w), int)
    np.add.at(count, (np.nonzero(samples)[0] // s, np.nonzero(samples)[1] // s), 1)
    assert count.max() <= 1, f"frame {indices[k]}: a stratum holds {count.max()} gradient samples"
    assert 0 < samples.sum() <= strata_w * strata_h, f"frame {indices[k]}: {samples.sum()} gradient samples"
    assert (sources[k][samples] < W * H).all(), "a source index outside the previous frame"

x0, y0 = (W // 2) // s * s, int(H * 0.7) // s * s  # a crop of 8x8 strata on the floor, on the grid
crop = np.s_[y0:y0 + 8 * s, x0:x0 + 8 * s]
fig, axes = plt.subplots(1, 2, figsize=(10, 3.4))
axes[0].imshow(display(inp["direct.G"]), cmap="gray")
axes[0].add_patch(plt.Rectangle((x0, y0), 8 * s, 8 * s, fill=False, color="red"))
axes[0].set_title(f"direct illumination, frame {frame}: the crop", fontsize=9)
axes[1].imshow(np.where(is_sample[crop], 1.0, 0.2 * display(inp["direct.G"][crop])), cmap="magma", vmin=0, vmax=1)
axes[1].set_xticks(np.arange(-0.5, 8 * s, s)); axes[1].set_yticks(np.arange(-0.5, 8 * s, s))
axes[1].set_xticklabels([]); axes[1].set_yticklabels([]); axes[1].grid(color="white", lw=0.5)
axes[1].set_title("gradient samples (bright), one per stratum at most", fontsize=9)
plt.show()"""),
    new_markdown_cell(r"""## 2. The gradient image: $\delta$ and $\Delta$ per stratum [ASVGF18 Eq. 3, 13, Sec. 3.4]

The pass `gradient` (filters/asvgf/gradient_image.cpp) makes an image on the stratum grid, per stream (here
`direct`, as the luminance of the demodulated illumination). A stratum with a sample gets that sample's
$\delta$ [ASVGF18 Eq. 3] and its normalisation [ASVGF18 Eq. 13], the larger of the two luminances,

$$\Delta_{i,\bar j} = \max\left(f_i(\tilde G_{i-1,j}, \xi_{i-1,j}),\ f_{i-1}(G_{i-1,j}, \xi_{i-1,j})\right) \quad \text{(Eq. 13)}$$

so that $|\delta| / \Delta$ is a relative change: 1 when a light switches on, or when the sample falls into
full shadow. A stratum without a sample gets $\delta = \Delta = 0$. The layers `filter.direct.gradient.delta`
and `filter.direct.gradient.norm` hold each stratum's value at all of its pixels. The cell computes both
again from the input frame with numpy and compares them with the dump. Few strata have $\delta \ne 0$:
only where a shadow's edge crossed the sample between the two frames."""),
    new_code_cell("""def gradient_image(k):
    \"\"\"delta [ASVGF18 Eq. 3] and Delta [Eq. 13] of frame k's strata, from its input, at every pixel.\"\"\"
    f_now = luminance(np.stack([inputs[k][f"direct.{c}"] for c in "RGB"], axis=-1))  # f_i(G~, xi_{i-1,j})
    f_before = inputs[k]["gradient.prev_direct"]                                       # f_{i-1}(G, xi_{i-1,j})
    samples = sources[k] != NONE
    delta, norm = np.zeros((strata_h, strata_w), np.float32), np.zeros((strata_h, strata_w), np.float32)
    ys, xs = np.nonzero(samples)
    delta[ys // s, xs // s] = f_now[samples] - f_before[samples]
    norm[ys // s, xs // s] = np.maximum(f_now[samples], f_before[samples])
    expand = lambda strata: np.repeat(np.repeat(strata, s, axis=0), s, axis=1)[:H, :W]
    return expand(delta), expand(norm)

for k in range(1, len(names)):
    delta, norm = gradient_image(k)
    # The checks: the dump is Eq. 3 and 13 of the input, and |delta| <= Delta (both luminances are >= 0).
    assert np.allclose(asvgf[k]["filter.direct.gradient.delta"], delta, rtol=1e-5, atol=1e-6), f"delta, frame {indices[k]}"
    assert np.allclose(asvgf[k]["filter.direct.gradient.norm"], norm, rtol=1e-5, atol=1e-6), f"Delta, frame {indices[k]}"
    assert (np.abs(delta) <= norm).all()

delta, norm = out["filter.direct.gradient.delta"], out["filter.direct.gradient.norm"]
changed = np.abs(delta[::s, ::s]) > 0
print(f"frame {frame}: delta != 0 in {changed.sum()} of {(norm[::s, ::s] > 0).sum()} strata with a sample")
d = max(np.abs(delta).max(), 1e-6)
show_maps([delta], ["delta (Eq. 3): red darker, blue brighter"], cmap="RdBu", vmin=-d, vmax=d)
show_maps([norm, np.divide(np.abs(delta), norm, out=np.zeros_like(norm), where=norm > 0)],
          ["Delta (Eq. 13)", "|delta| / Delta of one sample"])"""),
    new_markdown_cell(r"""## 3. Reconstruction: $\hat\delta$ and $\hat\Delta$ [ASVGF18 Eq. 7-12]

One sample per stratum, most of them 0, some $\pm\Delta$: too sparse and too noisy to use as it is. The pass
`gradient_atrous` (filters/asvgf/gradient_atrous.cpp) fills the grid with five iterations of a
joint-bilateral a-trous filter on the strata, taps $2^k$ strata apart, a 3x3 box $h$ and SVGF's
edge-stopping weights, steered by the strata's mean luminance $\hat l^{(0)}$:

$$\hat l^{(k+1)}(p) = \frac{\sum_q h(q)\, w(p, q)\, \hat l^{(k)}(q)}{\sum_q h(q)\, w(p, q)} \quad \text{(Eq. 7)}, \qquad
  w(p, q) = w_z\, w_n\, w_l \quad \text{(Eq. 8-11)}$$

$\delta$ and $\Delta$ are filtered with the same weights [ASVGF18 Eq. 12]:

$$\hat\delta^{(k+1)}(p) = \frac{\sum_q h\, w\, \hat\delta^{(k)}(q)}{\sum_q h\, w}, \qquad
  \hat\Delta^{(k+1)}(p) = \frac{\sum_q h\, w\, \hat\Delta^{(k)}(q)}{\sum_q h\, w}$$

Strata without a sample stay in both sums with 0: the density of samples is in both, and cancels in the
quotient of the next section. The signs stay too: the leading edge of a moving shadow gets darker
($\delta < 0$), its trailing edge brighter ($\delta > 0$), and where both fall in one footprint they cancel.
Below, the last iteration's $\hat\delta$ and $\hat\Delta$ (`filter.direct.gradient.level4.delta` and `.norm`
with the default five iterations)."""),
    new_code_cell("""gradient_levels = sorted({int(k.split(".")[3][len("level"):]) for k in out if re.fullmatch(r"filter\\.direct\\.gradient\\.level\\d+\\.delta", k)})
top = f"filter.direct.gradient.level{gradient_levels[-1]}"
print(f"{len(gradient_levels)} iterations; the last one's layers: {top}.delta, {top}.norm")
delta_hat, norm_hat = out[f"{top}.delta"], out[f"{top}.norm"]
d = max(np.abs(delta_hat).max(), 1e-6)
show_maps([delta, delta_hat], ["delta: the samples", f"delta^ after iteration {gradient_levels[-1]} (Eq. 12)"],
          cmap="RdBu", vmin=-d, vmax=d)
show_maps([out[f"filter.direct.gradient.level{k}.norm"] for k in (0, gradient_levels[-1])],
          [f"Delta^ after iteration {k} (Eq. 12)" for k in (0, gradient_levels[-1])])"""),
    new_markdown_cell(r"""## 4. $\lambda$ and the adaptive $\alpha_i$ [ASVGF18 Eq. 14, 15, Sec. 3.5]

The pass `adaptive_alpha` (filters/asvgf/adaptive_alpha.cpp) turns the reconstruction into the share of the
history that is out of date,

$$\lambda(p) = \min\left(1,\ \frac{|\hat\delta(p)|}{\hat\Delta(p)}\right) \quad \text{(Eq. 14)}$$

(0 where $\hat\Delta = 0$: no sample in reach, the history is kept). The sparse samples can miss a change
next door, so each pixel takes the largest $\lambda$ of the 3x3 strata around its own [ASVGF18 Sec. 3.5],
and blends with

$$\alpha_i(p) = \left(1 - \lambda_{\max}(p)\right) \alpha + \lambda_{\max}(p), \qquad \alpha = 0.1 \quad \text{(Eq. 15)}$$

so $\alpha_i = 0.1$ where nothing changed and $\alpha_i = 1$ (the history dropped) where the lighting changed
completely. The cell computes both again from $\hat\delta$ and $\hat\Delta$, compares them with the dumps
`filter.direct.lambda` and `filter.direct.alpha`, and then shows them over a few frames. In the 320x180
sequence $\alpha_i$ comes near 1 at the pillars' feet, where their shadows are sharp and move about a pixel
a frame, and rises on the pillars themselves, which move relative to the light. Over the soft shadows further
out on the floor it stays near 0.15 (mostly below 0.25): they change little from one frame to the next.
On a static scene it would be 0.1 everywhere."""),
    new_code_cell("""def adaptive_alpha(k):
    \"\"\"lambda [ASVGF18 Eq. 14] and alpha_i [Eq. 15, the 3x3 maximum of Sec. 3.5] of frame k, at every pixel.\"\"\"
    d_hat, n_hat = asvgf[k][f"{top}.delta"][::s, ::s], asvgf[k][f"{top}.norm"][::s, ::s]  # one value a stratum
    lam = np.where(n_hat > 0, np.minimum(np.float32(1), np.abs(d_hat) / np.where(n_hat > 0, n_hat, 1)), 0)
    padded = np.pad(lam, 1)  # lambda >= 0, so the 0 outside the grid never wins the maximum
    lam_max = np.max([padded[1 + dy:1 + dy + strata_h, 1 + dx:1 + dx + strata_w]
                      for dy in (-1, 0, 1) for dx in (-1, 0, 1)], axis=0)
    alpha_i = (np.float32(1) - lam_max) * ALPHA + lam_max
    expand = lambda strata: np.repeat(np.repeat(strata, s, axis=0), s, axis=1)[:H, :W]
    return expand(lam), expand(alpha_i)

floor = np.all([f["normal.Y"] > 0.99 for f in inputs], axis=0)  # the floor's normal is +Y; pillars' faces are not
for k in range(1, len(names)):
    lam, alpha_i = adaptive_alpha(k)
    a = asvgf[k]["filter.direct.alpha"]
    # The checks: the dumps are Eq. 14 and 15; ALPHA <= alpha_i <= 1 everywhere; and every moving shadow lifts
    # alpha_i: with the same random numbers a static floor gives delta = 0 exactly, but the shadows sweep
    # over all of it, so (nearly) every floor pixel has a change within reach of the reconstruction.
    assert np.allclose(asvgf[k]["filter.direct.lambda"], lam, atol=1e-6), f"lambda, frame {indices[k]}"
    assert np.allclose(a, alpha_i, atol=1e-6), f"alpha_i, frame {indices[k]}"
    assert a.min() >= ALPHA - 1e-6 and a.max() <= 1 + 1e-6, f"alpha_i in [{a.min()}, {a.max()}], frame {indices[k]}"
    lifted = (a[floor] > ALPHA + 1e-6).mean()
    assert lifted > 0.9, f"frame {indices[k]}: alpha_i > alpha on only {lifted:.0%} of the floor"
    print(f"frame {indices[k]:3d}: alpha_i > 0.1 on {lifted:.0%} of the floor, largest {a.max():.3f}")

shown = sorted(set(np.linspace(1, last, 4).round().astype(int)))  # a few frames, frame 0 has no samples
show([display(rgb(inputs[k], "direct")) for k in shown], [f"1-spp direct, frame {indices[k]}" for k in shown])
show_maps([asvgf[k]["filter.direct.lambda"] for k in shown], [f"lambda (Eq. 14), frame {indices[k]}" for k in shown],
          vmin=0, vmax=1)
show_maps([asvgf[k]["filter.direct.alpha"] for k in shown], [f"alpha_i (Eq. 15), frame {indices[k]}" for k in shown],
          vmin=0, vmax=1)"""),
    new_markdown_cell(r"""## 5. SVGF's lagging history, A-SVGF's adaptive one [SVGF17 Sec. 4.1, ASVGF18 Sec. 4]

SVGF blends $C'_i(p) = \alpha\, C_i(p) + (1 - \alpha)\, C'_{i-1}(p')$ with $\alpha = \max(0.2, 1/n)$ and
drops the history only where the consistency tests fail, a disocclusion. A shadow sweeping over the static
floor fails none of them: SVGF's history length $n$ counts every frame there, and each frame keeps 80% of
the history, the old shadow included. A-SVGF blends with $\alpha_i$ instead [ASVGF18 Sec. 4], and
shortens the history with it, $n_i = 1 + (1 - \lambda_{\max})\, n_{i-1}$, so that the variance of a dropped history is
estimated spatially, as after a disocclusion (filters/asvgf/README.md, "Deviations and choices").

Below, the history lengths `filter.direct.history_length` of both methods, their integrated colour
$C'$ (`filter.direct.temporal`) beside the reference, and one floor pixel over time: the one where
A-SVGF dropped the most history (the largest sum of $\alpha_i$ over the frames)."""),
    new_code_cell("""n_max = len(names)
show_maps([svgf[k]["filter.direct.history_length"] for k in shown], [f"SVGF n, frame {indices[k]}" for k in shown],
          vmin=1, vmax=n_max)
show_maps([asvgf[k]["filter.direct.history_length"] for k in shown], [f"A-SVGF n, frame {indices[k]}" for k in shown],
          vmin=1, vmax=n_max)
show([display(rgb(svgf[last], "filter.direct.temporal")), display(rgb(asvgf[last], "filter.direct.temporal")),
      display(rgb(refs[last], "direct"))], [f"SVGF C', frame {frame}", f"A-SVGF C', frame {frame}", "reference direct"])"""),
    new_code_cell("""# The floor pixel where A-SVGF dropped the most history over the sequence.
alpha_sum = np.sum([f["filter.direct.alpha"] for f in asvgf], axis=0)
y, x = np.unravel_index(np.argmax(np.where(floor, alpha_sum, -1)), alpha_sum.shape)
series = {name: [luminance(rgb(f, layer))[y, x] for f in sequence]
          for name, sequence, layer in [("reference", refs, "direct"), ("SVGF C'", svgf, "filter.direct.temporal"),
                                      ("A-SVGF C'", asvgf, "filter.direct.temporal"), ("1-spp input", inputs, "direct")]}
fig, ax = plt.subplots(figsize=(7, 3.6))
ax.plot(indices, series["reference"], "k-", lw=2, label="reference")
ax.plot(indices, series["SVGF C'"], "o-", label="SVGF C'")
ax.plot(indices, series["A-SVGF C'"], "s-", label="A-SVGF C'")
ax.plot(indices, series["1-spp input"], ".", color="grey", label="1-spp input")
ax.set_xlabel("frame"); ax.set_ylabel("luminance of direct (demodulated)")
twin = ax.twinx()
twin.plot(indices, [f["filter.direct.alpha"][y, x] for f in asvgf], ":", color="tab:red", label="alpha_i")
twin.set_ylim(0, 1); twin.set_ylabel("alpha_i", color="tab:red")
ax.legend(fontsize=8, loc="upper left"); ax.set_title(f"pixel ({x}, {y})", fontsize=9)
plt.show()
reference = luminance(rgb(refs[last], "direct"))
for name, dump in (("SVGF C'", svgf), ("A-SVGF C'", asvgf)):
    error = np.abs(np.array(series[name]) - np.array(series["reference"]))
    floor_error = np.abs(luminance(rgb(dump[last], "filter.direct.temporal")) - reference)[floor].mean()
    print(f"{name:10} |C' - reference| at ({x}, {y}): mean {error[1:].mean():.4f}, largest {error.max():.4f}; "
          f"over the floor in frame {frame}: mean {floor_error:.4f}")"""),
    new_markdown_cell("""## 6. One pixel, every term: `rtdr probe`

`rtdr probe --pass adaptive_alpha` filters the frames up to this one, then runs the pass again at the pixel
above, recording every term it computes: the stratum, its $\\hat\\delta$, $\\hat\\Delta$ and $\\lambda$, the
largest $\\lambda$ around it, and $\\alpha_i$. The cell prints the text and checks the JSON against the dump."""),
    new_code_cell("""command = [RTDR, "probe", "--method", "asvgf", "--in", IN, "--frame", str(frame), "--pixel", f"{x},{y}",
           "--pass", "adaptive_alpha"]
print(subprocess.run(command, check=True, capture_output=True, text=True).stdout)
terms = json.loads(subprocess.run(command + ["--json"], check=True, capture_output=True, text=True).stdout)["terms"]
probed = {t["name"]: t["value"] for t in terms}
# The check: the probe computes what the filter dumped.
assert abs(probed["alpha_i"][0] - out["filter.direct.alpha"][y, x]) < 1e-6, (probed["alpha_i"], out["filter.direct.alpha"][y, x])
assert abs(probed["lambda(p)"][0] - out["filter.direct.lambda"][y, x]) < 1e-6"""),
    new_markdown_cell(r"""## Exercise: where does the gradient come from?

1. From the probe's $\hat\delta(p)$ and $\hat\Delta(p)$, compute $\lambda(p)$ by hand [ASVGF18 Eq. 14], and
   from its largest $\lambda$ around $p$ the $\alpha_i$ of Eq. 15. Do they match?
2. The cell below renders the same frames with `--gradient-seed-reuse 0`: each gradient sample is shaded
   with new random numbers, as in [ASVGF18 Eq. 4-5], instead of its old ones [ASVGF18 Eq. 6]. Where does
   $\lambda$ grow, and why? What would A-SVGF do with a scene where nothing moves?
3. A pillar is 0.2 m wide. At 320x180 that is about 6 pixels, two strata; in the test's 128x72 sequence it
   is less than one. Using the section on the reconstruction, explain why $\lambda$ stays small there.
   Which would help more: `--gradient-stratum-size 2`, or a larger image?
4. Filter with `--asvgf-alpha-max-radius 0` (no 3x3 maximum) and with `--asvgf-history-rule 1` (SVGF's
   history length), and plot the pixel of section 5 again. What changes, and when?
5. Section 5 also printed each method's mean error over the whole floor. Which is lower? Compare SVGF's
   $\alpha = 0.2$ with the $\alpha_i$ that A-SVGF uses over most of the floor, and say what that costs."""),
    new_code_cell("""import tempfile

work = tempfile.mkdtemp()
first, size = f"{indices[0]}-{frame}", f"{W}x{H}"
subprocess.run([RTDR, "render", "--scene", "pillars", "--frames", first, "--size", size, "--gradients",
                "--gradient-seed-reuse", "0", "--out", os.path.join(work, "in")], check=True, capture_output=True)
subprocess.run([RTDR, "filter", "--method", "asvgf", "--in", os.path.join(work, "in"), "--out",
                os.path.join(work, "asvgf"), "--dump-passes"], check=True, capture_output=True)
new_seed = read_layers(os.path.join(work, "asvgf", names[-1]), "filter.direct.lambda", "filter.direct.alpha")
show_maps([out["filter.direct.lambda"], new_seed["filter.direct.lambda"]],
          ["lambda, same random numbers (Eq. 6)", "lambda, new random numbers (Eq. 4-5)"], vmin=0, vmax=1)
print(f"mean alpha_i: {out['filter.direct.alpha'].mean():.3f} with seed reuse, "
      f"{new_seed['filter.direct.alpha'].mean():.3f} without")"""),
]
