// Every filter pass, declared once: its name, what it reads, the layers it writes (name pattern, type,
// meaning, equation), the parameters it reads, and what `rtdr probe` prints for it. These declarations are
// data that the rest of the project iterates:
// - the golden pipeline (filters/svgf/svgf.cpp) and the Vulkan one (gpu/svgf_vulkan.cpp) name every layer they
//   dump through them (dump_layer);
// - `rtdr probe --pass NAME` takes its pass names and their descriptions from them;
// - `rtdr compare` expects every layer they declare for the method (Method::dump_channels);
// - the tests take their layer lists from them, and tests/docs_buffers_test.cpp checks that docs/buffers.md
//   ("Filter passes") documents exactly these layers.
// Adding a pass: declare its layers and the pass here, dump them with dump_layer, add a row to docs/buffers.md.
#pragma once

#include "core/frame.h"
#include "filters/image.h"

#include <string>
#include <string_view>
#include <vector>

namespace rtdr {

// An RGB layer is three float channels, <layer>.R, <layer>.G, <layer>.B; a scalar layer is one float channel
// named like the layer itself.
enum class LayerType { Rgb, Scalar };

// Where a layer goes: the output frame of `rtdr filter`, or the dump (--dump-passes) beside it.
enum class LayerUse { Output, Dump };

// One layer a pass writes. In `pattern`, "<s>" stands for the illumination stream (direct or indirect, or combined:
// their sum filtered as one stream, SvgfParams::streams = 1) and "<i>" for the level of the spatial filter, 0 to
// levels - 1; a layer without them is written once per frame.
struct LayerDecl {
  std::string_view pattern;
  LayerType type;
  LayerUse use;
  std::string_view meaning;
  std::string_view cite;  // the equation or section it holds, "[SVGF17 Sec. 4.1]"
};

// The layers, one constant each, so that the code writing a layer and the code reading it name the same
// declaration. Their rows in docs/buffers.md ("Filter passes") say the same in prose.
namespace layers {
inline constexpr LayerDecl kColor{
    "color", LayerType::Rgb, LayerUse::Output,
    "the filtered radiance, linear HDR: emission + max(albedo, 0.001) (direct + indirect)", "[SVGF17 Sec. 3]"};
inline constexpr LayerDecl kDisplay{"display", LayerType::Rgb, LayerUse::Output,
                                    "`color` tone mapped, then temporally antialiased where the method uses TAA",
                                    "[Reinhard02 Eq. 3], [Karis14]"};
inline constexpr LayerDecl kTemporal{"filter.<s>.temporal", LayerType::Rgb, LayerUse::Dump, "integrated colour C'",
                                     "[SVGF17 Sec. 4.1]"};
inline constexpr LayerDecl kMoment1{"filter.<s>.moments.mu1", LayerType::Scalar, LayerUse::Dump,
                                    "integrated first luminance moment mu1'", "[SVGF17 Sec. 4.2]"};
inline constexpr LayerDecl kMoment2{"filter.<s>.moments.mu2", LayerType::Scalar, LayerUse::Dump,
                                    "integrated second luminance moment mu2'", "[SVGF17 Sec. 4.2]"};
inline constexpr LayerDecl kHistoryLength{"filter.<s>.history_length", LayerType::Scalar, LayerUse::Dump,
                                          "history length n in frames (1 after a disocclusion)", "[SVGF17 Sec. 4.1]"};
inline constexpr LayerDecl kVariance{"filter.<s>.variance", LayerType::Scalar, LayerUse::Dump,
                                     "luminance variance: mu2' - mu1'^2, or the 7x7 spatial estimate while n < 4",
                                     "[SVGF17 Sec. 4.2]"};
inline constexpr LayerDecl kVarianceSpatial{"filter.<s>.variance.spatial", LayerType::Scalar, LayerUse::Dump,
                                            "1 where the variance is the 7x7 spatial estimate (n < "
                                            "variance_min_history), 0 where it is mu2' - mu1'^2 or there is no surface",
                                            "[SVGF17 Sec. 4.2]"};
inline constexpr LayerDecl kLevel{"filter.<s>.level<i>", LayerType::Rgb, LayerUse::Dump,
                                  "the output of level i of the spatial filter", "[SVGF17 Eq. 1]"};
inline constexpr LayerDecl kLevelVariance{"filter.<s>.level<i>.variance", LayerType::Scalar, LayerUse::Dump,
                                          "the propagated variance of a-trous level i", "[SVGF17 Sec. 4.3]"};
inline constexpr LayerDecl kLevelPrefiltered{"filter.<s>.level<i>.prefiltered_variance", LayerType::Scalar,
                                             LayerUse::Dump, "g3x3 of level i's input variance, steering w_l",
                                             "[SVGF17 Eq. 5]"};
inline constexpr LayerDecl kFiltered{"filter.<s>.filtered", LayerType::Rgb, LayerUse::Dump,
                                     "the stream's result, the last level's output (methods without a spatial filter "
                                     "do not write it: their result is filter.<s>.temporal; a-eaw's is filter.<s>.ema)",
                                     "[SVGF17 Sec. 3]"};
inline constexpr LayerDecl kEma{"filter.<s>.ema", LayerType::Rgb, LayerUse::Dump,
                                "the temporal EMA of the spatial filter's result, with the adaptive alpha (a-eaw)",
                                "[ASVGF18 Eq. 1, Sec. 4]"};
inline constexpr LayerDecl kTonemapped{"filter.tonemapped", LayerType::Rgb, LayerUse::Dump,
                                       "`color` tone mapped, before TAA", "[Reinhard02 Eq. 3]"};
// A-SVGF's gradient passes [ASVGF18 Sec. 3.4, 3.5]: per-stratum values, replicated to every pixel of the stratum.
inline constexpr LayerDecl kGradientDelta{"filter.<s>.gradient.delta", LayerType::Scalar, LayerUse::Dump,
                                          "the stratum's temporal gradient delta, 0 where no gradient sample landed",
                                          "[ASVGF18 Eq. 3]"};
inline constexpr LayerDecl kGradientNorm{"filter.<s>.gradient.norm", LayerType::Scalar, LayerUse::Dump,
                                         "the stratum's Delta, the larger of the two luminances; 0 without a sample",
                                         "[ASVGF18 Eq. 13]"};
inline constexpr LayerDecl kGradientLuminance{"filter.<s>.gradient.luminance", LayerType::Scalar, LayerUse::Dump,
                                              "the mean luminance of the stratum's pixels, l^(0)", "[ASVGF18 Sec. 3.4]"};
inline constexpr LayerDecl kGradientVariance{"filter.<s>.gradient.variance", LayerType::Scalar, LayerUse::Dump,
                                             "the variance of the luminance in the stratum", "[ASVGF18 Sec. 3.4]"};
inline constexpr LayerDecl kGradientLevelDelta{"filter.<s>.gradient.level<i>.delta", LayerType::Scalar,
                                               LayerUse::Dump, "delta^ after reconstruction iteration i",
                                               "[ASVGF18 Eq. 12]"};
inline constexpr LayerDecl kGradientLevelNorm{"filter.<s>.gradient.level<i>.norm", LayerType::Scalar, LayerUse::Dump,
                                              "Delta^ after reconstruction iteration i", "[ASVGF18 Eq. 12]"};
inline constexpr LayerDecl kGradientLevelLuminance{"filter.<s>.gradient.level<i>.luminance", LayerType::Scalar,
                                                   LayerUse::Dump, "l^ after reconstruction iteration i",
                                                   "[ASVGF18 Eq. 7]"};
inline constexpr LayerDecl kGradientLevelVariance{"filter.<s>.gradient.level<i>.variance", LayerType::Scalar,
                                                  LayerUse::Dump, "Var(l^) after reconstruction iteration i",
                                                  "[SVGF17 Sec. 4.3]"};
inline constexpr LayerDecl kLambda{"filter.<s>.lambda", LayerType::Scalar, LayerUse::Dump,
                                   "the stratum's lambda = min(1, abs(delta^) / Delta^), 0 where Delta^ = 0",
                                   "[ASVGF18 Eq. 14]"};
inline constexpr LayerDecl kAlpha{"filter.<s>.alpha", LayerType::Scalar, LayerUse::Dump,
                                  "the temporal weight alpha_i from the largest lambda of the 3x3 strata around",
                                  "[ASVGF18 Eq. 15, Sec. 3.5]"};
// TRMV's passes [TRMV21 Sec. 5] (filters/trmv/): one layer per component, visibility (scalar), diffuse and
// glossy indirect light (RGB).
inline constexpr LayerDecl kTrmvPenumbraWidth{"filter.trmv.visibility.penumbra", LayerType::Scalar, LayerUse::Dump,
                                              "W = D (d_r - d_b) / d_b, the penumbra's width at an in-shadow "
                                              "pixel, metres; 0 where the shadow ray reached the light",
                                              "[LLK*19, TRMV21 Sec. 4.1]"};
inline constexpr LayerDecl kTrmvSigmaX{"filter.trmv.visibility.sigma_x", LayerType::Scalar, LayerUse::Dump,
                                       "the penumbra filter's std across, pixels: the splatted W / (6 m_x)",
                                       "[LLK*19, TRMV21 Sec. 5]"};
inline constexpr LayerDecl kTrmvSigmaY{"filter.trmv.visibility.sigma_y", LayerType::Scalar, LayerUse::Dump,
                                       "the penumbra filter's std down, pixels: the splatted W / (6 m_y)",
                                       "[LLK*19, TRMV21 Sec. 5]"};
inline constexpr LayerDecl kTrmvSplatX{"filter.trmv.visibility.splat_x", LayerType::Scalar, LayerUse::Dump,
                                       "the splatted shadow motion, x, pixels: the mean of the m^V that landed, "
                                       "else the surface motion",
                                       "[TRMV21 Sec. 4.1]"};
inline constexpr LayerDecl kTrmvSplatY{"filter.trmv.visibility.splat_y", LayerType::Scalar, LayerUse::Dump,
                                       "the splatted shadow motion, y, pixels", "[TRMV21 Sec. 4.1]"};
inline constexpr LayerDecl kTrmvSplatLanded{"filter.trmv.visibility.splat_landed", LayerType::Scalar, LayerUse::Dump,
                                            "1 where a valid m^V of the pixel's receiving surface landed, else 0",
                                            "[TRMV21 Sec. 4.1]"};
inline constexpr LayerDecl kTrmvVisibilitySpatial{"filter.trmv.visibility.spatial", LayerType::Scalar, LayerUse::Dump,
                                                  "c~, the spatially filtered 1-spp visibility", "[TRMV21 Sec. 5]"};
inline constexpr LayerDecl kTrmvDiffuseSpatial{"filter.trmv.diffuse.spatial", LayerType::Rgb, LayerUse::Dump,
                                               "c~, the spatially filtered 1-spp diffuse indirect light",
                                               "[TRMV21 Sec. 5]"};
inline constexpr LayerDecl kTrmvGlossySpatial{"filter.trmv.glossy.spatial", LayerType::Rgb, LayerUse::Dump,
                                              "c~, the spatially filtered 1-spp glossy indirect light",
                                              "[TRMV21 Sec. 5]"};
inline constexpr LayerDecl kTrmvTheta{"filter.trmv.visibility.theta", LayerType::Scalar, LayerUse::Dump,
                                      "theta, radians, between n(s_i) and s_i -> s^V_{i-1}; pi/2 without evidence",
                                      "[TRMV21 Eq. 4]"};
inline constexpr LayerDecl kTrmvAlphaV{"filter.trmv.visibility.alpha", LayerType::Scalar, LayerUse::Dump,
                                       "alpha^V = 1 - G(theta - pi/2; 0, 0.1) (1 - alpha)", "[TRMV21 Eq. 4]"};
inline constexpr LayerDecl kTrmvDiffuseReshaded{"filter.trmv.diffuse.reshaded", LayerType::Rgb, LayerUse::Dump,
                                                "the diffuse history re-shaded from the six cones at x^O where the "
                                                "dual vector applies, else 0",
                                                "[TRMV21 Eq. 11]"};
inline constexpr LayerDecl kTrmvVisibilityTemporal{"filter.trmv.visibility.temporal", LayerType::Scalar,
                                                   LayerUse::Dump, "cbar_i, the blend of c~ and the clamped history",
                                                   "[TRMV21 Eq. 2]"};
inline constexpr LayerDecl kTrmvVisibilityClamped{"filter.trmv.visibility.clamped", LayerType::Scalar, LayerUse::Dump,
                                                  "cbar*_{i-1}, the history clamped to mu +- gamma sigma of c~",
                                                  "[TRMV21 Sec. 5]"};
inline constexpr LayerDecl kTrmvDiffuseTemporal{"filter.trmv.diffuse.temporal", LayerType::Rgb, LayerUse::Dump,
                                                "cbar_i, the blend of c~ and the clamped history", "[TRMV21 Eq. 2]"};
inline constexpr LayerDecl kTrmvDiffuseClamped{"filter.trmv.diffuse.clamped", LayerType::Rgb, LayerUse::Dump,
                                               "cbar*_{i-1}, the history clamped to mu +- gamma sigma of c~",
                                               "[TRMV21 Sec. 5]"};
inline constexpr LayerDecl kTrmvGlossyTemporal{"filter.trmv.glossy.temporal", LayerType::Rgb, LayerUse::Dump,
                                               "cbar_i, the blend of c~ and the clamped history", "[TRMV21 Eq. 2]"};
inline constexpr LayerDecl kTrmvGlossyClamped{"filter.trmv.glossy.clamped", LayerType::Rgb, LayerUse::Dump,
                                              "cbar*_{i-1}, the history clamped to mu +- gamma sigma of c~",
                                              "[TRMV21 Sec. 5]"};
inline constexpr LayerDecl kTrmvWeightA{"filter.trmv.visibility.w_a", LayerType::Scalar, LayerUse::Dump,
                                        "w_A = (alpha^V - alpha)^2", "[TRMV21 Eq. 7]"};
inline constexpr LayerDecl kTrmvVisibilityWeightC{"filter.trmv.visibility.w_c", LayerType::Scalar, LayerUse::Dump,
                                                  "w_C = abs(cbar* - cbar) / (cbar + epsilon)", "[TRMV21 Eq. 8]"};
inline constexpr LayerDecl kTrmvDiffuseWeightC{"filter.trmv.diffuse.w_c", LayerType::Scalar, LayerUse::Dump,
                                               "w_C on luminance", "[TRMV21 Eq. 8]"};
inline constexpr LayerDecl kTrmvGlossyWeightC{"filter.trmv.glossy.w_c", LayerType::Scalar, LayerUse::Dump,
                                              "w_C on luminance", "[TRMV21 Eq. 8]"};
inline constexpr LayerDecl kTrmvVisibilityCleaned{"filter.trmv.visibility.cleaned", LayerType::Scalar, LayerUse::Dump,
                                                  "cbar_i after the clean-up: the filtered visibility",
                                                  "[TRMV21 Sec. 5]"};
inline constexpr LayerDecl kTrmvDiffuseCleaned{"filter.trmv.diffuse.cleaned", LayerType::Rgb, LayerUse::Dump,
                                               "cbar_i after the clean-up: the filtered diffuse indirect light",
                                               "[TRMV21 Sec. 5]"};
inline constexpr LayerDecl kTrmvGlossyCleaned{"filter.trmv.glossy.cleaned", LayerType::Rgb, LayerUse::Dump,
                                              "cbar_i after the clean-up: the filtered glossy indirect light",
                                              "[TRMV21 Sec. 5]"};
}  // namespace layers

// What a pass runs on: the whole frame once, each illumination stream, or each level of each stream.
enum class PassScope { Frame, Stream, StreamLevel };

struct PassDecl {
  std::string_view name;    // `rtdr probe --pass NAME`, and the key of its time in Method::pass_times
  std::string_view golden;  // the file of its golden per-pixel function
  std::string_view cite;    // what it implements
  PassScope scope;
  std::string_view reads;   // its inputs: layers of the input frame (docs/buffers.md) and earlier passes' layers
  std::vector<const LayerDecl*> writes;
  std::vector<std::string_view> params;  // rows of its parameter table (svgf_params.h, eaw.h, tonemap.h, taa.h)
  std::string_view probe;   // what `rtdr probe --pass NAME` prints, term by term
};

// Every pass of every method, in the order a frame runs them.
const std::vector<PassDecl>& filter_passes();

// One entry of a method's list of passes: the pass, and how many levels of it run (for PassScope::StreamLevel).
// A method is such a list, in the order its frame runs them (svgf_passes, trmv_passes).
struct PassUse {
  const PassDecl* pass;
  int levels = 0;
};
// Every channel of the dump of a method whose passes are `passes`: each pass's dump layers for `streams` and its
// levels, each channel once. What both back ends of the method dump (Method::dump_channels).
std::vector<std::string> dump_channels_of(const std::vector<PassUse>& passes,
                                          const std::vector<std::string>& streams = {"direct", "indirect"});
// The declaration of pass `name`; throws rtdr::Error listing the passes when there is none.
const PassDecl& find_pass(std::string_view name);

// The layer's name for one stream and level: "filter.<s>.level<i>" -> "filter.direct.level2".
std::string layer_name(const LayerDecl& layer, std::string_view stream = {}, int level = -1);
// Its channels: "<name>.R", "<name>.G", "<name>.B" for an RGB layer, "<name>" for a scalar one.
std::vector<std::string> layer_channels(const LayerDecl& layer, std::string_view stream = {}, int level = -1);
// The name of the one stream of a filter that does not separate direct and indirect light (SvgfParams::streams = 1).
inline constexpr const char* kCombinedStream = "combined";

// Every channel of `layer` for `streams` and `levels` levels, as far as its pattern repeats.
std::vector<std::string> expand_layer(const LayerDecl& layer, int levels,
                                      const std::vector<std::string>& streams = {"direct", "indirect"});
// Whether `channel` is one of `layer`'s channels for some stream and level.
bool layer_has_channel(const LayerDecl& layer, std::string_view channel);

// The passes that write `channel`, joined by ", " ("color.R" -> "modulate"; "filter.direct.level2.R" ->
// "atrous, eaw"); "?" for a channel no pass declares. For error messages.
std::string pass_writing(const std::string& channel);

// Writes `plane` into `dump` as `layer` for one stream and level; nothing when `dump` is null. The plane's
// kind must match the layer's type (checked: a mismatch is a programming error and throws).
void dump_layer(Frame* dump, const LayerDecl& layer, std::string_view stream, int level, const RgbPlane& plane);
void dump_layer(Frame* dump, const LayerDecl& layer, std::string_view stream, int level, const FloatPlane& plane);

}  // namespace rtdr
