// Temporal antialiasing [Karis14: B. Karis, "High Quality Temporal Supersampling", SIGGRAPH 2014 course
// "Advances in Real-Time Rendering in Games"], the last pass of SVGF [SVGF17 Sec. 3, "Post Processing"].
//
// Pass: taa_pass(current, history, motion, params, jitter) -> output, which is also the next frame's history.
//   in:  current = this frame's tone-mapped display colour in [0, 1] (tonemap.h), rendered with sub-pixel
//        jitter j_cur; history = last frame's TAA output (empty on the first frame); motion = the G-buffer's
//        motion.X/Y (docs/buffers.md); the jitter of this frame and of the previous one (TaaJitter)
//   out: antialiased display colour, un-jittered: pixel p estimates the average over its square [p, p+1)
//
// Per pixel: (1) reproject: read the history, bilinearly, where this pixel's content was last frame;
// (2) bound it: the 3x3 neighbourhood of the current frame, in YCoCg, gives an axis-aligned box (min,
// max); a history outside it is stale (disocclusion, changed shading) and is clipped onto the box (padded
// by 1/1024, see the deviations) along the line towards the neighbourhood mean [Karis14] (or clamped per
// component); (3) blend: an exponential moving average with weight alpha on the current frame; (4) back to RGB.
//
// Display space. TAA runs after tone mapping, the order of SVGF17 Sec. 3 (Fig. 2): averaged HDR values let
// rare very bright samples dominate and flicker, and the box around a bright edge would be huge. Karis14
// makes the same point for HDR input, weighting samples by 1 / (1 + luma) to approximate blending after a
// tone map; here the blend simply happens after one. Inputs are expected in [0, 1].
//
// Jitter and motion, exactly. make_view (raster/view.h) moves the projected image by j pixels, so the sample
// at pixel centre c = p + (0.5, 0.5) sees what an un-jittered camera sees at c - j. The renderer's motion
// m = x_{i-1} - x_i (motion/backproject.h) is measured between the two frames' JITTERED screens, so for a
// static scene and camera m = j_prev - j_cur, not 0. TAA wants the jitter-free motion
//     m0 = m - (j_prev - j_cur)
// because both the history and the output are un-jittered images: the content at c now was at c + m0
// in the last output. Without this correction a static image would be resampled at a new sub-pixel offset
// every frame and blur. If your motion vectors are already jitter-free, pass TaaJitter{} (both zero).
// The current sample is used for pixel p as it is, without re-centring: its offset -j_cur lies inside the
// pixel's square, and averaging over the jitter sequence is what box-filters the square (the supersampling).
//
// Deviations from Karis14 (each a simplification a port may upgrade, except the padded clip, which keeps the
// ports within a bound of this reference):
// - History fetch is bilinear; Karis14 fetches with a Catmull-Rom (bicubic) filter, sharper under motion.
//   Bilinear blurs a moving image a little more each frame, but is exact for the linear ramps we test on.
// - The box is the plain 3x3 min/max; Karis14 also blends it with the 5-tap "plus" box to round it off.
// - The clip's box is padded by e = kTaaClipPadding = 1/1024 on every face (taa_shared.h). Karis14 clips onto the
//   bare box, which jumps where the box is flat in a channel (any grey neighbourhood's Co and Cg): a history on
//   the face is kept, one an ulp beyond it is replaced by the mean. Padded, the clip is continuous, and an error
//   dh in the history moves the output by at most |dh| (1 + |h - mean| / e), so a GPU port an ulp off the golden
//   function stays within a bound of it (tests/gpu_svgf_test.cpp). The cost: a history up to e (a quarter of an
//   8-bit step) outside the box survives.
// - The motion vector is this pixel's; Karis14 takes the one of the nearest depth in the 3x3 (edge dilation).
// - No luminance-weighted blend (Karis14's 1 / (1 + luma)): we are already in display space.
// - The current colour is not filtered to the pixel centre (Karis14 resolves it with a Blackman-Harris fit).
// - Missing or off-screen history: the output is the current colour (no spatial fallback).
//
// Every tunable, declared once: X(type, name, default, min, max, symbol, source), as in svgf_params.h.
#pragma once

