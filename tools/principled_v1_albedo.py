#!/usr/bin/python3
"""Directional albedo of three diffuse BRDFs at roughness 1, and the closed furnace each predicts: the numbers
behind trace/README.md, "Differences from Cycles".

    /usr/bin/python3 tools/principled_v1_albedo.py [BASE] [ROUGHNESS]      (defaults 0.5 and 1; numpy only, ~30 s)
    /usr/bin/python3 tools/principled_v1_albedo.py --room SCENE.gltf DIR    (DIR: tools/compare_cycles.sh's output folder)

The three BRDFs, metallic 0, specular 0.5:
(a) Blender 3.4 Cycles' Principled BSDF (v1): two closures added with no energy coupling,
      f = base/pi [(1 - FL/2)(1 - FV/2) + RR (FL + FV + FL FV (RR - 1))]        principled diffuse, FULL
        + F(l.h) D(h) G1(v) G1(l) / (4 n.v n.l)                                    GGX, single scattering
    FL = (1 - n.l)^5, FV = (1 - n.v)^5, RR = roughness (1 + l.v) = 2 roughness (l.h)^2: the split form of
    Burley 2015 ("Extending the Disney BRDF to a BSDF with Integrated Subsurface Scattering", Sec. 2.3) as
    intern/cycles/kernel/closure/bsdf_principled_diffuse.h (Blender 3.x) evaluates it: a Lambert-like part,
    darker at grazing angles, plus a retro-reflection that grows with roughness. The GGX closure
    (intern/cycles/kernel/svm/svm_closure.h, intern/cycles/kernel/closure/bsdf_microfacet.h) has
    alpha = roughness^2, the uncorrelated Smith G1(v) G1(l), and Fresnel interpolate_fresnel_color with cspec0 = 0.08 specular = 0.04 at
    ior = 2 / (1 - sqrt(0.08 specular)) - 1 = 1.5, which reduces to the exact dielectric Fresnel of ior 1.5.
    The glTF importer chooses the "GGX" distribution, which is single scattering (Multiscatter GGX is not used).
(b) RTDR's glTF dielectric (trace/brdf.h): the GGX lobe with Schlick's Fresnel F0 = 0.04 and the
    height-correlated G2, plus the albedo-scaled Lambert base/pi (1 - E_spec(n.v)) (1 - E_spec(n.l)) / (1 - E_avg),
    so its directional albedo is base + (1 - base) E_spec(n.v). E_spec is computed here by the same quadrature
    and compared with trace/ggx_albedo_table.h.
(c) Lambert, Cycles' Diffuse BSDF of roughness 0 and glTF's diffuse lobe: albedo = base.

Directional albedo A(mu_v) = int f(v, l) n.l d(omega_l), by Gauss-Legendre in n.l (256 nodes) times the
midpoint rule in azimuth (256 over [0, pi], the BRDFs are symmetric in it).

The furnace: a camera at the centre of a closed sphere whose inside is the material with emission LE (0.5).
A chord of a sphere meets it at the same angle at both ends, so the radiance leaving the wall at angle
mu = n.omega is the same function L(mu) everywhere, and
    L(mu_v) = LE + int f(v, l) L(n.l) n.l d(omega_l),
a one-dimensional integral equation; it is solved by the Nystrom method on the Gauss-Legendre nodes, summed
over BOUNCES (64) bounces as Cycles' max_bounces counts them, and the camera sees L(1) (every pixel's ray
leaves the centre and meets the wall head-on). Lambert: L = LE / (1 - base) = 1 exactly at base 0.5.
tools/cycles_furnace_blender.py renders that furnace in Cycles to check (a).

--room estimates, from the albedos alone, how much brighter Cycles' Principled render of a scene is than its
Lambert render (both from tools/compare_cycles.sh, DIR/cycles_principled.exr and DIR/cycles_lambert.exr), over
the pixels that are not emitters or next to one: each pixel of the Lambert render scaled by A_PV1(n.v) / base per
channel at its first hit (n and position from RTDR's layers in DIR/rtdr, the camera from SCENE.gltf, base from
RTDR's albedo layer). It assumes uniform incident light and ignores the later vertices, which Principled v1
brightens too, so it falls short of the measured ratio by about what the second vertex adds.
"""
import os
import re
import sys

