// Image metrics: RMSE, relative MSE, SSIM, LDR-FLIP, temporal error and lag. What each one measures, on which
// images, and the sources of every constant are in metrics.h.
#include "eval/metrics.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

namespace rtdr {
namespace {

void check_same_size(const RgbPlane& test, const RgbPlane& reference, const char* metric) {
  if (test.width != reference.width || test.height != reference.height || test.data.empty())
    throw Error(std::string(metric) + ": images must be non-empty and of equal size (test " + std::to_string(test.width) +
                "x" + std::to_string(test.height) + ", reference " + std::to_string(reference.width) + "x" +
                std::to_string(reference.height) + ")");
}

void check_region(const RgbPlane& image, const Region& region, const char* metric) {
  if (region.size() != image.data.size())
    throw Error(std::string(metric) + ": the region has " + std::to_string(region.size()) + " pixels, the image " +
                std::to_string(image.data.size()));
}

// Sum of per-row partial sums in row order: the same result for any thread count.
double sum_rows(const std::vector<double>& row_sums) {
  double total = 0.0;
  for (double s : row_sums) total += s;
  return total;
}

// ---- SSIM [Wang04] ---------------------------------------------------------------------------------------

// The 1D Gaussian window exp(-i^2 / (2 sigma^2)), i in [-radius, radius], normalised to unit sum [Wang04
// Sec. III-C]. The 2D window is the product of two of these, so it also sums to 1.
std::vector<double> gaussian_window(double sigma, int radius) {
  std::vector<double> w(2 * radius + 1);
  double sum = 0.0;
  for (int i = -radius; i <= radius; ++i) sum += w[i + radius] = std::exp(-double(i * i) / (2.0 * sigma * sigma));
  for (double& v : w) v /= sum;
  return w;
}

// Gaussian-weighted sums of x, y, x^2, y^2, xy over a window: the raw moments behind [Wang04 Eq. 14-16].
struct WindowMoments {
  double x = 0, y = 0, xx = 0, yy = 0, xy = 0;
  // One pixel pair (x_i, y_i) with weight w_i.
  void add(double w, double xi, double yi) {
    x += w * xi, y += w * yi, xx += w * xi * xi, yy += w * yi * yi, xy += w * xi * yi;
  }
  // A partial window (already weighted along x), weighted along y.
  void add(double w, const WindowMoments& m) { x += w * m.x, y += w * m.y, xx += w * m.xx, yy += w * m.yy, xy += w * m.xy; }
};

// Mean SSIM of one channel over the pixels whose whole window lies inside the image.
double ssim_channel(const RgbPlane& test, const RgbPlane& reference, int channel) {
  const int W = test.width, H = test.height, r = kSsimRadius;
  const std::vector<double> w = gaussian_window(kSsimSigma, r);
  // C1 = (K1 L)^2, C2 = (K2 L)^2 with the data range L = 1 [Wang04 Eq. 13].
  const double C1 = kSsimK1 * kSsimK1, C2 = kSsimK2 * kSsimK2;
  // Pass 1: along x, the 1D-weighted moments around every column that has r pixels on both sides.
  Plane<WindowMoments> along_x(W, H);
  parallel_rows(H, [&](int py) {
    for (int px = r; px < W - r; ++px)
      for (int k = -r; k <= r; ++k)
        along_x.at(px, py).add(w[k + r], test.at(px + k, py)[channel], reference.at(px + k, py)[channel]);
  });
  // Pass 2: along y, completing the 11x11 window; then SSIM at each interior pixel.
  std::vector<double> row_sums(H, 0.0);
  parallel_rows(H, [&](int py) {
    if (py < r || py >= H - r) return;
    for (int px = r; px < W - r; ++px) {
      WindowMoments m;
      for (int k = -r; k <= r; ++k) m.add(w[k + r], along_x.at(px, py + k));
      // Weighted means, variances and covariance [Wang04 Eq. 14-16]; the weights sum to 1, so
      // sum w (x - mu_x)^2 = sum w x^2 - mu_x^2 (the population form, as Wang04 and scikit-image's
      // use_sample_covariance=False).
      const double mu_x = m.x, mu_y = m.y;
      const double sigma_x2 = m.xx - mu_x * mu_x, sigma_y2 = m.yy - mu_y * mu_y, sigma_xy = m.xy - mu_x * mu_y;
      // SSIM(x, y) = (2 mu_x mu_y + C1)(2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 + sigma_y^2 + C2))
      // [Wang04 Eq. 13].
      row_sums[py] += ((2.0 * mu_x * mu_y + C1) * (2.0 * sigma_xy + C2)) /
                      ((mu_x * mu_x + mu_y * mu_y + C1) * (sigma_x2 + sigma_y2 + C2));
    }
  });
  // Mean SSIM over the interior pixels [Wang04 Eq. 17].
  return sum_rows(row_sums) / (double(W - 2 * r) * double(H - 2 * r));
}

// ---- FLIP [FLIP20] ----------------------------------------------------------------------------------------

// Linear sRGB (Rec. 709 primaries, D65) -> CIE XYZ, the matrix of IEC 61966-2-1:1999 Sec. 5.2; its middle row
// is core/color.h's luminance. Written row by row; glm stores columns, hence the transpose.
const glm::mat3 kRgbToXyz = glm::transpose(glm::mat3(0.4124f, 0.3576f, 0.1805f,    //
                                                     0.2126f, 0.7152f, 0.0722f,    //
                                                     0.0193f, 0.1192f, 0.9505f));  //
const glm::mat3 kXyzToRgb = glm::inverse(kRgbToXyz);
// The reference white (X_n, Y_n, Z_n): D65, i.e. RGB white (1, 1, 1) in XYZ, so white has Cx = Cz = a* = b* = 0.
const glm::vec3 kWhite = kRgbToXyz * glm::vec3(1.0f);

// YCxCz, the linearised opponent space FLIP filters in (Zhang and Wandell's S-CIELAB space, CIELAB without
// the cube root): Y' = 116 Y / Y_n - 16, Cx = 500 (X / X_n - Y / Y_n), Cz = 200 (Y / Y_n - Z / Z_n).
glm::vec3 xyz_to_ycxcz(const glm::vec3& xyz) {
  const glm::vec3 t = xyz / kWhite;
  return {116.0f * t.y - 16.0f, 500.0f * (t.x - t.y), 200.0f * (t.y - t.z)};
}
glm::vec3 ycxcz_to_xyz(const glm::vec3& ycxcz) {
  const float ty = (ycxcz.x + 16.0f) / 116.0f;
  return glm::vec3(ty + ycxcz.y / 500.0f, ty, ty - ycxcz.z / 200.0f) * kWhite;
}

// CIE 1976 L*a*b* (CIE 15:2004 Sec. 8.2.1): f(t) = t^(1/3) above (6/29)^3, else t / (3 (6/29)^2) + 4/29.
glm::vec3 xyz_to_lab(const glm::vec3& xyz) {
  const float delta = 6.0f / 29.0f;
  auto f = [&](float t) { return t > delta * delta * delta ? std::cbrt(t) : t / (3.0f * delta * delta) + 4.0f / 29.0f; };
  const glm::vec3 t = xyz / kWhite;
  return {116.0f * f(t.y) - 16.0f, 500.0f * (f(t.x) - f(t.y)), 200.0f * (f(t.y) - f(t.z))};
}

// Hunt adjustment [FLIP20]: a* <- 0.01 L* a*, b* <- 0.01 L* b*, chroma scaled by L* / 100, so dark colours
// count as less colourful (colourfulness grows with luminance: the Hunt effect).
glm::vec3 hunt(const glm::vec3& lab) { return {lab.x, 0.01f * lab.x * lab.y, 0.01f * lab.x * lab.z}; }

// HyAB colour distance (Abasi, Amani Tehran, Fairchild 2020), used by [FLIP20] for large colour differences:
// city-block in L*, Euclidean in (a*, b*).
float hyab(const glm::vec3& p, const glm::vec3& q) {
  return std::abs(p.x - q.x) + std::hypot(p.y - q.y, p.z - q.z);
}

// FLIP's constants (see metrics.h for where they were checked).
constexpr float kQc = 0.7f;   // q_c: exponent compressing the colour difference
constexpr float kPc = 0.4f;   // p_c: the fraction of c_max below which errors are mapped linearly...
constexpr float kPt = 0.95f;  // p_t: ...onto [0, p_t]; the rest of [0, c_max] goes to (p_t, 1]
constexpr float kQf = 0.5f;   // q_f: exponent of the feature difference
constexpr float kW = 0.082f;  // w: feature width in degrees; the feature filters' sigma is 0.5 w ppd pixels
// The contrast sensitivity functions as sums of Gaussians, S(x) = sum_i a_i sqrt(pi / b_i) exp(-pi^2 x^2 / b_i),
// x in degrees: achromatic (Y'), red-green (Cx) and blue-yellow (Cz) [FLIP20].
struct Csf {
  float a1, b1, a2, b2;
};
constexpr Csf kCsfY{1.0f, 0.0047f, 0.0f, 1e-5f};
constexpr Csf kCsfCx{1.0f, 0.0053f, 0.0f, 1e-5f};
constexpr Csf kCsfCz{34.1f, 0.04f, 13.5f, 0.025f};

// The CSF kernel of one channel as separable terms: K(x, y) = sum_i h_i(x) h_i(y) with
// h_i(x) = sqrt(a_i sqrt(pi / b_i)) exp(-pi^2 x^2 / b_i),
// so K(x, y) = sum_i a_i sqrt(pi / b_i) exp(-pi^2 (x^2 + y^2) / b_i), the CSF's spatial form in 2D.
// K is normalised to unit sum over its (2r + 1)^2 taps by dividing every h_i by sqrt(sum_i (sum_x h_i(x))^2).
std::vector<std::vector<float>> csf_terms(const Csf& csf, double ppd, int radius) {
  const double pi = std::numbers::pi;
  std::vector<std::vector<float>> terms;
  double total = 0.0;  // sum of K over all taps = sum_i (sum_x h_i(x))^2
  for (const auto& [a, b] : {std::pair{csf.a1, csf.b1}, std::pair{csf.a2, csf.b2}}) {
    if (a == 0.0f) continue;  // a_2 = 0: a single Gaussian
    std::vector<float> h(2 * radius + 1);
    double sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
      const double x = i / ppd;  // pixel offset in degrees of visual angle
      sum += h[i + radius] = float(std::sqrt(a * std::sqrt(pi / b)) * std::exp(-pi * pi * x * x / b));
    }
    total += sum * sum;
    terms.push_back(std::move(h));
  }
  for (std::vector<float>& h : terms)
    for (float& v : h) v = float(v / std::sqrt(total));
  return terms;
}

// 2D convolution with the separable kernel hx(x) hy(y), borders clamped to the edge pixel.
FloatPlane convolve_separable(const FloatPlane& in, const std::vector<float>& hx, const std::vector<float>& hy) {
  const int rx = int(hx.size()) / 2, ry = int(hy.size()) / 2;
  FloatPlane along_x(in.width, in.height), out(in.width, in.height);
  parallel_rows(in.height, [&](int y) {
    for (int x = 0; x < in.width; ++x) {
      float s = 0.0f;
      for (int k = -rx; k <= rx; ++k) s += hx[k + rx] * at_clamped(in, x + k, y);
      along_x.at(x, y) = s;
    }
  });
  parallel_rows(in.height, [&](int y) {
    for (int x = 0; x < in.width; ++x) {
      float s = 0.0f;
      for (int k = -ry; k <= ry; ++k) s += hy[k + ry] * at_clamped(along_x, x, y + k);
      out.at(x, y) = s;
    }
  });
  return out;
}

// One channel filtered by its CSF: the sum of its separable terms.
FloatPlane csf_filter(const FloatPlane& channel, const Csf& csf, double ppd, int radius) {
  FloatPlane out(channel.width, channel.height);
  for (const std::vector<float>& h : csf_terms(csf, ppd, radius)) {
    const FloatPlane term = convolve_separable(channel, h, h);
    for (size_t i = 0; i < out.data.size(); ++i) out.data[i] += term.data[i];
  }
  return out;
}

// An image in YCxCz, one plane per channel. Inputs are clamped to [0, 1] first (LDR-FLIP).
std::array<FloatPlane, 3> to_ycxcz(const RgbPlane& rgb) {
  std::array<FloatPlane, 3> out{FloatPlane(rgb.width, rgb.height), FloatPlane(rgb.width, rgb.height),
                                FloatPlane(rgb.width, rgb.height)};
  for (size_t i = 0; i < rgb.data.size(); ++i) {
    const glm::vec3 c = xyz_to_ycxcz(kRgbToXyz * glm::clamp(rgb.data[i], 0.0f, 1.0f));
    for (int k = 0; k < 3; ++k) out[k].data[i] = c[k];
  }
  return out;
}

// Colour pipeline [FLIP20]: CSF-filtered YCxCz -> linear RGB clamped to [0, 1] -> L*a*b* -> Hunt -> HyAB,
// then compressed with q_c and mapped to [0, 1] by (p_c, p_t, c_max). Per-pixel colour error Delta E_c.
FloatPlane colour_error(const std::array<FloatPlane, 3>& test, const std::array<FloatPlane, 3>& reference, double ppd) {
  // Kernel radius: 3 standard deviations of the widest Gaussian; exp(-pi^2 x^2 / b) has sigma sqrt(b / (2 pi^2))
  // degrees, and the largest b is the blue-yellow b_1 = 0.04 (radius 10 pixels at 67 PPD).
  const double pi = std::numbers::pi;
  const int radius = int(std::ceil(3.0 * std::sqrt(double(kCsfCz.b1) / (2.0 * pi * pi)) * ppd));
  const Csf csfs[3] = {kCsfY, kCsfCx, kCsfCz};
  std::array<FloatPlane, 3> ft, fr;
  for (int k = 0; k < 3; ++k) {
    ft[k] = csf_filter(test[k], csfs[k], ppd, radius);
    fr[k] = csf_filter(reference[k], csfs[k], ppd, radius);
  }
  // c_max: the HyAB distance^q_c between pure green and pure blue, the largest in the RGB cube [FLIP20].
  const glm::vec3 green = hunt(xyz_to_lab(kRgbToXyz * glm::vec3(0, 1, 0)));
  const glm::vec3 blue = hunt(xyz_to_lab(kRgbToXyz * glm::vec3(0, 0, 1)));
  const float c_max = std::pow(hyab(green, blue), kQc);
  FloatPlane error(test[0].width, test[0].height);
  parallel_rows(error.height, [&](int y) {
    for (int x = 0; x < error.width; ++x) {
      const size_t i = error.index(x, y);
      // Back to linear RGB, clamped into the cube, then to Hunt-adjusted L*a*b*.
      auto lab_of = [&](const std::array<FloatPlane, 3>& f) {
        const glm::vec3 rgb = kXyzToRgb * ycxcz_to_xyz({f[0].data[i], f[1].data[i], f[2].data[i]});
        return hunt(xyz_to_lab(kRgbToXyz * glm::clamp(rgb, 0.0f, 1.0f)));
      };
      const float delta = std::pow(hyab(lab_of(ft), lab_of(fr)), kQc);
      // Small errors (below p_c c_max) spread over [0, p_t]; the rest is squeezed into (p_t, 1].
      error.at(x, y) = delta < kPc * c_max ? kPt / (kPc * c_max) * delta
                                           : kPt + (delta - kPc * c_max) / (c_max - kPc * c_max) * (1.0f - kPt);
    }
  });
  return error;
}

// The feature filters of [FLIP20]: a Gaussian g, its first derivative -x g (edges) and its second
// derivative (x^2 / sigma^2 - 1) g (points), sigma = 0.5 w ppd pixels, radius ceil(3 sigma). g sums to 1; the
// positive taps of each derivative sum to 1 and the negative taps to -1 (so a flat image gives 0, up to rounding).
// The 2D filters are products: edge_x = (-x g)(x) g(y), point_x = ((x^2/sigma^2 - 1) g)(x) g(y), and the same
// along y; normalising the 1D factors normalises the products the same way.
struct FeatureFilters {
  std::vector<float> g, edge, point;
};
FeatureFilters feature_filters(double ppd) {
  const double sigma = 0.5 * kW * ppd;
  const int radius = int(std::ceil(3.0 * sigma));
  FeatureFilters f{std::vector<float>(2 * radius + 1), {}, {}};
  f.edge = f.point = f.g;
  double g_sum = 0, edge_pos = 0, edge_neg = 0, point_pos = 0, point_neg = 0;
  for (int i = -radius; i <= radius; ++i) {
    const double g = std::exp(-double(i * i) / (2.0 * sigma * sigma));
    const double edge = -i * g, point = (double(i * i) / (sigma * sigma) - 1.0) * g;
    g_sum += g;
    (edge > 0 ? edge_pos : edge_neg) += std::abs(edge);
    (point > 0 ? point_pos : point_neg) += std::abs(point);
    f.g[i + radius] = float(g), f.edge[i + radius] = float(edge), f.point[i + radius] = float(point);
  }
  for (int k = 0; k <= 2 * radius; ++k) {
    f.g[k] = float(f.g[k] / g_sum);
    f.edge[k] = float(f.edge[k] / (f.edge[k] > 0 ? edge_pos : edge_neg));
    f.point[k] = float(f.point[k] / (f.point[k] > 0 ? point_pos : point_neg));
  }
  return f;
}

// Feature pipeline [FLIP20]: on the achromatic channel (Y' + 16) / 116 (= Y / Y_n in [0, 1]; the paper's
// "division by 100" is 116 per the authors' errata) of the unfiltered images, the gradient and point-response
// magnitudes; Delta E_f = ((1 / sqrt 2) max(| |edge_t| - |edge_r| |, | |point_t| - |point_r| |))^q_f.
FloatPlane feature_error(const FloatPlane& y_test, const FloatPlane& y_reference, double ppd) {
  const FeatureFilters f = feature_filters(ppd);
  auto magnitudes = [&](const FloatPlane& y_prime) {
    FloatPlane a(y_prime.width, y_prime.height);
    for (size_t i = 0; i < a.data.size(); ++i) a.data[i] = (y_prime.data[i] + 16.0f) / 116.0f;
    const FloatPlane ex = convolve_separable(a, f.edge, f.g), ey = convolve_separable(a, f.g, f.edge);
    const FloatPlane px = convolve_separable(a, f.point, f.g), py = convolve_separable(a, f.g, f.point);
    std::pair<FloatPlane, FloatPlane> m{FloatPlane(a.width, a.height), FloatPlane(a.width, a.height)};
    for (size_t i = 0; i < a.data.size(); ++i)
      m.first.data[i] = std::hypot(ex.data[i], ey.data[i]), m.second.data[i] = std::hypot(px.data[i], py.data[i]);
    return m;
  };
  const auto [edge_t, point_t] = magnitudes(y_test);
  const auto [edge_r, point_r] = magnitudes(y_reference);
  FloatPlane error(y_test.width, y_test.height);
  for (size_t i = 0; i < error.data.size(); ++i) {
    const float d = std::max(std::abs(edge_t.data[i] - edge_r.data[i]), std::abs(point_t.data[i] - point_r.data[i]));
    error.data[i] = std::pow(d / std::sqrt(2.0f), kQf);
  }
  return error;
}

}  // namespace