#define RTDR_TAA_PARAMS(X)                                                                                          \
  X(float, alpha, 0.1f, 0.0f, 1.0f, "alpha",                                                                          \
    "weight of the current frame: 'Typically we blend 10% of the current frame' (Salvi 2016, GDC, "                  \
    "'An Excursion in Temporal Supersampling')")                                                                     \
  X(int, clip_history, 1, 0, 1, "",                                                                                   \
    "1: clip the history towards the 3x3 mean onto the padded YCoCg box (Karis14); 0: clamp each YCoCg component")   \
  X(int, jitter_period, 8, 1, 1 << 20, "",                                                                            \
    "Halton(2,3) points before the jitter repeats; 8 as in Unreal Engine 4's TAA, the TAA of Karis14")

#include "filters/image.h"
#include "filters/probe.h"
#include "filters/params.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace rtdr {

struct TaaParams {
  RTDR_TAA_PARAMS(RTDR_PARAM_FIELD)
};

std::vector<ParamInfo> taa_param_table();
std::vector<double> param_values(const TaaParams& params);
// Throws rtdr::Error naming the first parameter outside its range.
void validate(const TaaParams& p);
std::string describe(const TaaParams& p);

// The sub-pixel jitter of this frame and of the previous one, in pixels: each is View::jitter
// (raster/view.h), e.g. taa_jitter(frame) and taa_jitter(frame - 1). Both zero when motion is jitter-free.
struct TaaJitter {
  glm::vec2 current{0.0f};
  glm::vec2 previous{0.0f};
};

// Frame `frame`'s jitter in [-0.5, 0.5)^2 pixels: the Halton points of bases 2 and 3 [Halton and Smith 1964,
// as cited by SVGF17 Sec. 3] minus 0.5, with index (frame mod period) + 1 (index 0 is (0, 0) in every base:
// it would sample a pixel corner).
// Frame 0 -> (1/2, 1/3) - 0.5 = (0, -1/6), frame 1 -> (1/4, 2/3) - 0.5, ...; negative frames wrap too.
glm::vec2 taa_jitter(int frame, int period = TaaParams{}.jitter_period);
// The radical inverse of index in `base`: its digits mirrored behind the point (Halton's sequence).
float halton(int index, int base);

// YCoCg [Malvar and Sullivan 2003, JVT-I014]: luma Y and two chroma differences, a linear map of RGB.
// Y = R/4 + G/2 + B/4, Co = R/2 - B/2, Cg = -R/4 + G/2 - B/4; the inverse is R = Y + Co - Cg,
// G = Y + Cg, B = Y - Co - Cg. Karis14 bounds the history in YCoCg: luma and chroma get their own extents.
glm::vec3 rgb_to_ycocg(const glm::vec3& rgb);
glm::vec3 ycocg_to_rgb(const glm::vec3& ycocg);

// The renderer's motion between jittered screens made jitter-free: m0 = m - (j_prev - j_cur) (see above).
glm::vec2 jitter_free_motion(glm::vec2 motion, const TaaJitter& jitter);
// Where pixel (x, y)'s content was in the previous (un-jittered) output, in screen units: pixel centre + m0.
glm::vec2 taa_history_position(int x, int y, glm::vec2 motion, const TaaJitter& jitter);
// The bilinear value of `plane` at screen position `position` (pixel centres at +0.5), taps clamped to the
// image. The caller checks that the position is on screen.
glm::vec3 sample_bilinear(const RgbPlane& plane, glm::vec2 position, Probe* probe = nullptr);
// The point where the segment from `mean` (inside the box) to `history` leaves the padded box
// [box_min - e, box_max + e], e = kTaaClipPadding (taa_shared.h); `history` itself when it is inside. Karis14's
// "clip" (against "clamp", which moves each component alone), padded so that it is continuous in its inputs.
glm::vec3 clip_towards_mean(const glm::vec3& history, const glm::vec3& mean, const glm::vec3& box_min,
                            const glm::vec3& box_max, Probe* probe = nullptr);

// The golden per-pixel function. `history` may be empty (width 0): then, as when the history position is
// off screen, the output is the current colour.
glm::vec3 taa_pixel(const RgbPlane& current, const RgbPlane& history, const Vec2Plane& motion, int x, int y,
                    const TaaParams& params, const TaaJitter& jitter = {}, Probe* probe = nullptr);

// taa_pixel over a frame. motion must have current's size, history current's size or none (throws rtdr::Error).
RgbPlane taa_pass(const RgbPlane& current, const RgbPlane& history, const Vec2Plane& motion, const TaaParams& params,
                  const TaaJitter& jitter = {});

}  // namespace rtdr
