// TRMV's splat of shadow motion vectors [TRMV21 Sec. 4.1]: shadow motion for every pixel near a shadow.
//
// Pass: trmv_splat_pass(planes, size) -> the splatted shadow motion per pixel.
//   in:  m^V and its validity per pixel (motion.shadow, motion/shadow.h, [TRMV21 Eq. 3]), the back-projected
//        surface motion (`motion`, [TRMV21 Eq. 1]), the instance id (`id.instance`) and the normal of each pixel's
//        surface, and optionally one more property of each in-shadow pixel to carry along (the penumbra filter's
//        std, filters/trmv/penumbra.h); the window's side
//   out: one motion vector per pixel: the mean of the valid m^V that land on it, else the surface motion; whether
//        any landed; and the mean of the carried property over the same splats (0 where none landed)
//
// Only pixels whose shadow ray was blocked have an Eq. 3 vector, yet the pixels around a shadow need it as much:
// a lit pixel that the shadow has just left holds last frame's shadow in its history. TRMV21 Sec. 4.1 "interprets
// the filtering of shadows as the splatting of each in-shadow pixel's visibility, along with other associated
// properties", "implemented using a fixed-size filter", the splats "weight averaged into the center of each
// filter". The paper leaves the size and the weights open. Ours:
// - the window is the shadow spatial filter's fixed window, the one the paper names: 31x31 at 1080p, scaled to the
//   frame (filters/trmv/footprint.h; TrmvParams::splat_size sets another). It was 9x9 at any size, less than a
//   frame's shadow motion on fence at 640x360 (8.5 px); filters/trmv/README.md has the measurement;
// - the weights are equal (a box), and a splat lands only on the receiving surface of the splatting pixel: the same
//   instance (`id.instance`) and normals within kTrmvSplatNormalCosine (SVGF's temporal normal test, 25.8 degrees),
//   so a floor shadow's vector does not land on the slats in front of it, nor a slat's on the next slat of the
//   same mesh, nor round a fold of the receiver. (The test was depths within 10 %: on fence the slats stand
//   within 10 % of the depth of the floor behind them.)
// - a pixel on which no splat lands keeps its surface motion; a pixel without surface keeps (0, 0).
// A box window and a symmetric surface test make the splat the same as a gather: pixel p averages the valid m^V of
// the window centred on p. The golden function is written as that gather, one pixel at a time.
// The splat was the render side's (motion.shadow_splat, renderer version 4); its window is the filter's, so the
// filter makes it, from the rendered motion.shadow.
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/trmv/splat_shared.h"  // kTrmvSplatNormalCosine (shared with the port)

#include <glm/glm.hpp>

namespace rtdr {

// The planes the splat reads, all of one size.
struct TrmvSplatPlanes {
  Vec2Plane shadow;          // m^V, motion.shadow [TRMV21 Eq. 3]
  UIntPlane valid;           // motion.shadow.valid
  Vec2Plane surface_motion;  // `motion` [TRMV21 Eq. 1]
  UIntPlane instance;        // id.instance; kInvalidId: no surface
  RgbPlane normal;           // the surface normal, unit
  FloatPlane carried;        // optional (empty: none): a property of the in-shadow pixels, averaged with m^V
};

struct TrmvSplatPixel {
  glm::vec2 motion{0.0f};
  bool landed = false;   // a valid m^V landed: `motion` is their mean, not the surface motion
  float carried = 0.0f;  // the mean of the carried property over the splats that landed (0 without one)
};

struct TrmvSplatOutput {
  Vec2Plane motion;   // the splatted shadow motion
  UIntPlane landed;   // 1 where a vector landed
  FloatPlane carried; // the carried property's mean (0 where none landed)
};

// Pixel q is on pixel p's receiving surface: the same instance, normals within kTrmvSplatNormalCosine.
bool trmv_splat_same_surface(const TrmvSplatPlanes& in, int px, int py, int qx, int qy);

// The golden per-pixel function: the splatted motion at pixel (x, y), window side `size`.
TrmvSplatPixel trmv_splat_pixel(const TrmvSplatPlanes& in, int size, int x, int y, Probe* probe = nullptr);

// Throws rtdr::Error unless the planes share a size (the carried one when given) and `size` is odd and at least 1:
// the checks of trmv_splat_pass, which its port makes too (gpu/trmv_splat_gpu.h).
void check_trmv_splat_inputs(const TrmvSplatPlanes& in, int size);

// Every pixel's splatted motion (parallel over rows, deterministic). `size` is the window's side.
TrmvSplatOutput trmv_splat_pass(const TrmvSplatPlanes& in, int size);

}  // namespace rtdr
