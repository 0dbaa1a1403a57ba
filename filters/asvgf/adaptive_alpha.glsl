// GLSL mirror of filters/asvgf/adaptive_alpha.h's helpers, for the ports that form A-SVGF's ratios and weights
// (adaptive_alpha.comp, and gradient_image.comp when it normalises per sample): #include
// "filters/asvgf/adaptive_alpha.glsl". GPU only: every result is `precise`, so no fma contraction or reordering
// changes the rounding; the C++ rounds after each operation in the same order.
#ifndef RTDR_FILTERS_ASVGF_ADAPTIVE_ALPHA_GLSL
#define RTDR_FILTERS_ASVGF_ADAPTIVE_ALPHA_GLSL

// min(1, k (|delta| / Delta)^p), 0 where Delta <= 0, p = 1 or 2 (gradient_ratio): lambda of [ASVGF18 Eq. 14] for
// p = k = 1.
float gradient_ratio(float delta, float norm, int exponent, float scale) {
  if (!(norm > 0.0)) return 0.0;
  precise float q = abs(delta) / norm;
  if (exponent == 2) {
    precise float squared = q * q;  // Q2RTX: "make small changes less significant"
    q = squared;
  }
  precise float scaled = scale * q;
  return min(1.0, scaled);
}

// alpha_i = (1 - lambda) alpha + lambda [ASVGF18 Eq. 15] (adaptive_alpha).
float adaptive_alpha(float alpha, float lambda) {
  precise float alpha_i = (1.0 - lambda) * alpha + lambda;
  return alpha_i;
}

#endif  // RTDR_FILTERS_ASVGF_ADAPTIVE_ALPHA_GLSL
