// Tests of eval/experiment.cpp's plumbing: method specs with their back end, the method factory, and which pass
// times make up ms_total, the cache of gradient inputs, a spec's own gradient input, and the observer. What the metrics measure is tested in eval_metrics_test.cpp, and what they say about the
// methods in eval_stability_test.cpp; the Vulkan ports under rtdr eval in app_eval_test.cpp.
#include "eval/experiment.h"

#include "core/error.h"
#include "eval/frame_cache.h"
#include "eval/metrics.h"
#include "scenes/gltf_loader.h"

#include "cli_fixtures.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <map>

namespace fs = std::filesystem;

namespace {

// The "none" method, with a made-up "transfer" time added to its pass times: what the Vulkan ports report beside
// their device times.
class WithTransfer : public rtdr::Method {
 public:
  static constexpr double kTransferMs = 1000.0;
  std::string name() const override { return inner_->name(); }
  rtdr::Frame filter(const rtdr::Frame& in, rtdr::Frame* dump) override {
    rtdr::Frame out = inner_->filter(in, dump);
    times_ = inner_->pass_times();
    times_[rtdr::kTransferPass] = kTransferMs;
    return out;
  }
  void reset() override { inner_->reset(); }
  rtdr::Probe probe(const std::string& pass, int x, int y, const std::string& stream, int level) const override {
    return inner_->probe(pass, x, y, stream, level);
  }
  std::vector<std::string> probe_passes() const override { return inner_->probe_passes(); }
  rtdr::InputChannels inputs() const override { return inner_->inputs(); }
  std::vector<std::string> dump_channels() const override { return inner_->dump_channels(); }

 private:
  std::unique_ptr<rtdr::Method> inner_ = rtdr::make_method("none");
};

rtdr::EvalConfig tiny_config(const std::vector<std::string>& specs) {
  rtdr::EvalConfig c;
  c.scene = "pillars";
  for (const std::string& s : specs) c.methods.push_back(rtdr::parse_method_spec(s));
  c.first_frame = 0;
  c.last_frame = 1;
  c.width = 24;
  c.height = 16;
  c.ref_spp = 2;
  c.cache_dir = "";
  return c;
}

}  // namespace

TEST_CASE("method specs: parameters, back end and illumination records, each checked") {
  const rtdr::MethodSpec plain = rtdr::parse_method_spec("svgf:atrous_levels=3");
  CHECK(plain.name == "svgf");
  CHECK(plain.params == "atrous_levels=3");
  CHECK(plain.svgf.atrous_levels == 3);
  CHECK(plain.backend == "cpu");
  CHECK(plain.illumination.empty());

  const rtdr::MethodSpec port = rtdr::parse_method_spec("svgf:backend=vulkan:illumination=fp16:kernel_size=3");
  CHECK(port.backend == "vulkan");
  CHECK(port.illumination == "fp16");
  CHECK(port.svgf.kernel_size == 3);
  CHECK(port.params == "backend=vulkan:illumination=fp16:kernel_size=3");  // the CSV tells the rows apart
  CHECK(rtdr::parse_method_spec("svgf:backend=cpu").backend == "cpu");

  // A method's own defaults first, then the keys of either table (svgf_params.h, asvgf_params.h).
  const rtdr::MethodSpec asvgf = rtdr::parse_method_spec("asvgf:gradient_levels=3:alpha=0.3");
  CHECK(asvgf.asvgf.gradient_levels == 3);
  CHECK(asvgf.svgf.alpha == 0.3f);
  CHECK(asvgf.svgf.alpha_moments == 0.1f);  // asvgf's default, not svgf's 0.2
  CHECK(asvgf.svgf.kernel_size == 3);
  CHECK(rtdr::spec_params(asvgf).asvgf.gradient_levels == 3);
  CHECK_THROWS_WITH(rtdr::parse_method_spec("asvgf:gradient_levels=11"), Catch::Contains("gradient_levels"));

  // trmv's own table first: its alpha is TRMV's (the svgf table has a row of the same name); motion by name.
  const rtdr::MethodSpec trmv = rtdr::parse_method_spec("trmv:alpha=0.3:clamp_gamma=0:motion=traditional");
  CHECK(trmv.trmv.alpha == 0.3f);
  CHECK(trmv.svgf.alpha == rtdr::SvgfParams{}.alpha);
  CHECK(trmv.trmv.clamp_gamma == 0.0f);
  CHECK(trmv.trmv.motion == 0);
  CHECK(rtdr::spec_params(trmv).trmv.alpha == 0.3f);
  CHECK(rtdr::parse_method_spec("trmv:motion=shadow").trmv.motion == 1);
  CHECK(rtdr::parse_method_spec("trmv:motion=dual").trmv.motion == 2);
  CHECK(rtdr::parse_method_spec("trmv:motion=glossy").trmv.motion == 3);
  CHECK(rtdr::parse_method_spec("trmv").trmv.motion == 4);  // the paper: each component its own vector
  CHECK_THROWS_WITH(rtdr::parse_method_spec("trmv:motion=mirror"),
                    Catch::Contains("motion=traditional|shadow|dual|glossy|all"));

  for (const char* bad : {"svgf:backend=metal", "svgf:backend=", "svgf:backend", "svgf:illumination=fp16",
                          "svgf:backend=cpu:illumination=fp32", "svgf:backend=vulkan:illumination=fp8",
                          "svgf:sigma_q=1", "svgf:atrous_levels=11", "nothing:backend=vulkan"}) {
    INFO(bad);
    CHECK_THROWS_AS(rtdr::parse_method_spec(bad), rtdr::Error);
  }
}

