// Tests of eval/run_memory.cpp: a frame's planes counted on one pixel are those of a frame of any size; the
// estimate's arithmetic per command; a size just over a budget (passed in) is refused with the size and the
// estimate, and the size at the budget and an ordinary one against this machine's budget are not.
#include "eval/run_memory.h"

#include "core/error.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"

#include <catch2/catch.hpp>

using namespace rtdr;

TEST_CASE("run memory: a frame's planes counted on one pixel are those of a real frame, as bytes too") {
  const Scene scene = load_scene("cornell");
  RenderSettings settings;
  const Frame frame = render_frame(scene, 3, 12, 7, settings);
  CHECK(rendered_frame_planes(scene, settings, false) == frame_planes(frame));
  CHECK(frame_bytes(frame) == frame_planes(frame) * 4 * 12 * 7);
  const Frame gradients = render_frame_with_gradients(scene, 0, 12, 7, settings, {}, nullptr);
  CHECK(rendered_frame_planes(scene, settings, true) == frame_planes(gradients));
  CHECK(frame_planes(gradients) > frame_planes(frame));  // gradient.source, prev_direct, ... on top
  settings.trace.shading_samples = 4;  // TRMV's input adds direct.shading
  CHECK(rendered_frame_planes(scene, settings, false) == frame_planes(render_frame(scene, 0, 2, 2, settings)));
}

TEST_CASE("run memory: the planes each command keeps, and the bytes at a size") {
  CHECK(render_planes(90, false).planes == 180);
  CHECK(render_planes(90, true).planes == 270);
  CHECK(eval_planes(90, 3, 40).planes == 3 * (90 + 11) + 90 + 40);
  CHECK(eval_planes(90, 3, 40, 2, 3).planes == 3 * (2 * 90 + 3 * 11) + 90 + 40);  // two inputs, three references
  CHECK(bench_planes(90, 10, 40).planes == 940);
  CHECK(run_bytes(render_planes(90, false), 640, 360) == uint64_t(180) * 4 * 640 * 360);
  CHECK(run_bytes({uint64_t(1) << 62, ""}, 16384, 16384) == UINT64_MAX);  // saturates, never wraps
}

TEST_CASE("run memory: a size just over the budget is refused with the size and the estimate, one at it is not") {
  const RunPlanes run = render_planes(90, true);
  const MemoryBudget budget{run_bytes(run, 640, 360), "MemAvailable"};
  CHECK_NOTHROW(require_run_fits("render", 640, 360, run, budget));
  CHECK_THROWS_WITH(require_run_fits("render", 641, 360, run, budget),
                    "--size 641x360: render would hold about 238 MiB (3 frames of 90 planes: the frame, what it is "
                    "made from, the previous, 4 bytes a pixel each), more than the 237 MiB of memory available "
                    "(bound by MemAvailable); choose a smaller --size");
  // An ordinary size fits this machine's budget, whatever the command.
  const Scene scene = load_scene("cornell");
  const uint64_t planes = rendered_frame_planes(scene, {}, true);
  for (const RunPlanes& r : {render_planes(planes, true), eval_planes(planes, 10, 60), bench_planes(planes, 25, 60)})
    CHECK_NOTHROW(require_run_fits("a command", 320, 180, r, memory_budget()));
  CHECK_THROWS_AS(require_run_fits("render", 16384, 16384, render_planes(planes, true), {uint64_t(64) << 30, "x"}),
                  Error);
}
