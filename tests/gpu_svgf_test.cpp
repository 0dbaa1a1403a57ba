// Tests of gpu/svgf_vulkan.cpp: the whole SVGF pipeline on the device, histories kept there between frames,
// against the golden SvgfFilter (filters/svgf/svgf.cpp) frame by frame on rendered sequences, with the validation
// layer on. Skipped, with a message, where no Vulkan device exists.
//
// Bound (kPipelineRelError): per channel of the colour (before tone mapping), max |gpu - golden| / max(|golden|, 1e-2)
// <= 2e-3 on every pixel of every frame. Why: the colour passes other than the a-trous level are bit-exact on lavapipe,
// and Vulkan lets them differ by a few ulp at most (the temporal pass's divisions: gpu_temporal_test); a level differs
// by at most 5e-5 relative (gpu_atrous_test: GLSL's exp and log), and 5 levels in a row at most 2.5e-4. The first
// level's output is the next frame's colour history, weighted (1 - alpha) = 0.8 in the next temporal pass, so a frame
// carries 0.8 of the last frame's error, 0.8^2 of the one before: at most 2.5e-4 / (1 - 0.8) = 1.25e-3 in steady state.
// The edge-stopping weights see those differences too, and the variance as well (its spatial estimate for short
// histories may differ by 4e-4 of mu2', gpu_variance_test; it reaches the colour only through the scale of w_l,
// [SVGF17 Eq. 5]): 2e-3 leaves room for their second-order effect. The floor 1e-2 keeps near-black pixels from
// dividing by almost nothing.
//
// With fp16 illumination records (the ports' _fp16 builds) the bound is 2e-2 (gpu/port_bounds.h). Why: a
// frame's colour goes through 7 stores into halves, each within u = 2^-10 relative (gpu_fixtures.h): the noisy
// input (u/2: the host rounds to nearest), the temporal output and the 5 levels' outputs. With the weights held
// fixed every pass is a convex combination of non-negative colours, which keeps relative errors: the temporal
// output is within alpha u/2 + (1 - alpha) E_h + u of the golden one, where E_h is the colour history's error,
// the first level's output of the frame before (E_h = that frame's temporal error + u). In steady state
// E_h = 10.5 u and the colour is within 14.5 u = 1.4e-2. The weights respond to the rounded luminances and
// standard deviations as well [SVGF17 Eq. 5]; measured: at most 2.8e-3 on the shipped scenes (flicker; lavapipe).
//
// The display colour (after TAA) is checked against the golden tone mapping and TAA (tonemap(), taa_pass()) of the
// pipeline's own colour and its own previous display, per channel: |gpu - golden| <= kDisplayAbsError = 1e-3
// (display values are in [0, 1]). Derivation: only the tone-mapped current colours differ, by at most 1e-6 per
// channel (tests/gpu_tonemap_test.cpp); the history is the same previous display on both sides. The YCoCg of the
// current, hence the box faces F and the mean m, then move by at most 1e-6 (each YCoCg row's weights sum to 1 in
// absolute value). The history clip onto the padded box (taa_shared.h) has t = (F - m) / d with d = h - m and
// F - m >= e, so t moves by at most (t dF + t (1 - t) dm) / e <= 1e-6 / e, and the clipped history
// m + t (h - m) by at most (1 - t) dm + dt |h - m| <= 1e-6 (1 + 1/e) = 1.025e-3 for |h - m| <= 1 (display
// colours). The blend weighs it by 1 - alpha = 0.9 and adds alpha * 1e-6: 9.23e-4. The TAA port on equal inputs
// is within 2e-6 (tests/gpu_taa_test.cpp), except that its mean sum / 9 (2.5 ulp, 1.5e-7) moves t by up to
// t (1 - t) / e <= 256 times that: 0.9 * 256 * 1.5e-7 = 3.5e-5, and the golden mean's own rounding (0.5 ulp)
// 7e-6. In all 9.7e-4 <= 1e-3; the rest covers a history (a TAA output) a little outside [0, 1], where a box
// corner leaves the RGB cube: |h - m| up to 1.03. On lavapipe, whose divisions round correctly, the difference
// is 0.
//
// Before the padding the display could not be bounded at all: Karis14's bare box jumps where it is flat in a
// channel (box_min = box_max = mean: Co and Cg of any grey neighbourhood), a history an ulp inside it keeping
// t = 1 and one an ulp outside clipping to t = 0, so a tone map an ulp off the golden one (a GPU's division is
// not correctly rounded) could move a display pixel to the mean. Nor could the display be compared with the
// golden pipeline's: with colours 1e-6 apart, 19.5% of pillars' display pixels differed by more than
// kPipelineRelError within 10 frames, and the differences persisted through the TAA history. Padded, the
// fraction of display pixels beyond kPipelineRelError against the golden pipeline's display is printed (not
// asserted; colours up to 2e-3 apart may move a display by 1025 times that where the clip is at its steepest):
// measured 0% on every shipped scene on lavapipe, the largest difference 1.9e-6 (occlusion).
#include "gpu/svgf_vulkan.h"

