// rtdr eval: every method on one scene against reference frames; metrics.csv, the three charts and the strip in
// --out. What is measured on which images: eval/experiment.h; what the charts and the strip show: eval/charts.py.
#include "app/backend.h"
#include "app/commands.h"
#include "app/preview.h"
#include "app/sequence.h"
#include "core/atomic_file.h"
#include "core/data_path.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/subprocess.h"
#include "eval/experiment.h"
#include "eval/render_plan.h"
#include "filters/method.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>
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
  std::string plan;  // --plan FILE: write the renders the run needs, run nothing
  bool gradients = false;
  GradientParams gradient;
  std::string chart_metrics = "rmse,ssim,flip";
  std::string strip;      // the specs strip.png shows; "" for every method that ran, up to strip_max
  int strip_max = 10;
  std::string strip_crop = "auto";
};

// The specs named in --methods (every method for "all"), without the sweeps.
std::vector<std::string> named_specs(const std::string& methods) {
  if (methods == "all") return method_names();
  std::vector<std::string> texts;
  std::stringstream ss(methods);
  for (std::string m; std::getline(ss, m, ',');)
    if (!m.empty()) texts.push_back(m);
  return texts;
}

std::vector<MethodSpec> method_specs(const EvalOptions& o) {
  std::vector<std::string> texts = named_specs(o.methods);
  if (o.sweep)
    for (const std::string& s : standard_sweep(texts)) texts.push_back(s);
  std::vector<MethodSpec> specs;
  for (const std::string& t : texts) specs.push_back(parse_method_spec(t));
  return specs;
}

// The tiles of strip.png (eval/strip.py), in order: the 1-spp input, the methods that ran (those of --strip, or
// every one up to --strip-max), the reference. `none` is the input remodulated, the same image: its tile is the
// input's. Each tile's last frame is written as a PNG into `folder`; returns (label, path) pairs and says on the
// terminal what was left out.
std::vector<std::pair<std::string, std::string>> write_strip_tiles(
    const EvalOptions& o, const std::vector<std::pair<std::string, RgbPlane>>& last_frame, const std::string& folder) {
  std::vector<std::string> chosen;  // the specs to show, in the order run
  std::set<std::string> wanted;
  if (!o.strip.empty())
    for (const std::string& spec : named_specs(o.strip)) wanted.insert(spec);
  bool none = false;
  for (size_t k = 1; k + 1 < last_frame.size(); ++k) {
    const std::string& spec = last_frame[k].first;
    if (spec == "none") none = true;
    else if (o.strip.empty() || wanted.count(spec)) chosen.push_back(spec);
  }
  if (int(chosen.size()) > o.strip_max) {
    std::printf("strip.png shows the first %d of the %zu methods that ran (--strip-max; choose with --strip)\n",
                o.strip_max, chosen.size());
    chosen.resize(size_t(o.strip_max));
  }
  std::vector<std::pair<std::string, std::string>> tiles;
  std::filesystem::create_directories(folder);
  for (const auto& [label, image] : last_frame) {
    const bool input = &label == &last_frame.front().first, reference = &label == &last_frame.back().first;
    if (!input && !reference && std::find(chosen.begin(), chosen.end(), label) == chosen.end()) continue;
    // Absolute, so that no path is taken for an option of charts.py (a --out of "-x").
    const std::string path = std::filesystem::absolute(folder + "/tile_" + std::to_string(tiles.size()) + ".png").string();
    write_display_png(path, image);
    tiles.push_back({input && none ? label + " (= none)" : label, path});
  }
  return tiles;
}

