// Tests for core/sampler: the hash-based Owen-scrambled Sobol' (0,2)-sequence of Burley 2020 and the
// per-pixel seeds. What a student should take away, in the order of the test cases:
//   1. every value lies in [0, 1) and the sequence is a pure function of (seed, index);
//   2. the first 2^k points of a dimension pair form a (0, k, 2)-net, for any seed and any pair;
//   3. different seeds and different pairs give independent-looking numbers;
//   4. pixel seeds do not collide between neighbouring pixels or frames;
//   5. the payoff: on a smooth integrand the error is far below that of independent random points.
#include "core/sampler.h"

#include <catch2/catch.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <set>
#include <vector>

using Catch::Detail::Approx;

namespace {

// The point of dimension pair `pair` (0 = the first next_2d call) of sample `index` under `seed`.
glm::vec2 point_of_pair(uint32_t seed, uint32_t index, int pair) {
  rtdr::Sampler sampler(seed, index);
  glm::vec2 p = sampler.next_2d();
  for (int skipped = 0; skipped < pair; ++skipped) p = sampler.next_2d();
  return p;
}

// The float's bits, so "bit-identical" means exactly that (0.0f and -0.0f would compare equal as floats).
uint32_t bits_of(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// Pearson's sample correlation coefficient r of two equally long series.
double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = double(a.size());
  double sum_a = 0, sum_b = 0, sum_aa = 0, sum_bb = 0, sum_ab = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sum_a += a[i];
    sum_b += b[i];
    sum_aa += a[i] * a[i];
    sum_bb += b[i] * b[i];
    sum_ab += a[i] * b[i];
  }
  const double cov = sum_ab / n - (sum_a / n) * (sum_b / n);
  const double var_a = sum_aa / n - (sum_a / n) * (sum_a / n);
  const double var_b = sum_bb / n - (sum_b / n) * (sum_b / n);
  return cov / std::sqrt(var_a * var_b);
}

// A uniform number in [0, 1) from 24 random bits of the reference generator (never rounds up to 1).
double reference_uniform(std::mt19937& rng) { return double(rng() >> 8) * 0x1p-24; }

}  // namespace

TEST_CASE("Sampler: every value u has 0 <= u < 1") {
  // 256 seeds x 64 indices x 8 pairs = 131072 points; the smallest and largest coordinates seen.
  float smallest = 1.0f, largest = 0.0f;
  for (uint32_t seed = 0; seed < 256; ++seed) {
    for (uint32_t index = 0; index < 64; ++index) {
      rtdr::Sampler sampler(rtdr::hash_u32(seed), index);
      for (int pair = 0; pair < 8; ++pair) {
        const glm::vec2 p = sampler.next_2d();
        smallest = std::min({smallest, p.x, p.y});
        largest = std::max({largest, p.x, p.y});
      }
    }
  }
  CHECK(smallest >= 0.0f);
  CHECK(largest < 1.0f);
  // And not squeezed into a sub-range: with 262144 coordinates the extremes come within 1e-3 of 0 and 1.
  CHECK(smallest < 1e-3f);
  CHECK(largest > 1.0f - 1e-3f);
}

TEST_CASE("Sampler: the same (seed, index) gives a bit-identical sequence") {
  // Two samplers built from the same arguments, 100 next_2d calls each, compared bit for bit;
  // next_1d also consumes a whole pair, so interleaving it keeps both in step.
  for (uint32_t index : {0u, 1u, 7u, 1000u}) {
    rtdr::Sampler first(0xC0FFEEu, index), second(0xC0FFEEu, index);
    int differing = 0;
    for (int call = 0; call < 100; ++call) {
      const glm::vec2 a = first.next_2d(), b = second.next_2d();
      if (bits_of(a.x) != bits_of(b.x) || bits_of(a.y) != bits_of(b.y)) ++differing;
      if (bits_of(first.next_1d()) != bits_of(second.next_1d())) ++differing;
    }
    INFO("sample index " << index);
    CHECK(differing == 0);
  }
}

