// TRMV's six cones of incident radiance [TRMV21 Sec. 4.3, Sec. 5, Eq. 9-11]: how a pixel stores the diffuse
// indirect light arriving over its hemisphere, how two pixels with different normals share it, and how a pixel
// is re-shaded from it. The dual motion vector [TRMV21 Eq. 6] finds a disoccluded pixel a history pixel whose
// normal may differ; reusing the history's *colour* repeats its shading ("the bunny will simply be repeated",
// Fig. 6), while reusing its *incident radiance*, direction by direction in world space, and re-shading with the
// pixel's own normal does not.
//
// Functions (all deterministic, scalar reference code):
//   cone_overlap_solid_angle(theta_c, a): Omega, the solid angle two cones of half-angle theta_c share when
//     their axes are a radians apart [TRMV21 Eq. 9-10] (Mazonka 2012, "Solid angle of conical surfaces,
//     polyhedral cones, and intersecting spherical caps", arXiv:1205.1396):
//       gamma = arctan((cos theta_c - cos a cos theta_c) / (sin a cos theta_c))   (= a/2 for equal cones)
//       beta  = arccos(sin gamma / sin theta_c),  phi = arccos(tan gamma / tan theta_c)
//       Omega = 4 (beta - phi cos theta_c)
//     The formula is 0/0 at a = 0 and takes arccos of more than 1 for a > 2 theta_c; both ends are handled
//     (cones.cpp) and Omega is continuous at both: Omega(0) = 2 pi (1 - cos theta_c), the whole cap, falling
//     with slope -2 sin theta_c, and Omega(2 theta_c) = 0.
//   make_cone_layout(theta_c) -> ConeLayout: the six axes in the local frame (z = normal), each cone's solid
//     angle above the horizon Omega_k^+, the re-shading weights c_k, and the half-angle of the transfer weights.
//   cone_axes(layout, n): the axes in world space, through a deterministic orthonormal basis around n
//     (Duff et al. 2017, "Building an Orthonormal Basis, Revisited", JCGT 6(1)).
//   add_cone_sample(...): one path sample's share of the six per-cone estimates Lhat_k (unbiased).
//   reshade_cones(layout, L): the pixel's demodulated diffuse radiance from its six cones (corrected Eq. 11);
//   reshade_cones_literal(L): Eq. 11 as printed, which doubles a uniform field (below).
//   transfer_cones(layout, n_target, n_source, L): a source pixel's cones seen from a target pixel's normal, each
//     with the share of the target cone that the source's hemisphere covers [TRMV21 Sec. 4.3, Fig. 7];
//   blend_transferred(transfer, current): those cones for their share, this frame's cones for the rest.
//
// The layout: why not the paper's. The paper asks for "6 slightly overlapping cones with equal solid angles
// pi/3" and computes their overlap with the half-angle pi/6 [TRMV21 Sec. 4.3, Eq. 9-10]. These disagree: a cone
// of half-angle pi/6 spans 2 pi (1 - cos pi/6) = 0.842 sr, and pi/3 sr needs 33.56 degrees. Neither can do what
// the text asks: six caps of at most pi/3 sr total at most 2 pi, the hemisphere's solid angle, so they can cover
// it only without overlapping, which round caps cannot do. We keep the number six and choose the half-angle
// that covers: one cone around the normal and five evenly spaced around it at polar angle psi,
//   a_0 = (0, 0, 1),  a_k = (sin psi cos(2 pi (k-1)/5), sin psi sin(2 pi (k-1)/5), cos psi),  k = 1..5,
// in the frame (t, b, n). The paper-literal half-angle kConePaperHalfAngle = pi/6 stays as a variant.
//
// The covering half-angle, in closed form. A layout covers the hemisphere iff its half-angle is at least the
// largest angular distance from a direction of the hemisphere to its nearest axis. That largest distance is
// reached at a vertex of the axes' spherical Voronoi diagram clipped to the hemisphere. By the five-fold
// symmetry there are two kinds, both on the meridian halfway between two ring axes (azimuth pi/5):
//   P, equidistant from a_0, a_1, a_2, at polar angle rho: cos rho = cos psi cos rho + sin psi sin rho cos(pi/5),
//      so tan rho = tan(psi/2) / cos(pi/5); its distance to the nearest axis is rho;
//   E, on the horizon, equidistant from a_1 and a_2: its distance is d_E = arccos(sin psi cos(pi/5)).
// (The pole's cell never reaches the horizon: d_E <= pi/2.) So the covering radius is
//   R(psi) = max(rho(psi), d_E(psi))                                       -> cone_covering_radius(psi),
// rho rises with psi and d_E falls, and the optimum psi* has rho = d_E. With c = cos(pi/5) and t = tan(psi/2),
// cos rho = c / sqrt(c^2 + t^2) and sin psi = 2t / (1 + t^2); equating cos rho = c sin psi gives
//   3 t^4 + (4 c^2 - 2) t^2 - 1 = 0,   4 c^2 - 2 = 2 cos(2 pi/5) = 0.618034 (1 / golden ratio),
// t^2 = 0.483461, so psi* = 2 arctan t = 1.2151479 rad = 69.6228 degrees and
//   theta* = R(psi*) = arctan(t / c) = 0.7099577 rad = 40.6776 degrees (1.5181 sr per cone).
// (A brute-force scan of psi confirms the minimum; the test re-derives it, tests/trmv_cones_test.cpp.) The
// ring's neighbours are 66.87 degrees apart and 69.62 degrees from a_0, so at theta* every neighbouring pair
// overlaps (2 theta* = 81.36 degrees); at the paper's pi/6 (2 theta = 60 degrees) no pair does, and 26.8 % of
// the hemisphere's solid angle lies in no cone, 30.5 % of its cosine-weighted measure (sum_k c_k = 2.1834, not
// pi; measured by the test).
//
// Re-shading: the corrected Eq. 11. Radiance is constant within a cone; a direction w inside N(w) cones takes
// the mean of their values, i.e. the partition weights 1[w in k] / N(w), which sum to 1 wherever N(w) >= 1.
// For a Lambertian surface (f_r = 1/pi on demodulated values) the outgoing radiance is then
//   L_o = (1/pi) integral_H L(w) cos theta dw = (1/pi) sum_k c_k L_k,
//   c_k = integral_H cos theta 1[w in k] / N(w) dw,       sum_k c_k = integral_H cos theta dw = pi
// on a covering layout, so a uniform field L gives L_o = L. The paper's Eq. 11, L = f_r sum_k L_k pi/3, has no
// cosine and weighs each cone by its nominal solid angle: a uniform field gives (1/pi) 6 L pi/3 = 2 L, twice
// the right answer (reshade_cones_literal keeps it for comparison). c_k is computed once per layout by the
// midpoint rule on a (u, phi) grid, u = sin^2 theta, on which cos theta dw = du dphi / 2 is uniform: every cell
// weighs pi / n^2, so sum_k c_k = pi up to float rounding when every cell centre is covered. The five ring
// cones are congruent and take the mean of their five grid values (the grid's rounding at their boundaries
// differs by up to 4e-5 between them); since sum_k c_k is exact, what remains is the error of c_0, whose
// boundary is smooth on the grid. With n = 1024 (kConeQuadratureGrid) the c_k agree with a 4096 grid to 1e-6:
// c_0 = 1.115767, c_1..c_5 = 0.405165 at theta_c = kConeCoveringHalfAngle (the test measures it).
//
// The per-cone estimate from one path sample (the notes, Sec. 4.3): a BSDF sample w with pdf p(w) that brings
// incident radiance L_in(w) adds  Lhat_k = L_in(w) 1[w in cone k] / (p(w) Omega_k^+)  to cone k. Its mean is
// the mean of L_in over the part of cone k above the horizon, the part the re-shading integrates; Omega_k^+ is
// that part's solid angle (cone_solid_angle_above_horizon, closed form), not the whole cap's, or the ring cones,
// which reach 69.6 + 40.7 = 110.3 degrees from the normal, would read dark in a furnace. Directions below the
// horizon, or with p(w) = 0, add nothing. Note: under cosine-weighted sampling (p = cos theta / pi) the ring
// cones' estimate has a logarithmically divergent variance, from the 1/cos theta of grazing samples; the mean
// converges, the spread of single-sample estimates is heavy-tailed.
//
// Choices the paper leaves open:
// - The transfer weight [TRMV21 Sec. 4.3: "using the overlapping solid angles between each pair of cones as the
//   filtering weight"]: target cone k (axis a_k around n_target) takes
//     L'_k = sum_m Omega(angle(a_k, b_m)) L_m / sum_m Omega(angle(a_k, b_m)),  b_m the source axes,
//   with Omega of Eq. 9-10 at the half-angle theta_T = min(theta_c, s/2 - 0.0005 rad), s = 66.87 degrees the
//   smallest spacing of two axes of the layout. At the paper's pi/6 that is Eq. 9-10 as printed (pi/6 < s/2).
//   At the covering half-angle, neighbouring cones overlap, and with the layout's own half-angle a pixel
//   transferring to itself (n_target = n_source) would blur each cone into its neighbours; at theta_T = 33.41
//   degrees only b_k overlaps a_k then, and the transfer is the identity. The 0.0005 rad keeps rounding of the
//   world axes from making neighbours touch.
// - The share [TRMV21 Sec. 4.3, Fig. 7: directions outside the overlap of the two hemispheres "should remain using
//   only the spatial content from frame i"]: the source's cones hold the radiance of the source's hemisphere only.
//   Target cone k estimates the mean radiance of its part above the target's horizon (Omega_k^+, above), so the
//   share is that part's fraction inside the source's hemisphere too:
//     f_k = Omega(C_k, H_t, H_s) / Omega(C_k, H_t),   C_k the cap, H_t and H_s the two hemispheres,
//   counted on kConeShareGrid^2 directions of C_k uniform in solid angle (a midpoint grid in (cos, azimuth) about
//   a_k: an intersection of a cap and two half-spaces has no closed form short of spherical polygons; the grid's
//   error, under 2 % of the cap, is tested against Monte Carlo). Equal normals give f_k = 1 exactly. The history is
//     H_k = f_k L'_k + (1 - f_k) L~_k,  L~_k the pixel's own cone of frame i (filtered)
//   (blend_transferred).
//   A target cone that no source cone overlaps (normals far apart) has no transferred radiance: f_k = 0, frame i's
//   own. (Before: a full transfer, f_k = 1, and such a cone took the mean of the source's six; TrmvParams
//   cone_transfer = 0 keeps that for comparison.)
// - n must be unit length; the basis is Duff et al.'s, core/geometry.h's orthonormal_basis, as the BSDF's.
#pragma once