#include "gpu/port_bounds.h"

#include "filters/asvgf/adaptive_alpha.h"
#include "filters/image.h"
#include "filters/method.h"
#include "filters/passes.h"
#include "scenes/catalog.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"
#include "trace/render_frame.h"

#include "cli_fixtures.h"
#include "gpu_fixtures.h"

#include "app/sequence.h"
#include "core/exr_io.h"
#include "eval/frame_diff.h"
#include "filters/svgf/modulate.h"
#include "filters/svgf/prefilter.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using Catch::Detail::Approx;
using namespace rtdr;
using namespace rtdr::gpu_test;

namespace {

// The bounds derived above, from the table rtdr compare reports against (gpu/port_bounds.h): written once.
const PortBound& kColourBound = *find_port_bound("svgf", "color.R");
const double kPipelineRelError = kColourBound.fp32;
constexpr double kRelFloor = kPortRelFloor;
constexpr double kDisplayAbsError = 1e-3;  // against the golden TAA of the port's own colour: not rtdr compare's

// The colour bound for the context's illumination records.
double pipeline_rel_error(const VulkanContext& context) { return kColourBound.bound(half_records(context)); }

// The bound of a dumped channel of `method`, for the context's records (the table must state one).
double dump_bound(const VulkanContext& context, const std::string& method, const std::string& channel) {
  const PortBound* bound = find_port_bound(method, channel);
  REQUIRE(bound != nullptr);
  return bound->bound(half_records(context));
}

// The largest absolute difference over the three channels (compare_rgb, gpu_fixtures.h: a NaN counts as infinite).
double max_abs_error(const RgbPlane& gpu, const RgbPlane& golden) {
  REQUIRE(gpu.data.size() == golden.data.size());
  const glm::dvec3 abs = compare_rgb(gpu, golden).abs;
  return std::max({abs.x, abs.y, abs.z});
}

// Per pixel, the largest relative error of its three channels in `layer`.
std::vector<double> rel_errors(const Frame& gpu, const Frame& golden, const std::string& layer) {
  const RgbPlane a = rgb_plane(gpu, layer), b = rgb_plane(golden, layer);
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  std::vector<double> errors(a.data.size(), 0.0);
  for (size_t i = 0; i < a.data.size(); ++i)
    for (int c = 0; c < 3; ++c)  // a NaN on either side counts as an infinite error
      errors[i] = std::max(errors[i], rel_difference(a.data[i][c], b.data[i][c], kRelFloor));
  return errors;
}

struct PipelineErrors {
  double colour = 0.0;            // the largest relative error of the colour, over all frames
  double display = 0.0;           // the largest absolute error of the display against the golden TAA of its inputs
  double display_outliers = 0.0;  // the largest fraction of a frame's display pixels beyond kPipelineRelError
                                  // against the golden pipeline's display (not asserted)
  double display_golden = 0.0;    // the largest absolute error against the golden pipeline's display (not asserted)
};

Vec2Plane in_motion(const Frame& in) { return SurfacePlanes::from_frame(in).motion; }

// Runs both back ends over `frames` frames of `scene` and checks every frame within the bounds.
PipelineErrors compare_pipelines(VulkanContext& context, const std::string& scene_name, int w, int h, int frames) {
  const Scene scene = load_scene(scene_name);
  SvgfFilter golden{SvgfOptions{}};
  SvgfVulkan gpu(context, SvgfOptions{});
  PipelineErrors worst;
  RgbPlane previous_display;
  for (int f = 0; f < frames; ++f) {
    const Frame in = render_frame(scene, f, w, h, {});
    const Frame expected = golden.filter(in, nullptr);
    const Frame got = gpu.filter(in, nullptr);
    const std::vector<double> colour = rel_errors(got, expected, "color");
    const double colour_max = *std::max_element(colour.begin(), colour.end());
    const std::vector<double> display = rel_errors(got, expected, "display");
    const double outliers =
        double(std::count_if(display.begin(), display.end(), [](double e) { return !(e <= kPipelineRelError); })) /
        double(display.size());
    INFO(scene_name << " frame " << f << ": colour max relative error " << colour_max);
    CHECK(colour_max <= pipeline_rel_error(context));
    // The display is the golden TAA of the pipeline's own tone-mapped colour and previous display.
    const RgbPlane tonemapped = tonemap(rgb_plane(got, "color"), TonemapParams{});
    const RgbPlane display_expected =
        f == 0 ? tonemapped : taa_pass(tonemapped, previous_display, in_motion(in), TaaParams{});
    const double display_max = max_abs_error(rgb_plane(got, "display"), display_expected);
    INFO(scene_name << " frame " << f << ": display max absolute error " << display_max);
    CHECK(display_max <= kDisplayAbsError);
    previous_display = rgb_plane(got, "display");
    worst.colour = std::max(worst.colour, colour_max);
    worst.display = std::max(worst.display, display_max);
    worst.display_golden =
        std::max(worst.display_golden, max_abs_error(rgb_plane(got, "display"), rgb_plane(expected, "display")));
    worst.display_outliers = std::max(worst.display_outliers, outliers);
  }
  return worst;
}

}  // namespace

