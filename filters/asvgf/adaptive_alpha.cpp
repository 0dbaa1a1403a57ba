// The adaptive temporal weight [ASVGF18 Sec. 3.5, Eq. 14-15]. See adaptive_alpha.h.
#include "filters/asvgf/adaptive_alpha.h"

#include "core/parallel.h"

#include <algorithm>
#include <cmath>

namespace rtdr {

float gradient_ratio(float delta, float norm, int exponent, float scale) {
  // min(1, k (|delta| / Delta)^p); no sample in reach (Delta = 0): 0. p = k = 1 is Eq. 14 exactly (1 q = q).
  if (!(norm > 0.0f)) return 0.0f;
  float q = std::abs(delta) / norm;
  if (exponent == 2) q = q * q;  // Q2RTX: "make small changes less significant"
  return std::min(1.0f, scale * q);
}

float gradient_lambda(float delta, float norm) {
  // lambda(p) = min(1, |delta^(p)| / Delta^(p)) [ASVGF18 Eq. 14]; no sample in reach (Delta^ = 0): 0.
  return gradient_ratio(delta, norm, 1, 1.0f);
}

float adaptive_alpha(float alpha, float lambda) {
  // alpha_i(p) = (1 - lambda(p)) alpha + lambda(p) [ASVGF18 Eq. 15].
  return (1.0f - lambda) * alpha + lambda;
}

AdaptiveAlphaPixel adaptive_alpha_pixel(const GradientValues& g, int s, const AdaptiveAlphaParams& params, int x,
                                        int y, Probe* probe) {
  const int sx = x / s, sy = y / s, radius = params.radius;
  note(probe, "stratum", glm::vec2(float(sx), float(sy)), "[ASVGF18 Sec. 3.3]");
  // The maximum over the (2r + 1)^2 strata around (sx, sy) [ASVGF18 Sec. 3.5].
  AdaptiveAlphaPixel out;
  for (int qy = sy - radius; qy <= sy + radius; ++qy)
    for (int qx = sx - radius; qx <= sx + radius; ++qx) {
      if (!inside(g.norm, qx, qy)) continue;
      const float lambda = gradient_ratio(g.delta.at(qx, qy), g.norm.at(qx, qy), params.exponent, params.scale);
      if (probe && qx == sx && qy == sy) {
        note(probe, "delta^(p)", g.delta.at(qx, qy), "[ASVGF18 Eq. 12]");
        note(probe, "Delta^(p)", g.norm.at(qx, qy), "[ASVGF18 Eq. 12, Eq. 13]");
        note(probe, "p, k", glm::vec2(float(params.exponent), params.scale), "gradient_exponent, gradient_scale");
        note(probe, "lambda(p)", lambda, "[ASVGF18 Eq. 14] min(1, k (|delta^| / Delta^)^p)");
      }
      out.lambda_max = std::max(out.lambda_max, lambda);
    }
  note(probe, "max lambda over the strata around p", out.lambda_max, "[ASVGF18 Sec. 3.5]");
  // Eq. 15 for the colour and, with the same lambda, for the moments: what the temporal pass reads.
  out.alpha = adaptive_alpha(params.alpha, out.lambda_max);
  out.alpha_moments = adaptive_alpha(params.alpha_moments, out.lambda_max);
  note(probe, "alpha", params.alpha, "[ASVGF18 Sec. 5]");
  note(probe, "alpha_i", out.alpha, "[ASVGF18 Eq. 15]");
  note(probe, "alpha_mu", params.alpha_moments, "the moments' base weight");
  note(probe, "alpha_mu_i", out.alpha_moments, "[ASVGF18 Eq. 15] for the moments");
  return out;
}

AdaptiveAlpha adaptive_alpha_pass(const GradientValues& g, int s, int width, int height,
                                  const AdaptiveAlphaParams& params) {
  AdaptiveAlpha out{FloatPlane(g.norm.width, g.norm.height), FloatPlane(width, height), FloatPlane(width, height),
                    FloatPlane(width, height)};
  for (int sy = 0; sy < g.norm.height; ++sy)
    for (int sx = 0; sx < g.norm.width; ++sx)
      out.lambda.at(sx, sy) = gradient_ratio(g.delta.at(sx, sy), g.norm.at(sx, sy), params.exponent, params.scale);
  parallel_rows(height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const AdaptiveAlphaPixel p = adaptive_alpha_pixel(g, s, params, x, y);
      out.lambda_max.at(x, y) = p.lambda_max;
      out.alpha.at(x, y) = p.alpha;
      out.alpha_moments.at(x, y) = p.alpha_moments;
    }
  });
  return out;
}

}  // namespace rtdr
