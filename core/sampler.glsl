// GLSL mirror of core/sampler.h's integer hashes and of SamplePair (core/sampler.cpp), for the render side's
// Vulkan ports (#include "core/sampler.glsl"; needs GL_GOOGLE_include_directive). Integer operations only, with
// the constants of core/sampler_shared.h: every result is the C++ one bit for bit (uint arithmetic wraps modulo
// 2^32 in both), so a seed replays the same sample [ASVGF18 Sec. 3.2, Eq. 6].
#ifndef RTDR_TRACE_SAMPLER_GLSL
#define RTDR_TRACE_SAMPLER_GLSL

#include "core/sampler_shared.h"

// A well-mixing 32-bit integer hash, the "lowbias32" finalizer (sampler.h's hash_u32).
uint hash_u32(uint x) {
  x ^= x >> 16;
  x *= RTDR_HASH_MULTIPLIER_1;
  x ^= x >> 15;
  x *= RTDR_HASH_MULTIPLIER_2;
  x ^= x >> 16;
  return x;
}

// sampler.h's hash_combine: v mixed into seed.
uint hash_combine(uint seed, uint v) {
  return hash_u32(seed ^ (v + RTDR_HASH_COMBINE_CONSTANT + (seed << 6) + (seed >> 2)));
}

// sampler.cpp's reverse_bits: the 32 bits mirrored.
uint reverse_bits(uint x) { return bitfieldReverse(x); }

// sampler.cpp's sobol_dim1_by_bits: Sobol' dimension 1, the xor of the direction numbers v_k (v_0 = 2^31,
// v_k = v_{k-1} xor (v_{k-1} >> 1)) whose bit k is set in the index. (The C++ reads it from a byte table built
// from this loop, for speed; the values are the same.)
uint sobol_dim1(uint index) {
  uint result = 0u;
  for (uint v = 0x80000000u; index != 0u; index >>= 1, v ^= v >> 1)
    if ((index & 1u) != 0u) result ^= v;
  return result;
}

// sampler.cpp's laine_karras_permutation and owen_scramble (Burley 2020, Listing 2).
uint laine_karras_permutation(uint x, uint seed) {
  x += seed;
  x ^= x * RTDR_LAINE_KARRAS_MULTIPLIER_1;
  x ^= x * RTDR_LAINE_KARRAS_MULTIPLIER_2;
  x ^= x * RTDR_LAINE_KARRAS_MULTIPLIER_3;
  x ^= x * RTDR_LAINE_KARRAS_MULTIPLIER_4;
  return x;
}
uint owen_scramble(uint x, uint seed) { return reverse_bits(laine_karras_permutation(reverse_bits(x), seed)); }

// sampler.cpp's to_unit_float: 32-bit fixed point in [0, 1), exact (24 bits times a power of two).
float to_unit_float(uint x) { return float(x >> 8) * (1.0 / 16777216.0); }

// SamplePair(seed, pair).at(index), which is the `pair`-th next_2d() of Sampler(seed, index): bit for bit.
vec2 sample_pair_at(uint seed, uint pair, uint index) {
  const uint pair_seed = hash_combine(seed, pair);
  const uint shuffled = owen_scramble(index, hash_combine(pair_seed, RTDR_SAMPLE_PAIR_SHUFFLE_SALT));
  const uint x = reverse_bits(laine_karras_permutation(shuffled, hash_combine(pair_seed, RTDR_SAMPLE_PAIR_X_SALT)));
  const uint y = owen_scramble(sobol_dim1(shuffled), hash_combine(pair_seed, RTDR_SAMPLE_PAIR_Y_SALT));
  return vec2(to_unit_float(x), to_unit_float(y));
}

#endif  // RTDR_TRACE_SAMPLER_GLSL
