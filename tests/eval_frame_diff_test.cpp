// Tests of eval/frame_diff.cpp: the per-channel worst absolute and relative differences on frames worked out by
// hand, the floor, NaN and infinities, and the errors for frames that cannot be compared.
#include "eval/frame_diff.h"

#include "core/error.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using Catch::Detail::Approx;
using namespace rtdr;

namespace {

// A frame of one row holding `values` in channel `name`.
Frame row(const std::string& name, const std::vector<float>& values) {
  Frame f(int(values.size()), 1);
  f.add_float(name).data = values;
  return f;
}

}  // namespace

TEST_CASE("diff_channels finds each channel's worst absolute and relative pixel, worked by hand") {
  // Absolute: |101 - 100| = 1 at x = 0 is the largest. Relative (floor 1e-2): 1 / 100 = 0.01 at x = 0,
  // 0.1 / 0.1 = 1 at x = 1, and at x = 2 a reference under the floor: 0.002 / 0.01 = 0.2.
  Frame test = row("a.R", {101.0f, 0.2f, 0.003f, 7.0f});
  Frame reference = row("a.R", {100.0f, 0.1f, 0.001f, 7.0f});
  test.add_float("b.Y").data = {1.0f, 2.0f, 3.0f, 4.0f};
  reference.add_float("b.Y").data = {1.0f, 2.0f, 3.0f, 4.0f};
  const std::vector<ChannelDiff> diffs = diff_channels(test, reference, 1e-2);
  REQUIRE(diffs.size() == 2);

  const ChannelDiff& a = diffs[0];
  CHECK(a.channel == "a.R");
  CHECK(a.abs.error == 1.0);
  CHECK(a.abs.x == 0);
  CHECK(a.abs.y == 0);
  CHECK(a.abs.test == 101.0f);
  CHECK(a.abs.reference == 100.0f);
  CHECK(a.rel.error == Approx((double(0.2f) - double(0.1f)) / double(0.1f)).epsilon(1e-12));
  CHECK(a.rel.x == 1);
  CHECK(a.rel.test == 0.2f);
  CHECK(a.rel.reference == 0.1f);
  CHECK(rel_difference(0.003f, 0.001f, 1e-2) == Approx((double(0.003f) - double(0.001f)) / 1e-2));

  // Equal channels: no error, and no worst pixel.
  const ChannelDiff& b = diffs[1];
  CHECK(b.channel == "b.Y");
  CHECK(b.abs.error == 0.0);
  CHECK(b.rel.error == 0.0);
  CHECK(b.abs.x == -1);
  CHECK(b.rel.y == -1);
}

TEST_CASE("diff_channels counts a NaN as an infinite difference and equal infinities as none") {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  CHECK(abs_difference(inf, inf) == 0.0);
  CHECK(std::isinf(abs_difference(nan, 1.0f)));
  CHECK(std::isinf(abs_difference(1.0f, nan)));
  CHECK(std::isinf(abs_difference(nan, nan)));
  CHECK(std::isinf(abs_difference(-inf, inf)));

  // The NaN is the worst pixel even after a large finite difference.
  const std::vector<ChannelDiff> diffs =
      diff_channels(row("c.R", {1e30f, nan, inf}), row("c.R", {0.0f, 1.0f, inf}), 1e-2);
  REQUIRE(diffs.size() == 1);
  CHECK(std::isinf(diffs[0].abs.error));
  CHECK(diffs[0].abs.x == 1);
  CHECK(std::isinf(diffs[0].rel.error));
  CHECK(diffs[0].rel.x == 1);
}

TEST_CASE("diff_channels keeps the first of equally bad pixels, and keep_worst the earlier frame") {
  const std::vector<ChannelDiff> diffs = diff_channels(row("d.R", {0.0f, 1.0f, 0.0f, 1.0f}),
                                                       row("d.R", {0.0f, 0.0f, 0.0f, 0.0f}), 1.0);
  CHECK(diffs[0].abs.x == 1);
  CHECK(diffs[0].rel.x == 1);
  PixelError worst{0.5, 3, 4, 1.0f, 0.5f};
  CHECK_FALSE(keep_worst(worst, {0.5, 7, 8, 2.0f, 1.5f}));
  CHECK(worst.x == 3);
  CHECK(keep_worst(worst, {0.75, 7, 8, 2.0f, 1.25f}));
  CHECK(worst.x == 7);
  CHECK(worst.error == 0.75);
}

TEST_CASE("diff_channels rejects frames it cannot compare, naming why") {
  const Frame a = row("e.R", {1.0f, 2.0f});
  CHECK_THROWS_WITH(diff_channels(a, row("e.R", {1.0f, 2.0f, 3.0f}), 1e-2), Catch::Contains("different sizes"));
  CHECK_THROWS_WITH(diff_channels(a, row("f.R", {1.0f, 2.0f}), 1e-2),
                    Catch::Contains("'e.R' is only in the tested frame"));
  Frame more = row("e.R", {1.0f, 2.0f});
  more.add_float("g.R");
  CHECK_THROWS_WITH(diff_channels(a, more, 1e-2), Catch::Contains("'g.R' is missing from the tested frame"));
  CHECK_THROWS_WITH(diff_channels(a, a, 0.0), Catch::Contains("floor must be positive"));
}
