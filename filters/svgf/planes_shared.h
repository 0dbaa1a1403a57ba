// How the SVGF shader ports keep planes on the GPU, written once for the C++ that packs and unpacks them
// (gpu/svgf_planes.h) and the GLSL that reads them (filters/svgf/*.comp). Both compilers include this file.
//
// Every plane is row-major, pixel (x, y) at texel y * width + x, and fp32, except the illumination records of the
// fp16 builds (below). Inputs are read through core/shader_shared.h's RTDR_INPUT_* (texel buffers on lavapipe,
// storage buffers on a GPU); outputs are std430 arrays of the same texels. Several planes share one texel, so
// that a tap costs one fetch per record rather than one per plane (docs/performance.md, "Filters: the Vulkan
// ports"):
//   surface      RGBA32F  (n.x, n.y, n.z, z): world normal and linear view depth; z = kNoSurfaceDepth (-1) where
//                         the pixel has no surface (a visible surface always has z > 0, in front of the camera)
//   illumination both streams of a pixel side by side, two records per pixel (a plane twice as wide): record 2i
//                the direct stream's (kDirectStream), 2i + 1 the indirect stream's (kIndirectStream), so that a tap
//                gathers a pixel's two from one cache line: with one fetch in the fp16 storage build.
//                RGBA32F  (r, g, b, variance) per stream: its colour and its variance estimate; the noisy input and
//                         the temporal output carry variance 0 (the variance pass fills it in). 32 bytes a pixel.
//                RGBA16F  (r, g, b, sqrt(variance)) in the fp16 builds (RTDR_HALF_ILLUMINATION, <stem>_fp16*.spv;
//                         IlluminationRecords::Fp16): 16 bytes a pixel, half the bytes for the a-trous taps to
//                         gather, each value rounded to 11 significant bits and saturated at kHalfMax where it is
//                         stored. The standard deviation rather than the variance: a variance's range is the square
//                         of a colour's, so fp16 would hold the small variances of converged pixels as subnormals, a
//                         few bits each, and saturate a firefly's; the luminance weight [SVGF17 Eq. 5] divides by
//                         that standard deviation, and stored as the variance it made the pipeline's colour 5x less
//                         accurate (docs/performance.md, "Packed illumination"). Read and written with
//                         RTDR_INPUT_ILLUMINATION and RTDR_OUTPUT_ILLUMINATION, which take and give the variance.
//   moments      RGBA32F  (mu1', mu2', n, 0): the temporal pass's luminance moments and history length
//   colour       RGBA32F  (r, g, b, 0): albedo, emission, remodulated colour, display colour
//   depth_grad   RG32F    (dz/dx, dz/dy);  motion RG32F (pixels);  mesh R32UI (id.mesh, RTDR_INVALID_ID: none)
// The direct and the indirect stream, filtered separately [SVGF17 Sec. 3], go through each pass in the same
// dispatch: they share the G-buffer reads, the illumination fetches and every edge-stopping and reprojection term
// that depends on the G-buffer alone. The moments stay one plane per stream.
#ifndef RTDR_FILTERS_SVGF_PLANES_SHARED_H
#define RTDR_FILTERS_SVGF_PLANES_SHARED_H

#include "core/shader_shared.h"

#ifdef __cplusplus
namespace rtdr {
#endif

// The depth a surface record holds where the pixel has no surface.
RTDR_SHARED_CONST float kNoSurfaceDepth = -1.0f;

// A stream's record within a pixel's illumination pair (record 2i + stream), and its index in Illumination.stream.
RTDR_SHARED_CONST int kDirectStream = 0;
RTDR_SHARED_CONST int kIndirectStream = 1;

// Every SVGF port runs one invocation per pixel in workgroups of 64 invocations, a multiple of every vendor's
// subgroup size, whose shape the host fixes per device when it creates the pipelines (specialization constants
// kSvgfGroupSizeXConstant and kSvgfGroupSizeYConstant, SvgfShaders):
//   GPU:                 8x8 tiles, the shape measured on the H100 (docs/performance.md); the shaders' default.
//   CPU device (lavapipe): 32x2 rows. lavapipe runs a workgroup 8 invocations along x at a time, and a row of 32
//                        reads 512 contiguous bytes of a 16-byte plane: at the a-trous step 16, 8x8 tiles took
//                        1.4x as long there.
RTDR_SHARED_CONST RTDR_SHARED_UINT kSvgfGroupSizeX = 8;
RTDR_SHARED_CONST RTDR_SHARED_UINT kSvgfGroupSizeY = 8;
RTDR_SHARED_CONST RTDR_SHARED_UINT kSvgfCpuGroupSizeX = 32;
RTDR_SHARED_CONST RTDR_SHARED_UINT kSvgfCpuGroupSizeY = 2;
RTDR_SHARED_CONST int kSvgfGroupSizeXConstant = 0;
RTDR_SHARED_CONST int kSvgfGroupSizeYConstant = 1;

#ifdef __cplusplus
}  // namespace rtdr
#else
// A pixel's illumination, both streams: stream[kDirectStream], stream[kIndirectStream], each (r, g, b, variance).
struct Illumination {
  vec4 stream[2];
};

// RTDR_INPUT_ILLUMINATION(binding, name): an illumination plane and name(i), pixel i's Illumination;
// RTDR_OUTPUT_ILLUMINATION(binding, name): a written one and name(i, c), which stores the Illumination c.
#ifdef RTDR_HALF_ILLUMINATION
// The variance is the square of the stored standard deviation: exact in fp32 (11 significant bits squared). The
// variances stored are never negative (the variance pass clamps at 0; the a-trous levels sum squares).
vec4 variance_record(vec4 record) { return vec4(record.rgb, record.w * record.w); }
vec4 deviation_record(vec4 record) { return vec4(record.rgb, sqrt(record.w)); }
#define RTDR_INPUT_ILLUMINATION(b, name)                                                    \
  RTDR_INPUT_RGBA16F_PAIR(b, name##_halves)                                                 \
  Illumination name(int i) {                                                                \
    const vec4 records[2] = name##_halves(i);                                               \
    return Illumination(vec4[2](variance_record(records[0]), variance_record(records[1]))); \
  }
#define RTDR_OUTPUT_ILLUMINATION(b, name)                                           \
  RTDR_OUTPUT_RGBA16F_PAIR(b, name##_halves)                                        \
  void name(int i, Illumination c) {                                                \
    name##_halves(i, deviation_record(c.stream[0]), deviation_record(c.stream[1])); \
  }
#else
#define RTDR_INPUT_ILLUMINATION(b, name) \
  RTDR_INPUT_RGBA_PAIR(b, name##_floats) \
  Illumination name(int i) { return Illumination(name##_floats(i)); }
#define RTDR_OUTPUT_ILLUMINATION(b, name) \
  RTDR_OUTPUT_RGBA_PAIR(b, name##_floats) \
  void name(int i, Illumination c) { name##_floats(i, c.stream[0], c.stream[1]); }
#endif

// SurfacePlanes::covered: the surface record's pixel has a surface.
bool has_surface(vec4 surface) { return surface.w != kNoSurfaceDepth; }
#endif

#endif  // RTDR_FILTERS_SVGF_PLANES_SHARED_H
