// Per-pixel seeds and the low-discrepancy sampler that the path tracer draws every random number from.
//
// A path's random numbers are a function of (seed, sample index) alone, so re-shading the same surface
// sample with the same seed gives the identical result [ASVGF18 Sec. 3.2, Eq. 6]. The sequence is the 2D
// Sobol' (0,2)-sequence, Owen-scrambled and shuffled by hashing (Burley 2020, "Practical Hash-based Owen
// Scrambling", JCGT 9(4)); successive dimension pairs are decorrelated by giving each pair its own
// scramble and shuffle seed (Burley 2020 Sec. 4, "padding"). With one sample per pixel and frame
// (index 0), the per-frame seed alone randomises the point; the reference renderer takes indices
// 0..N-1 under one seed and so gets a stratified, low-discrepancy set per pixel.
#pragma once

#include "core/sampler_shared.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace rtdr {

// A well-mixing 32-bit integer hash (the "lowbias32" finalizer of C. Wellons' hash prospector). Its constants are
// core/sampler_shared.h's, shared with the GLSL mirror core/sampler.glsl.
inline uint32_t hash_u32(uint32_t x) {
  x ^= x >> 16;
  x *= RTDR_HASH_MULTIPLIER_1;
  x ^= x >> 15;
  x *= RTDR_HASH_MULTIPLIER_2;
  x ^= x >> 16;
  return x;
}

inline uint32_t hash_combine(uint32_t seed, uint32_t v) {
  return hash_u32(seed ^ (v + RTDR_HASH_COMBINE_CONSTANT + (seed << 6) + (seed >> 2)));
}

// The seed of pixel (x, y) in frame f, regenerated deterministically every frame.
inline uint32_t pixel_seed(uint32_t global_seed, int frame, int x, int y) {
  return hash_combine(hash_combine(hash_combine(hash_u32(global_seed), uint32_t(frame)), uint32_t(x)), uint32_t(y));
}

// One dimension pair of every sample under one seed: at(index) is the point that the `pair`-th next_2d() of
// Sampler(seed, index) returns (pair 0 = the first call), bit for bit. The pair's scramble seeds are hashed once,
// so a loop over many sample indices of one pair (trace/shading.h) does not hash them again for every point.
class SamplePair {
 public:
  SamplePair(uint32_t seed, uint32_t pair);
  glm::vec2 at(uint32_t index) const;

 private:
  uint32_t shuffle_seed_, x_seed_, y_seed_;
};

class Sampler {
 public:
  Sampler(uint32_t seed, uint32_t sample_index) : seed_(seed), index_(sample_index) {}

  // The next two dimensions of this sample, in [0, 1)^2.
  glm::vec2 next_2d();
  // The next dimension (half of a fresh pair; the other half is discarded so pairs stay aligned).
  float next_1d() { return next_2d().x; }

 private:
  uint32_t seed_;
  uint32_t index_;
  uint32_t pair_ = 0;
};

}  // namespace rtdr
