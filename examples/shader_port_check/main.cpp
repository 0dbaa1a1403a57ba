// A shader-port check, as a user of RTDR writes it in their own repository: run one level of SVGF's a-trous
// filter [SVGF17 Eq. 1-5] twice on the same inputs, once with "my port" (plain C++ standing in for your shader)
// and once with RTDR's golden pass, and compare every output channel with RTDR's comparison helper. Exit 0 when
// the port matches the golden pass exactly, 1 when it does not.
#include "eval/frame_diff.h"      // rtdr::diff_channels: worst absolute and relative difference per channel
#include "filters/svgf/atrous.h"  // rtdr::atrous_level: the golden pass
#include "filters/user_buffers.h"  // rtdr::BufferView: your buffers, with their strides, as planes

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace {

// ---- My port: one a-trous level over row-major float arrays, one invocation per pixel, as a compute shader ----
struct PortInputs {
  int width = 0, height = 0;
  std::vector<float> rgb;           // 3 floats per pixel: this level's demodulated colour
  std::vector<float> variance;      // Var(l) per pixel
  std::vector<float> prefiltered;   // g3x3(Var(l)) per pixel, the luminance weight's variance
  std::vector<float> depth;         // linear view depth
  std::vector<float> depth_grad;    // 2 floats per pixel: d depth / dx, d depth / dy
  std::vector<float> normal;        // 3 floats per pixel, unit length
  std::vector<uint32_t> mesh;       // 0xFFFFFFFF: no surface
};

float luma(const float* c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

void my_atrous_port(const PortInputs& in, int level, std::vector<float>& rgb_out, std::vector<float>& var_out) {
  const float h[5] = {1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};
  const float sigma_z = 1.0f, sigma_n = 128.0f, sigma_l = 4.0f, epsilon = 1e-4f;
  const int step = 1 << level;
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      const int p = y * in.width + x;
      if (in.mesh[p] == 0xFFFFFFFFu) {  // no surface: passed through
        std::copy_n(&in.rgb[3 * p], 3, &rgb_out[3 * p]);
        var_out[p] = in.variance[p];
        continue;
      }
      const float l_p = luma(&in.rgb[3 * p]);
      const float scale_l = sigma_l * std::sqrt(std::max(0.0f, in.prefiltered[p])) + epsilon;
      float sum_w = 0.0f, sum_c[3] = {0.0f, 0.0f, 0.0f}, sum_var = 0.0f;
      for (int j = -2; j <= 2; ++j)
        for (int k = -2; k <= 2; ++k) {
          int qx = x + k * step;
          const int qy = y + j * step;
#ifdef PORT_OFF_BY_ONE
          if (k == 2 && j == 0) qx += 1;  // the bug: the right-hand tap of the centre row reads one pixel too far
#endif
          if (qx < 0 || qy < 0 || qx >= in.width || qy >= in.height) continue;
          const int q = qy * in.width + qx;
          if (in.mesh[q] == 0xFFFFFFFFu) continue;
          float w = 1.0f;  // the centre tap
          if (k != 0 || j != 0) {
            const float dx = float(x - qx), dy = float(y - qy);
            const float predicted =
                sigma_z * std::abs(in.depth_grad[2 * p] * dx + in.depth_grad[2 * p + 1] * dy) + epsilon;
            const float w_z = std::exp(-std::abs(in.depth[p] - in.depth[q]) / predicted);
            const float n_dot = in.normal[3 * p] * in.normal[3 * q] + in.normal[3 * p + 1] * in.normal[3 * q + 1] +
                                in.normal[3 * p + 2] * in.normal[3 * q + 2];
            const float w_n = std::pow(std::max(0.0f, n_dot), sigma_n);
            const float w_l = std::exp(-std::abs(l_p - luma(&in.rgb[3 * q])) / scale_l);
            w = w_z * w_n * w_l;
          }
          const float hq = h[k + 2] * h[j + 2];  // the 2D kernel's weight at this tap
          sum_w += hq * w;
          for (int c = 0; c < 3; ++c) sum_c[c] += hq * w * in.rgb[3 * q + c];
          sum_var += hq * hq * w * w * in.variance[q];
        }
      for (int c = 0; c < 3; ++c) rgb_out[3 * p + c] = sum_c[c] / sum_w;
      var_out[p] = sum_var / (sum_w * sum_w);
    }
}

// ---- The test: made-up inputs, the port, the golden pass, the comparison ----

// A floor seen at a slant with a box standing on it, a strip of sky, and noisy colour.
PortInputs make_inputs(int width, int height) {
  PortInputs in;
  in.width = width;
  in.height = height;
  const size_t n = size_t(width) * size_t(height);
  in.rgb.resize(3 * n);
  in.variance.resize(n);
  in.depth.resize(n);
  in.depth_grad.resize(2 * n);
  in.normal.resize(3 * n);
  in.mesh.resize(n);
  uint32_t seed = 1;
  auto random = [&] { return float((seed = seed * 1664525u + 1013904223u) >> 8) / float(1 << 24); };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t p = size_t(y) * size_t(width) + size_t(x);
      const bool sky = y < 3, box = x >= 20 && x < 30 && y >= 8 && y < 20;
      in.mesh[p] = sky ? 0xFFFFFFFFu : (box ? 1u : 0u);
      in.depth[p] = sky ? 0.0f : (box ? 4.0f : 10.0f - 0.2f * float(y));
      in.depth_grad[2 * p] = 0.0f;
      in.depth_grad[2 * p + 1] = sky || box ? 0.0f : -0.2f;
      in.normal[3 * p + 1] = box ? 0.0f : 1.0f;
      in.normal[3 * p + 2] = box ? 1.0f : 0.0f;
      for (int c = 0; c < 3; ++c) in.rgb[3 * p + c] = sky ? 0.0f : (box ? 2.0f : 0.5f) * random();
      in.variance[p] = sky ? 0.0f : 0.1f * random();
    }
  return in;
}