#include <glm/glm.hpp>

#include <array>

namespace rtdr {

inline constexpr int kConeCount = 6;
// psi*, the ring's polar angle that minimises the covering half-angle (derived above): 69.6228 degrees.
inline constexpr float kConeRingPolarAngle = 1.2151479f;
// theta* = R(psi*), the smallest half-angle with which six cones cover the hemisphere: 40.6776 degrees.
inline constexpr float kConeMinimalCoveringHalfAngle = 0.7099577f;
// The default: theta* rounded up to 0.7100 rad (40.68 degrees). The 4.2e-5 rad margin keeps float rounding of
// the dot products (~1e-7) from opening a hole at the critical points P and E.
inline constexpr float kConeCoveringHalfAngle = 0.7100f;
// The paper's half-angle, pi/6 [TRMV21 Eq. 9-10]; does not cover the hemisphere (above).
inline constexpr float kConePaperHalfAngle = 0.52359878f;
// The side of the (u, phi) quadrature grid of c_k (above).
inline constexpr int kConeQuadratureGrid = 1024;
// The side of the (cos, azimuth) grid of a cone's directions that counts f_k, the transfer's share (above).
inline constexpr int kConeShareGrid = 16;

using ConeValues = std::array<glm::vec3, kConeCount>;
using ConeAxes = std::array<glm::vec3, kConeCount>;

struct ConeLayout {
  float half_angle = 0.0f;                        // theta_c, radians
  ConeAxes axes{};                                // a_k in the local frame, z = normal; a_0 = (0, 0, 1)
  std::array<float, kConeCount> cosine_weight{};  // c_k, sum pi on a covering layout
  std::array<float, kConeCount> solid_angle{};    // Omega_k^+, the cone's solid angle above the horizon
  float transfer_half_angle = 0.0f;               // theta_T of the transfer weights (above)
};

// 2 pi (1 - cos theta_c), the solid angle of one cone.
float cone_solid_angle(float theta_c);
// Omega(a) of two cones of half-angle theta_c with axes a radians apart [TRMV21 Eq. 9-10]; a in [0, pi].
float cone_overlap_solid_angle(float theta_c, float a);
// The solid angle of a cone of half-angle theta_c whose axis lies at polar angle psi, above the plane z = 0.
float cone_solid_angle_above_horizon(float theta_c, float psi);
// R(psi): the largest angle from a direction of the hemisphere to the nearest of the six axes when the ring lies
// at polar angle psi, 0 < psi <= pi/2 (derived above). The layout covers iff theta_c >= R(psi).
float cone_covering_radius(float psi);
// w lies in the cone of half-angle theta_c around `axis` (both unit), boundary included.
bool cone_contains(float theta_c, glm::vec3 axis, glm::vec3 w);

// c_k by the midpoint rule on an n x n (u, phi) grid over the hemisphere (above); axes in the local frame.
std::array<float, kConeCount> cone_cosine_weights(const ConeAxes& axes, float theta_c, int n);
// The layout for half-angle theta_c: ring at kConeRingPolarAngle, c_k on the kConeQuadratureGrid grid.
ConeLayout make_cone_layout(float theta_c = kConeCoveringHalfAngle);
// The layout's axes in world space around the unit normal n: a_0 = n.
ConeAxes cone_axes(const ConeLayout& layout, glm::vec3 n);

// Adds one path sample to the six per-cone estimates: Lhat_k += L_in 1[w in cone k] / (pdf Omega_k^+). w is a
// world direction, axes = cone_axes(layout, n); nothing is added for pdf <= 0 or w at or below the horizon.
// Averaged over N samples, Lhat_k / N estimates the mean incident radiance of cone k above the horizon.
void add_cone_sample(const ConeLayout& layout, const ConeAxes& axes, glm::vec3 w, glm::vec3 L_in, float pdf,
                     ConeValues& Lhat);
// The same, with the world axes computed from the normal n.
void add_cone_sample(const ConeLayout& layout, glm::vec3 n, glm::vec3 w, glm::vec3 L_in, float pdf,
                     ConeValues& Lhat);

// L_o = (1/pi) sum_k c_k L_k, demodulated (Lambert, f_r = 1/pi) [TRMV21 Eq. 11, with the cosine].
glm::vec3 reshade_cones(const ConeLayout& layout, const ConeValues& L);
// L = f_r sum_k L_k pi/3, f_r = 1/pi: Eq. 11 as printed [TRMV21 Eq. 11]; 2 L for a uniform field.
glm::vec3 reshade_cones_literal(const ConeValues& L);

// f_k: the share of the part of a cone (half-angle theta_c, unit `axis`) above the target's horizon (unit n_target)
// that lies above the source's too (unit n_source) [TRMV21 Sec. 4.3, Fig. 7] (above); 0 when no part is above the
// target's horizon.
float cone_share_in_hemisphere(float theta_c, glm::vec3 axis, glm::vec3 n_target, glm::vec3 n_source);

// A transfer's result: the carried cones L'_k and each target cone's share f_k (0 where no source cone overlaps).
struct ConeTransfer {
  ConeValues values{};
  std::array<float, kConeCount> share{};
};

// The source pixel's cones (around n_source) carried to the target pixel's cones (around n_target), weighted by
// the overlap of each pair of cones [TRMV21 Sec. 4.3, Eq. 9-10] at layout.transfer_half_angle, with their shares
// (above). `full` = true: the former transfer, every share 1 and the source's mean where no source cone overlaps.
ConeTransfer transfer_cones(const ConeLayout& layout, glm::vec3 n_target, glm::vec3 n_source, const ConeValues& source,
                            bool full = false);
// H_k = f_k L'_k + (1 - f_k) current_k [TRMV21 Sec. 4.3, Fig. 7].
ConeValues blend_transferred(const ConeTransfer& transfer, const ConeValues& current);

}  // namespace rtdr
