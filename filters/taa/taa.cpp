// Temporal antialiasing after Karis14: reproject the history, clip it to the current 3x3 YCoCg box, blend.
// The method, the jitter convention and the deviations from Karis14 are in taa.h.
#include "filters/taa/taa.h"

#include "core/error.h"
#include "core/parallel.h"
#include "filters/taa/taa_shared.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace rtdr {

std::vector<ParamInfo> taa_param_table() { return {RTDR_TAA_PARAMS(RTDR_PARAM_ROW)}; }
std::vector<double> param_values(const TaaParams& params) { return {RTDR_TAA_PARAMS(RTDR_PARAM_VALUE)}; }
void validate(const TaaParams& p) { check_params("taa", taa_param_table(), param_values(p)); }
std::string describe(const TaaParams& p) { return describe_params(taa_param_table(), param_values(p)); }

float halton(int index, int base) {
  // Write index in `base` and mirror its digits behind the point: 6 = 110 in base 2 -> 0.011 = 3/8.
  float digit_weight = 1.0f;
  float value = 0.0f;
  while (index > 0) {
    digit_weight /= float(base);               // 1/base, 1/base^2, ... for the 1st, 2nd, ... digit
    value += digit_weight * float(index % base);  // the lowest remaining digit goes right after the point
    index /= base;
  }
  return value;
}

glm::vec2 taa_jitter(int frame, int period) {
  const int wrapped = ((frame % period) + period) % period;  // in [0, period), also for negative frames
  const int index = wrapped + 1;                             // skip index 0, the pixel corner (0, 0)
  return glm::vec2(halton(index, 2), halton(index, 3)) - 0.5f;
}

glm::vec3 rgb_to_ycocg(const glm::vec3& rgb) {
  // [Malvar and Sullivan 2003]: Y = R/4 + G/2 + B/4, Co = R/2 - B/2, Cg = -R/4 + G/2 - B/4.
  return {0.25f * rgb.r + 0.5f * rgb.g + 0.25f * rgb.b,  //
          0.5f * rgb.r - 0.5f * rgb.b,                   //
          -0.25f * rgb.r + 0.5f * rgb.g - 0.25f * rgb.b};
}

glm::vec3 ycocg_to_rgb(const glm::vec3& ycocg) {
  // The inverse [Malvar and Sullivan 2003]: R = Y + Co - Cg, G = Y + Cg, B = Y - Co - Cg.
  const float Y = ycocg.x, Co = ycocg.y, Cg = ycocg.z;
  return {Y + Co - Cg, Y + Cg, Y - Co - Cg};
}

glm::vec2 jitter_free_motion(glm::vec2 motion, const TaaJitter& jitter) {
  // The renderer's motion is between the two jittered screens; remove the jitter change (taa.h).
  return motion - (jitter.previous - jitter.current);
}

glm::vec2 taa_history_position(int x, int y, glm::vec2 motion, const TaaJitter& jitter) {
  // The content at this pixel's centre was at centre + m0 in the last (un-jittered) output.
  return glm::vec2(float(x) + 0.5f, float(y) + 0.5f) + jitter_free_motion(motion, jitter);
}

glm::vec3 sample_bilinear(const RgbPlane& plane, glm::vec2 position, Probe* probe) {
  // In "index space" pixel i's centre is at i: the four centres around the position are the taps.
  const glm::vec2 u = position - 0.5f;
  const int x0 = int(std::floor(u.x)), y0 = int(std::floor(u.y));
  const float fx = u.x - float(x0), fy = u.y - float(y0);  // fractions towards the right and lower taps
  note(probe, "bilinear top-left tap (x0, y0)", glm::vec2(float(x0), float(y0)), "");
  note(probe, "bilinear fractions (fx, fy)", glm::vec2(fx, fy), "");
  // Weights are the areas of the opposite sub-rectangles; taps off the image repeat the edge pixel.
  return (1.0f - fx) * (1.0f - fy) * at_clamped(plane, x0, y0) + fx * (1.0f - fy) * at_clamped(plane, x0 + 1, y0) +
         (1.0f - fx) * fy * at_clamped(plane, x0, y0 + 1) + fx * fy * at_clamped(plane, x0 + 1, y0 + 1);
}

// The history colour clipped along the line towards the neighbourhood mean [Karis14 history clip], onto the box
// padded by e = kTaaClipPadding on every face (taa_shared.h): without the padding, where the box is flat in a
// channel, t jumps from 1 to 0 as the history crosses the face; with it, t is continuous and the output moves by
// at most |dh| (1 + |h - mean| / e) when the history moves by dh.
glm::vec3 clip_towards_mean(const glm::vec3& history, const glm::vec3& mean, const glm::vec3& box_min,
                            const glm::vec3& box_max, Probe* probe) {
  // Walk from the mean towards the history: mean + t (history - mean), t in [0, 1]. Each face the history is
  // beyond stops the walk where the segment crosses it; the first crossing (smallest t) is on the box.
  float t = 1.0f;
  for (int i = 0; i < 3; ++i) {
    const float d = history[i] - mean[i];
    const float face_max = box_max[i] + kTaaClipPadding;  // at least e beyond the mean: d >= e where it clips
    const float face_min = box_min[i] - kTaaClipPadding;
    if (history[i] > face_max) t = std::min(t, (face_max - mean[i]) / d);  // d > 0: mean < face_max < history
    if (history[i] < face_min) t = std::min(t, (face_min - mean[i]) / d);  // d < 0: history < face_min < mean
  }
  note(probe, "clip t (1: inside the padded box)", t, "Karis14: clip towards the mean; padding taa_shared.h");
  return mean + t * (history - mean);
}

