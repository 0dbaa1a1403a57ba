#!/usr/bin/python3
"""Writes trace/ggx_albedo_table.h: the directional albedo E_spec(roughness, mu) of RTDR's GGX specular lobe
for the glTF dielectric (F0 = 0.04, Schlick's Fresnel, height-correlated Smith G2), and its cosine-weighted
hemispherical average E_avg(roughness) = 2 int_0^1 E_spec(mu) mu dmu, for the albedo scaling of the diffuse
lobe in trace/brdf.cpp (Kelemen and Szirmay-Kalos 2001; Kulla and Conty 2017, "Revisiting Physically Based
Shading at Imageworks").

Run: /usr/bin/python3 tools/make_ggx_albedo_table.py > trace/ggx_albedo_table.h   (numpy only; a few minutes on 2 cores)

The integral, written over visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible Normals",
Eq. 17): with l = reflect(-v, h), d(omega_l) = 4 (v.h) d(omega_h) and D_v(h) = G1(v) (v.h) D(h) / mu,
    E_spec(mu) = int f_spec(v, l) (n.l) d(omega_l) = int F(v.h) G2(v, l) / G1(v) [n.l > 0] D_v(h) d(omega_h),
a mean over visible normals. It is computed by a midpoint rule on a K x K grid of the unit square, mapped to
visible normals by Heitz's construction (stretch, projected disk, unstretch). This is an implementation of
its own, in numpy, of the same formulas as trace/brdf.cpp, so tests/trace_brdf_test.cpp, which
recomputes entries with the C++ BRDF by a quadrature over half vectors, checks the two against each other.

Entries: roughness r_i = i / (N_R - 1), alpha = max(1e-3, r^2) (trace/brdf.h's ggx_alpha); mu_j = (j / (N_MU - 1))^2,
denser towards grazing angles, where a smooth lobe's albedo changes fastest; the first is evaluated at
mu = 1e-4 (at mu = 0 the lobe is not defined). Between entries the table is bilinear in (roughness, sqrt(mu)).

Conservative near grazing: a near-mirror lobe's E(mu) is concave close to mu = 0 (masking pulls it down at the
horizon, Fresnel up just above it), so a chord falls below it, and the diffuse lobe, weighted by 1 - E_table,
would get energy the specular lobe already reflected: a white dielectric of roughness 0 reflected 1.017 at
89 degrees with a uniform grid of 32. So in the first GRAZING_SEGMENTS segments the albedo is also computed at
CHECKS_PER_SEGMENT interior points, and where the chord lies below it both ends are raised by the largest
deficit. At roughness 0 that is 0.022 in the first segment (n.v < 2.5e-4, the last 0.9 degree before grazing)
and at most 3.3e-3 beyond it; at roughness >= 0.5 at most 1.3e-4 (the generator prints each raise on stderr).
The table then errs towards losing energy.

E_avg is the exact integral of the table as the lookup interpolates it (piecewise linear in sqrt(mu)),
computed with a fine midpoint rule in mu, so the diffuse lobe weighted by (1 - E(mu_o)) (1 - E(mu_i)) / (1 - E_avg)
has directional albedo base (1 - E(mu_o)) to about 1e-7.
"""
import sys

import numpy as np

N_R = 32
N_MU = 64
K = 384  # midpoint grid per entry: K^2 visible normals (1e-5 from K = 512 at the entries checked)
GRAZING_SEGMENTS = 16  # mu segments, from mu = 0, whose entries are made conservative (see the docstring)
CHECKS_PER_SEGMENT = 4
F0 = 0.04
MIN_ALPHA = 1e-3


def smith_lambda(mu, alpha):
    # Heitz 2014, "Understanding the Masking-Shadowing Function", Eq. 72, for GGX.
    mu2 = np.maximum(mu * mu, 1e-12)
    tan2 = np.maximum(0.0, 1.0 - mu2) / mu2
    return 0.5 * (-1.0 + np.sqrt(1.0 + alpha * alpha * tan2))


def visible_normals(v, alpha, u1, u2):
    # Heitz 2018, Sec. 2: stretch v, sample the projected disk of the hemisphere, unstretch.
    vh = np.array([alpha * v[0], alpha * v[1], v[2]])
    vh /= np.linalg.norm(vh)
    len2 = vh[0] ** 2 + vh[1] ** 2
    t1 = np.array([-vh[1], vh[0], 0.0]) / np.sqrt(len2) if len2 > 0 else np.array([1.0, 0.0, 0.0])
    t2 = np.cross(vh, t1)
    r = np.sqrt(u1)
    phi = 2.0 * np.pi * u2
    p1 = r * np.cos(phi)
    s = 0.5 * (1.0 + vh[2])
    p2 = (1.0 - s) * np.sqrt(np.maximum(0.0, 1.0 - p1 * p1)) + s * r * np.sin(phi)
    p3 = np.sqrt(np.maximum(0.0, 1.0 - p1 * p1 - p2 * p2))
    nh = p1[:, None] * t1 + p2[:, None] * t2 + p3[:, None] * vh
    h = np.stack([alpha * nh[:, 0], alpha * nh[:, 1], np.maximum(1e-12, nh[:, 2])], axis=1)
    return h / np.linalg.norm(h, axis=1)[:, None]


