// Every tunable of TRMV's filter side [TRMV21 Sec. 3-5], declared once (filters/params.h explains the X-macro).
// The edge-stopping sigmas and epsilon that guide the joint-bilateral filters (w_z, w_n) are SVGF's
// (svgf_params.h): the paper names its guides nowhere, and SVGF's functions are called as they are.
//
// X(type, name, default, min, max, symbol, source)
#define RTDR_TRMV_PARAMS(X)                                                                                       \
  X(float, alpha, 0.1f, 0.0f, 1.0f, "alpha", "TRMV21 Sec. 5: 'alpha = 0.1 in our case' (Eq. 2's blend weight)")  \
  X(float, falloff_sigma, 0.1f, 1e-3f, 3.2f, "sigma",                                                             \
    "TRMV21 Eq. 4: G(theta - pi/2; 0, 0.1), in radians (filters/trmv/falloff.h says why)")                         \
  X(float, clamp_gamma, 3.0f, 0.0f, 1e3f, "gamma",                                                                \
    "TRMV21 Sec. 5: history clamped to mu +- 3 sigma; 1 = Salvi's baseline; 0 = no clamp")                         \
  X(int, clamp_radius, 1, 0, 16, "", "TRMV21 Sec. 5 'each x_i's neighborhood': a (2r+1)^2 window of c~, 3x3")     \
  X(int, footprint_height, 1080, 1, 100000, "",                                                                   \
    "TRMV21 Sec. 6 renders 1920x1080: the windows below are pixels at this height, scaled by H / footprint_height " \
    "(filters/trmv/footprint.h); the frame's own height keeps them unscaled")                                       \
  X(int, spatial_radius, 15, 0, 64, "", "TRMV21 Sec. 5: 'a separable 31x31 joint bilateral filter' for shadows")  \
  X(float, spatial_sigma, 5.0f, 0.0f, 1e3f, "",                                                                   \
    "spatial std of that filter, px: not given; radius / 3 puts +-3 std inside the 31x31 window")                 \
  X(int, shadow_filter, 0, 0, 1, "",                                                                              \
    "TRMV21 Sec. 4.1, 5: 0 the fixed 31x31 ('already good enough'); 1 the std from the penumbra's width (the "       \
    "light's extent, the blocker and receiver distances, [LLK*19]), capped at the 31x31's (filters/trmv/penumbra.h)") \
  X(int, splat_size, 0, 0, 255, "",                                                                               \
    "TRMV21 Sec. 4.1: the splat's window; 0 the shadow filter's fixed window, else an odd side at footprint_height")  \
  X(int, diffuse_filter, 1, 0, 1, "",                                                                             \
    "TRMV21 Sec. 5: diffuse light and each cone: 1 'a 4-level a-trous wavelet filter, essentially 32x32'; 0 the "   \
    "shadows' separable bilateral")                                                                                  \
  X(int, atrous_levels, 4, 1, 8, "", "TRMV21 Sec. 5: the a-trous's levels of a 3x3 kernel at footprint_height")   \
  X(int, glossy_filter, 1, 0, 1, "",                                                                              \
    "TRMV21 Sec. 5: glossy light: 1 the BRDF lobe's footprint ([LLK*19], filters/trmv/reflection.h); 0 the "         \
    "shadows' separable bilateral")                                                                                  \
  X(int, glossy_radius, 15, 1, 64, "",                                                                            \
    "the lobe filter's window cap at footprint_height: not given; the shadow filter's 31x31")                       \
  X(int, cleanup_size, 9, 1, 63, "", "TRMV21 Sec. 5: the clean-up is 'a fixed size 9x9' (odd side)")              \
  X(float, cleanup_sigma_max, 5.0f, 0.0f, 1e3f, "", "TRMV21 Sec. 5: clean-up std min(w_A + w_C, 5), px")          \
  X(float, cleanup_eps, 0.001f, 1e-9f, 1.0f, "epsilon", "TRMV21 Eq. 8: 'epsilon is set to 0.001'")               \
  X(int, history_after_cleanup, 0, 0, 1, "",                                                                      \
    "TRMV21 Sec. 5 leaves it open: 0 keeps cbar_i before the clean-up as next frame's history, 1 after it")        \
  X(int, motion, 4, 0, 4, "",                                                                                     \
    "TRMV21 Sec. 4: whose vectors the histories follow: 0 all the surface motion (Eq. 1, 'Trad.'); 1 visibility the " \
    "shadow's (Eq. 3); 2 diffuse the dual (Eq. 6); 3 glossy the glossy (Eq. 5); 4 each its own, the paper's")          \
  X(int, history_test, 1, 0, 1, "",                                                                               \
    "1: a history is read only where the previous pixel is what its vector claims (filters/trmv/temporal.h), and "  \
    "the clamp's window keeps to the pixel's surface; 0: forced reuse, the paper's 'Trad. (No clamp)'")              \
  X(int, shadow_receiver_test, 0, 0, 1, "",                                                                       \
    "TRMV21 Eq. 4 handles another receiver: 0 no test on the shadow vector's history; 1 the same mesh")             \
  X(int, falloff_carry, 1, 0, 1, "",                                                                              \
    "TRMV21 Sec. 4.1: 1 n(s_i) and s_i carried back to frame i-1 ('inverse transformed if the shadow receiver "    \
    "moves'); 0 the current ones")                                                                                   \
  X(int, glossy_draw, 1, 0, 1, "",                                                                                \
    "TRMV21 Eq. 5: 1 the stochastic vector, one draw of the lobe; 0 the lobe's centre mu")                          \
  X(int, cones, 1, 0, 1, "",                                                                                      \
    "TRMV21 Sec. 4.3: a disoccluded pixel's diffuse history is 1 re-shaded from the six cones at x^O (Eq. 11), "      \
    "0 the colour at x^O (Fig. 6's repetition)")                                                                    \
  X(float, cone_half_angle, 0.71f, 0.1f, 1.5f, "theta_c",                                                         \
    "TRMV21 Eq. 9-10, radians: 0.71 covers the hemisphere with six cones (cones.h); the paper's pi/6 = 0.5236 does not") \
  X(int, cone_transfer, 1, 0, 1, "",                                                                              \
    "TRMV21 Sec. 4.3, Fig. 7: 1 each cone's transferred history by the share of it the source hemisphere covers, "  \
    "frame i's cone for the rest; 0 full reuse, the source's mean where no source cone overlaps")

#pragma once
#include "filters/params.h"

#include <string>

namespace rtdr {

// The motion row's values by name, as `trmv:motion=NAME` spells them (index = value).
inline constexpr const char* kTrmvMotionNames[] = {"traditional", "shadow", "dual", "glossy", "all"};
// The value of a motion name, or -1.
int trmv_motion_from_name(const std::string& name);
// Which vector each component's history follows under `motion` (the motion row).
inline bool trmv_uses_shadow(int motion) { return motion == 1 || motion == 4; }
inline bool trmv_uses_dual(int motion) { return motion == 2 || motion == 4; }
inline bool trmv_uses_glossy(int motion) { return motion == 3 || motion == 4; }

struct TrmvParams {
  RTDR_TRMV_PARAMS(RTDR_PARAM_FIELD)
};

std::vector<ParamInfo> trmv_param_table();
std::vector<double> param_values(const TrmvParams& params);
// Throws rtdr::Error naming the first parameter outside its range, or a window side (cleanup_size, splat_size
// other than 0) that is even: a window centred on the pixel has an odd side.
void validate(const TrmvParams& params);
// Sets the parameter called `key`; false when there is no such row.
bool set_param(TrmvParams& params, const std::string& key, double value);

}  // namespace rtdr
