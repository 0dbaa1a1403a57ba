// The plan of a run's renders: see render_plan.h.
#include "eval/render_plan.h"

#include "core/error.h"
#include "eval/frame_cache.h"
#include "filters/method.h"
#include "scenes/gltf_loader.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>

namespace rtdr {
namespace fs = std::filesystem;
namespace {

// One sequence the run reads: its frames first_frame..last_frame, rendered with these settings.
struct Sequence {
  std::string what;
  RenderSettings settings;
  const GradientParams* gradients = nullptr;  // null: without gradient samples
};

// `rtdr render`'s flag of a gradient parameter table row (app/options.cpp add_gradient_flags): --gradient-<name>,
// hyphens for underscores.
std::string gradient_flag(std::string name) {
  for (char& c : name)
    if (c == '_') c = '-';
  return "--gradient-" + name;
}

// The `rtdr render` command line of frames first..last of `s`, but --out: every keyed attribute of
// trace/render_key.h that a flag sets is given, so the frames carry exactly the key the eval looks up.
std::vector<std::string> render_argv(const std::string& rtdr, const Scene& scene, const EvalConfig& c,
                                     const Sequence& s, int first, int last) {
  // rtdr render has no flag for the regularized roughness: it renders with the default, as run_eval does.
  if (s.settings.trace.regularized_roughness != TraceOptions{}.regularized_roughness)
    throw Error("--plan: rtdr render cannot be given a regularized roughness other than its default");
  std::vector<std::string> argv = {
      rtdr, "render",
      "--scene", fs::absolute(scene.source).lexically_normal().string(),
      "--frames", std::to_string(first) + "-" + std::to_string(last),
      "--size", std::to_string(c.width) + "x" + std::to_string(c.height),
      "--spp", std::to_string(s.settings.spp),
      "--seed", std::to_string(s.settings.seed),
      "--max-bounces", std::to_string(s.settings.trace.max_bounces),
      "--shading-samples", std::to_string(s.settings.trace.shading_samples)};
  if (s.gradients) {
    argv.push_back("--gradients");
    const std::vector<ParamInfo> table = gradient_param_table();
    const std::vector<double> values = param_values(*s.gradients);
    for (size_t k = 0; k < table.size(); ++k) {
      argv.push_back(gradient_flag(table[k].name));
      argv.push_back(std::to_string(int64_t(values[k])));  // every row is an int, as render_key writes it
    }
  }
  return argv;
}

}  // namespace

std::vector<RenderJob> plan_renders(const EvalConfig& c, const std::string& rtdr) {
  check_eval_config(c);
  if (c.cache_dir.empty())
    throw Error("--plan lists the frames the cache lacks: give it a --cache (one every machine sees at the same path)");
  const Scene scene = load_scene(c.scene);
  const std::string cache_dir = fs::absolute(c.cache_dir).lexically_normal().string();
  const FrameCache cache(cache_dir, scene);
  // What the methods read decides what is rendered. The golden method of each spec stands for it on any back end:
  // a Vulkan port reads what its golden method reads (the same InputChannels functions), and needs no device here.
  std::vector<std::unique_ptr<Method>> methods;
  std::vector<const Method*> made;
  for (const MethodSpec& spec : c.methods) {
    methods.push_back(make_method(spec.name, spec_params(spec)));
    made.push_back(methods.back().get());
  }
  const EvalRenders renders = eval_renders(c, made);

  std::vector<RenderJob> jobs;
  const auto key = [&](const Sequence& s, int f) {
    return render_key(scene, f, c.width, c.height, s.settings, s.gradients);
  };
  const auto add_job = [&](const Sequence& s, int first, int last) {
    RenderJob job;
    job.what = s.what;
    job.argv = render_argv(rtdr, scene, c, s, first, last);
    job.first = first;
    job.last = last;
    for (int f = first; f <= last; ++f) job.entries.push_back(cache.path(key(s, f)));
    job.dependent = s.gradients != nullptr;
    if (job.dependent && first > 0) job.previous = cache.path(key(s, first - 1));
    job.cache = cache_dir;
    job.pixels = int64_t(c.width) * c.height;
    job.spp = s.settings.spp;
    jobs.push_back(job);
  };
  // Frames that depend on nothing: one job each, for those the cache lacks (FrameCache::get renders them).
  const auto add_frames = [&](const Sequence& s) {
    for (int f = c.first_frame; f <= c.last_frame; ++f)
      if (!cache.has(key(s, f))) add_job(s, f, f);
  };
  for (const RenderSettings& reference : renders.references) add_frames({"reference", reference});
  for (const EvalRenders::Input& input : renders.inputs) {
    if (!input.gradient) {
      add_frames({"input", input.settings});
      continue;
    }
    // Runs of frames, each from the one before: cut as FrameCache::gradient_frames renders them.
    const Sequence s{"input with gradient samples", input.settings, &*input.gradient};
    const auto cached = [&](int f) { return cache.has(key(s, f)); };
    for (const GradientRun& run : gradient_runs(c.first_frame, c.last_frame, cached)) add_job(s, run.first, run.last);
  }
  return jobs;
}

std::string plan_line(const RenderJob& job, int index) {
  nlohmann::ordered_json line;
  line["job"] = index;
  line["what"] = job.what;
  line["frames"] = {job.first, job.last};
  line["dependent"] = job.dependent;
  line["argv"] = job.argv;
  line["entries"] = job.entries;
  line["previous"] = job.previous.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(job.previous);
  line["cache"] = job.cache;
  line["pixels"] = job.pixels;
  line["spp"] = job.spp;
  line["cost"] = job.cost();
  try {
    return line.dump();
  } catch (const nlohmann::json::exception&) {  // a path that is not UTF-8 has no JSON string
    throw Error("--plan: a path of job " + std::to_string(index) + " is not UTF-8, which JSON cannot hold: '" +
                job.entries.front() + "'");
  }
}

}  // namespace rtdr