TEST_CASE("run_eval makes every method before rendering, and without a factory runs the golden passes only") {
  const fs::path cache = rtdr::cli::scratch("rtdr_eval_experiment_test", "cache");
  rtdr::EvalConfig c = tiny_config({"svgf", "svgf:backend=vulkan"});
  c.cache_dir = cache.string();
  CHECK_THROWS_WITH(rtdr::run_eval(c), Catch::Contains("svgf:backend=vulkan") && Catch::Contains("cpu only"));
  CHECK(fs::is_empty(cache));  // no frame was rendered first

  // A factory that fails on the second spec fails just as early.
  c.make_method = [](const rtdr::MethodSpec& spec) -> std::unique_ptr<rtdr::Method> {
    if (spec.backend == "vulkan") throw rtdr::Error("no device");
    return rtdr::make_method(spec.name, spec.svgf);
  };
  CHECK_THROWS_WITH(rtdr::run_eval(c), "no device");
  CHECK(fs::is_empty(cache));
}

TEST_CASE("ms_total is the sum of the pass times without the host's transfer, which has its own column") {
  rtdr::EvalConfig c = tiny_config({"none", "svgf"});
  int made = 0;
  c.make_method = [&made](const rtdr::MethodSpec& spec) -> std::unique_ptr<rtdr::Method> {
    ++made;
    if (spec.name == "none") return std::make_unique<WithTransfer>();
    return rtdr::make_method(spec.name, spec.svgf);
  };
  const rtdr::EvalResult result = rtdr::run_eval(c);
  CHECK(made == 2);
  REQUIRE(result.rows.size() == 4);  // 2 methods x 2 frames
  for (const rtdr::MetricsRow& row : result.rows) {
    INFO(row.method << " frame " << row.frame);
    double sum = 0.0;
    for (const auto& [pass, ms] : row.ms)
      if (pass != "transfer") sum += ms;
    CHECK(row.ms.size() >= 2);
    CHECK(row.ms_total == Approx(sum).epsilon(1e-12));
    CHECK(row.ms.count("transfer") == (row.method == "none" ? 1u : 0u));
    if (row.method == "none") CHECK(row.ms.at("transfer") == WithTransfer::kTransferMs);
  }
}