double rmse(const RgbPlane& test, const RgbPlane& reference) {
  check_same_size(test, reference, "rmse");
  double sum = 0.0;
  for (size_t i = 0; i < test.data.size(); ++i) {
    const glm::dvec3 d = glm::dvec3(test.data[i]) - glm::dvec3(reference.data[i]);
    sum += glm::dot(d, d);  // (x - y)^2 summed over R, G, B
  }
  return std::sqrt(sum / (3.0 * double(test.data.size())));
}

double relmse(const RgbPlane& test, const RgbPlane& reference, double eps) {
  check_same_size(test, reference, "relmse");
  if (!(eps > 0.0)) throw Error("relmse: eps must be > 0, got " + std::to_string(eps));
  double sum = 0.0;
  for (size_t i = 0; i < test.data.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double x = test.data[i][c], y = reference.data[i][c];
      sum += (x - y) * (x - y) / (y * y + eps);  // [Rousselle11]
    }
  return sum / (3.0 * double(test.data.size()));
}

double ssim(const RgbPlane& test, const RgbPlane& reference) {
  check_same_size(test, reference, "ssim");
  const int window = 2 * kSsimRadius + 1;
  if (test.width < window || test.height < window)
    throw Error("ssim: images must be at least " + std::to_string(window) + "x" + std::to_string(window) + ", got " +
                std::to_string(test.width) + "x" + std::to_string(test.height));
  // Per channel, then the mean of the three (scikit-image's channel_axis).
  return (ssim_channel(test, reference, 0) + ssim_channel(test, reference, 1) + ssim_channel(test, reference, 2)) / 3.0;
}