TEST_CASE("the Vulkan pipeline follows the golden SVGF over 10 frames of pillars, history kept on the device") {
  const auto context = validated_context();
  INFO("device: " << context->device_name());
  const PipelineErrors worst = compare_pipelines(*context, "pillars", 96, 54, 10);
  WARN("pillars, 10 frames at 96x54: colour max relative error "
       << worst.colour << " (bound " << pipeline_rel_error(*context)
       << "); display max absolute error " << worst.display
       << " (bound " << kDisplayAbsError << "); against the golden display (not asserted): "
       << worst.display_outliers * 100.0 << "% of pixels beyond " << kPipelineRelError << ", max absolute error "
       << worst.display_golden);
  check_no_validation_messages(*context);
}

TEST_CASE("the Vulkan pipeline follows the golden SVGF on rendered frames of every shipped scene") {
  const auto context = validated_context();
  for (const std::string& name : shipped_scene_names()) {
    const PipelineErrors worst = compare_pipelines(*context, name, 64, 36, 6);
    WARN(name << ", 6 frames at 64x36: colour max relative error " << worst.colour << "; display max absolute error "
              << worst.display << "; against the golden display (not asserted): " << worst.display_outliers * 100.0
              << "% of pixels beyond " << kPipelineRelError << ", max absolute error " << worst.display_golden);
  }
  check_no_validation_messages(*context);
}

TEST_CASE("a frame's batch submitted again gives the same frame (rtdr bench --submits)") {
  const auto context = validated_context();
  const Scene scene = load_scene("pillars");
  SvgfVulkan once(*context, SvgfOptions{}), thrice(*context, SvgfOptions{});
  thrice.set_submits(3);
  for (int f = 0; f < 3; ++f) {
    const Frame in = render_frame(scene, f, 32, 18, {});
    const Frame a = once.filter(in, nullptr), b = thrice.filter(in, nullptr);
    CHECK(rgb_plane(a, "color").data == rgb_plane(b, "color").data);
    CHECK(rgb_plane(a, "display").data == rgb_plane(b, "display").data);
  }
  check_no_validation_messages(*context);
}

TEST_CASE("the Vulkan pipeline refuses what only the golden pipeline does") {
  const auto context = validated_context();
  SvgfOptions accum;
  accum.name = "accum";
  accum.spatial = SpatialFilter::None;
  CHECK_THROWS_WITH(SvgfVulkan(*context, accum), Catch::Contains("has no Vulkan port"));
  SvgfVulkan gpu(*context, SvgfOptions{});
  const Frame in = render_frame(load_scene("cornell"), 0, 16, 9, {});
  gpu.filter(in, nullptr);
  CHECK_THROWS_WITH(gpu.filter(render_frame(load_scene("cornell"), 1, 18, 9, {}), nullptr),
                    Catch::Contains("frame size changed"));
  check_no_validation_messages(*context);
}