// The chart and strip options, checked before anything is rendered (charts.py would only refuse them at the end).
void check_chart_options(const EvalOptions& o, const std::vector<MethodSpec>& specs, Size size) {
  std::stringstream metrics(o.chart_metrics);
  const std::set<std::string> known = {"rmse", "relmse", "ssim", "flip", "umbra_rmse"};
  for (std::string m; std::getline(metrics, m, ',');)
    if (!known.count(m)) throw Error("--chart-metrics: '" + m + "' is not one of rmse, relmse, ssim, flip, umbra_rmse");
  if (!o.strip.empty())
    for (const std::string& spec : named_specs(o.strip))
      if (std::none_of(specs.begin(), specs.end(), [&](const MethodSpec& s) { return s.text == spec; }))
        throw Error("--strip names '" + spec + "', which is not one of the methods that run (--methods, --sweep)");
  if (o.strip_crop == "auto" || o.strip_crop == "full") return;
  std::vector<long> v;  // X, Y, W, H: whole numbers, each below the size's limit
  std::stringstream crop(o.strip_crop);
  for (std::string part; std::getline(crop, part, ',');) {
    long n = -1;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), n);
    v.push_back(ec == std::errc() && end == part.data() + part.size() && n >= 0 && n <= 16384 ? n : -1);
  }
  if (v.size() != 4 || *std::min_element(v.begin(), v.end()) < 0 || v[2] < 1 || v[3] < 1 ||
      v[0] + v[2] > size.width || v[1] + v[3] > size.height)
    throw Error("--strip-crop '" + o.strip_crop + "' is not auto, full or X,Y,W,H inside the " + o.size + " frame");
}

// --plan: the renders this run needs and its cache lacks, one JSON line per job (eval/render_plan.h), written whole;
// nothing is rendered and --out is not touched. argv[0] of each job is this rtdr, by its absolute path.
void write_plan(const EvalConfig& config, const std::string& file) {
  const std::vector<RenderJob> jobs = plan_renders(config, std::filesystem::read_symlink("/proc/self/exe").string());
  std::string text;
  int frames = 0;
  double cost = 0.0;
  for (size_t k = 0; k < jobs.size(); ++k) {
    text += plan_line(jobs[k], int(k)) + "\n";
    frames += jobs[k].last - jobs[k].first + 1;
    cost += double(jobs[k].cost());
  }
  write_text_file(file, text);
  if (jobs.empty())
    std::printf("wrote no job to %s: the cache holds every frame this run needs\n", file.c_str());
  else
    std::printf("wrote %zu job(s) to %s: %d frame(s) the cache lacks, %.4g pixel samples; run them with "
                "tools/farm.py, then this command without --plan (docs/scaling.md)\n", jobs.size(), file.c_str(),
                frames, cost);
}

void run_eval_command(const EvalOptions& o) {
  const Size size = parse_size(o.size);
  const FrameRange frames = parse_frames(o.frames);
  EvalConfig config;
  config.scene = o.scene;
  config.methods = method_specs(o);
  check_chart_options(o, config.methods, size);
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
  if (!o.plan.empty()) return write_plan(config, o.plan);
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
  const std::string tile_folder = out.file(".strip-tiles");  // inside the staging folder, removed before the commit
  const auto tiles = write_strip_tiles(o, result.last_frame, tile_folder);
  // The chart script gets its arguments as a vector, never through a shell: a path or scene name holding a
  // quote is just a name; a value joined to its option by '=' stays a value even if it starts with '-', and "--"
  // ends the options, so a path that starts with '-' is not taken for one. Installed, the script is <prefix>/share/rtdr/eval/.
  std::vector<std::string> charts = {"/usr/bin/python3", data_path("eval/charts.py", RTDR_SOURCE_DIR "/eval/charts.py"),
                                     "--title=" + o.scene, "--metrics=" + o.chart_metrics,
                                     "--crop=" + o.strip_crop, "--lines="};
  for (const std::string& spec : named_specs(o.methods)) charts.back() += (charts.back().back() == '=' ? "" : ",") + spec;
  for (const auto& [label, path] : tiles) charts.insert(charts.end(), {"--tile", label, path});
  charts.insert(charts.end(), {"--", out.file("metrics.csv"), out.staging()});
  const ProgramResult drawn = run_program(charts);
  std::error_code ec;
  std::filesystem::remove_all(tile_folder, ec);
  if (drawn.exit_code != 0) throw Error("the charts failed: " + last_line(drawn.error_output));
  out.commit();
  std::printf("wrote metrics.csv, speed_vs_accuracy.png, error_over_frames.png, temporal_error.png and strip.png "
              "in %s\n", o.out.c_str());
  std::printf("metrics.csv: rmse, relmse, brightness_error on linear HDR radiance; ssim, flip, temporal_error on "
              "tone-mapped display values (eval/README.md)\n");
  std::printf("strip.png, in reading order:");
  for (const auto& [label, path] : tiles) std::printf(" | %s", label.c_str());
  std::printf("\n");
}

}  // namespace