TEST_CASE("SamplePair: at(index) is the pair-th next_2d of Sampler(seed, index), bit for bit") {
  int differing = 0;
  for (uint32_t seed : {0u, 0xC0FFEEu})
    for (uint32_t pair = 0; pair < 4; ++pair) {
      const rtdr::SamplePair points(seed, pair);
      for (uint32_t index = 0; index < 256; ++index) {
        const glm::vec2 a = points.at(index), b = point_of_pair(seed, index, int(pair));
        differing += bits_of(a.x) != bits_of(b.x) || bits_of(a.y) != bits_of(b.y);
      }
    }
  CHECK(differing == 0);
}

TEST_CASE("Sampler: next_1d is the first coordinate of the next pair") {
  // sampler.h: "half of a fresh pair; the other half is discarded so pairs stay aligned".
  rtdr::Sampler one_d(99u, 5u), two_d(99u, 5u);
  for (int pair = 0; pair < 10; ++pair) CHECK(bits_of(one_d.next_1d()) == bits_of(two_d.next_2d().x));
}

TEST_CASE("Sampler: a different seed gives different points") {
  // For 1024 indices, the first pair under seed 17 against seed 18: identical points should essentially
  // never happen (two independent 24-bit coordinates agreeing has probability 2^-48).
  int identical = 0;
  for (uint32_t index = 0; index < 1024; ++index)
    if (point_of_pair(17u, index, 0) == point_of_pair(18u, index, 0)) ++identical;
  CHECK(identical == 0);
}

TEST_CASE("Sampler: the first 2^k points of a pair form a (0, k, 2)-net") {
  // A (0, k, 2)-net in base 2: every elementary interval [a/2^i, (a+1)/2^i) x [b/2^j, (b+1)/2^j) with
  // i + j = k (area 2^-k) holds exactly one of the 2^k points. Sobol' dimensions 0 and 1 form a
  // (0,2)-sequence, so every aligned block of 2^k indices is such a net; Owen scrambling permutes
  // elementary intervals among themselves and the index shuffle maps an aligned block onto another
  // aligned block, so both preserve it (Burley 2020, Sec. 3 and 4).
  for (uint32_t seed : {0u, 1u, 0xDEADBEEFu, 20240611u}) {
    for (int pair : {0, 2}) {  // the 1st and the 3rd pair: each pair has its own scramble
      for (int k = 4; k <= 10; ++k) {
        const uint32_t n = 1u << k;
        std::vector<glm::vec2> points(n);
        for (uint32_t index = 0; index < n; ++index) points[index] = point_of_pair(seed, index, pair);
        for (int i = 0; i <= k; ++i) {
          const int j = k - i;
          // Count the points per interval; the interval of x is floor(x 2^i) (exact: x has 24 bits).
          std::vector<int> count(size_t(n), 0);
          for (const glm::vec2& p : points) {
            const uint32_t a = uint32_t(p.x * float(1u << i)), b = uint32_t(p.y * float(1u << j));
            ++count[(a << j) | b];
          }
          int intervals_not_holding_one = 0;
          for (int c : count)
            if (c != 1) ++intervals_not_holding_one;
          INFO("seed " << seed << ", pair " << pair << ", k " << k << ", intervals 2^-" << i << " x 2^-" << j);
          CHECK(intervals_not_holding_one == 0);
        }
      }
    }
  }
}

TEST_CASE("Sampler: different pairs of the same sample are uncorrelated") {
  // Over 16384 indices of one seed, the correlation coefficient between any coordinate of pair p and any
  // coordinate of pair q. For independent uniforms r has standard deviation 1 / sqrt(16384) = 0.0078,
  // so |r| < 0.05 is a 6-sigma bound that a shared (unpadded) scramble would break at once (r = 1).
  constexpr uint32_t kIndices = 16384;
  constexpr int kPairs = 3;
  // coordinate[2 * pair + axis][index]
  std::vector<std::vector<double>> coordinate(2 * kPairs, std::vector<double>(kIndices));
  for (uint32_t index = 0; index < kIndices; ++index) {
    rtdr::Sampler sampler(0x5EEDu, index);
    for (int pair = 0; pair < kPairs; ++pair) {
      const glm::vec2 p = sampler.next_2d();
      coordinate[size_t(2 * pair)][index] = p.x;
      coordinate[size_t(2 * pair + 1)][index] = p.y;
    }
  }
  for (int pair_p = 0; pair_p < kPairs; ++pair_p) {
    for (int pair_q = pair_p + 1; pair_q < kPairs; ++pair_q) {
      for (int axis_p = 0; axis_p < 2; ++axis_p) {
        for (int axis_q = 0; axis_q < 2; ++axis_q) {
          const double r = correlation(coordinate[size_t(2 * pair_p + axis_p)], coordinate[size_t(2 * pair_q + axis_q)]);
          INFO("pair " << pair_p << " axis " << axis_p << " against pair " << pair_q << " axis " << axis_q << ": r = " << r);
          CHECK(std::abs(r) < 0.05);
        }
      }
    }
  }
}