FlipResult flip(const RgbPlane& test, const RgbPlane& reference, double pixels_per_degree) {
  check_same_size(test, reference, "flip");
  if (!(pixels_per_degree > 0.0))
    throw Error("flip: pixels per degree must be > 0, got " + std::to_string(pixels_per_degree));
  const std::array<FloatPlane, 3> t = to_ycxcz(test), r = to_ycxcz(reference);
  const FloatPlane delta_c = colour_error(t, r, pixels_per_degree);
  const FloatPlane delta_f = feature_error(t[0], r[0], pixels_per_degree);
  // Combination [FLIP20]: Delta E = Delta E_c^(1 - Delta E_f); features raise small colour errors towards 1.
  FlipResult result{0.0, FloatPlane(test.width, test.height)};
  for (size_t i = 0; i < result.map.data.size(); ++i) {
    result.map.data[i] = std::pow(delta_c.data[i], 1.0f - delta_f.data[i]);
    result.mean += result.map.data[i];
  }
  result.mean /= double(result.map.data.size());
  return result;
}

double temporal_error(const RgbPlane& current, const RgbPlane& previous) {
  check_same_size(current, previous, "temporal_error");
  // "the average luminance of the difference between consecutive frames" [SVGF17 Sec. 5.4]. The difference is
  // taken per channel and made absolute before its luminance: a signed luminance difference would let a pixel
  // that turns from red to an equally bright green count as unchanged, and let brighter and darker pixels
  // cancel in the average. |luminance(a) - luminance(b)| <= luminance(|a - b|), equal when all three channels
  // move the same way.
  double sum = 0.0;
  for (size_t i = 0; i < current.data.size(); ++i) sum += luminance(glm::abs(current.data[i] - previous.data[i]));
  return sum / double(current.data.size());
}