// The dump (--dump-passes, rtdr compare) against the golden dump, frame by frame. What is asserted, per channel,
// relative to max(|golden|, kRelFloor) as in compare_pipelines:
// - the colours (temporal, every level, filtered, tone-mapped) and mu1', the luminance of the integrated colour:
//   within the pipeline's colour bound, for the same reasons (convex combinations of the same inputs; tone mapping
//   x / (1 + x) only shrinks a relative error, and its port adds at most 1e-6: gpu_tonemap_test);
// - mu2', a convex combination of squared luminances: the square of that bound, (1 + e)^2 - 1;
// - the history length: exactly, since the consistency tests read the G-buffer alone, which both sides read as
//   the same fp32 values, and the port's tests are bit-exact (gpu_temporal_test);
// - not the variances: mu2' - mu1'^2 cancels where the luminance hardly varies, so their relative difference has
//   no bound independent of the frame (gpu_variance_test and gpu_atrous_test check them on equal inputs); nor the
//   display (see the banner).
// And the dump is what the passes consumed: remodulating its filtered streams gives the pipeline's colour, and tone
// mapping that colour its tone-mapped layer, within those ports' 1e-6 (gpu_modulate_test, gpu_tonemap_test); each
// level's prefiltered variance is the golden prefilter of the variance that level read (the variance pass's output,
// then the level before's), within the a-trous port's 5e-5 relative to max(|golden|, 1e-3) (gpu_atrous_test: the
// prefilter has no transcendental and matches exactly); the filtered stream is the last level's output.
TEST_CASE("the Vulkan pipeline's dump holds the golden dump's layers, within bounds, and changes no result") {
  const auto context = validated_context();
  const double bound = pipeline_rel_error(*context);
  const Scene scene = load_scene("pillars");
  SvgfFilter golden{SvgfOptions{}};
  SvgfVulkan plain(*context, SvgfOptions{}), dumped(*context, SvgfOptions{});
  for (int f = 0; f < 4; ++f) {
    const Frame in = render_frame(scene, f, 48, 27, {});
    Frame expected_dump, dump;
    golden.filter(in, &expected_dump);
    const Frame out = dumped.filter(in, &dump), reference = plain.filter(in, nullptr);
    CHECK(rgb_plane(out, "color").data == rgb_plane(reference, "color").data);
    CHECK(rgb_plane(out, "display").data == rgb_plane(reference, "display").data);

    const std::vector<ChannelDiff> diffs = diff_channels(dump, expected_dump, kRelFloor);  // throws on other names
    CHECK(diffs.size() == expected_dump.float_channels().size());
    // The port dumps exactly the layers the passes declare (filters/passes.h), as the golden pipeline does.
    std::vector<std::string> declared = dumped.dump_channels(), channels;
    for (const auto& [name, plane] : dump.float_channels()) channels.push_back(name);
    std::sort(declared.begin(), declared.end());
    CHECK(channels == declared);
    int asserted = 0;
    for (const ChannelDiff& d : diffs) {
      const auto ends_with = [&](const std::string& tail) {
        return d.channel.size() >= tail.size() &&
               d.channel.compare(d.channel.size() - tail.size(), tail.size(), tail) == 0;
      };
      INFO("frame " << f << ", " << d.channel << ": max relative difference " << d.rel.error << " at ("
                    << d.rel.x << ", " << d.rel.y << "), max absolute " << d.abs.error);
      if (ends_with(".R") || ends_with(".G") || ends_with(".B") || ends_with("moments.mu1")) {
        CHECK(d.rel.error <= bound);
        CHECK(dump_bound(*context, "svgf", d.channel) == bound);
        ++asserted;
      } else if (ends_with("moments.mu2")) {
        CHECK(d.rel.error <= dump_bound(*context, "svgf", d.channel));
        CHECK(dump_bound(*context, "svgf", d.channel) == Approx((1.0 + bound) * (1.0 + bound) - 1.0));
        ++asserted;
      } else if (ends_with("history_length") || ends_with("variance.spatial")) {
        // n is exact (gpu_temporal_test), and which variance follows from it
        CHECK(d.abs.error <= dump_bound(*context, "svgf", d.channel));
        CHECK(dump_bound(*context, "svgf", d.channel) == 0.0);
        ++asserted;
      }
    }
    // 2 streams x (temporal, 5 levels, filtered) x RGB + mu1, mu2, n, which variance, and the tone-mapped RGB.
    CHECK(asserted == 2 * (7 * 3 + 4) + 3);

    const RgbPlane colour = remodulate(rgb_plane(dump, layer_name(layers::kFiltered, "direct")),
                                       rgb_plane(dump, layer_name(layers::kFiltered, "indirect")),
                                       rgb_plane(in, "albedo"), rgb_plane(in, "emission"));
    const double any = std::numeric_limits<double>::infinity();  // the relative bound alone
    check_rgb_within(rgb_plane(out, "color"), colour, any, 1e-6);
    check_rgb_within(rgb_plane(dump, layer_name(layers::kTonemapped)),
                     tonemap(rgb_plane(out, "color"), TonemapParams{}), any, 1e-6);
    for (const std::string stream : {"direct", "indirect"}) {
      std::string input = layer_name(layers::kVariance, stream);
      for (int level = 0; level < SvgfParams{}.atrous_levels; ++level) {
        const FloatPlane expected = prefilter_variance(dump.float_channel(input));
        const std::string prefiltered = layer_name(layers::kLevelPrefiltered, stream, level);
        const FloatPlane& got = dump.float_channel(prefiltered);
        double worst = 0.0;
        for (size_t i = 0; i < expected.data.size(); ++i)
          worst = std::max(worst, rel_difference(got.data[i], expected.data[i], 1e-3));
        INFO(prefiltered << " against the golden prefilter of " << input);
        CHECK(worst <= 5e-5);
        input = layer_name(layers::kLevelVariance, stream, level);
      }
      CHECK(rgb_plane(dump, layer_name(layers::kFiltered, stream)).data ==
            rgb_plane(dump, layer_name(layers::kLevel, stream, SvgfParams{}.atrous_levels - 1)).data);
    }
  }
  check_no_validation_messages(*context);
}

