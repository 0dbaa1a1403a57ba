// Channel-by-channel differences between two frames. See frame_diff.h.
#include "eval/frame_diff.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtdr {

double abs_difference(float test, float reference) {
  if (test == reference) return 0.0;  // equal infinities too, whose difference would be NaN
  const double d = std::abs(double(test) - double(reference));
  return std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
}

double rel_difference(float test, float reference, double rel_floor) {
  return abs_difference(test, reference) / std::max(std::abs(double(reference)), rel_floor);
}

bool keep_worst(PixelError& worst, const PixelError& candidate) {
  if (!(candidate.error > worst.error)) return false;
  worst = candidate;
  return true;
}

std::vector<ChannelDiff> diff_channels(const Frame& test, const Frame& reference, double rel_floor) {
  if (!(rel_floor > 0.0)) throw Error("the relative error's floor must be positive, got " + std::to_string(rel_floor));
  if (test.width() != reference.width() || test.height() != reference.height())
    throw Error("frames of different sizes: " + std::to_string(test.width()) + "x" + std::to_string(test.height()) +
                " against " + std::to_string(reference.width()) + "x" + std::to_string(reference.height()));
  for (const auto& [name, plane] : test.float_channels())
    if (!reference.float_channels().count(name)) throw Error("channel '" + name + "' is only in the tested frame");
  std::vector<ChannelDiff> diffs;
  for (const auto& [name, ref] : reference.float_channels()) {
    if (!test.float_channels().count(name)) throw Error("channel '" + name + "' is missing from the tested frame");
    const FloatPlane& t = test.float_channel(name);
    ChannelDiff d{name, {}, {}};
    for (int y = 0; y < ref.height; ++y)
      for (int x = 0; x < ref.width; ++x) {
        const float a = t.at(x, y), b = ref.at(x, y);
        keep_worst(d.abs, {abs_difference(a, b), x, y, a, b});
        keep_worst(d.rel, {rel_difference(a, b, rel_floor), x, y, a, b});
      }
    diffs.push_back(std::move(d));
  }
  return diffs;
}

}  // namespace rtdr
