// Temporal antialiasing after Karis14, the Vulkan port of taa_pixel (taa.cpp), line for line: reproject the
// history (pixel centre + m - (j_prev - j_cur)), fetch it bilinearly, bound it by the current 3x3 YCoCg box
// (clip towards the mean onto the box padded by kTaaClipPadding, or clamp), blend alpha * current +
// (1 - alpha) * history. Missing or off-screen history: the current colour. One invocation per pixel.
//   in:  bindings 0-2: current, history (colour records), motion; out: binding 3: output. Layout:
//   filters/svgf/planes_shared.h, taa_shared.h.
// GPU only: every arithmetic result is `precise`, so no fma contraction changes the rounding; the C++ rounds
// after each operation in the same order.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "filters/taa/taa_shared.h"

// The workgroup's shape, fixed by the host per device (taa_shared.h).
layout(local_size_x_id = kTaaGroupSizeXConstant, local_size_y_id = kTaaGroupSizeYConstant,
       local_size_x = kTaaGroupSizeX, local_size_y = kTaaGroupSizeY) in;

RTDR_INPUT_RGBA(0, current_in)
RTDR_INPUT_RGBA(1, history_in)
RTDR_INPUT_RG(2, motion_in)
layout(std430, set = 0, binding = 3) writeonly buffer Output { vec4 output_out[]; };

layout(push_constant) uniform Push { TaaPush push; };

// GPU only: the push constants, copied once at the top of main(). lavapipe loads a push constant lane by lane at
// each use; the copy is loaded once.
TaaPush frame;

// filters/image.h's at_clamped: the pixel at (x, y) with x, y clamped into the image.
int index_clamped(int x, int y) { return clamp(y, 0, int(frame.height) - 1) * int(frame.width) + clamp(x, 0, int(frame.width) - 1); }
vec3 current_at_clamped(int x, int y) { return current_in(index_clamped(x, y)).rgb; }
vec3 history_at_clamped(int x, int y) { return history_in(index_clamped(x, y)).rgb; }

vec3 rgb_to_ycocg(vec3 rgb) {
  // [Malvar and Sullivan 2003]: Y = R/4 + G/2 + B/4, Co = R/2 - B/2, Cg = -R/4 + G/2 - B/4.
  precise vec3 ycocg = vec3(0.25 * rgb.r + 0.5 * rgb.g + 0.25 * rgb.b,  //
                            0.5 * rgb.r - 0.5 * rgb.b,                   //
                            -0.25 * rgb.r + 0.5 * rgb.g - 0.25 * rgb.b);
  return ycocg;
}

vec3 ycocg_to_rgb(vec3 ycocg) {
  // The inverse [Malvar and Sullivan 2003]: R = Y + Co - Cg, G = Y + Cg, B = Y - Co - Cg.
  const float Y = ycocg.x, Co = ycocg.y, Cg = ycocg.z;
  precise vec3 rgb = vec3(Y + Co - Cg, Y + Cg, Y - Co - Cg);
  return rgb;
}

vec2 jitter_free_motion(vec2 motion) {
  // The renderer's motion is between the two jittered screens; remove the jitter change (taa.h).
  precise vec2 m0 = motion - (frame.jitter_previous - frame.jitter_current);
  return m0;
}

vec2 taa_history_position(int x, int y, vec2 motion) {
  // The content at this pixel's centre was at centre + m0 in the last (un-jittered) output.
  precise vec2 q = vec2(float(x) + 0.5, float(y) + 0.5) + jitter_free_motion(motion);
  return q;
}

vec3 sample_bilinear(vec2 position) {
  // In "index space" pixel i's centre is at i: the four centres around the position are the taps.
  precise vec2 u = position - 0.5;
  const int x0 = int(floor(u.x)), y0 = int(floor(u.y));
  precise float fx = u.x - float(x0), fy = u.y - float(y0);  // fractions towards the right and lower taps
  // Weights are the areas of the opposite sub-rectangles; taps off the image repeat the edge pixel.
  precise vec3 value = (1.0 - fx) * (1.0 - fy) * history_at_clamped(x0, y0) +
                       fx * (1.0 - fy) * history_at_clamped(x0 + 1, y0) +
                       (1.0 - fx) * fy * history_at_clamped(x0, y0 + 1) + fx * fy * history_at_clamped(x0 + 1, y0 + 1);
  return value;
}

