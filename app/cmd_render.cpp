// rtdr render: the G-buffer sequence of a scene, one multi-layer EXR per frame plus a PNG preview.
#include "app/commands.h"
#include "app/preview.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "raster/gbuffer_frame.h"
#include "scenes/gltf_loader.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace rtdr {
namespace {

struct RenderOptions {
  std::string scene = "pillars";
  std::string frames = "0-9";
  std::string size = "640x360";
  std::string out = "out/render";
};

std::string frame_file(const std::string& dir, int frame, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.%s", frame, ext);
  return (std::filesystem::path(dir) / name).string();
}

void make_output_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw Error("--out '" + dir + "' is not a directory that can be created (" + ec.message() + ")");
}

void run_render(const RenderOptions& o) {
  // Validate every argument before doing any work, so bad input never leaves partial output.
  const Size size = parse_size(o.size);
  const FrameRange frames = parse_frames(o.frames);
  const Scene scene = load_scene(o.scene);
  make_output_dir(o.out);

  const auto start = std::chrono::steady_clock::now();
  for (int f = frames.first; f <= frames.last; ++f) {
    const Frame frame = render_gbuffer_frame(scene, f, size.width, size.height);
    write_exr(frame_file(o.out, f, "exr"), frame);
    write_preview_png(frame_file(o.out, f, "png"), frame);
    std::printf("frame %d  t = %.4f s  -> %s\n", f, scene.time_of_frame(f), frame_file(o.out, f, "exr").c_str());
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int count = frames.last - frames.first + 1;
  std::printf("rendered %d frame(s) of '%s' at %dx%d in %.2f s; EXR layers in docs/buffers.md, previews *.png\n",
              count, scene.name.c_str(), size.width, size.height, seconds);
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand("render", "render a scene's G-buffer sequence to multi-layer EXR files");
  sub->add_option("--scene", o->scene, "shipped scene name (see scenes/) or path to a .gltf file")
      ->capture_default_str();
  sub->add_option("--frames", o->frames, "inclusive frame range A-B (or one frame A); frame f is at t = f/fps")
      ->capture_default_str();
  sub->add_option("--size", o->size, "image size WIDTHxHEIGHT")->capture_default_str();
  sub->add_option("--out", o->out, "output directory (created if missing)")->capture_default_str();
  return {sub, [o] { run_render(*o); }};
}

}  // namespace rtdr