import numpy as np

LE = 0.5            # the furnace wall's emitted radiance
BOUNCES = 64        # Cycles' max_bounces in tools/cycles_furnace_blender.py
N_MU, N_PHI = 256, 256
HERE = os.path.dirname(os.path.abspath(__file__))

# Quadrature over the hemisphere of l: nodes mu_l (Gauss-Legendre on [0, 1]) x phi (midpoint on [0, pi]), weights
# for int ... dmu_l dphi over the full circle (x 2 for the symmetry in phi).
x, w = np.polynomial.legendre.leggauss(N_MU)
MU_L, W_MU = 0.5 * (x + 1.0), 0.5 * w
PHI = (np.arange(N_PHI) + 0.5) * np.pi / N_PHI
W_PHI = np.pi / N_PHI


def directions(mu_v):
    """v and the grid of l in the frame n = z, v in the xz plane; returns n.l, l.v, n.h, l.h on the grid."""
    sin_v = np.sqrt(max(0.0, 1.0 - mu_v * mu_v))
    mu_l = MU_L[:, None]
    sin_l = np.sqrt(1.0 - mu_l * mu_l)
    l_dot_v = sin_v * sin_l * np.cos(PHI)[None, :] + mu_v * mu_l
    h_len = np.sqrt(np.maximum(2.0 + 2.0 * l_dot_v, 1e-12))       # |l + v|
    n_dot_h = (mu_l + mu_v) / h_len
    l_dot_h = (1.0 + l_dot_v) / h_len
    return np.broadcast_to(mu_l, l_dot_v.shape), l_dot_v, n_dot_h, l_dot_h


def ggx_d(n_dot_h, alpha):
    """GGX (Trowbridge-Reitz) normal distribution D(h) (Walter et al. 2007, Eq. 33)."""
    a2 = alpha * alpha
    c2 = n_dot_h * n_dot_h
    return a2 / (np.pi * (c2 * (a2 - 1.0) + 1.0) ** 2)


def smith_lambda(mu, alpha):
    """Smith's Lambda for GGX (Heitz 2014, Eq. 72); G1 = 1 / (1 + Lambda)."""
    tan2 = (1.0 - mu * mu) / np.maximum(mu * mu, 1e-12)
    return 0.5 * (np.sqrt(1.0 + alpha * alpha * tan2) - 1.0)


def fresnel_dielectric(cos_i, eta):
    """Exact unpolarised Fresnel reflectance of a dielectric of relative ior eta (Cycles' fresnel_dielectric_cos)."""
    c = np.abs(cos_i)
    g = eta * eta - 1.0 + c * c
    g = np.sqrt(np.maximum(g, 0.0))
    a = (g - c) / (g + c)
    b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0)
    return 0.5 * a * a * (1.0 + b * b)


def principled_v1(mu_v, base, roughness, specular=0.5):
    """(diffuse, specular) parts of Cycles 3.4's Principled v1 BRDF f on the grid of l, metallic 0."""
    mu_l, l_dot_v, n_dot_h, l_dot_h = directions(mu_v)
    fl, fv = (1.0 - mu_l) ** 5, (1.0 - mu_v) ** 5
    rr = roughness * (1.0 + l_dot_v)                                   # = 2 roughness (l.h)^2
    diffuse = base / np.pi * ((1.0 - 0.5 * fl) * (1.0 - 0.5 * fv) + rr * (fl + fv + fl * fv * (rr - 1.0)))
    alpha = roughness * roughness
    ior = 2.0 / (1.0 - np.sqrt(0.08 * specular)) - 1.0                 # 1.5 at specular 0.5: F0 = 0.04
    g = 1.0 / ((1.0 + smith_lambda(mu_v, alpha)) * (1.0 + smith_lambda(mu_l, alpha)))   # G1(v) G1(l)
    spec = fresnel_dielectric(l_dot_h, ior) * ggx_d(n_dot_h, alpha) * g / (4.0 * mu_v * mu_l)
    return diffuse, spec


