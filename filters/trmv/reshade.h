// TRMV's cones at work [TRMV21 Sec. 4.3, Sec. 5, Eq. 11]: per pixel, six cones of incident diffuse radiance,
// filtered in space and accumulated in time; at a disoccluded pixel, the history re-shaded from the cones found
// along the dual motion vector, with the pixel's own normal.
//
// Pass: trmv_reshade_pass(inputs, surface, dual, prev, layout, params) -> the cone history, the re-shaded
//       history and where it applies.
//   in:  this frame's path sample at the primary hit (path.direction, path.incoming, path.pdf: one direction w,
//        the indirect radiance arriving along it, its pdf); the surface (normal, depth, id.mesh, motion); the dual
//        motion (motion.dual and motion.dual.valid, motion/dual.h); last frame's cone history; the spatial filter
//        (the diffuse light's: TrmvParams::diffuse_filter, with the frame's TrmvWindows)
//   out: the six cones of every pixel, this frame's history (next frame reads it);
//        reshaded = L_o of [TRMV21 Eq. 11] (the corrected form, cones.h) at every pixel whose dual vector applies,
//        from the previous cones at x^O carried to this pixel's normal; reshaded_valid = 1 there
//
// Per cone k, the steps of the paper's other components, in its order (filter, then accumulate) [TRMV21 Sec. 5]:
//   Lhat_k   one path sample's estimate of cone k's mean radiance (add_cone_sample, cones.h)
//   L~_k     the diffuse light's spatial filter of Lhat_k (the 4-level a-trous, atrous.h): "spatial ... filtering
//            for each cone individually"
//   Lbar_k   = alpha L~_k + (1 - alpha) H_k                                         [TRMV21 Eq. 2, per cone]
// where the history H_k is last frame's Lbar_k fetched bilinearly along the surface motion (SVGF's consistency
// test, temporal.h), except at a pixel the dual vector marks disoccluded: there H_k = f_k L'_k + (1 - f_k) L~_k,
// L' = transfer_cones(Lbar at x^O, from the normal there to this pixel's) [TRMV21 Sec. 4.3, Eq. 9-10], the cones
// of the surface seen beside the occluder, re-oriented, for the share f_k of each cone that the source's hemisphere
// covers, and the pixel's own filtered cone for the rest [TRMV21 Sec. 4.3, Fig. 7] (cones.h).
//
// The diffuse component's temporal pass (temporal.h) then takes, at those pixels, reshade_cones of that H as its
// history instead of the colour at x^O: the history carries the radiance arriving there, and the pixel shades it
// with its own normal, so a wall's history no longer repeats a box's shading (TRMV21 Fig. 6).
//
// Choices the paper leaves open (filters/trmv/README.md, "Deviations and choices"):
// - The cones' history is not clamped: the re-shaded value passes through the diffuse component's clamp, which
//   is where the paper clamps ("per cone" clamping would need each cone's own noisy neighbourhood).
// - "The overlapping solid angles between each pair of cones as the filtering weight" is used where normals
//   differ, at the transfer (cones.h); the spatial filter weighs cone k of a neighbour against cone k of the
//   pixel, with SVGF's normal weight standing in for the overlap of nearly equal normals.
// - x^O's cones are read at the nearest pixel, floor(x^O), with that pixel's normal, where it shows the pixel's own
//   mesh (the dual vector's test, temporal.h); another mesh or none there, or x^O off the previous image: the pixel
//   has no re-shaded history (the temporal pass then takes the spatial result alone).
// - The re-shading is Lambert's (f_r = 1/pi on demodulated values), the diffuse lobe without the albedo
//   scaling of trace/brdf.h: the two differ by the specular layer's share, 1-4 % at roughness 1 (trace/README.md).
#pragma once

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/surface_planes.h"
#include "filters/svgf/svgf_params.h"
#include "filters/trmv/cones.h"
#include "filters/trmv/temporal.h"
#include "filters/trmv/trmv_params.h"

