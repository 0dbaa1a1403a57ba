// The constants of core/sampler.h's integer hashes, written once for C++ (hash_u32, hash_combine) and GLSL
// (core/sampler.glsl, for the render side's ports). Plain preprocessor with `u`-suffixed literals, which both
// languages read as 32-bit unsigned integers, so a port's hash is the C++ one bit for bit: the same seed gives the
// same sample on both sides [ASVGF18 Sec. 3.2, Eq. 6].
#ifndef RTDR_CORE_SAMPLER_SHARED_H
#define RTDR_CORE_SAMPLER_SHARED_H

// The two multipliers of the "lowbias32" finalizer (C. Wellons' hash prospector), hash_u32.
#define RTDR_HASH_MULTIPLIER_1 0x7feb352du
#define RTDR_HASH_MULTIPLIER_2 0x846ca68bu
// hash_combine's added constant: 2^32 / golden ratio (Boost's hash_combine).
#define RTDR_HASH_COMBINE_CONSTANT 0x9e3779b9u
// SamplePair's three seeds of a dimension pair, hashed into its pair seed: the index's shuffle, then the x and the
// y scramble (core/sampler.cpp; Burley 2020, Listing 3).
#define RTDR_SAMPLE_PAIR_SHUFFLE_SALT 0xa511e9b3u
#define RTDR_SAMPLE_PAIR_X_SALT 0x63d83595u
#define RTDR_SAMPLE_PAIR_Y_SALT 0x8c7a2f13u
// The four multipliers of the Laine-Karras permutation (Burley 2020, Listing 2), core/sampler.cpp.
#define RTDR_LAINE_KARRAS_MULTIPLIER_1 0x6c50b47cu
#define RTDR_LAINE_KARRAS_MULTIPLIER_2 0xb82f1e52u
#define RTDR_LAINE_KARRAS_MULTIPLIER_3 0xc7afe638u
#define RTDR_LAINE_KARRAS_MULTIPLIER_4 0x8d22f6e6u

#endif  // RTDR_CORE_SAMPLER_SHARED_H
