"""The cells of trmv_walkthrough.ipynb: TRMV's four motion vectors (surface, shadow, glossy, dual) on one frame each
of fence, glossy and occlusion, and where each one fails (make_notebooks.py writes the notebook)."""
from nbformat.v4 import new_code_cell, new_markdown_cell

from common_cell import COMMON

TRMV_WALKTHROUGH = [
    new_markdown_cell(r"""# TRMV's four motion vectors: surface, shadow, glossy, dual

A temporal filter fetches each pixel's history from where its content was in the previous frame. The usual
motion vector follows the pixel's *surface* [TRMV21 Eq. 1]. That is the wrong place for anything that does not
move with the surface: a shadow moves with its light and its blocker, a reflection with the reflected object,
and a pixel that a moving object has just uncovered was hidden last frame, so its surface has no history at all.
TRMV (Zeng et al. 2021, filters/trmv/README.md) computes one vector per effect. `rtdr render` writes all four
into every frame (docs/buffers.md, motion/README.md), and the filter spreads the shadow vector to the pixels
around each shadow (the splat, filters/trmv/splat.h):

| layer | vector | follows |
|---|---|---|
| `motion.X/Y` | $m = x_{i-1} - x_i$ [TRMV21 Eq. 1] | the surface point |
| `motion.shadow.X/Y/valid` | $m^V$ [TRMV21 Eq. 3] | the shadow: light sample, blocker, receiver plane |
| `filter.trmv.visibility.splat_x/y/landed` | $m^V$ spread over the shadow filter's window [TRMV21 Sec. 4.1] (`rtdr filter --dump-passes`) | the shadow, for the lit pixels beside it too |
| `motion.glossy.X/Y/valid` | $m^R$ [TRMV21 Eq. 5] | the reflected point's mirror image, plus one draw of the lobe |
| `motion.dual.X/Y/valid` | $x^O_{i-1} - x_i$ [TRMV21 Eq. 6] | at disoccluded pixels: a step back by the occluder's motion |

All are in pixels with one convention: the content at pixel centre $x_i$ was at $x_i + m$ in the previous
frame, y down. Where a vector is not valid its layer holds (0, 0), except the splat's and the dual's, which
hold the surface motion there.

The sections take one frame each of three shipped scenes (scenes/README.md): `fence` (a fence slides over a
still floor, its shadows sweep across it), `glossy` (an orbiting camera over a metallic floor of roughness
0.15) and `occlusion` (a static camera, two boxes sliding in front of a textured wall). Then one vector is
rebuilt by hand from the layers, and the last section shows where each vector fails.

The data comes from `RTDR_TRMV_FENCE`, `RTDR_TRMV_GLOSSY`, `RTDR_TRMV_GLOSSY_RESEED` and `RTDR_TRMV_OCCLUSION`:
folders that hold a frame and the one before it (the reseeded glossy folder, the last frame alone, rendered
with another seed); and `RTDR_TRMV_FENCE_DUMP`, the fence's frames filtered by trmv with their dumps. To make
them yourself:

```sh
build/app/rtdr render --scene fence --frames 7-8 --size 320x180 --shading-samples 16 --out out/trmv-walkthrough/fence
build/app/rtdr filter --method trmv --in out/trmv-walkthrough/fence --out out/trmv-walkthrough/fence-trmv --dump-passes
build/app/rtdr render --scene glossy --frames 19-20 --size 320x180 --out out/trmv-walkthrough/glossy
build/app/rtdr render --scene glossy --frames 20 --size 320x180 --seed 1 --out out/trmv-walkthrough/glossy-reseed
build/app/rtdr render --scene occlusion --frames 39-40 --size 320x180 --out out/trmv-walkthrough/occlusion
```

The test suite runs the notebook on 160x90 frames (tests/run_notebooks.sh); every number below is computed
and printed, so it is the one of the frames you give it.

To see these vectors at work in TRMV's own passes, every pass of every frame, and click any pixel to see every
term of its equation, open a sequence with the shading term in the browser (docs/view.md):

```sh
build/app/rtdr render --scene fence --frames 0-8 --size 320x180 --shading-samples 64 --out out/trmv-walkthrough/fence-seq
build/app/rtdr view --in out/trmv-walkthrough/fence-seq --method trmv
```"""),
    new_code_cell(COMMON + """

FENCE = os.environ.get("RTDR_TRMV_FENCE", "out/trmv-walkthrough/fence")
FENCE_DUMP = os.environ.get("RTDR_TRMV_FENCE_DUMP", "out/trmv-walkthrough/fence-trmv")
GLOSSY = os.environ.get("RTDR_TRMV_GLOSSY", "out/trmv-walkthrough/glossy")
GLOSSY_RESEED = os.environ.get("RTDR_TRMV_GLOSSY_RESEED", "out/trmv-walkthrough/glossy-reseed")
OCCLUSION = os.environ.get("RTDR_TRMV_OCCLUSION", "out/trmv-walkthrough/occlusion")
NONE = np.uint32(4294967295)  # a uint id layer where there is nothing (no surface, no blocker, no hit)

def read_frame(path):
    \"\"\"read_exr, with the uint layers (ids, validity) as stored: read as float they are scaled to [0, 1].\"\"\"
    frame = read_exr(path)
    inp = oiio.ImageInput.open(path)
    for k, name in enumerate(inp.spec().channelnames):
        if inp.spec().channelformat(k).basetype == oiio.UINT:
            frame[name] = inp.read_image(0, 0, k, k + 1, "uint")[..., 0]
    inp.close()
    return frame

def last_two(folder):
    \"\"\"The previous and the current frame of a folder, and the current one's index.\"\"\"
    names = frame_files(folder)
    return read_frame(os.path.join(folder, names[-2])), read_frame(os.path.join(folder, names[-1])), frame_index(names[-1])

def colour(frame):
    \"\"\"The 1-spp colour, emission + max(albedo, 0.001) (direct + indirect) (docs/buffers.md).\"\"\"
    return rgb(frame, "emission") + np.maximum(rgb(frame, "albedo"), 1e-3) * (rgb(frame, "direct") + rgb(frame, "indirect"))

def vec(frame, name):
    \"\"\"A motion layer as (X, Y), pixels.\"\"\"
    return frame[name + ".X"], frame[name + ".Y"]

def centres(frame):
    \"\"\"The pixel centres x_i, (x + 0.5, y + 0.5).\"\"\"
    H, W = frame["depth.Z"].shape
    return np.meshgrid(np.arange(W) + 0.5, np.arange(H) + 0.5)

def target(frame, name):
    \"\"\"Where a vector points: x_i + m, the previous screen position.\"\"\"
    cx, cy = centres(frame)
    mx, my = vec(frame, name)
    return cx + mx, cy + my

def off_screen(frame, px, py):
    H, W = frame["depth.Z"].shape
    return (px < 0) | (px >= W) | (py < 0) | (py >= H)

def lookup(layer, px, py):
    \"\"\"A previous frame's layer at the pixel that holds (px, py), the nearest-pixel read; NONE off screen.\"\"\"
    H, W = layer.shape
    xi, yi = np.floor(px).astype(int), np.floor(py).astype(int)
    inside = (xi >= 0) & (xi < W) & (yi >= 0) & (yi < H)
    return np.where(inside, layer[np.clip(yi, 0, H - 1), np.clip(xi, 0, W - 1)], NONE)

def box_mean(values, mask, r):
    \"\"\"The mean of values over the pixels of mask within (2r + 1)^2 pixels; NaN where none.\"\"\"
    H, W = values.shape
    v, m = np.pad(np.where(mask, values, 0.0), r), np.pad(mask.astype(float), r)
    total = sum(v[dy:dy + H, dx:dx + W] for dy in range(2 * r + 1) for dx in range(2 * r + 1))
    count = sum(m[dy:dy + H, dx:dx + W] for dy in range(2 * r + 1) for dx in range(2 * r + 1))
    return np.where(count > 0, total / np.maximum(count, 1), np.nan)

def field(ax, frame, name, mask, vmax, title):
    \"\"\"A vector's X component, red where content came from the left (m.x < 0), blue from the right.\"\"\"
    cmap = plt.get_cmap("RdBu").copy()
    cmap.set_bad("0.8")  # grey: no vector
    shown = ax.imshow(np.ma.masked_where(~mask, frame[name + ".X"]), cmap=cmap, vmin=-vmax, vmax=vmax)
    ax.set_title(title, fontsize=9)
    ax.axis("off")
    return shown

def arrows(ax, background, frame, name, mask, crop, step, title, cmap=None, color="yellow"):
    \"\"\"Arrows from pixel centres to x_i + m on a crop (y0, y1, x0, x1), every step pixels, where mask.\"\"\"
    H, W = frame["depth.Z"].shape
    y0, y1, x0, x1 = crop
    ax.imshow(background, cmap=cmap, extent=(0, W, H, 0))
    ys, xs = np.mgrid[y0:y1:step, x0:x1:step]
    keep = mask[ys, xs]
    mx, my = vec(frame, name)
    ax.quiver(xs[keep] + 0.5, ys[keep] + 0.5, mx[ys, xs][keep], my[ys, xs][keep], angles="xy", scale_units="xy",
              scale=1, color=color, width=0.006)
    ax.set_xlim(x0, x1); ax.set_ylim(y1, y0)
    ax.set_title(title, fontsize=9)
    ax.set_xticks([]); ax.set_yticks([])

fence_prev, fence, fence_index = last_two(FENCE)
fence_dump = read_exr(os.path.join(FENCE_DUMP, frame_files(FENCE_DUMP)[-1]))
glossy_prev, glossy, glossy_index = last_two(GLOSSY)
glossy_reseed = read_frame(os.path.join(GLOSSY_RESEED, frame_files(GLOSSY_RESEED)[-1]))
occ_prev, occ, occ_index = last_two(OCCLUSION)
H, W = fence["depth.Z"].shape
print(f"fence frame {fence_index}, glossy frame {glossy_index}, occlusion frame {occ_index}; {W}x{H} pixels")
assert frame_index(frame_files(GLOSSY_RESEED)[-1]) == glossy_index, "the reseeded glossy frame is another frame"
for f in (fence, glossy, occ):
    assert f["motion.shadow.valid"].dtype == np.uint32 and f["id.instance"].dtype == np.uint32"""),
    new_markdown_cell(r"""## 1. The shadow vector on the fence [TRMV21 Eq. 3, Sec. 4.1]

Under the fence the floor does not move: its surface motion is 0, and a filter that fetches along it blends the
slats' shadows of earlier frames into this one, so the shadows smear (the ghosting of [TRMV21 Fig. 8]). The
shadow vector follows the shadow instead (motion/shadow.h):

$$x^V_{i-1} = P_{i-1}\ \mathrm{intersect}\left[T^{-1} l_i \to T^{-1} b_i\ ;\ T^{-1}\,\mathrm{plane}(s_i)\right], \qquad m^V = x^V_{i-1} - x_i \quad \text{(Eq. 3)}$$

the line from the pixel's light sample $l_i$ through its blocker $b_i$, both carried back to the previous frame
with their own motion, meets the receiver's plane where the same shadow point was. It exists only where the
pixel's shadow ray was blocked: `motion.shadow.valid`. The lit pixels beside a shadow need it as much (their
history holds last frame's shadow), so the filter's splat gives every pixel the mean of the valid $m^V$ within
the shadow filter's window on the same receiving surface, and the surface motion where none landed [TRMV21
Sec. 4.1]. The window is the paper's 31x31 at 1080 rows, scaled to the frame's height (filters/trmv/footprint.h).

Below: the frame, its 1-spp visibility, then the X components (red: the content came from the left,
$m_x < 0$; grey: no vector) of the surface motion, of $m^V$ and of the splat, and the valid masks. The fence
moves right in this frame, so its shadows came from the left."""),
    new_code_cell("""floor = fence["id.instance"] == 0  # the floor; the back wall is instance 1, the slats and rails the rest
shadow_valid = fence["motion.shadow.valid"] == 1
splat_valid = fence_dump["filter.trmv.visibility.splat_landed"] == 1
fence["splat.X"], fence["splat.Y"] = fence_dump["filter.trmv.visibility.splat_x"], fence_dump["filter.trmv.visibility.splat_y"]
surface = fence["id.instance"] != NONE
vmax = max(1.0, np.abs(fence["motion.shadow.X"]).max())
show([display(colour(fence)), fence["direct.visibility"]],
     [f"fence, frame {fence_index}, 1 spp", "direct.visibility (1 spp: 0 or 1)"], cmap="gray")
fig, axes = plt.subplots(1, 3, figsize=(13, 2.8), constrained_layout=True)
field(axes[0], fence, "motion", surface, vmax, "surface motion m.x [Eq. 1]")
field(axes[1], fence, "motion.shadow", shadow_valid, vmax, "shadow vector m^V.x where valid [Eq. 3]")
shown = field(axes[2], fence, "splat", surface, vmax, "splat [Sec. 4.1] (surface motion where none landed)")
fig.colorbar(shown, ax=axes, shrink=0.8, label="pixels")
plt.show()
show([shadow_valid, splat_valid], ["motion.shadow.valid: the shadow ray was blocked",
                                   "splat_landed: a valid m^V of the same surface within the window"], cmap="gray")

m = np.hypot(*vec(fence, "motion"))
mv = np.hypot(*vec(fence, "motion.shadow"))
print(f"floor: largest |surface motion| {m[floor].max():.2g} px; {(shadow_valid & floor).sum()} floor pixels have a "
      f"shadow vector, median |m^V| {np.median(mv[shadow_valid & floor]):.2f} px; the splat reaches {(splat_valid & floor).sum()}")
# The checks: the floor is still, yet its shadows move, and the splat covers at least the pixels with m^V.
assert m[floor].max() < 0.01, "the fence's floor moves"
assert (shadow_valid & floor).sum() > 0.05 * floor.sum(), "almost no shadow vectors on the fence's floor"
assert np.median(mv[shadow_valid & floor]) > 1.0, "the shadows on the floor barely move"
assert not (shadow_valid & ~splat_valid).any(), "a pixel with m^V that the splat missed\""""),
    new_markdown_cell(r"""On a crop of the floor, the two vectors as arrows from the pixel centre to where they point (every second
pixel). The surface motion's arrows have length 0; the shadow vectors point left, to where the slat's
shadow was. Does the shadow vector find the same shadow? The path record names each pixel's blocker
(`path.blocker.instance`, one slat each), so the cell looks up which slat shadowed the pixel that $x_i + m^V$
falls in, in the previous frame, and compares it with the slat that shadows $x_i$ now."""),
    new_code_cell("""rows, cols = np.nonzero(shadow_valid & floor)
y0 = max(0, int(np.median(rows)) - H // 8); x0 = max(0, W // 2 - W // 8)
crop = (y0, min(H, y0 + H // 4), x0, min(W, x0 + W // 4))
fig, axes = plt.subplots(1, 2, figsize=(10, 3.6))
arrows(axes[0], fence["direct.visibility"], fence, "motion", surface, crop, 2, "surface motion (all 0 on the floor)", cmap="gray")
arrows(axes[1], fence["direct.visibility"], fence, "motion.shadow", shadow_valid, crop, 2, "shadow vector m^V", cmap="gray")
plt.show()

blocker = fence["path.blocker.instance"]
# The two rails run along x, across the image: their shadows look the same wherever they move, so leave them out.
width = lambda k: np.ptp(np.nonzero(fence["id.instance"] == k)[1]) if (fence["id.instance"] == k).any() else 0
rails = [k for k in np.unique(blocker[shadow_valid]) if width(k) > W // 2]
slats = shadow_valid & floor & ~np.isin(blocker, rails)
same = {}
for name in ("motion.shadow", "motion"):
    px, py = target(fence, name)
    same[name] = (lookup(fence_prev["path.blocker.instance"], px, py)[slats] == blocker[slats]).mean()
print(f"{slats.sum()} floor pixels in a slat's shadow: the same slat shadowed x_i + m^V in frame {fence_index - 1} "
      f"for {same['motion.shadow']:.0%} of them, x_i + m (the floor's own motion) for {same['motion']:.0%}")
# The check: the shadow vector finds the same slat's shadow far more often than the surface motion.
assert same["motion.shadow"] > 1.5 * same["motion"], same"""),
    new_markdown_cell(r"""Not every pixel finds its slat: the light is an area light and each pixel has one light sample, so the pixel
at $x_i + m^V$ sampled another point of the light last frame, and its shadow ray may have passed between the
slats or hit the next one. $m^V$ is the motion of *this* sample's shadow point.

## 2. One vector by hand: the shadow vector's validity and the splat

The shadow vector exists only where the pixel's shadow ray was blocked: `path.blocker.instance` is not
4294967295 (motion/shadow.h lists the other conditions, which rarely bite). The splat is a gather: a pixel's
splatted vector is the mean of the valid `motion.shadow` in its window (the shadow filter's: side 31 at 1080
rows, S H / 1080 here, the nearest odd side, at least 3) whose pixel shows the same instance (`id.instance`)
with a normal within 25.8 degrees (cosine 0.9), and its own surface motion where none is (filters/trmv/splat.h).
The cell computes it for one lit floor pixel beside a shadow, term by term, then for the whole frame with numpy,
and compares with the filter's dump."""),
    new_code_cell("""blocked = fence["path.blocker.instance"] != NONE
print(f"blocked shadow rays: {blocked.sum()}; valid shadow vectors: {shadow_valid.sum()}; "
      f"blocked without a vector: {(blocked & ~shadow_valid).sum()}")
assert not (shadow_valid & ~blocked).any(), "a shadow vector without a blocked shadow ray"

side = 2 * max(1, int(np.floor((31 * H / 1080 - 1) / 2 + 0.5))) + 1  # the splat's window (footprint.h)
r = side // 2
instance = fence["id.instance"]
normal = np.stack([fence["normal.X"], fence["normal.Y"], fence["normal.Z"]], axis=-1).astype(np.float32)
def same_surface(y, x, ys, xs):
    \"\"\"Pixels (ys, xs) on pixel (y, x)'s receiving surface: the same instance, normals within cosine 0.9.\"\"\"
    return (instance[ys, xs] == instance[y, x]) & ((normal[ys, xs] * normal[y, x]).sum(-1) >= np.float32(0.9))

def splat_pixel(x, y):
    \"\"\"The splat at (x, y), from the layers [TRMV21 Sec. 4.1]: (mean, how many landed).\"\"\"
    ys, xs = np.mgrid[max(0, y - r):min(H, y + r + 1), max(0, x - r):min(W, x + r + 1)]
    land = shadow_valid[ys, xs] & same_surface(y, x, ys, xs)
    if instance[y, x] == NONE or not land.any():
        return np.array([fence["motion.X"][y, x], fence["motion.Y"][y, x]]), 0
    return np.array([fence["motion.shadow.X"][ys, xs][land].mean(), fence["motion.shadow.Y"][ys, xs][land].mean()]), land.sum()

# One lit floor pixel that the splat reached: it has no m^V of its own.
candidates = np.argwhere(splat_valid & floor & ~shadow_valid)
y, x = candidates[len(candidates) // 2]
by_hand, landed = splat_pixel(x, y)
stored = np.array([fence["splat.X"][y, x], fence["splat.Y"][y, x]])
print(f"window {side}x{side} at {H} rows; pixel ({x}, {y}): visibility {fence['direct.visibility'][y, x]:.0f}, "
      f"no shadow vector of its own; {landed} valid m^V in its window on its surface")
print(f"  their mean {by_hand.round(4)}; the filter's splat {stored.round(4)}; surface motion "
      f"({fence['motion.X'][y, x]:.4f}, {fence['motion.Y'][y, x]:.4f})")
assert landed > 0 and np.allclose(by_hand, stored, atol=1e-4), (by_hand, stored)

# Every pixel: the same gather, side^2 shifted copies of the frame at once.
sum_x, sum_y, count = np.zeros((H, W)), np.zeros((H, W)), np.zeros((H, W))
pad = lambda a, v: np.pad(a, [(r, r), (r, r)] + [(0, 0)] * (a.ndim - 2), constant_values=v)
vx, vy, vv = pad(fence["motion.shadow.X"], 0), pad(fence["motion.shadow.Y"], 0), pad(shadow_valid, False)
vi, vn = pad(instance, NONE), pad(normal, 0)
for dy in range(side):
    for dx in range(side):
        qn = vn[dy:dy + H, dx:dx + W]
        land = vv[dy:dy + H, dx:dx + W] & (vi[dy:dy + H, dx:dx + W] == instance) & ((qn * normal).sum(-1) >= np.float32(0.9))
        sum_x += np.where(land, vx[dy:dy + H, dx:dx + W], 0); sum_y += np.where(land, vy[dy:dy + H, dx:dx + W], 0)
        count += land
landed_any = (count > 0) & (instance != NONE)
splat_x = np.where(landed_any, sum_x / np.maximum(count, 1), fence["motion.X"])
splat_y = np.where(landed_any, sum_y / np.maximum(count, 1), fence["motion.Y"])
error = max(np.abs(splat_x - fence["splat.X"])[instance != NONE].max(), np.abs(splat_y - fence["splat.Y"])[instance != NONE].max())
agree = (landed_any == splat_valid).mean()
print(f"the whole frame: splat by hand against the filter's, largest difference {error:.2g} px; "
      f"landed the same at {agree:.2%} of the pixels")
# A normal's dot product within a rounding of the cosine may land on one side and not the other.
assert error < 1e-3 and agree > 0.999, (error, agree)"""),
    new_markdown_cell(r"""## 3. The glossy vector on the glossy floor [TRMV21 Eq. 5]

The floor of `glossy` is a metal of roughness 0.15, and the camera orbits. A reflection moves with the
reflected object and the camera, not with the floor: history fetched along the floor's motion comes from
where the reflected box was not (the ghosts of [TRMV21 Fig. 11]). TRMV mirrors the pixel's secondary hit $h_i$
in the reflector's previous plane, projects that virtual image $v$ with the previous camera ($\mu$), and then
draws *one* sample of a Gaussian $\Sigma$ that stands for the glossy lobe's footprint (motion/glossy.h):

$$x^R_{i-1} = \mathrm{sample}\left(P_{i-1}\ \mathrm{mirror}\left[T^{-1} h_i,\ T^{-1}\,\mathrm{plane}(s_i)\right],\ \Sigma\right), \qquad m^R = x^R_{i-1} - x_i \quad \text{(Eq. 5)}$$

Below: the glossy indirect light, the surface motion's X, one draw $m^R$ per pixel, and the mean of $m^R$ over
9x9 floor pixels, which averages the draws towards $\mu$ (with $\mu$'s own variation over the window, and
what is left of the draws' noise). Where the floor's vector and the reflection's differ, the surface motion
fetches the wrong history. The camera orbits the room's centre: the near floor moves one way across the
image, the reflected room (its virtual image lies below the floor, far away) the other."""),
    new_code_cell("""metal = glossy["material.metallic"] == 1  # the floor: metallic 1, roughness 0.15 (scenes/README.md)
glossy_valid = glossy["motion.glossy.valid"] == 1
g_surface = glossy["id.instance"] != NONE
print(f"frame {glossy_index}: floor pixels {metal.sum()}, roughness {np.unique(glossy['material.roughness'][metal])}; "
      f"glossy vectors valid on {(glossy_valid & metal).sum()} of them, elsewhere on {(glossy_valid & ~metal).sum()}")
# The checks: the floor has glossy vectors almost everywhere, and only pixels whose BSDF ray hit something have one.
assert (glossy_valid & metal).sum() > 0.9 * metal.sum(), "few glossy vectors on the glossy floor"
assert not (glossy_valid & (glossy["path.secondary.instance"] == NONE)).any()

mean_x = box_mean(glossy["motion.glossy.X"], glossy_valid & metal, 4)
vmax = 2 * np.abs(glossy["motion.X"][g_surface]).max()
show([display(rgb(glossy, "indirect.glossy")), display(colour(glossy))],
     [f"indirect.glossy (demodulated), frame {glossy_index}", "1-spp colour"])
fig, axes = plt.subplots(1, 3, figsize=(13, 2.8), constrained_layout=True)
field(axes[0], glossy, "motion", g_surface, vmax, "surface motion m.x [Eq. 1]")
field(axes[1], glossy, "motion.glossy", glossy_valid, vmax, "glossy vector m^R.x: one draw [Eq. 5]")
shown = field(axes[2], {"mean.X": mean_x}, "mean", ~np.isnan(mean_x), vmax, "m^R.x, mean over 9x9 floor pixels")
fig.colorbar(shown, ax=axes, shrink=0.8, label="pixels (clipped)")
plt.show()
# The floor in three bands of rows, far to near: the mean of each vector's x there (and the mean's standard error:
# each m^R is one draw, so its mean is uncertain by the draws' spread / sqrt(pixels)).
on_floor = glossy_valid & metal
row = np.nonzero(on_floor)[0]
edges = np.percentile(row, [0, 100 / 3, 200 / 3, 100])
print(f"{'floor rows':14} {'pixels':>7} {'mean m.x':>9} {'mean m^R.x':>10}")
for band, (top, bottom) in enumerate(zip(edges[:-1], edges[1:])):
    rows_in = (np.arange(H)[:, None] >= top) & (np.arange(H)[:, None] <= bottom) & on_floor
    mr = glossy["motion.glossy.X"][rows_in]
    se = mr.std() / np.sqrt(mr.size)
    print(f"{int(top):3d}-{int(bottom):<3d} {['far', 'middle', 'near'][band]:6} {mr.size:7d} {glossy['motion.X'][rows_in].mean():+9.2f} "
          f"{mr.mean():+9.2f} +- {se:.2f}")
# The check: near the camera the reflection moves unlike the floor, by many standard errors.
assert abs(mr.mean() - glossy["motion.X"][rows_in].mean()) > 4 * se, "the near floor's reflections move with the floor\""""),
    new_markdown_cell(r"""**Its spread.** The footprint is wide: the lobe of roughness 0.15 spreads a reflection over many pixels, and
$m^R$ is one random draw from it with random numbers of its own (`kGlossyStream`, motion/glossy.h).
`RTDR_TRMV_GLOSSY_RESEED` is the same frame rendered with `--seed 1`: the same camera, the same surface
motion, another draw. Two independent draws differ by a vector of covariance $2\Sigma$, so
$\sqrt{\overline{|m^R_a - m^R_b|^2} / 2}$ estimates $\sqrt{\mathrm{trace}\,\Sigma}$. filters/trmv/README.md
gives "sqrt(trace Sigma) about 13 px at 160x90" on this floor (from tests/motion_glossy_test.cpp); the cell's
estimate is a root mean square over the whole floor, and the spread varies across it (exercise 3)."""),
    new_code_cell("""assert np.array_equal(glossy["motion.X"], glossy_reseed["motion.X"]), "the surface motion depends on the seed"
both = glossy_valid & (glossy_reseed["motion.glossy.valid"] == 1) & metal
jump = np.hypot(glossy["motion.glossy.X"] - glossy_reseed["motion.glossy.X"], glossy["motion.glossy.Y"] - glossy_reseed["motion.glossy.Y"])
spread = np.sqrt((jump[both] ** 2).mean() / 2)
print(f"two draws of frame {glossy_index} (seeds 0 and 1), {both.sum()} floor pixels: they differ by "
      f"{np.median(jump[both]):.1f} px (median), {np.percentile(jump[both], 90):.1f} px (90th percentile); "
      f"sqrt(trace Sigma) estimated {spread:.1f} px at {W}x{H}")
# The check: the draw is random, the footprint many pixels wide.
assert np.median(jump[both]) > 1.0, "the glossy vector barely changes with the seed"

crop = (H // 2, min(H, H // 2 + H // 3), W // 8, W // 8 + H // 3)
fig, axes = plt.subplots(1, 3, figsize=(14, 3.8))
background = display(colour(glossy))
arrows(axes[0], background, glossy, "motion", metal, crop, 4, "surface motion")
arrows(axes[1], background, glossy, "motion.glossy", glossy_valid, crop, 4, "glossy vector, seed 0")
arrows(axes[2], background, glossy_reseed, "motion.glossy", glossy_reseed["motion.glossy.valid"] == 1, crop, 4,
       "glossy vector, seed 1")
plt.show()
fig, ax = plt.subplots(figsize=(6, 2.6))
ax.hist(jump[both], bins=60, color="tab:purple")
ax.set_xlabel("|m^R(seed 0) - m^R(seed 1)|, pixels"); ax.set_ylabel("floor pixels")
plt.show()"""),
    new_markdown_cell(r"""## 4. The dual vector on the occlusion scene [TRMV21 Eq. 6]

The camera is still, the wall is still, the boxes slide: the orange one to the right, the blue cube to the
left. A wall pixel just uncovered by a box was hidden in the previous frame: its surface motion $m$ (0 here)
points at $y = x_i + m$, which in frame $i - 1$ showed the box. TRMV looks elsewhere (motion/dual.h):

$$x^O_{i-1} = y + (x_i - z), \qquad y = x_i + m, \qquad z = \text{the occluder's point at } y \text{, carried to frame } i$$

$z - y$ is the occluder's screen motion $v$, so $x^O = y - v$: from the pixel, step back by what the box did,
against its motion, beside it, onto whatever stood there last frame. `motion.dual.valid` marks the
disoccluded pixels (the pixel's point lay more than 1 % behind what the previous frame showed at $y$); elsewhere
`motion.dual` is the surface motion, bit for bit.

Below: the 1-spp frame (lit by bounced light only, so mostly noise), the albedo of the frame before and of this
one, the disoccluded pixels, and on a crop at the orange box's trailing edge the albedo of both frames, with the
pixel centres $x_i$ (= $y$, the wall is still) and the arrows to $x^O$."""),
    new_code_cell("""dual_valid = occ["motion.dual.valid"] == 1
ids = occ["id.instance"]
moving = [k for k in np.unique(ids[ids != NONE]) if np.abs(occ["motion.X"][ids == k]).mean() > 0.1]  # the boxes
print(f"frame {occ_index}: {dual_valid.sum()} disoccluded pixels; the moving instances {moving}, "
      + ", ".join(f"{k}: m.x {occ['motion.X'][ids == k].mean():+.2f} px" for k in moving))
show([display(colour(occ)), rgb(occ_prev, "albedo"), rgb(occ, "albedo"), dual_valid],
     [f"1-spp colour, frame {occ_index} (bounced light only)", f"albedo, frame {occ_index - 1}",
      f"albedo, frame {occ_index}", "motion.dual.valid"], cmap="gray")

ys, xs = np.nonzero(dual_valid)
px, py = (a[dual_valid] for a in target(occ, "motion"))       # y = x_i + m
ox, oy = (a[dual_valid] for a in target(occ, "motion.dual"))  # x^O
occluder = lookup(occ_prev["id.instance"], px, py)   # what frame i-1 showed at y
at_xo = lookup(occ_prev["id.instance"], ox, oy)      # what it showed at x^O
print(f"frame {occ_index - 1} at y (nearest pixel): " + ", ".join(f"instance {k}: {(occluder == k).sum()}" for k in np.unique(occluder)))
print(f"frame {occ_index - 1} at x^O (nearest pixel): {(at_xo != occluder).sum()} of {len(at_xo)} off the box that "
      f"uncovered them; {(at_xo == occluder).sum()} on its edge pixel")
# The checks: disoccluded pixels exist; y lands on a box; x^O - y is that box's own motion m.x (v = -m: x^O steps back).
assert dual_valid.sum() > 0, "no disoccluded pixels on occlusion"
assert np.isin(occluder, moving).all(), "a disoccluded pixel whose y is not on a box"
box_motion = np.array([occ["motion.X"][ids == k].mean() for k in occluder])
step = occ["motion.dual.X"][dual_valid] - occ["motion.X"][dual_valid]
assert (np.sign(step) == np.sign(box_motion)).all() and np.allclose(step, box_motion, rtol=0.25), (step, box_motion)
assert (at_xo != occluder).mean() > 0.5, "x^O lands on the box that uncovered the pixel"

orange = moving[int(np.argmin([occ["motion.X"][ids == k].mean() for k in moving]))]  # moves right: m.x < 0
rows, cols = ys[occluder == orange], xs[occluder == orange]
size = max(12, H // 6)
cy0, cx0 = max(0, int(rows.mean()) - size // 2), max(0, int(cols.mean()) - size // 2)
crop = (cy0, min(H, cy0 + size), cx0, min(W, cx0 + size))
fig, axes = plt.subplots(1, 2, figsize=(10, 4.4))
for ax, frame, title in ((axes[0], occ_prev, f"frame {occ_index - 1}: y (dots) on the box, arrows to x^O beside it"),
                         (axes[1], occ, f"frame {occ_index}: the same pixels, uncovered")):
    ax.imshow(rgb(frame, "albedo"), extent=(0, W, H, 0))
    ax.plot(px, py, "o", ms=3, color="cyan")
    ax.set_xlim(crop[2], crop[3]); ax.set_ylim(crop[1], crop[0]); ax.set_title(title, fontsize=9)
axes[0].quiver(xs + 0.5, ys + 0.5, occ["motion.dual.X"][dual_valid], occ["motion.dual.Y"][dual_valid], angles="xy",
               scale_units="xy", scale=1, color="yellow", width=0.006)
plt.show()"""),
    new_markdown_cell(r"""$x^O$ lies one box step behind the box's trailing edge, a pixel or two at these sizes, so the nearest pixel of
$x^O$ is sometimes the box's own edge pixel: a pixel is the box's when its *centre* is covered, and $x^O$ can
fall on the covered side of a pixel whose centre the box's edge just reaches.
(tests/motion_dual_test.cpp checks $x^O$ against the box's exact edge, at 1/8 pixel.)

**By hand, one pixel.** $y = x_i + m$; the occluder is the box frame $i - 1$ shows at $y$; where that box point
is now, $z = y + v$, the current frame's `motion` of the box there is $-v$ (a translating box moves all its
points alike); so $x^O = y - v$. The cell does this for one disoccluded pixel, prints each term, then does it
for all of them, and checks that `motion.dual` equals `motion` wherever `motion.dual.valid` is 0."""),
    new_code_cell("""def dual_by_hand(x, y):
    \"\"\"x^O_{i-1} of pixel (x, y) from the layers of occlusion's two frames [TRMV21 Eq. 6].\"\"\"
    x_i = np.array([x + 0.5, y + 0.5])
    m = np.array([occ["motion.X"][y, x], occ["motion.Y"][y, x]])
    y_ = x_i + m
    box = occ_prev["id.instance"][int(y_[1]), int(y_[0])]               # the occluder at y, frame i-1
    v = -np.array([occ["motion.X"][ids == box].mean(), occ["motion.Y"][ids == box].mean()])  # its step, roughly
    z = y_ + v                                                          # where its point at y is now
    if ids[int(z[1]), int(z[0])] == box:                                # its motion there, exactly
        v = -np.array([occ["motion.X"][int(z[1]), int(z[0])], occ["motion.Y"][int(z[1]), int(z[0])]])
    return x_i, m, y_, box, v, y_ - v

x, y = xs[len(xs) // 2], ys[len(ys) // 2]
x_i, m, y_, box, v, x_o = dual_by_hand(x, y)
stored = x_i + np.array([occ["motion.dual.X"][y, x], occ["motion.dual.Y"][y, x]])
print(f"pixel ({x}, {y}): x_i = {x_i}, m = {m.round(4)}, y = x_i + m = {y_.round(3)}")
print(f"  frame {occ_index - 1} shows instance {box} at y; its step v = z - y = {v.round(3)}")
print(f"  x^O = y - v = {x_o.round(3)}; x_i + motion.dual = {stored.round(3)}")
errors = np.array([np.abs(dual_by_hand(x, y)[-1] - np.array([x + 0.5 + occ["motion.dual.X"][y, x],
                                                            y + 0.5 + occ["motion.dual.Y"][y, x]])).max()
                   for y, x in zip(ys, xs)])
print(f"all {len(errors)} disoccluded pixels: largest |x^O by hand - x_i - motion.dual| {errors.max():.3f} px")
assert errors.max() < 0.1, errors.max()

changed = (occ["motion.dual.X"] != occ["motion.X"]) | (occ["motion.dual.Y"] != occ["motion.Y"])
print(f"motion.dual differs from motion at {changed.sum()} pixels, {(changed & ~dual_valid).sum()} of them not disoccluded")
for f in (fence, glossy, occ):  # on every scene: the dual vector is the surface motion, bit for bit, where not valid
    differs = (f["motion.dual.X"] != f["motion.X"]) | (f["motion.dual.Y"] != f["motion.Y"])
    assert not (differs & (f["motion.dual.valid"] == 0)).any(), "motion.dual differs from motion at a valid-0 pixel\""""),
    new_markdown_cell(r"""## 5. Where each one fails

Each vector follows one effect, under assumptions. The paper names its failures [TRMV21 Sec. 6, 7, Fig. 14, 15];
the project's docs say which ones ours keep. Each paragraph quotes a file and, where the frames can show it,
computes the evidence.

### The shadow vector: one light sample, and only blocked rays

- "One light sample per pixel gives one m^V, from that sample's light (TRMV21 Sec. 6: several moving lights
  are a stated failure)" (motion/shadow.h). A pixel under two lights holds the vector of whichever it sampled;
  were both lights moving, neighbours would follow different shadows and the splat would average them. `glossy`
  has two lights (a ceiling panel and a strip by the back wall): the cell counts which one each shadow vector
  follows, and how many have a neighbour that follows the other.
- "Only pixels whose shadow ray was blocked have m^V; filters/trmv/splat.h spreads it" (motion/shadow.h). In a
  penumbra the 1-spp ray is blocked at random, and a lit pixel the shadow has just left has none: on the fence,
  the splat gives it its neighbours' mean. The splat's own limit: its window, the shadow filter's (31x31 at 1080
  rows, scaled to the frame): a shadow edge that moves farther than half of it in a frame leaves lit pixels
  that no vector reaches (filters/trmv/splat.h)."""),
    new_code_cell("""lights = glossy["path.light.instance"]
g_shadow = glossy["motion.shadow.valid"] == 1
print(f"glossy, frame {glossy_index}: {g_shadow.sum()} shadow vectors; by the light they follow: "
      + ", ".join(f"instance {k}: {(lights[g_shadow] == k).sum()}" for k in np.unique(lights[g_shadow])))
other = np.zeros((H, W), bool)
padded_light, padded_valid = np.pad(lights, 1, constant_values=NONE), np.pad(g_shadow, 1)
for dy in range(3):
    for dx in range(3):
        other |= padded_valid[dy:dy + H, dx:dx + W] & (padded_light[dy:dy + H, dx:dx + W] != lights)
print(f"  {(other & g_shadow).sum()} of them have a 3x3 neighbour whose vector follows the other light")
show([np.where(g_shadow, lights.astype(float), np.nan)], ["the light each shadow vector follows (glossy)"], cmap="coolwarm")
assert len(np.unique(lights[lights != NONE])) >= 2, "glossy should have two lights"

lit_reached = floor & fence["direct.visibility"].astype(bool) & splat_valid
print(f"fence: of the {(splat_valid & floor).sum()} floor pixels the splat reaches, {(shadow_valid & floor).sum()} have "
      f"an m^V of their own; {lit_reached.sum()} are lit this frame and move with the shadow only through the splat")"""),
    new_markdown_cell(r"""### The glossy vector: curved reflectors, and a new draw every frame

- "Curved reflectors are the paper's stated failure [TRMV21 Sec. 7, Fig. 14]: the tangent plane at s_i stands in
  for the mirror, with no special handling" (motion/glossy.h). The shipped scenes have no curved reflector, so
  there is nothing to measure here.
- The draw. Each frame draws $m^R$ anew, so even where nothing changes the history is fetched from a different
  place of the footprint every frame. filters/trmv/README.md measures it on this scene at 320x180 (its Fig. 11
  table): with the glossy vector the temporal error is higher and SSIM lower than with the surface motion, with
  the clamp and far more without it, where nothing bounds the scattered fetches; against that, the stability
  table there shows a gain on the floor's structured error of under a per cent. The cell compares, at each floor pixel, this frame's vector with the
  previous frame's: the surface motion changes by a fraction of a pixel, the glossy vector jumps."""),
    new_code_cell("""steady = metal & (glossy_prev["material.metallic"] == 1) & glossy_valid & (glossy_prev["motion.glossy.valid"] == 1)
change = {name: np.hypot(glossy[name + ".X"] - glossy_prev[name + ".X"], glossy[name + ".Y"] - glossy_prev[name + ".Y"])[steady]
          for name in ("motion", "motion.glossy")}
print(f"floor pixels, frame {glossy_index - 1} -> {glossy_index}: the surface motion changes by "
      f"{np.median(change['motion']):.3f} px (median), the glossy vector by {np.median(change['motion.glossy']):.1f} px")
assert np.median(change["motion.glossy"]) > 10 * np.median(change["motion"])"""),
    new_markdown_cell(r"""### The dual vector: repeated content, and nothing to fix at the leading side

- $x^O$ copies what stood beside the box: "Copying history from there repeats that surface's look ("the bunny
  will simply be repeated", Fig. 6), which the cones of Sec. 4.3 soften (filters/trmv/cones.h)"
  (motion/dual.h). The cones re-shade the borrowed history for the pixel's own normal; they pay only where
  $x^O$ lands on a surface that faces elsewhere. filters/trmv/README.md, "The paper's Fig. 12 on our occlusion
  scene (dual vector, cones)": "Behind a translating box x^O lands on the same flat wall as the pixel, where the
  colour at x^O is already the right history", so there the cones cost noise (the band RMSE with the cones
  and with the colour at x^O, in that README's stability table). The cell counts where $x^O$ lands on the pixel's own surface, or on another
  one that faces the same way. In the frames we tried (frame 40 at 160x90 and 320x180) every $x^O$ did, but for
  the nearest-pixel reads onto the box's edge pixel of section 4: nothing for the cones to fix.
- Only the trailing side. A box uncovers the wall behind it and covers the wall ahead of it: every disoccluded
  pixel is on its trailing side. Ahead of it nothing is disoccluded, so the dual vector is the surface motion
  there; what changes there is the light the box brings to the wall, which no vector follows (the ghosting
  under a sudden local change of irradiance, [TRMV21 Fig. 15])."""),
    new_code_cell("""normal = np.stack([occ[f"normal.{c}"] for c in "XYZ"], axis=-1)[dual_valid]
prev_normal = np.stack([lookup(occ_prev[f"normal.{c}"], ox, oy) for c in "XYZ"], axis=-1)
own = lookup(occ_prev["id.instance"], ox, oy) == ids[dual_valid]
facing = (normal * prev_normal).sum(-1) > 0.99
edge = at_xo == occluder  # the nearest-pixel read onto the box's own edge pixel (section 4)
print(f"{len(own)} disoccluded pixels: x^O on the pixel's own surface for {own.sum()}, on another surface facing the "
      f"same way for {(facing & ~own).sum()}, on one facing elsewhere (the cones' case, Fig. 6) for {(~facing).sum()}, "
      f"{(~facing & edge).sum()} of which read the box's own edge pixel")

trailing = {}
for k in moving:
    mine = occluder == k
    centre = np.nonzero(ids == k)[1].mean() + 0.5  # the box's mean x now
    # The box's motion m.x < 0: it moved right, its trailing side is on the left (x < centre); m.x > 0 the reverse.
    behind = np.sign(xs[mine] + 0.5 - centre) == np.sign(occ["motion.X"][ids == k].mean())
    trailing[k] = (behind.sum(), (~behind).sum())
    print(f"box {k}: {behind.sum()} disoccluded pixels on its trailing side, {(~behind).sum()} on its leading side")
assert all(lead == 0 for _, lead in trailing.values()), trailing"""),
    new_markdown_cell(r"""### All four: vectors that point off screen

A vector that points outside the previous image has no history to fetch. The paper does not handle it
([TRMV21 Fig. 15]); filters/trmv/README.md, "Deviations and choices": "Where no history is found, alpha = 1
and cbar_i = c~_i", among others for "x_{i-1} off the previous image (the paper does not handle off-screen
vectors, its Fig. 15c)". The pixel then starts afresh from its spatially filtered value. An orbiting camera
pushes surface points out at one border; the glossy vector's wide draws leave the image more often still."""),
    new_code_cell("""print(f"{'scene':10} {'vector':22} {'valid':>7} {'off screen':>11}")
counts = {}
for scene, frame in (("fence", fence), ("glossy", glossy), ("occlusion", occ)):
    for name, valid in (("motion", frame["id.instance"] != NONE), ("motion.shadow", frame["motion.shadow.valid"] == 1),
                        ("motion.glossy", frame["motion.glossy.valid"] == 1), ("motion.dual", frame["motion.dual.valid"] == 1)):
        off = off_screen(frame, *target(frame, name)) & valid
        counts[scene, name] = (valid.sum(), off.sum())
        print(f"{scene:10} {name:22} {valid.sum():7d} {off.sum():7d} ({off.sum() / max(valid.sum(), 1):.1%})")
glossy_off = off_screen(glossy, *target(glossy, "motion.glossy")) & glossy_valid
show([np.where(g_surface, off_screen(glossy, *target(glossy, "motion")), np.nan), np.where(glossy_valid, glossy_off, np.nan)],
     ["glossy: surface motion off screen (yellow)", "glossy: glossy vector off screen (yellow)"])
# The check: the orbiting camera pushes some surface points out of the previous image.
assert counts["glossy", "motion"][1] > 0"""),
    new_markdown_cell(r"""## Exercise

1. In section 1, about half of the slat-shadowed pixels found their slat at $x_i + m^V$. Render the fence's two
   frames with `--spp 16` and look up the previous `direct.visibility` (now a fraction) at $x_i + m^V$ and at
   $x_i + m$. Which vector lands in the darker place? Why can't a 1-spp $m^V$ do better than the sample it
   was made from?
2. The splat averages the valid $m^V$ of the shadow filter's window (`side` in section 2). Near the camera the
   fence's shadows move the most: find the largest $|m^V|$ on the floor. For what speed would that window stop
   covering a shadow's edge, and at which frame height would the fence's shadows outrun it?
3. Section 3 estimated $\sqrt{\mathrm{trace}\,\Sigma}$ over the whole floor. Where on the floor is the spread
   widest, and why (think of the distance $d = |v - s^C|$ and the incidence angle in motion/glossy.h)?
   Render the glossy scene at twice the size: how does the spread in pixels change?
4. Section 4 found every disoccluded pixel on a box's trailing side, and $x^O$ on the wall. Render the frames
   where the blue cube passes in front of the orange box (around frame 45) and look where $x^O$ lands for the
   pixels of the orange box that the cube uncovers: on what, and with which normal?
5. Render a dozen fence frames and filter them with `rtdr filter --method trmv --trmv-motion 0` (every history
   along the surface motion) and with `--trmv-motion 1` (the visibility along the splatted shadow vector),
   both with `--dump-passes` (filters/trmv/README.md, "The method `trmv`"). Compare
   `filter.trmv.visibility.temporal` on the floor: where do the slats' shadows smear?"""),
]