// The history colour clipped along the line towards the neighbourhood mean [Karis14 history clip], onto the box
// padded by e = kTaaClipPadding on every face (taa_shared.h says why: a continuous clip).
vec3 clip_towards_mean(vec3 history, vec3 mean, vec3 box_min, vec3 box_max) {
  // Walk from the mean towards the history: mean + t (history - mean), t in [0, 1]. Each face the history is
  // beyond stops the walk where the segment crosses it; the first crossing (smallest t) is on the box.
  float t = 1.0;
  [[unroll]] for (int i = 0; i < 3; ++i) {
    precise float d = history[i] - mean[i];
    precise float face_max = box_max[i] + kTaaClipPadding;  // at least e beyond the mean: d >= e where it clips
    precise float face_min = box_min[i] - kTaaClipPadding;
    if (history[i] > face_max) {  // d > 0: mean < face_max < history
      precise float t_face = (face_max - mean[i]) / d;
      t = min(t, t_face);
    }
    if (history[i] < face_min) {  // d < 0: history < face_min < mean
      precise float t_face = (face_min - mean[i]) / d;
      t = min(t, t_face);
    }
  }
  precise vec3 clipped = mean + t * (history - mean);
  return clipped;
}

vec3 taa_pixel(int x, int y) {
  const vec3 c = current_at_clamped(x, y);

  // 1. Reprojection: where this pixel's content was in the last output [Karis14; TRMV21 Eq. 1 for m].
  const vec2 q = taa_history_position(x, y, motion_in(y * int(frame.width) + x).xy);
  const bool history_on_screen = frame.has_history != 0u && q.x >= 0.0 && q.y >= 0.0 && q.x < float(frame.width) &&
                                 q.y < float(frame.height);
  if (!history_on_screen) return c;  // no history to trust: the current colour alone
  const vec3 h = sample_bilinear(q);

  // 2. The 3x3 neighbourhood of the current frame, in YCoCg: its box (min, max) and its mean [Karis14].
  const float inf = uintBitsToFloat(0x7f800000u);
  vec3 box_min = vec3(inf), box_max = vec3(-inf);
  precise vec3 sum = vec3(0.0);
  [[unroll]] for (int dy = -1; dy <= 1; ++dy) {
    [[unroll]] for (int dx = -1; dx <= 1; ++dx) {
      const vec3 s = rgb_to_ycocg(current_at_clamped(x + dx, y + dy));  // the image edge repeats
      box_min = min(box_min, s);
      box_max = max(box_max, s);
      sum += s;
    }
  }
  // The float mean of equal values can land an ulp outside their box; keep it inside so the clip is defined.
  precise vec3 sum_over_9 = sum / 9.0;
  const vec3 mean = clamp(sum_over_9, box_min, box_max);
  const vec3 c_ycocg = rgb_to_ycocg(c);
  const vec3 h_ycocg = rgb_to_ycocg(h);

  // 3. Bound the history: clip along the line to the mean (Karis14), or clamp each component.
  const vec3 h_bounded = frame.clip_history != 0u ? clip_towards_mean(h_ycocg, mean, box_min, box_max)
                                                  : clamp(h_ycocg, box_min, box_max);

  // 4. Exponential moving average: alpha of the current frame, 1 - alpha of the bounded history [Karis14].
  precise vec3 blended = frame.alpha * c_ycocg + (1.0 - frame.alpha) * h_bounded;
  const vec3 out_rgb = ycocg_to_rgb(blended);
  return out_rgb;
}

void main() {
  frame = push;  // the push constants, read once (see above)
  // This invocation's pixel; the last tiles overhang the frame.
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= frame.width || pixel.y >= frame.height) return;
  const vec3 out_rgb = taa_pixel(int(pixel.x), int(pixel.y));
  output_out[pixel.y * frame.width + pixel.x] = vec4(out_rgb, 0.0);
}
