// Shadow motion for every pixel near a shadow: the splat of TRMV21 Sec. 4.1.
//
// Pass: splat_shadow_motion(shadow motion, surface motion, depth) -> motion.shadow_splat per pixel.
//   in:  m^V and its validity per pixel (motion/shadow.h, [TRMV21 Eq. 3]), the back-projected surface motion
//        (`motion`, [TRMV21 Eq. 1]) and the linear view depth of the visibility buffer
//   out: one motion vector per pixel: the mean of the valid m^V that land on it, else the surface motion; and
//        whether any landed (motion.shadow_splat.valid)
//
// Only pixels whose shadow ray was blocked have an Eq. 3 vector, yet the pixels around a shadow need it as much:
// a lit pixel that the shadow has just left holds last frame's shadow in its history. TRMV21 Sec. 4.1 "interprets
// the filtering of shadows as the splatting of each in-shadow pixel's visibility, along with other associated
// properties", with a fixed-size filter, the splats "weight averaged into the center of each filter". The paper
// leaves the size and the weights open. Ours:
// - the window is kShadowSplatSize x kShadowSplatSize pixels (9 x 9: the size of TRMV's clean-up filter
//   [TRMV21 Sec. 5], the other fixed window of the method; a shadow edge moving up to 4 pixels a frame is covered);
// - the weights are equal (a box), and a splat lands only on pixels of the same surface as the splatting pixel:
//   their depths differ by at most kShadowSplatDepthRelative of the larger (SVGF's temporal depth test, 10 %), so
//   a pillar's shadow does not spread onto the pillar;
// - a pixel on which no splat lands keeps its surface motion; a pixel without surface keeps (0, 0).
// A box window and a symmetric depth test make the splat the same as a gather: pixel p averages the valid m^V of
// the window centred on p. The golden function is written as that gather, one pixel at a time.
#pragma once

#include "motion/shadow.h"
#include "motion/shadow_splat_shared.h"  // kShadowSplatSize, kShadowSplatDepthRelative (shared with the port)

#include <glm/glm.hpp>

#include <vector>

namespace rtdr {

struct SplatMotion {
  glm::vec2 motion{0.0f};
  bool landed = false;  // a valid m^V landed: `motion` is their mean, not the surface motion
};

// The golden per-pixel function: the splatted motion at pixel (x, y). Planes are row-major, width x height.
SplatMotion splat_shadow_motion_pixel(const std::vector<ShadowMotion>& shadow, const std::vector<glm::vec2>& surface_motion,
                                    const std::vector<float>& depth, int width, int height, int size, int x, int y);

// Throws rtdr::Error unless the three planes hold width x height pixels and `size` is odd and at least 1: the
// checks of splat_shadow_motion, which its port makes too (gpu/motion_shadow_gpu.h).
void check_splat_inputs(const std::vector<ShadowMotion>& shadow, const std::vector<glm::vec2>& surface_motion,
                        const std::vector<float>& depth, int width, int height, int size);

// Every pixel's splatted motion, row-major. `size` is the window's side, odd and at least 1.
std::vector<SplatMotion> splat_shadow_motion(const std::vector<ShadowMotion>& shadow,
                                           const std::vector<glm::vec2>& surface_motion, const std::vector<float>& depth,
                                           int width, int height, int size);

}  // namespace rtdr