TEST_CASE("gradient inputs are cached under every gradient parameter and continue from the latest cached frame") {
  const rtdr::Scene scene = rtdr::load_scene("pillars");
  const fs::path dir = rtdr::cli::scratch("rtdr_eval_experiment_test", "gradients");
  rtdr::FrameCache cache(dir.string(), scene);
  const rtdr::RenderSettings settings;
  const rtdr::GradientParams params;
  rtdr::GradientParams other;
  other.light_cdf = 1;
  const auto path = [&](int f) { return cache.path(rtdr::render_key(scene, f, 24, 16, settings, &params)); };
  CHECK(path(3) != cache.path(rtdr::render_key(scene, 3, 24, 16, settings, &other)));
  CHECK(path(3) != cache.path(rtdr::render_key(scene, 3, 24, 16, settings)));
  CHECK_THAT(path(3), Catch::Contains("pillars-24x16-spp1-gradients-"));

  // The sequence as render_frame_with_gradients makes it, each frame from the one before.
  std::vector<rtdr::Frame> direct;
  for (int f = 0; f <= 5; ++f)
    direct.push_back(rtdr::render_frame_with_gradients(scene, f, 24, 16, settings, params, f ? &direct.back() : nullptr));
  const auto same = [](const rtdr::Frame& a, const rtdr::Frame& b) {
    return a.float_channel("direct.R").data == b.float_channel("direct.R").data &&
           a.uint_channel("gradient.source").data == b.uint_channel("gradient.source").data &&
           a.uint_channel("rng.seed").data == b.uint_channel("rng.seed").data;
  };

  // Frames 2-3 from an empty cache: frames 0 and 1 are rendered first, and every frame is stored.
  const std::vector<rtdr::Frame> a = cache.gradient_frames(2, 3, 24, 16, settings, params);
  REQUIRE(a.size() == 2);
  CHECK(same(a[0], direct[2]));
  CHECK(same(a[1], direct[3]));
  for (int f = 0; f <= 3; ++f) CHECK(fs::exists(path(f)));

  // Without frames 0-2 in the cache, frames 4-5 continue from frame 3 alone and are still the same sequence.
  for (int f = 0; f <= 2; ++f) fs::remove(path(f));
  const std::vector<rtdr::Frame> b = cache.gradient_frames(4, 5, 24, 16, settings, params);
  REQUIRE(b.size() == 2);
  CHECK(same(b[0], direct[4]));
  CHECK(same(b[1], direct[5]));
  CHECK_FALSE(fs::exists(path(0)));

  // run_eval with gradients gives every method those frames: "none" passes its input through.
  rtdr::EvalConfig c = tiny_config({"none"});
  c.cache_dir = dir.string();
  c.gradients = true;
  c.first_frame = 4;
  c.last_frame = 5;
  const rtdr::EvalResult result = rtdr::run_eval(c);
  CHECK(result.rows.size() == 2);
  CHECK_FALSE(fs::exists(path(0)));  // frames 4-5 came from the cache
  c.gradient.stratum_size = 9;
  CHECK_THROWS_WITH(rtdr::run_eval(c), Catch::Contains("stratum_size"));
}