// A-SVGF on the device: the gradient image, its 5 reconstruction iterations and lambda and alpha_i per stream, then
// SVGF's passes with alpha_i per pixel and the 3x3 box [ASVGF18 Sec. 3.4, 3.5, 4], against the golden SvgfFilter with
// method "asvgf", frame by frame on a pillars sequence rendered with gradient samples (its moving lights make lambda
// reach 1 and drop histories).
// Bound: not derived; a regression guard from what lavapipe measures. On equal inputs the gradient image, lambda
// and alpha ports are bit-identical on lavapipe and the reconstruction within 4.3e-4 of its scale after five
// iterations (gpu_gradient_atrous_test), but lambda = |delta^| / Delta^ has no bound relative to those differences
// where Delta^ is small, and a different alpha_i moves the colour by d(alpha_i) |C - C'_{i-1}|, which has no
// a-priori bound either. Asserted: alpha_i per pixel within kAsvgfAlphaError = 1e-3 absolute; the colour within
// SVGF's bound for the records (pipeline_rel_error: 2e-3 for fp32, 2e-2 for fp16, floor kRelFloor), whose
// derivation holds with alpha_i fixed; and the pipeline's alpha_i equal to the golden adaptive_alpha_pass of its
// own dumped reconstruction within 1e-6, so that a wrong chaining of the ports cannot hide inside the guards.
// Measured on lavapipe (llvmpipe, LLVM 15), 8 frames at 96x54, largest lambda 1: alpha_i within 4.2e-7, the colour
// within 3.7e-6 (fp32 records) and 2.1e-3 (fp16), alpha_i against its own reconstruction exact.
TEST_CASE("the Vulkan pipeline follows the golden A-SVGF over 8 frames of pillars with gradient samples") {
  const auto context = validated_context();
  const double kAsvgfAlphaError = dump_bound(*context, "asvgf", layer_name(layers::kAlpha, "direct"));
  const double kAsvgfRelError = dump_bound(*context, "asvgf", "color.R");
  const Scene scene = load_scene("pillars");
  const SvgfOptions options = method_options("asvgf");
  SvgfFilter golden(options);
  SvgfVulkan gpu(*context, options);
  Frame previous;
  double worst_colour = 0.0, worst_alpha = 0.0, worst_chain = 0.0, largest_lambda = 0.0;
  for (int f = 0; f < 8; ++f) {
    INFO("frame " << f);
    Frame in = render_frame_with_gradients(scene, f, 96, 54, {}, {}, f == 0 ? nullptr : &previous);
    Frame expected_dump, dump;
    const Frame expected = golden.filter(in, &expected_dump);
    const Frame got = gpu.filter(in, &dump);
    const std::vector<double> colour = rel_errors(got, expected, "color");
    const double colour_max = *std::max_element(colour.begin(), colour.end());
    CHECK(colour_max <= kAsvgfRelError);
    worst_colour = std::max(worst_colour, colour_max);
    for (const std::string stream : {"direct", "indirect"}) {
      const FloatPlane& alpha = dump.float_channel(layer_name(layers::kAlpha, stream));
      const FloatPlane& alpha_expected = expected_dump.float_channel(layer_name(layers::kAlpha, stream));
      const FloatPlane& lambda = expected_dump.float_channel(layer_name(layers::kLambda, stream));
      for (size_t i = 0; i < alpha.data.size(); ++i) {
        worst_alpha = std::max(worst_alpha, double(std::abs(alpha.data[i] - alpha_expected.data[i])));
        largest_lambda = std::max(largest_lambda, double(lambda.data[i]));
      }
      // The port's alpha_i is the golden Eq. 14-15 of its own last reconstruction iteration.
      if (f > 0) {
        const int s = frame_stratum_size(in, "asvgf"), last = options.asvgf.gradient_levels - 1;
        const int gw = (in.width() + s - 1) / s, gh = (in.height() + s - 1) / s;
        GradientValues reconstructed{FloatPlane(gw, gh), FloatPlane(gw, gh), FloatPlane(gw, gh), FloatPlane(gw, gh)};
        const FloatPlane& delta = dump.float_channel(layer_name(layers::kGradientLevelDelta, stream, last));
        const FloatPlane& norm = dump.float_channel(layer_name(layers::kGradientLevelNorm, stream, last));
        for (int sy = 0; sy < gh; ++sy)
          for (int sx = 0; sx < gw; ++sx) {
            reconstructed.delta.at(sx, sy) = delta.at(sx * s, sy * s);
            reconstructed.norm.at(sx, sy) = norm.at(sx * s, sy * s);
          }
        const AdaptiveAlpha chained = adaptive_alpha_pass(reconstructed, s, in.width(), in.height(),
                                                          adaptive_alpha_params(options.svgf, options.asvgf));
        for (size_t i = 0; i < alpha.data.size(); ++i)
          worst_chain = std::max(worst_chain, double(std::abs(alpha.data[i] - chained.alpha.data[i])));
      }
    }
    CHECK(worst_alpha <= kAsvgfAlphaError);
    CHECK(worst_chain <= 1e-6);
    previous = std::move(in);
  }
  CHECK(largest_lambda == 1.0);  // some history was dropped whole: the adaptive alpha was exercised
  WARN("asvgf, pillars, 8 frames at 96x54 on " << context->device_name() << ": colour max relative error "
                                               << worst_colour << " (guard " << kAsvgfRelError
                                               << "); alpha_i max absolute error " << worst_alpha << " (guard "
                                               << kAsvgfAlphaError << "); against Eq. 14-15 of its own reconstruction "
                                               << worst_chain);
  check_no_validation_messages(*context);
}