def rtdr_specular(mu_v, roughness):
    """RTDR's dielectric GGX lobe on the grid of l (trace/brdf.h): Schlick F0 = 0.04, height-correlated G2."""
    mu_l, _, n_dot_h, l_dot_h = directions(mu_v)
    alpha = max(1e-3, roughness * roughness)
    f = 0.04 + 0.96 * (1.0 - l_dot_h) ** 5
    g2 = 1.0 / (1.0 + smith_lambda(mu_v, alpha) + smith_lambda(mu_l, alpha))
    return f * ggx_d(n_dot_h, alpha) * g2 / (4.0 * mu_v * mu_l)


def integrate(f):
    """int f n.l d(omega_l) over the hemisphere, f on the grid of l."""
    return 2.0 * W_PHI * np.sum(W_MU[:, None] * MU_L[:, None] * f)


def e_spec(mu_v, roughness):
    return integrate(rtdr_specular(mu_v, roughness))


def e_spec_table(mu_v, roughness):
    """E_spec from trace/ggx_albedo_table.h, bilinear in (roughness, sqrt(mu)) as trace/brdf.cpp reads it."""
    text = open(os.path.join(HERE, "..", "trace", "ggx_albedo_table.h"), encoding="utf-8").read()
    body = text[text.index("kSpecularAlbedo"):]
    rows = [np.array([float(v) for v in re.findall(r"[-0-9.e]+(?=f)", r)]) for r in re.findall(r"\{([^{}]*)\}", body)]
    table = np.array(rows[:32])
    ri = roughness * (table.shape[0] - 1)
    r0 = min(int(ri), table.shape[0] - 2)
    s = np.sqrt(mu_v) * (table.shape[1] - 1)
    j0 = min(int(s), table.shape[1] - 2)
    tr, ts = ri - r0, s - j0
    row = (1 - tr) * table[r0] + tr * table[r0 + 1]
    return (1 - ts) * row[j0] + ts * row[j0 + 1]


def e_avg(roughness):
    return 2.0 * np.sum(W_MU * MU_L * np.array([e_spec(m, roughness) for m in MU_L]))


def furnace(brdf_of_mu_v):
    """L(1) of the sphere furnace for a BRDF given as mu_v -> f on the grid of l (docstring above)."""
    # Kernel K[i, j] = w_j mu_j int f(mu_i, mu_j, phi) dphi, on the Gauss-Legendre nodes; row "head" at mu_v = 1.
    def row(mu_v):
        return 2.0 * W_PHI * W_MU * MU_L * brdf_of_mu_v(mu_v).sum(axis=1)
    k = np.array([row(m) for m in MU_L])
    head = row(1.0)
    radiance = np.full(N_MU, LE)        # bounce 0: emission
    total = radiance.copy()
    for _ in range(BOUNCES - 1):        # the camera's hit adds one more bounce below: BOUNCES in all
        radiance = k @ radiance
        total += radiance
    infinite = np.linalg.solve(np.eye(N_MU) - k, np.full(N_MU, LE))
    return LE + head @ total, LE + head @ infinite