int lag_frames(const std::vector<double>& error, int change_frame, double threshold) {
  if (change_frame < 0 || change_frame >= int(error.size()))
    throw Error("lag_frames: change frame " + std::to_string(change_frame) + " is outside the series of " +
                std::to_string(error.size()) + " frames");
  // The first frame at or after the change whose error is at or below the threshold (NaN never is).
  for (int k = 0; change_frame + k < int(error.size()); ++k)
    if (error[change_frame + k] <= threshold) return k;
  return -1;  // never recovered within the series
}

int lag_frames_relative(const std::vector<double>& error, int change_frame, double tolerance) {
  if (change_frame < 1 || change_frame >= int(error.size()))
    throw Error("lag_frames_relative: change frame " + std::to_string(change_frame) +
                " needs frames before it, in a series of " + std::to_string(error.size()) + " frames");
  // The level before the change: the mean error of frames [0, change_frame), NaNs (no value) skipped.
  double sum = 0.0;
  int count = 0;
  for (int k = 0; k < change_frame; ++k)
    if (!std::isnan(error[k])) sum += error[k], ++count;
  if (count == 0)
    throw Error("lag_frames_relative: no error values before the change frame " + std::to_string(change_frame));
  return lag_frames(error, change_frame, sum / count * (1.0 + tolerance));
}

