// rtdr eval: every method on one scene against reference frames; metrics.csv, the three charts and a
// side-by-side strip in --out. What is measured on which images: eval/experiment.h.
#include "app/backend.h"
#include "app/commands.h"
#include "app/preview.h"
#include "app/sequence.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/subprocess.h"
#include "eval/experiment.h"
#include "filters/method.h"

#include <cstdio>
#include <memory>
#include <sstream>

namespace rtdr {
namespace {

struct EvalOptions {
  std::string scene = "pillars";
  std::string methods = "all";
  bool sweep = false;
  std::string frames = "0-23";
  std::string size = "320x180";
  int ref_spp = 256;
  uint32_t seed = 0;
  int max_bounces = 1;
  std::string cache = "out/cache";
  std::string out = "out/eval";
  bool gradients = false;
  GradientParams gradient;
};

std::vector<MethodSpec> method_specs(const EvalOptions& o) {
  std::vector<std::string> texts;
  if (o.methods == "all") {
    texts = method_names();
  } else {
    std::stringstream ss(o.methods);
    for (std::string m; std::getline(ss, m, ',');)
      if (!m.empty()) texts.push_back(m);
  }
  if (o.sweep)
    for (const std::string& s : standard_sweep(texts)) texts.push_back(s);
  std::vector<MethodSpec> specs;
  for (const std::string& t : texts) specs.push_back(parse_method_spec(t));
  return specs;
}

// The last frame of every method side by side, left to right in the order printed.
void write_strip(const std::string& path, const std::vector<std::pair<std::string, RgbPlane>>& images) {
  const int w = images.front().second.width, h = images.front().second.height, n = int(images.size());
  RgbPlane strip(w * n, h);
  for (int k = 0; k < n; ++k)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) strip.at(k * w + x, y) = images[size_t(k)].second.at(x, y);
  write_display_png(path, strip);
}

void run_eval_command(const EvalOptions& o) {
  const Size size = parse_size(o.size);
  const FrameRange frames = parse_frames(o.frames);
  EvalConfig config;
  config.scene = o.scene;
  config.methods = method_specs(o);
  config.first_frame = frames.first;
  config.last_frame = frames.last;
  config.width = size.width;
  config.height = size.height;
  config.ref_spp = o.ref_spp;
  config.seed = o.seed;
  config.max_bounces = o.max_bounces;
  config.cache_dir = o.cache;
  config.gradients = o.gradients;
  config.gradient = o.gradient;
  validate(o.gradient);
  SpecMethods methods;  // outlives every method run_eval makes
  config.make_method = [&methods](const MethodSpec& spec) { return methods.make(spec); };
  StagedOutputDir out(o.out);  // every output appears at the end, or none does

  EvalResult result;
  {
    // The bar counts frames rendered (or read from the cache) and filtered; run_eval knows the total.
    std::unique_ptr<ProgressBar> bar;
    result = run_eval(config, [&](int done, int total) {
      if (!bar) bar = std::make_unique<ProgressBar>("eval " + o.scene, uint64_t(total));
      bar->advance();
      static_cast<void>(done);
    });
  }
  write_metrics_csv(out.file("metrics.csv"), result.rows);
  write_strip(out.file("strip.png"), result.last_frame);
  // The chart script gets its arguments as a vector, never through a shell: a path or scene name holding a
  // quote is just a name. "--" ends the options, so a name that starts with '-' is not taken for one.
  const ProgramResult charts = run_program({"/usr/bin/python3", RTDR_SOURCE_DIR "/eval/charts.py",
                                            "--title=" + o.scene, "--", out.file("metrics.csv"), out.staging()});
  if (charts.exit_code != 0)
    throw Error("the charts failed: " + last_line(charts.error_output));
  out.commit();
  std::printf("wrote metrics.csv, speed_vs_accuracy.png, error_over_frames.png, temporal_error.png and strip.png "
              "in %s\n", o.out.c_str());
  std::printf("metrics.csv: rmse, relmse, brightness_error on linear HDR radiance; ssim, flip, temporal_error on "
              "tone-mapped display values (eval/README.md)\n");
  std::printf("strip.png, left to right:");
  for (const auto& [name, image] : result.last_frame) std::printf(" | %s", name.c_str());
  std::printf("\n");
}

}  // namespace

Command add_eval_command(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* sub = app.add_subcommand("eval", "run methods against reference frames: metrics.csv, charts, a strip");
  sub->add_option("--scene", o->scene, "shipped scene name or .gltf path")->capture_default_str();
  sub->add_option("--methods", o->methods,
                  "comma-separated method specs (name[:param=value...]) or all; backend=vulkan runs svgf on the "
                  "shader ports, illumination=fp16 with half records; gradient_<row> gives a method its own gradient "
                  "input, e.g. asvgf:gradient_stratum_size=2 (eval/README.md)")
      ->capture_default_str();
  sub->add_flag("--sweep", o->sweep,
                "add the parameter sweeps: svgf's a-trous levels, alpha and 3x3 kernel; with asvgf, 2x2 and 4x4 strata");
  sub->add_option("--frames", o->frames, frames_help(""))->capture_default_str();
  sub->add_option("--size", o->size, "image size WIDTHxHEIGHT")->capture_default_str();
  sub->add_option("--ref-spp", o->ref_spp, "samples per pixel of the reference frames")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  sub->add_option("--seed", o->seed, "seed of the 1-spp inputs (references use another)")->capture_default_str();
  sub->add_option("--max-bounces", o->max_bounces,
                  "indirect bounces of inputs and references; 0: next-event estimation only, one shadow ray per "
                  "pixel (a method spec's max_bounces=N gives it inputs and references of its own)")
      ->check(CLI::Range(0, 1024))->capture_default_str();
  sub->add_option("--cache", o->cache, "where rendered frames are cached (\"\" for none)")->capture_default_str();
  sub->add_option("--out", o->out, "output directory")->capture_default_str();
  sub->add_flag("--gradients", o->gradients,
                "every method's input has A-SVGF's gradient samples (rtdr render --gradients), rendered from frame 0");
  add_gradient_flags(sub, o->gradient);
  return {sub, [o] { run_eval_command(*o); }};
}

}  // namespace rtdr
