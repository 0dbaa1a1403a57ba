// TRMV's window sizes at any resolution. The paper renders at 1920x1080 [TRMV21 Sec. 6] and gives its windows in
// pixels there: the shadow filter 31x31, the clean-up 9x9, the diffuse a-trous "4-level ... essentially 32x32"
// [TRMV21 Sec. 5]. A window is a region of the scene as the image sees it, so at another resolution it is the same
// fraction of the image: a window of side S at the height H_0 = footprint_height (1080) has side S H / H_0 at the
// height H. The realisations, each the nearest one to that side:
//   - a (2r + 1)^2 window:     r_H = max(1, round((S H / H_0 - 1) / 2)), S = 2 r + 1; r = 0 stays 0 (the identity)
//   - the spatial std:         sigma_H = sigma r_H / r, so that +-3 std fills the window as it does at H_0
//   - an a-trous of L levels:  its 3x3 levels reach S = 2^(L+1) - 1 (31 for 4); L_H = max(1, round(log2(S H / H_0
//                              + 1) - 1)), the level count whose reach is nearest in the log
// The floor of one pixel each way (3x3, one level) keeps every filter a filter: at 1080p / 9 = 120 rows the
// clean-up's 9x9 would be a single pixel. The floor is the only place where a small frame is filtered more than the
// scaled 1080p frame, and tests/trmv_footprint_test.cpp checks each rule at the heights the project uses.
// The clamp's 3x3 neighbourhood [TRMV21 Sec. 5] is not a footprint but the smallest neighbourhood, and stays 3x3.
// Footprints that the filter computes from the scene in pixels (the glossy lobe's, the penumbra's) need no scaling:
// only their caps are the paper's window sizes, scaled by these rules.
#pragma once

#include "filters/trmv/trmv_params.h"

namespace rtdr {

// H / H_0.
double trmv_size_scale(int height, int footprint_height);
// r_H for a window of radius r (side 2 r + 1) at H_0.
int trmv_scaled_radius(int radius, int height, int footprint_height);
// sigma_H for a std sigma on a window of radius r at H_0 (sigma itself where r = 0).
float trmv_scaled_sigma(float sigma, int radius, int height, int footprint_height);
// L_H for an a-trous of `levels` 3x3 levels at H_0.
int trmv_scaled_levels(int levels, int height, int footprint_height);
// The odd side of a window that has side `side` at H_0 (2 r_H + 1, r = (side - 1) / 2).
int trmv_scaled_side(int side, int height, int footprint_height);

// Every window of the method at a frame `height` pixels high: TrmvParams' sizes at footprint_height, scaled.
struct TrmvWindows {
  int shadow_radius = 0;     // the shadow filter's (spatial_radius): 15 at 1080p, 5 at 360
  float shadow_sigma = 0.0f; // its std (spatial_sigma): 5 at 1080p, 5/3 at 360
  int splat_size = 1;        // the splat's side: the shadow filter's 2 r + 1, or splat_size scaled
  int atrous_levels = 1;     // the diffuse a-trous's levels: 4 at 1080p, 3 at 360
  int glossy_radius = 0;     // the lobe filter's cap (glossy_radius)
  int cleanup_radius = 0;    // the clean-up's ((cleanup_size - 1) / 2): 4 at 1080p, 1 at 360
};
TrmvWindows trmv_windows(const TrmvParams& params, int height);

}  // namespace rtdr