def specular_albedo(roughness, mu):
    alpha = max(MIN_ALPHA, roughness * roughness)
    v = np.array([np.sqrt(max(0.0, 1.0 - mu * mu)), 0.0, mu])
    g = (np.arange(K) + 0.5) / K
    u1, u2 = [a.ravel() for a in np.meshgrid(g, g, indexing="ij")]
    h = visible_normals(v, alpha, u1, u2)
    v_dot_h = h @ v
    l_z = 2.0 * v_dot_h * h[:, 2] - mu  # n.l of l = reflect(-v, h)
    fresnel = F0 + (1.0 - F0) * np.clip(1.0 - v_dot_h, 0.0, 1.0) ** 5
    lambda_v = smith_lambda(mu, alpha)
    g2_over_g1 = (1.0 + lambda_v) / (1.0 + lambda_v + smith_lambda(l_z, alpha))
    return float(np.mean(np.where(l_z > 0.0, fresnel * g2_over_g1, 0.0)))


def mu_of(j):
    return (j / (N_MU - 1)) ** 2


def interpolate(row, mu):
    # The lookup of trace/brdf.cpp: linear in s = sqrt(mu) between s_j = j / (N_MU - 1).
    return np.interp(np.sqrt(mu), np.linspace(0.0, 1.0, N_MU), row)


def average(row):
    # 2 int_0^1 E(mu) mu dmu of the interpolated row: with mu = s^2, = 4 int_0^1 E(s) s^3 ds, E linear in s on
    # each segment, so a midpoint rule of 4096 points per segment is exact to ~1e-9.
    n = 4096 * (N_MU - 1)
    s = (np.arange(n) + 0.5) / n
    return float(4.0 * np.mean(np.interp(s, np.linspace(0.0, 1.0, N_MU), row) * s ** 3))


def conservative(roughness, row):
    row = list(row)
    for j in range(GRAZING_SEGMENTS):
        deficit = 0.0
        for k in range(1, CHECKS_PER_SEGMENT + 1):
            s = (j + k / (CHECKS_PER_SEGMENT + 1)) / (N_MU - 1)
            deficit = max(deficit, specular_albedo(roughness, s * s) - float(interpolate(row, s * s)))
        row[j] += deficit
        row[j + 1] += deficit
        if deficit > 0.0:
            sys.stderr.write(f"roughness {roughness:.4f}: segment {j} raised by {deficit:.2e}\n")
    return row


def main():
    table = []
    for i in range(N_R):
        roughness = i / (N_R - 1)
        row = [specular_albedo(roughness, max(1e-4, mu_of(j))) for j in range(N_MU)]
        table.append(conservative(roughness, row))
    averages = [average(row) for row in table]
    out = sys.stdout
    out.write("// Generated by tools/make_ggx_albedo_table.py; do not edit. The directional albedo E_spec(roughness, mu)\n")
    out.write("// of the glTF dielectric's GGX specular lobe (F0 = 0.04), and its average E_avg(roughness): the method,\n")
    out.write("// the grid and the accuracy are in the generator's docstring and trace/brdf.h.\n")
    out.write("// Each entry is a mean over visible normals, E_spec(mu) = int F G2 / G1 D_v d(omega_h) (Heitz 2018, Eq. 17).\n")
    out.write("#pragma once\n\nnamespace rtdr::ggx_albedo_table {\n\n")
    out.write(f"inline constexpr int kRoughnessCount = {N_R};  // roughness i / {N_R - 1}\n")
    out.write(f"inline constexpr int kMuCount = {N_MU};         // mu = n.v = (j / {N_MU - 1})^2\n\n")
    out.write("// kSpecularAlbedo[i][j] = E_spec(roughness i / (kRoughnessCount - 1), mu (j / (kMuCount - 1))^2).\n")
    out.write("inline constexpr float kSpecularAlbedo[kRoughnessCount][kMuCount] = {\n")
    for row in table:
        out.write("    {" + ", ".join(f"{x:.7f}f" for x in row) + "},\n")
    out.write("};\n\n")
    out.write("// kAverageAlbedo[i] = 2 int_0^1 E_spec(roughness i / (kRoughnessCount - 1), mu) mu dmu, the row linear in sqrt(mu).\n")
    out.write("inline constexpr float kAverageAlbedo[kRoughnessCount] = {\n")
    for i in range(0, N_R, 8):
        out.write("    " + ", ".join(f"{x:.7f}f" for x in averages[i:i + 8]) + ",\n")
    out.write("};\n\n}  // namespace rtdr::ggx_albedo_table\n")


if __name__ == "__main__":
    main()
