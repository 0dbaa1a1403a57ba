// What a run of `rtdr render`, `eval` or `bench` holds in memory at once, estimated before it starts: a --size of
// 16384x16384 is refused with the size and the estimate, instead of ending in std::bad_alloc or the out-of-memory
// killer after minutes of work.
//
// How the estimate is made. Every plane holds 4 bytes per pixel (a float or a uint32: core/frame.h), so a run
// holds (the planes it keeps at once) x 4 x width x height bytes. The planes of a frame are counted on a real
// frame: one pixel rendered with the run's settings (render_frame, or render_frame_with_gradients), which has
// exactly the channels a frame of any size has. A method's planes are those its passes write
// (Method::dump_channels: its intermediate buffers and histories) and its input frame. Per command:
//   render  the frame being made; as much again for what it is made from (the visibility buffer, the G-buffer
//           and the radiance layers while they are traced, each fewer planes than the frame); and, with
//           --gradients, the previous frame: 2 or 3 frames.
//   eval    every input frame of the range at once (run_eval keeps them while each method runs over them), of
//           each input sequence (the specs' own bounces and gradient rows add sequences), and the 11 planes it keeps
//           of each reference (colour 3, display 3, direct luminance, depth, position 3), of each reference sequence
//           (one per bounces); one reference frame while it is rendered; and the method with the most planes.
//   bench   the frames a stage keeps: the sequence it filters (--stage filter: the warm-up and timed frames, and
//           the method's planes), or a frame, what it is made from and, for gradients, the previous frame.
// What does not grow with the image (the scene, Embree's BVH, the threads' stacks) is left out: where the
// estimate matters, it is small beside it. The estimate errs low rather than high: a refused run would have
// failed, and a run that passes may still need a little more.
#pragma once

#include "core/frame.h"
#include "core/memory_budget.h"
#include "filters/method.h"
#include "scenes/scene.h"
#include "trace/render_frame.h"

#include <cstdint>
#include <string>

namespace rtdr {

// The planes a run keeps at once, and how they were counted ("3 frames of 97 planes").
struct RunPlanes {
  uint64_t planes = 0;
  std::string how;
};

// The channels of `frame`, and their bytes.
uint64_t frame_planes(const Frame& frame);
uint64_t frame_bytes(const Frame& frame);

// The planes of a frame of `scene` rendered with `settings`, with gradient samples or not: counted on one pixel.
uint64_t rendered_frame_planes(const Scene& scene, const RenderSettings& settings, bool gradients);
// The planes method `method` keeps besides its input: the buffers its passes write (its dump channels).
uint64_t method_planes(const Method& method);

RunPlanes render_planes(uint64_t frame_planes, bool gradients);
RunPlanes eval_planes(uint64_t frame_planes, int frames, uint64_t most_method_planes, int input_sequences = 1,
                      int reference_sequences = 1);
RunPlanes bench_planes(uint64_t frame_planes, int frames, uint64_t method_planes);

// Bytes of `run` at width x height: planes x 4 x pixels (UINT64_MAX when that overflows).
uint64_t run_bytes(const RunPlanes& run, int width, int height);
// Throws a one-line rtdr::Error "--size WxH: <command> would hold about <bytes> (<how>, 4 bytes a pixel
// each), more than the <budget> of memory available (bound by <source>)" when run_bytes exceeds budget.bytes.
void require_run_fits(const std::string& command, int width, int height, const RunPlanes& run,
                      const MemoryBudget& budget);

}  // namespace rtdr