// A-SVGF's variants on the device (filters/asvgf/README.md, "Deviations and choices"): one stream (direct + indirect,
// svgf and asvgf), the gradient normalised per sample with the peers' square, abs(delta), against the golden
// SvgfFilter with the same parameters on 5 frames of pillars with gradient samples. Bounds as the test above: the
// colour within SVGF's pipeline bound, alpha_i within its guard; the dump holds the golden dump's layers (those of
// the one "combined" stream for streams = 1), n exact for svgf and within the alpha guard's reach for asvgf.
TEST_CASE("the Vulkan pipeline follows the golden A-SVGF's variants and SVGF's one stream") {
  constexpr double kAsvgfAlphaError = 1e-3;
  const auto context = validated_context();
  const double bound = pipeline_rel_error(*context);
  const Scene scene = load_scene("pillars");
  struct Variant {
    const char* method;
    int streams, normalize, exponent, absolute;
  };
  for (const Variant v : {Variant{"svgf", 1, 0, 1, 0}, Variant{"asvgf", 1, 0, 1, 0}, Variant{"asvgf", 2, 1, 2, 0},
                          Variant{"asvgf", 1, 1, 1, 0}, Variant{"asvgf", 2, 0, 1, 1}}) {
    INFO(v.method << ": streams " << v.streams << ", gradient_normalize " << v.normalize << ", gradient_exponent "
                  << v.exponent << ", gradient_abs " << v.absolute);
    MethodParams params = method_defaults(v.method);
    params.svgf.streams = v.streams;
    params.asvgf.gradient_normalize = v.normalize;
    params.asvgf.gradient_exponent = v.exponent;
    params.asvgf.gradient_abs = v.absolute;
    const SvgfOptions options = method_options(v.method, params);
    SvgfFilter golden(options);
    SvgfVulkan gpu(*context, options);
    Frame previous;
    double worst_colour = 0.0, worst_alpha = 0.0;
    for (int f = 0; f < 5; ++f) {
      Frame in = render_frame_with_gradients(scene, f, 64, 36, {}, {}, f == 0 ? nullptr : &previous);
      Frame expected_dump, dump;
      const Frame expected = golden.filter(in, &expected_dump), got = gpu.filter(in, &dump);
      const std::vector<double> colour = rel_errors(got, expected, "color");
      worst_colour = std::max(worst_colour, *std::max_element(colour.begin(), colour.end()));
      std::vector<std::string> golden_channels, channels;
      for (const auto& [name, plane] : expected_dump.float_channels()) golden_channels.push_back(name);
      for (const auto& [name, plane] : dump.float_channels()) channels.push_back(name);
      CHECK(channels == golden_channels);
      for (const std::string& stream : svgf_streams(params.svgf)) {
        // n: exact for svgf; for asvgf n_i = 1 + (1 - lambda) n_{i-1} follows lambda, whose port is within the
        // alpha guard's 1e-3 (d alpha_i = (1 - alpha) d lambda), so after f frames n is within 1e-3 f n.
        const FloatPlane &n = dump.float_channel(layer_name(layers::kHistoryLength, stream)),
                         &n_expected = expected_dump.float_channel(layer_name(layers::kHistoryLength, stream));
        for (size_t i = 0; i < n.data.size(); ++i)
          CHECK(std::abs(n.data[i] - n_expected.data[i]) <=
                (options.adaptive ? 1e-3 * (f + 1) * std::max(1.0f, n_expected.data[i]) : 0.0));
        if (!options.adaptive) continue;
        const FloatPlane &alpha = dump.float_channel(layer_name(layers::kAlpha, stream)),
                         &alpha_expected = expected_dump.float_channel(layer_name(layers::kAlpha, stream));
        for (size_t i = 0; i < alpha.data.size(); ++i)
          worst_alpha = std::max(worst_alpha, double(std::abs(alpha.data[i] - alpha_expected.data[i])));
      }
      previous = std::move(in);
    }
    WARN(v.method << " streams " << v.streams << " normalize " << v.normalize << " exponent " << v.exponent
                  << " abs " << v.absolute << " on " << context->device_name() << ": colour max relative error "
                  << worst_colour << " (bound " << bound << "), alpha_i " << worst_alpha);
    CHECK(worst_colour <= bound);
    CHECK(worst_alpha <= kAsvgfAlphaError);
  }
  check_no_validation_messages(*context);
}