glm::vec3 taa_pixel(const RgbPlane& current, const RgbPlane& history, const Vec2Plane& motion, int x, int y,
                    const TaaParams& params, const TaaJitter& jitter, Probe* probe) {
  const glm::vec3 c = current.at(x, y);
  note(probe, "current RGB", c, "");

  // 1. Reprojection: where this pixel's content was in the last output [Karis14; TRMV21 Eq. 1 for m].
  note(probe, "motion m", motion.at(x, y), "TRMV21 Eq. 1, between jittered screens");
  note(probe, "jitter-free motion m0 = m - (j_prev - j_cur)", jitter_free_motion(motion.at(x, y), jitter), "taa.h");
  const glm::vec2 q = taa_history_position(x, y, motion.at(x, y), jitter);
  note(probe, "history position pixel centre + m0", q, "taa.h: jitter and motion");
  const bool history_on_screen =
      history.width > 0 && q.x >= 0.0f && q.y >= 0.0f && q.x < float(history.width) && q.y < float(history.height);
  note(probe, "history on screen", history_on_screen ? 1.0f : 0.0f, "");
  if (!history_on_screen) return c;  // no history to trust: the current colour alone
  const glm::vec3 h = sample_bilinear(history, q, probe);
  note(probe, "history RGB (bilinear)", h, "Karis14 uses Catmull-Rom; bilinear here (taa.h)");

  // 2. The 3x3 neighbourhood of the current frame, in YCoCg: its box (min, max) and its mean [Karis14].
  constexpr float inf = std::numeric_limits<float>::infinity();
  glm::vec3 box_min(inf), box_max(-inf), sum(0.0f);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const glm::vec3 s = rgb_to_ycocg(at_clamped(current, x + dx, y + dy));  // the image edge repeats
      box_min = glm::min(box_min, s);
      box_max = glm::max(box_max, s);
      sum += s;
    }
  }
  // The float mean of equal values can land an ulp outside their box; keep it inside so the clip is defined.
  const glm::vec3 mean = glm::clamp(sum / 9.0f, box_min, box_max);
  note(probe, "box min (YCoCg)", box_min, "Karis14: 3x3 neighbourhood");
  note(probe, "box max (YCoCg)", box_max, "Karis14: 3x3 neighbourhood");
  note(probe, "box mean (YCoCg)", mean, "Karis14: 3x3 neighbourhood");
  const glm::vec3 c_ycocg = rgb_to_ycocg(c);
  const glm::vec3 h_ycocg = rgb_to_ycocg(h);
  note(probe, "current (YCoCg)", c_ycocg, "Malvar and Sullivan 2003");
  note(probe, "history (YCoCg)", h_ycocg, "Malvar and Sullivan 2003");

  // 3. Bound the history: clip along the line to the mean (Karis14), or clamp each component.
  const glm::vec3 h_bounded = params.clip_history ? clip_towards_mean(h_ycocg, mean, box_min, box_max, probe)
                                                  : glm::clamp(h_ycocg, box_min, box_max);
  note(probe, params.clip_history ? "history clipped (YCoCg)" : "history clamped (YCoCg)", h_bounded, "Karis14");

  // 4. Exponential moving average: alpha of the current frame, 1 - alpha of the bounded history [Karis14].
  const glm::vec3 blended = params.alpha * c_ycocg + (1.0f - params.alpha) * h_bounded;
  note(probe, "blend alpha c + (1 - alpha) h (YCoCg)", blended, "Karis14; alpha from Salvi 2016");
  const glm::vec3 out = ycocg_to_rgb(blended);
  note(probe, "output RGB", out, "");
  return out;
}

RgbPlane taa_pass(const RgbPlane& current, const RgbPlane& history, const Vec2Plane& motion, const TaaParams& params,
                  const TaaJitter& jitter) {
  validate(params);
  const std::string size = std::to_string(current.width) + "x" + std::to_string(current.height);
  if (motion.width != current.width || motion.height != current.height)
    throw Error("taa: motion must have the current frame's size " + size);
  if (history.width != 0 && (history.width != current.width || history.height != current.height))
    throw Error("taa: history must have the current frame's size " + size + " or be empty");
  RgbPlane out(current.width, current.height);
  parallel_rows(current.height, [&](int y) {
    for (int x = 0; x < current.width; ++x) out.at(x, y) = taa_pixel(current, history, motion, x, y, params, jitter);
  });
  return out;
}

}  // namespace rtdr