// A packed buffer of `channels` floats per pixel, as a view (filters/user_buffers.h: strides 0 mean packed).
rtdr::BufferView view(const std::vector<float>& v, int w, int h, int channels) {
  return rtdr::BufferView{v.data(), w, h, channels, 0, 0};
}

// An output as a frame of channels <name>.R/G/B and <name>.V, for the comparison helper.
rtdr::Frame as_frame(const rtdr::RgbPlane& rgb, const rtdr::FloatPlane& variance) {
  rtdr::Frame frame(rgb.width, rgb.height);
  rtdr::FloatPlane &r = frame.add_float("atrous.R"), &g = frame.add_float("atrous.G"),
                   &b = frame.add_float("atrous.B");
  for (size_t i = 0; i < rgb.data.size(); ++i) r.data[i] = rgb.data[i].r, g.data[i] = rgb.data[i].g, b.data[i] = rgb.data[i].b;
  frame.add_float("atrous.variance") = variance;
  return frame;
}

}  // namespace

int main() {
  const int width = 48, height = 32, level = 1;
  PortInputs in = make_inputs(width, height);

  // The golden pass, on RTDR's planes, read from the port's buffers.
  const rtdr::RgbPlane color = rtdr::rgb_plane(view(in.rgb, width, height, 3));
  const rtdr::FloatPlane variance = rtdr::float_plane(view(in.variance, width, height, 1));
  rtdr::SurfacePlanes surface;
  surface.depth = rtdr::float_plane(view(in.depth, width, height, 1));
  surface.depth_grad = rtdr::vec2_plane(view(in.depth_grad, width, height, 2));
  surface.normal = rtdr::rgb_plane(view(in.normal, width, height, 3));
  surface.mesh = rtdr::uint_plane(rtdr::BufferView{in.mesh.data(), width, height, 1, 0, 0});
  const rtdr::SvgfParams params;  // sigma_z 1, sigma_n 128, sigma_l 4, epsilon 1e-4, the 5x5 B3 kernel
  const rtdr::AtrousOutput golden = rtdr::atrous_level(color, variance, surface, level, params);

  // My port, given the same prefiltered variance the golden level computed.
  in.prefiltered = golden.prefiltered_variance.data;
  std::vector<float> rgb_out(in.rgb.size()), var_out(in.variance.size());
  my_atrous_port(in, level, rgb_out, var_out);

  // Every channel's worst absolute and relative difference, with its pixel and both values.
  const double rel_floor = 1e-2;
  const std::vector<rtdr::ChannelDiff> diffs = rtdr::diff_channels(
      as_frame(rtdr::rgb_plane(view(rgb_out, width, height, 3)), rtdr::float_plane(view(var_out, width, height, 1))),
      as_frame(golden.color, golden.variance), rel_floor);
  double worst = 0.0;
  std::printf("a-trous level %d, %dx%d: my port against RTDR's golden pass\n", level, width, height);
  for (const rtdr::ChannelDiff& d : diffs) {
    std::printf("  %-16s worst |port - golden| %.3g at (%d, %d): port %.9g, golden %.9g\n", d.channel.c_str(),
                d.abs.error, d.abs.x, d.abs.y, d.abs.test, d.abs.reference);
    worst = std::max(worst, d.abs.error);
  }
  std::printf("%s: worst difference %.3g\n", worst == 0.0 ? "PASS" : "FAIL", worst);
  return worst == 0.0 ? 0 : 1;
}