namespace {

// The rows of `rtdr compare --csv`, by (frame, channel).
// The device's build as the environment names it to rtdr (RTDR_VK_INPUTS, RTDR_VK_ILLUMINATION), and as a folder name.
std::string build_env(const VulkanContext& context) {
  return std::string("RTDR_VK_INPUTS=") + shader_inputs_name(context.shader_inputs()) +
         " RTDR_VK_ILLUMINATION=" + illumination_records_name(context.illumination_records());
}
std::string build_name(const VulkanContext& context) {
  return std::string(shader_inputs_name(context.shader_inputs())) + "_" +
         illumination_records_name(context.illumination_records());
}

std::map<std::pair<int, std::string>, std::vector<std::string>> read_compare_csv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "frame,channel,max_abs,abs_x,abs_y,abs_cpu,abs_vulkan,max_rel,rel_x,rel_y,rel_cpu,rel_vulkan");
  std::map<std::pair<int, std::string>, std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = rtdr::cli::csv_cells(line);
    REQUIRE(cells.size() == 12);
    rows[{std::stoi(cells[0]), cells[1]}] = cells;
  }
  return rows;
}

}  // namespace

// rtdr compare, run as a user would, against `rtdr filter` run on each back end: its CSV's worst pixel of a
// channel is where the two filters' EXR files differ most, by as much, with their values. The device's build is
// chosen through RTDR_VK_INPUTS and RTDR_VK_ILLUMINATION, which the report's first line must name, and a value
// that names no build is a one-line error.
TEST_CASE("rtdr compare reports where the filter's two back ends differ most, as their own outputs show") {
  const auto context = validated_context();
  using namespace rtdr::cli;
  const std::string env = build_env(*context);
  const fs::path dir = rtdr::cli::scratch("rtdr_gpu_svgf_test", "compare_" + build_name(*context));
  const std::string in = (dir / "in").string(), csv = (dir / "compare.csv").string();
  REQUIRE(run_rtdr("render --scene pillars --frames 0-2 --size 40x24 --out " + in, dir).exit_code == 0);

  const RunResult r = run_rtdr("compare --in " + in + " --csv " + csv, dir, env);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains(std::string(shader_inputs_name(context->shader_inputs())) + " inputs, " +
                                    illumination_records_name(context->illumination_records()) +
                                    " illumination records"));
  const auto rows = read_compare_csv(csv);
  CHECK(rows.size() == 3 * 81);  // 3 frames x (the dump's 75 channels, colour and display)

  for (const std::string backend : {"cpu", "vulkan"})
    REQUIRE(run_rtdr("filter --backend " + backend + " --in " + in + " --out " + (dir / backend).string(), dir, env)
                .exit_code == 0);
  for (int f = 0; f < 3; ++f) {
    const Frame cpu = read_exr(frame_path((dir / "cpu").string(), f, "exr")),
                gpu = read_exr(frame_path((dir / "vulkan").string(), f, "exr"));
    for (const ChannelDiff& d : diff_channels(gpu, cpu, 1e-2)) {
      INFO("frame " << f << ", " << d.channel);
      const std::vector<std::string>& row = rows.at({f, d.channel});
      CHECK(std::stod(row[2]) == Approx(d.abs.error).epsilon(1e-7));
      CHECK(std::stoi(row[3]) == d.abs.x);
      CHECK(std::stoi(row[4]) == d.abs.y);
      CHECK(std::stof(row[5]) == d.abs.reference);
      CHECK(std::stof(row[6]) == d.abs.test);
      CHECK(std::stod(row[7]) == Approx(d.rel.error).epsilon(1e-7));
    }
  }

  // --max-rel-error: the same report, then a one-line error and exit 1.
  const RunResult strict = run_rtdr("compare --in " + in + " --max-rel-error 0", dir, env);
  CHECK(strict.exit_code == 1);
  CHECK_THAT(strict.err, Catch::StartsWith("rtdr: error: ") && Catch::Contains("beyond --max-rel-error 0"));
  CHECK(std::count(strict.err.begin(), strict.err.end(), '\n') == 1);
  CHECK_THAT(strict.out, Catch::Contains("color.R"));

  // Bad input: one line, exit 1, no CSV.
  const std::string missing_csv = (dir / "missing.csv").string();
  const RunResult bad = run_rtdr("compare --in " + (dir / "nowhere").string() + " --csv " + missing_csv, dir, env);
  CHECK(bad.exit_code == 1);
  CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(missing_csv));

  // A build the environment names wrongly: one line naming the variable and its values.
  for (const std::string variable : {"RTDR_VK_INPUTS", "RTDR_VK_ILLUMINATION"}) {
    const RunResult wrong = run_rtdr("compare --in " + in, dir, variable + "=fp8");
    CHECK(wrong.exit_code == 1);
    CHECK_THAT(wrong.err, Catch::StartsWith("rtdr: error: " + variable + " must be ") &&
                              Catch::Contains(", got \"fp8\""));
    CHECK(std::count(wrong.err.begin(), wrong.err.end(), '\n') == 1);
  }
}