double brightness_error(const RgbPlane& test, const RgbPlane& reference) {
  return std::abs(brightness_bias(test, reference, Region(test.data.size(), 1)));
}

double rmse(const RgbPlane& test, const RgbPlane& reference, const Region& region) {
  check_same_size(test, reference, "rmse");
  check_region(test, region, "rmse");
  double sum = 0.0;
  size_t count = 0;
  for (size_t i = 0; i < test.data.size(); ++i) {
    if (!region[i]) continue;
    const glm::dvec3 d = glm::dvec3(test.data[i]) - glm::dvec3(reference.data[i]);
    sum += glm::dot(d, d);
    ++count;
  }
  return count ? std::sqrt(sum / (3.0 * double(count))) : std::numeric_limits<double>::quiet_NaN();
}

double brightness_bias(const RgbPlane& test, const RgbPlane& reference, const Region& region) {
  check_same_size(test, reference, "brightness_error");
  check_region(test, region, "brightness_error");
  double sum_test = 0.0, sum_reference = 0.0;
  for (size_t i = 0; i < test.data.size(); ++i) {
    if (!region[i]) continue;
    sum_test += luminance(test.data[i]);
    sum_reference += luminance(reference.data[i]);
  }
  return sum_reference > 0.0 ? (sum_test - sum_reference) / sum_reference : 0.0;
}