TEST_CASE("a spec's gradient_<row> keys give its method an input of its own, as the run would with those rows") {
  const rtdr::MethodSpec own = rtdr::parse_method_spec("asvgf:gradient_stratum_size=2:alpha=0.3");
  REQUIRE(own.gradient_rows.size() == 1);
  CHECK(own.gradient_rows[0] == std::pair<std::string, double>{"stratum_size", 2.0});
  CHECK(own.svgf.alpha == 0.3f);
  rtdr::GradientParams run;
  run.light_cdf = 1;
  const rtdr::GradientParams params = rtdr::spec_gradient(own, run);
  CHECK(params.stratum_size == 2);
  CHECK(params.light_cdf == 1);  // the run's other rows stay
  CHECK(rtdr::parse_method_spec("asvgf:gradient_levels=3").gradient_rows.empty());  // asvgf_params.h's row
  for (const char* bad : {"asvgf:gradient_stratum_size=9", "asvgf:gradient_stratum=2", "asvgf:stratum_size=2"}) {
    INFO(bad);
    CHECK_THROWS_AS(rtdr::parse_method_spec(bad), rtdr::Error);
  }

  // Fig. 5's study in one run: asvgf on 3x3 and 2x2 strata, and svgf on the run's (3x3) input.
  rtdr::EvalConfig c = tiny_config({"svgf", "asvgf", "asvgf:gradient_stratum_size=2"});
  c.height = 18;  // 2 and 3 divide 24 x 18: at most 1/4 and 1/9 of the pixels are gradient samples
  c.last_frame = 2;
  std::map<std::string, std::vector<double>> share, rmse;
  for (const rtdr::MetricsRow& row : rtdr::run_eval(c).rows) {
    share[row.method + row.params].push_back(row.gradient_share);
    rmse[row.method + row.params].push_back(row.rmse);
  }
  CHECK(share["asvgf"] == share["svgf"]);  // the same input
  CHECK(share["asvgf"][0] == 0.0);         // frame 0 has no frame before it
  CHECK(share["asvgf"][2] > 0.0);
  CHECK(share["asvgf"][2] <= 1.0 / 9.0);
  CHECK(share["asvgfgradient_stratum_size=2"][2] > share["asvgf"][2]);
  CHECK(share["asvgfgradient_stratum_size=2"][2] <= 1.0 / 4.0);
  // The same numbers as a run whose gradient input is 2x2 for every method.
  rtdr::EvalConfig two = tiny_config({"asvgf"});
  two.height = 18;
  two.last_frame = 2;
  two.gradient.stratum_size = 2;
  std::vector<double> expected;
  for (const rtdr::MetricsRow& row : rtdr::run_eval(two).rows) expected.push_back(row.rmse);
  CHECK(rmse["asvgfgradient_stratum_size=2"] == expected);

  // The sweep adds the stratum study only where asvgf is run.
  const std::vector<std::string> with = rtdr::standard_sweep({"svgf", "asvgf"});
  const std::vector<std::string> without = rtdr::standard_sweep({"svgf"});
  CHECK(std::count(with.begin(), with.end(), "asvgf:gradient_stratum_size=2") == 1);
  CHECK(std::count(with.begin(), with.end(), "asvgf:gradient_stratum_size=4") == 1);
  CHECK(with.size() == without.size() + 2);
  CHECK(rtdr::standard_sweep({"asvgf:alpha=0.2"}) == with);  // asvgf with parameters of its own runs too
}

TEST_CASE("run_eval shows the caller every filtered frame with its reference, and measures the moving umbrae") {
  rtdr::EvalConfig c = tiny_config({"none", "svgf"});
  c.width = 48;
  c.height = 27;
  c.last_frame = 3;
  std::vector<std::string> seen;
  std::vector<double> recomputed;
  c.observe = [&](const rtdr::MethodSpec& spec, int frame, const rtdr::Frame& out, const rtdr::RgbPlane& ref) {
    seen.push_back(spec.text + " " + std::to_string(frame));
    recomputed.push_back(rtdr::rmse(rtdr::rgb_plane(out, "color"), ref));
  };
  const rtdr::EvalResult result = rtdr::run_eval(c);
  CHECK(seen == std::vector<std::string>{"none 0", "none 1", "none 2", "none 3", "svgf 0", "svgf 1", "svgf 2", "svgf 3"});
  REQUIRE(result.rows.size() == recomputed.size());
  int umbra_frames = 0;
  for (size_t k = 0; k < recomputed.size(); ++k) {
    CHECK(result.rows[k].rmse == recomputed[k]);
    umbra_frames += !std::isnan(result.rows[k].umbra_rmse);
    CHECK(result.rows[k].gradient_share == 0.0);  // plain input
  }
  CHECK(umbra_frames > 0);  // pillars' shadows move under a still camera
}