#include <array>

namespace rtdr {

// The path sample of each pixel that the cones are estimated from (the path.* layers of docs/buffers.md).
struct TrmvConeInputs {
  RgbPlane direction;  // path.direction: w, unit, world space (0 where no ray was traced)
  RgbPlane incoming;   // path.incoming: L_in(w), not demodulated
  FloatPlane pdf;      // path.pdf: p(w), per steradian

  static TrmvConeInputs from_frame(const Frame& frame);  // throws rtdr::Error naming a missing layer
};

// The cones of every pixel, and what the next frame needs to read them: the normal each pixel's cones are
// oriented around, and the G-buffer (the history tests). Empty: first frame.
struct TrmvConeHistory {
  std::array<RgbPlane, kConeCount> cones;
  RgbPlane normal;
  SurfacePlanes surface;
  bool empty() const { return cones[0].width == 0; }
};

// The spatial filter the cones get: the diffuse light's (TrmvParams::diffuse_filter), at the frame's windows.
struct TrmvConeFilter {
  bool atrous = true;   // the a-trous (atrous.h), else the separable bilateral (spatial.h)
  int levels = 4;       // the a-trous's levels
  int radius = 15;      // the bilateral's radius and std
  float sigma = 5.0f;
};

struct TrmvReshadeOutput {
  TrmvConeHistory history;  // Lbar_k of this frame
  std::array<RgbPlane, kConeCount> filtered;  // L~_k of this frame (for the probe)
  RgbPlane reshaded;        // the diffuse history re-shaded from the cones at x^O [TRMV21 Eq. 11]; 0 elsewhere
  UIntPlane reshaded_valid; // 1 where `reshaded` applies
};

// One pixel's cone estimates from its path sample (add_cone_sample, cones.h); all 0 without a sample.
ConeValues trmv_cone_estimate(const ConeLayout& layout, glm::vec3 normal, glm::vec3 direction, glm::vec3 incoming,
                              float pdf);
// The history of pixel (x, y)'s cones at a disoccluded pixel: the previous cones at x^O carried to the pixel's
// normal (transfer_cones) and blended with `current`, the pixel's own filtered cones, by each cone's share
// (blend_transferred; `full`: the former full transfer, cones.h); false when floor(x^O) is off the previous image
// or does not show the pixel's mesh.
bool trmv_cones_at(const TrmvConeHistory& prev, const ConeLayout& layout, glm::vec2 x_o, const SurfacePlanes& surface,
                   int x, int y, const ConeValues& current, bool full, ConeValues& out, Probe* probe = nullptr);
// The golden per-pixel re-shading: reshade_cones of trmv_cones_at at x^O = pixel centre + the dual vector.
bool trmv_reshade_pixel(const TrmvConeHistory& prev, const ConeLayout& layout, const SurfacePlanes& surface,
                        const TrmvMotion& dual, const ConeValues& current, bool full, int x, int y, glm::vec3& out,
                        Probe* probe = nullptr);
// Each pixel's filtered cones L~_k, from its path sample (the estimate, then the spatial filter per cone).
std::array<RgbPlane, kConeCount> trmv_filtered_cones(const TrmvConeInputs& inputs, const SurfacePlanes& surface,
                                                     const ConeLayout& layout, const TrmvConeFilter& filter,
                                                     const SvgfParams& svgf);
// The cones of pixel (x, y) from the filtered planes.
ConeValues trmv_cones_of(const std::array<RgbPlane, kConeCount>& cones, int x, int y);

TrmvReshadeOutput trmv_reshade_pass(const TrmvConeInputs& inputs, const SurfacePlanes& surface,
                                    const TrmvMotion& dual, const TrmvConeHistory& prev, const ConeLayout& layout,
                                    const TrmvConeFilter& filter, const TrmvParams& params, const SvgfParams& svgf);

}  // namespace rtdr