std::vector<Region> umbra_regions(const std::vector<FloatPlane>& direct_luminance,
                                  const std::vector<RgbPlane>& position, const std::vector<FloatPlane>& depth) {
  if (direct_luminance.size() != depth.size() || position.size() != depth.size() || depth.empty())
    throw Error("umbra_regions: needs one direct-light, position and depth plane per frame, at least one frame");
  const int w = depth.front().width, h = depth.front().height;
  const size_t n = depth.front().data.size();
  for (size_t f = 0; f < depth.size(); ++f)
    if (depth[f].width != w || depth[f].height != h || direct_luminance[f].width != w ||
        direct_luminance[f].height != h || position[f].width != w || position[f].height != h)
      throw Error("umbra_regions: frame " + std::to_string(f) + " differs in size from the first");
  // Per pixel: does it see the same surface point in every frame, and the most direct light it ever receives.
  std::vector<uint8_t> still(n, 1);
  std::vector<float> most(n, 0.0f);
  for (size_t f = 0; f < depth.size(); ++f)
    for (size_t i = 0; i < n; ++i) {
      const float z0 = depth.front().data[i];
      const bool surface = z0 > 0.0f && depth[f].data[i] > 0.0f;  // depth 0: no surface (docs/buffers.md)
      if (!surface || glm::distance(position[f].data[i], position.front().data[i]) > 0.01f * z0) still[i] = 0;
      most[i] = std::max(most[i], direct_luminance[f].data[i]);
    }
  std::vector<Region> regions(depth.size(), Region(n, 0));
  for (size_t f = 0; f < depth.size(); ++f)
    for (size_t i = 0; i < n; ++i)
      regions[f][i] = still[i] && most[i] > 0.0f && direct_luminance[f].data[i] < kUmbraFraction * most[i];
  return regions;
}

}  // namespace rtdr