def room_estimate(scene_path, out_dir):
    import json

    import OpenImageIO as oiio

    def read(path):
        image = oiio.ImageInput.open(path)
        names, pixels = list(image.spec().channelnames), np.asarray(image.read_image(format="float"))
        image.close()
        return names, pixels

    def layer(names, pixels, prefix, channels="RGB"):
        return np.stack([pixels[:, :, names.index(prefix + c)] for c in channels], axis=2)

    with open(scene_path, encoding="utf-8") as f:
        camera = np.array(next(n for n in json.load(f)["nodes"] if "camera" in n).get("translation", (0, 0, 0)))
    names, pixels = read(os.path.join(out_dir, "rtdr", "frame_0000.exr"))
    emitter = layer(names, pixels, "emission.").sum(axis=2) > 0
    near = emitter.copy()
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            near |= np.roll(emitter, (dy, dx), axis=(0, 1))
    keep = ~near
    position, normal = layer(names, pixels, "position.", "XYZ"), layer(names, pixels, "normal.", "XYZ")
    base = layer(names, pixels, "albedo.")
    view = camera - position
    mu_v = np.clip(np.abs(np.sum(normal * view, axis=2)) / np.linalg.norm(view, axis=2), 1e-4, 1.0)
    # A_PV1(mu) = base A_diffuse(mu) / 1 + A_spec(mu): the diffuse closure is linear in base; tabulated in mu.
    grid = np.linspace(1e-4, 1.0, 65)
    a_diffuse = np.array([integrate(principled_v1(m, 1.0, 1.0)[0]) for m in grid])
    a_spec = np.array([integrate(principled_v1(m, 1.0, 1.0)[1]) for m in grid])
    gain = np.interp(mu_v, grid, a_diffuse)[..., None] + np.interp(mu_v, grid, a_spec)[..., None] / np.maximum(base, 1e-3)
    lambert = read(os.path.join(out_dir, "cycles_lambert.exr"))[1][:, :, :3]
    principled = read(os.path.join(out_dir, "cycles_principled.exr"))[1][:, :, :3]
    print("pixels not emitters nor next to one: %d of %d" % (keep.sum(), keep.size))
    print("Cycles Lambert / Principled, measured:             %.4f %.4f %.4f" % tuple(
        lambert[keep].mean(axis=0) / principled[keep].mean(axis=0)))
    print("  estimated from A_PV1 / base at the first hit:    %.4f %.4f %.4f" % tuple(
        lambert[keep].mean(axis=0) / (lambert * gain)[keep].mean(axis=0)))
    print("whole image, measured:                             %.4f %.4f %.4f" % tuple(
        lambert.mean(axis=(0, 1)) / principled.mean(axis=(0, 1))))


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--room":
        room_estimate(sys.argv[2], sys.argv[3])
        return
    base = float(sys.argv[1]) if len(sys.argv) > 1 else 0.5
    roughness = float(sys.argv[2]) if len(sys.argv) > 2 else 1.0
    print("directional albedo, base %.3g, roughness %.3g, metallic 0, specular 0.5 (F0 = 0.04)" % (base, roughness))
    print("%8s %9s %9s %9s %9s | %9s %9s %9s | %7s" % ("theta_v", "PV1", "PV1 diff", "PV1 spec", "PV1/RTDR",
                                                        "RTDR", "E_spec", "table", "Lambert"))
    for theta in (0, 30, 45, 60, 75, 80, 85, 89):
        mu = max(np.cos(np.radians(theta)), 1e-4)
        d, s = principled_v1(mu, base, roughness)
        a_d, a_s = integrate(d), integrate(s)
        e = e_spec(mu, roughness)
        rtdr = base + (1.0 - base) * e
        print("%8d %9.4f %9.4f %9.4f %9.4f | %9.4f %9.4f %9.4f | %7.4f" % (
            theta, a_d + a_s, a_d, a_s, (a_d + a_s) / rtdr, rtdr, e, e_spec_table(mu, roughness), base))
    # Cosine-weighted hemispherical averages: what a surface reflects of uniform (diffuse) light.
    avg = {name: 2.0 * np.sum(W_MU * MU_L * np.array([a(m) for m in MU_L])) for name, a in (
        ("PV1", lambda m: sum(integrate(p) for p in principled_v1(m, base, roughness))),
        ("RTDR", lambda m: base + (1.0 - base) * e_spec(m, roughness)))}
    print("hemispherical average (2 int A mu dmu): PV1 %.4f, RTDR %.4f, Lambert %.4f" % (avg["PV1"], avg["RTDR"], base))

    print("closed sphere furnace, camera at the centre, emission %.3g, %d bounces (infinite in brackets):" % (LE, BOUNCES))
    ea = e_avg(roughness)
    e_l = np.array([e_spec(m, roughness) for m in MU_L])[:, None]     # E_spec(n.l) on the grid of l

    def rtdr_brdf(mu_v):
        diffuse = base / np.pi * (1.0 - e_spec(mu_v, roughness)) * (1.0 - e_l) / (1.0 - ea)
        return diffuse + rtdr_specular(mu_v, roughness)

    for name, brdf in (("Principled v1", lambda m: sum(principled_v1(m, base, roughness))),
                       ("RTDR dielectric", rtdr_brdf),
                       ("Lambert", lambda m: np.full((N_MU, N_PHI), base / np.pi))):
        print("  %-16s %.4f (%.4f)" % ((name,) + furnace(brdf)))


if __name__ == "__main__":
    main()
