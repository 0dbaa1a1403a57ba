// Hash-based Owen-scrambled Sobol' (0,2)-sequence (Burley 2020). See sampler.h.
#include "core/sampler.h"

namespace rtdr {
namespace {

// Mirrors the 32 bits: swap neighbouring bits, then pairs, then nibbles; the byte swap finishes the job.
uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555U) | ((x & 0x55555555U) << 1);
  x = ((x >> 2) & 0x33333333U) | ((x & 0x33333333U) << 2);
  x = ((x >> 4) & 0x0F0F0F0FU) | ((x & 0x0F0F0F0FU) << 4);
  return __builtin_bswap32(x);
}

// Sobol' dimension 1: direction numbers v_0 = 2^31, v_k = v_{k-1} xor (v_{k-1} >> 1); the point is the
// xor of the v_k whose bit k is set in the index. Together with dimension 0 (the van der Corput sequence,
// the index's bits mirrored about the binary point) this is a (0,2)-sequence.
uint32_t sobol_dim1_by_bits(uint32_t index) {
  uint32_t result = 0;
  for (uint32_t v = 0x80000000U; index != 0; index >>= 1, v ^= v >> 1)
    if (index & 1U) result ^= v;
  return result;
}

// GPU/CPU speed only: the xor is linear in the index's bits, so it splits into its four bytes: table[b][x]
// is the xor for byte b holding x, and a point is four lookups instead of a loop over 32 bits.
struct SobolDim1Table {
  uint32_t table[4][256];
  SobolDim1Table() {
    for (uint32_t b = 0; b < 4; ++b)
      for (uint32_t x = 0; x < 256; ++x) table[b][x] = sobol_dim1_by_bits(x << (8 * b));
  }
};

uint32_t sobol_dim1(uint32_t index) {
  static const SobolDim1Table t;
  return t.table[0][index & 0xFF] ^ t.table[1][(index >> 8) & 0xFF] ^ t.table[2][(index >> 16) & 0xFF] ^
         t.table[3][index >> 24];
}

// Laine-Karras style hash that only lets each bit be affected by the bits below it; applied to the
// bit-reversed value it becomes a nested uniform (Owen) scramble (Burley 2020, Sec. 3 and Listing 2). Its
// multipliers, and SamplePair's salts, are core/sampler_shared.h's, shared with core/sampler.glsl.
uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * RTDR_LAINE_KARRAS_MULTIPLIER_1;
  x ^= x * RTDR_LAINE_KARRAS_MULTIPLIER_2;
  x ^= x * RTDR_LAINE_KARRAS_MULTIPLIER_3;
  x ^= x * RTDR_LAINE_KARRAS_MULTIPLIER_4;
  return x;
}

uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

// 32-bit fixed point in [0, 1) to float, never rounding up to 1.
float to_unit_float(uint32_t x) { return float(x >> 8) * 0x1p-24f; }

}  // namespace

// Each dimension pair gets its own seed: shuffle the index (an Owen scramble of the index itself), then
// scramble each of the two coordinates with a seed of its own (Burley 2020, Listing 3, two dimensions).
SamplePair::SamplePair(uint32_t seed, uint32_t pair) {
  const uint32_t pair_seed = hash_combine(seed, pair);
  shuffle_seed_ = hash_combine(pair_seed, RTDR_SAMPLE_PAIR_SHUFFLE_SALT);
  x_seed_ = hash_combine(pair_seed, RTDR_SAMPLE_PAIR_X_SALT);
  y_seed_ = hash_combine(pair_seed, RTDR_SAMPLE_PAIR_Y_SALT);
}

glm::vec2 SamplePair::at(uint32_t index) const {
  const uint32_t shuffled = owen_scramble(index, shuffle_seed_);
  // Dimension 0 is reverse_bits(shuffled); its Owen scramble reverse_bits(LK(reverse_bits(.))) then reverses
  // twice in a row, which cancels: reverse_bits(LK(shuffled)).
  const uint32_t x = reverse_bits(laine_karras_permutation(shuffled, x_seed_));
  const uint32_t y = owen_scramble(sobol_dim1(shuffled), y_seed_);
  return {to_unit_float(x), to_unit_float(y)};
}

glm::vec2 Sampler::next_2d() { return SamplePair(seed_, pair_++).at(index_); }

}  // namespace rtdr
