// TRMV's window sizes at any resolution, from the paper's 1920x1080 [TRMV21 Sec. 6]: the rules and why,
// filters/trmv/footprint.h.
#include "filters/trmv/footprint.h"

#include <algorithm>
#include <cmath>

namespace rtdr {

double trmv_size_scale(int height, int footprint_height) { return double(height) / double(footprint_height); }

int trmv_scaled_radius(int radius, int height, int footprint_height) {
  if (radius == 0) return 0;  // the identity stays the identity
  // The side S = 2 r + 1 scaled by H / H_0, then the nearest odd side, at least 3x3 (footprint.h).
  const double side = double(2 * radius + 1) * trmv_size_scale(height, footprint_height);
  return std::max(1, int(std::lround((side - 1.0) / 2.0)));
}

float trmv_scaled_sigma(float sigma, int radius, int height, int footprint_height) {
  if (radius == 0) return sigma;
  // sigma_H = sigma r_H / r: +-3 std fills the scaled window as +-3 std fills it at H_0 (spatial_sigma = r / 3).
  return sigma * float(trmv_scaled_radius(radius, height, footprint_height)) / float(radius);
}

int trmv_scaled_levels(int levels, int height, int footprint_height) {
  // Levels 0..L-1 of a 3x3 kernel, taps 2^i apart, reach 2^L - 1 pixels each way: side 2^(L+1) - 1.
  const double side = (std::ldexp(1.0, levels + 1) - 1.0) * trmv_size_scale(height, footprint_height);
  return std::max(1, int(std::lround(std::log2(side + 1.0) - 1.0)));
}

int trmv_scaled_side(int side, int height, int footprint_height) {
  return 2 * trmv_scaled_radius((side - 1) / 2, height, footprint_height) + 1;
}

TrmvWindows trmv_windows(const TrmvParams& p, int height) {
  const int h0 = p.footprint_height;
  TrmvWindows w;
  w.shadow_radius = trmv_scaled_radius(p.spatial_radius, height, h0);
  w.shadow_sigma = trmv_scaled_sigma(p.spatial_sigma, p.spatial_radius, height, h0);
  // The splat's window is the shadow filter's fixed one [TRMV21 Sec. 4.1], unless splat_size names another.
  w.splat_size = p.splat_size == 0 ? 2 * w.shadow_radius + 1 : trmv_scaled_side(p.splat_size, height, h0);
  w.atrous_levels = trmv_scaled_levels(p.atrous_levels, height, h0);
  w.glossy_radius = trmv_scaled_radius(p.glossy_radius, height, h0);
  w.cleanup_radius = trmv_scaled_radius((p.cleanup_size - 1) / 2, height, h0);
  return w;
}

}  // namespace rtdr