Command add_eval_command(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* sub = app.add_subcommand("eval", "run methods against reference frames: metrics.csv, charts, a strip");
  sub->add_option("--scene", o->scene, "shipped scene name or .gltf path")->capture_default_str();
  std::string names;
  for (const std::string& n : method_names()) names += (names.empty() ? "" : ", ") + n;
  sub->add_option("--methods", o->methods,
                  "comma-separated method specs name[:param=value...], or all; the names: " + names +
                      "; the parameters: rows of svgf_params.h, asvgf_params.h, trmv_params.h (trmv:motion=shadow); "
                      "backend=vulkan runs the method on its shader ports (svgf, asvgf, trmv), illumination=fp16 "
                      "with half records; gradient_<row> gives a method its own gradient input, e.g. "
                      "asvgf:gradient_stratum_size=2 (eval/README.md)")
      ->capture_default_str();
  sub->add_flag("--sweep", o->sweep,
                "add the parameter sweeps: svgf's a-trous levels, alpha and 3x3 kernel; with asvgf, 2x2 and 4x4 strata");
  sub->add_option("--frames", o->frames, frames_help(""))->capture_default_str();
  sub->add_option("--size", o->size, "image size WIDTHxHEIGHT; refused when the run would not fit in the memory available")
      ->capture_default_str();
  sub->add_option("--ref-spp", o->ref_spp, "samples per pixel of the reference frames")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  sub->add_option("--seed", o->seed, "seed of the 1-spp inputs (references use another)")->capture_default_str();
  sub->add_option("--max-bounces", o->max_bounces,
                  "indirect bounces of inputs and references; 0: next-event estimation only, one shadow ray per "
                  "pixel (a method spec's max_bounces=N gives it inputs and references of its own)")
      ->check(CLI::Range(0, 1024))->capture_default_str();
  sub->add_option("--cache", o->cache, "where rendered frames are cached (\"\" for none)")->capture_default_str();
  sub->add_option("--out", o->out, "output directory")->capture_default_str();
  sub->add_option("--plan", o->plan,
                  "render nothing: write to FILE the renders this run needs and --cache lacks, one JSON line per "
                  "rtdr render job, for tools/farm.py or a batch scheduler (docs/scaling.md)")
      ->type_name("FILE");
  sub->add_flag("--gradients", o->gradients,
                "every method's input has A-SVGF's gradient samples (rtdr render --gradients), rendered from frame 0");
  add_gradient_flags(sub, o->gradient);
  sub->add_option("--chart-metrics", o->chart_metrics,
                  "the metrics charted, one panel each: comma-separated columns of metrics.csv among rmse, relmse, "
                  "ssim, flip, umbra_rmse")
      ->capture_default_str();
  sub->add_option("--strip", o->strip, "comma-separated specs strip.png shows (default: every method that ran)");
  sub->add_option("--strip-max", o->strip_max, "at most this many methods in strip.png")
      ->check(CLI::Range(1, 64))->capture_default_str();
  sub->add_option("--strip-crop", o->strip_crop,
                  "strip.png's crop of the last frame: auto (the half-size window where the methods differ most), "
                  "full, or X,Y,W,H in pixels")
      ->capture_default_str();
  return {sub, [o] { run_eval_command(*o); }};
}

}  // namespace rtdr