TEST_CASE("Sampler: one sample per pixel (index 0) is uniform across seeds") {
  // The path tracer's real-time mode: index 0 under 65536 different seeds. The mean of a uniform on
  // [0, 1) is 1/2 with standard deviation sqrt(1/12) / sqrt(65536) = 0.0011, so 0.005 is 4.4 sigma.
  constexpr uint32_t kSeeds = 65536;
  double sum = 0.0;
  for (uint32_t seed = 0; seed < kSeeds; ++seed) {
    rtdr::Sampler sampler(seed, 0);
    sum += sampler.next_1d();
  }
  CHECK(sum / kSeeds == Approx(0.5).margin(0.005));
}

TEST_CASE("pixel_seed: no collisions across neighbouring pixels and frames") {
  // 64 x 64 pixels x 4 frames = 16384 seeds. Even a perfect 32-bit hash collides somewhere with
  // probability 16384^2 / 2^33 = 3%; these three global seeds were checked to be collision-free, so a
  // collision here means a structural fault (say, x and y entering symmetrically).
  for (uint32_t global_seed : {0u, 1u, 12345u}) {
    std::set<uint32_t> seen;
    for (int frame = 0; frame < 4; ++frame)
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) seen.insert(rtdr::pixel_seed(global_seed, frame, x, y));
    INFO("global seed " << global_seed);
    CHECK(seen.size() == 64u * 64u * 4u);
  }
  // The swap that a symmetric combination would miss: pixel (x, y) and pixel (y, x).
  CHECK(rtdr::pixel_seed(7u, 0, 3, 5) != rtdr::pixel_seed(7u, 0, 5, 3));
  // The global seed changes every pixel's seed.
  CHECK(rtdr::pixel_seed(7u, 0, 3, 5) != rtdr::pixel_seed(8u, 0, 3, 5));
}

TEST_CASE("Sampler: low discrepancy beats independent random points on a smooth integrand") {
  // Integrate f(x, y) = x y over the unit square (exact value 1/4) with N = 1024 points, 16 trials each.
  // Independent points: error ~ sigma_f / sqrt(N) with sigma_f^2 = E[x^2 y^2] - 1/16 = 1/9 - 1/16,
  // i.e. about 0.0069. An Owen-scrambled net converges like N^-1.5 on smooth functions (Owen 1997),
  // so its error should be more than 10x smaller (about 190x for these seeds).
  constexpr uint32_t kN = 1024;
  constexpr int kTrials = 16;
  constexpr double kExact = 0.25;

  double sobol_error = 0.0;
  for (int trial = 0; trial < kTrials; ++trial) {
    double sum = 0.0;
    for (uint32_t index = 0; index < kN; ++index) {
      const glm::vec2 p = point_of_pair(1000u + uint32_t(trial), index, 0);  // one seed per trial
      sum += double(p.x) * double(p.y);
    }
    sobol_error += std::abs(sum / kN - kExact) / kTrials;
  }

  std::mt19937 rng(7);  // the reference: independent uniform points
  double random_error = 0.0;
  for (int trial = 0; trial < kTrials; ++trial) {
    double sum = 0.0;
    for (uint32_t i = 0; i < kN; ++i) {
      const double x = reference_uniform(rng), y = reference_uniform(rng);
      sum += x * y;
    }
    random_error += std::abs(sum / kN - kExact) / kTrials;
  }

  INFO("mean |error|: Owen-scrambled Sobol' " << sobol_error << ", independent random " << random_error);
  CHECK(random_error > 1e-3);  // the reference really is noisy (expected mean |error| 0.8 x 0.0069 = 0.0055)
  CHECK(sobol_error * 10.0 < random_error);
}