// rtdr compare and rtdr filter --backend vulkan for the other two methods with ports, as a user runs them: asvgf on
// frames rendered with gradient samples, trmv on frames with the shading term. Every channel of the golden dump,
// the colour and the display are reported for every frame, and the colour is within the guard the pipeline tests
// hold it to (this file's A-SVGF test, tests/gpu_trmv_vulkan_test.cpp: SVGF's bound, 5e-3).
TEST_CASE("rtdr compare and rtdr filter --backend vulkan run asvgf and trmv on their ports") {
  const auto context = validated_context();
  using namespace rtdr::cli;
  const std::string env = build_env(*context);
  const fs::path dir = rtdr::cli::scratch("rtdr_gpu_svgf_test", "methods_" + build_name(*context));
  const std::map<std::string, std::pair<std::string, double>> methods = {
      {"asvgf", {"--scene pillars --gradients", pipeline_rel_error(*context)}},
      {"trmv", {"--scene fence --shading-samples 4", find_port_bound("trmv", "color.R")->fp32}}};
  for (const auto& [method, how] : methods) {
    INFO(method);
    const std::string in = (dir / (method + "_in")).string(), csv = (dir / (method + ".csv")).string();
    REQUIRE(run_rtdr("render " + how.first + " --frames 0-2 --size 40x24 --out " + in, dir).exit_code == 0);
    const RunResult r = run_rtdr("compare --method " + method + " --in " + in + " --csv " + csv, dir, env);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    const auto rows = read_compare_csv(csv);
    const size_t dumped = make_method(method)->dump_channels().size();
    CHECK(rows.size() == 3 * (dumped + 6));  // 3 frames x (the dump's channels, colour and display)
    for (int f = 0; f < 3; ++f)
      for (const std::string channel : {"color.R", "color.G", "color.B"}) {
        INFO("frame " << f << " " << channel);
        CHECK(std::stod(rows.at({f, channel})[7]) <= how.second);  // max_rel, relative to max(|cpu|, 1e-2)
      }
    const std::string out = (dir / (method + "_vulkan")).string();
    REQUIRE(run_rtdr("filter --backend vulkan --method " + method + " --in " + in + " --out " + out, dir, env)
                .exit_code == 0);
    CHECK(fs::exists(frame_path(out, 2, "exr")));
  }
}
