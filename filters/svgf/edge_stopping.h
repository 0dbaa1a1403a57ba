// The three edge-stopping functions of SVGF [SVGF17 Sec. 4.4, Eq. 3-5]: how much a tap q may contribute to
// pixel p, judged by depth, normal and luminance. Each returns a weight in [0, 1], and exactly 1 at q = p
// (for epsilon > 0 and n_p of unit length in exact arithmetic; see filters/svgf/atrous.cpp for how the
// a-trous treats the centre tap). The a-trous (filters/svgf/atrous.cpp) multiplies them [SVGF17 Eq. 2];
// the spatial variance fallback [SVGF17 Sec. 4.2] uses the depth and normal weights.
// Inputs: G-buffer values at p and q (filters/surface_planes.h), the parameters of svgf_params.h. Outputs: one float.
#pragma once

#include <glm/glm.hpp>

namespace rtdr {

// Depth weight w_z [SVGF17 Eq. 3]: exp(-|z(p) - z(q)| / (sigma_z |grad z(p) . (p - q)| + epsilon)).
// z is linear view depth, grad_z_p its derivative per screen pixel (depth.dX, depth.dY), offset_pq = p - q in
// pixels at the tap's real distance (the a-trous step 2^i included). Why linear depth: see edge_stopping.cpp.
float weight_depth(float z_p, float z_q, glm::vec2 grad_z_p, glm::vec2 offset_pq, float sigma_z, float epsilon);

// Normal weight w_n [SVGF17 Eq. 4]: max(0, n(p) . n(q))^sigma_n, world-space unit normals.
float weight_normal(glm::vec3 n_p, glm::vec3 n_q, float sigma_n);

// Luminance weight w_l [SVGF17 Eq. 5]: exp(-|l(p) - l(q)| / (sigma_l sqrt(g3x3(Var(l(p)))) + epsilon)), where
// variance_prefiltered_p is g3x3(Var)(p) from filters/svgf/prefilter.h.
float weight_luminance(float l_p, float l_q, float variance_prefiltered_p, float sigma_l, float epsilon);

// Eq. 5's denominator, sigma_l sqrt(g3x3(Var(l(p)))) + epsilon: the luminance change noise alone explains at p.
float luminance_scale(float variance_prefiltered_p, float sigma_l, float epsilon);

// The Vulkan ports mirror these functions in edge_stopping.glsl, which also holds the fused form the a-trous
// shader uses (GPU-only).

}  // namespace rtdr
