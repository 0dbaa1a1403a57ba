// Hostile files, the third round: what the files a user hands `rtdr` can declare or be. A FIFO or a
// folder where a glTF buffer, image or EXR frame should be; an 8 KB EXR that declares 3 GiB of pixels; a --size
// whose run cannot fit in memory; a previous frame whose ids lie beyond the scene; a frame that `rtdr check`
// passed and `filter` refused; a glTF URI that climbs out of the scene's folder. Run through the real binary with
// an argument vector, under a time limit (tests/bounded_run.h), so that a regression that hangs fails instead of
// hanging the suite. Labelled `hostile`. docs/reliability.md lists the promises they keep.
#include "bounded_run.h"
#include "hostile_fixtures.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstring>

using namespace hostile;

namespace {

// Long enough for the sanitized rtdr to load a scene and render a few tiny frames; a hang is far longer.
constexpr double kSeconds = 120.0;

// The bytes of a base64 text (RFC 4648, with padding), as glTF's data URIs hold them.
std::string base64_decode(const std::string& text) {
  std::string out;
  uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    const char* const alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* at = c ? std::strchr(alphabet, c) : nullptr;
    if (!at) continue;  // '=' padding
    bits = bits << 6 | uint32_t(at - alphabet);
    if ((count += 6) >= 8) out += char((bits >> (count -= 8)) & 0xFF);
  }
  return out;
}

// Cornell with its buffer in a file, `uri` as the scene names it, as most exporters write scenes; the buffer's
// bytes are written to `bin` unless it is empty.
json cornell_with_buffer_file(const std::string& uri, const fs::path& bin) {
  json scene = scene_json("cornell");
  const std::string data = scene["buffers"][0]["uri"];
  if (!bin.empty()) std::ofstream(bin, std::ios::binary) << base64_decode(data.substr(data.find(',') + 1));
  scene["buffers"][0]["uri"] = uri;
  return scene;
}

std::vector<std::string> render_args(const fs::path& scene, const fs::path& out) {
  return {"render", "--scene", scene.string(), "--frames", "0", "--size", "8x8", "--out", out.string()};
}

// Refused at once: not killed at the time limit, and the refused outcome of hostile_fixtures.h.
void require_refused_in_time(const BoundedRun& run, const fs::path& out, const std::string& says) {
  CHECK_FALSE(run.timed_out);
  require_refused(run.result, out, says);
}

}  // namespace

// ---- Regular files only: a FIFO never blocks, a folder is named as one ----

TEST_CASE("render: a glTF buffer that is a FIFO is refused at once, saying it is a FIFO") {
  const fs::path dir = scratch("fifo_buffer");
  const fs::path scene = write_scene(dir, cornell_with_buffer_file("scene.bin", dir / "scene.bin"));
  // Control: the same scene with its buffer in a regular file renders.
  require_finite_frames(run_rtdr_bounded(render_args(scene, dir / "good"), dir, kSeconds).result, dir / "good", 1);
  fs::remove(dir / "scene.bin");
  REQUIRE(::mkfifo((dir / "scene.bin").c_str(), 0600) == 0);
  require_refused_in_time(run_rtdr_bounded(render_args(scene, dir / "out"), dir, kSeconds), dir / "out",
                          "scene.bin': it is a FIFO, not a regular file");
  // bench --scenes loads the scene the same way.
  const BoundedRun bench = run_rtdr_bounded({"bench", "--stage", "raster", "--scenes", scene.string(), "--size", "8x8",
                                             "--runs", "1", "--warmup", "0", "--csv", (dir / "bench.csv").string()},
                                            dir, kSeconds);
  require_refused_in_time(bench, dir / "bench.csv", "it is a FIFO, not a regular file");
}

TEST_CASE("render: a glTF buffer that is a folder, and an image that is a FIFO, are refused saying what they are") {
  const fs::path dir = scratch("folder_buffer");
  fs::create_directories(dir / "scene.bin");
  const fs::path scene = write_scene(dir, cornell_with_buffer_file("scene.bin", ""));
  require_refused_in_time(run_rtdr_bounded(render_args(scene, dir / "out"), dir, kSeconds), dir / "out",
                          "scene.bin': it is a folder, not a regular file");
  // An image: tinygltf would go on without an image it cannot load; a refused file stops the load all the same.
  json textured = cornell_with_buffer_file("ok.bin", dir / "ok.bin");
  textured["images"] = json::array({{{"uri", "texture.png"}}});
  textured["textures"] = json::array({{{"source", 0}}});
  textured["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  REQUIRE(::mkfifo((dir / "texture.png").c_str(), 0600) == 0);
  require_refused_in_time(run_rtdr_bounded(render_args(write_scene(dir, textured, "textured.gltf"), dir / "out"), dir,
                                           kSeconds),
                          dir / "out", "texture.png': it is a FIFO, not a regular file");
}

TEST_CASE("render: a scene file that is a FIFO is refused at once, not read as a missing file") {
  const fs::path dir = scratch("fifo_scene");
  REQUIRE(::mkfifo((dir / "scene.gltf").c_str(), 0600) == 0);
  require_refused_in_time(run_rtdr_bounded(render_args(dir / "scene.gltf", dir / "out"), dir, kSeconds), dir / "out",
                          "the scene file is a FIFO, not a regular file");
}

TEST_CASE("filter and check: an EXR frame that is a FIFO or a folder is refused saying what it is") {
  for (const char* kind : {"FIFO", "folder"}) {
    INFO(kind);
    const fs::path in = changed_sequence(std::string("exr_") + kind, [](Frame&, int) {});
    fs::remove(in / "frame_0001.exr");
    if (std::string(kind) == "FIFO")
      REQUIRE(::mkfifo((in / "frame_0001.exr").c_str(), 0600) == 0);
    else
      fs::create_directories(in / "frame_0001.exr");
    const fs::path out = in.parent_path() / "out";
    const std::string says = "frame_0001.exr': it is a " + std::string(kind) + ", not a regular file";
    require_refused_in_time(run_rtdr_bounded({"filter", "--in", in.string(), "--out", out.string()}, in.parent_path(),
                                             kSeconds),
                            out, says);
    const BoundedRun check = run_rtdr_bounded({"check", "--in", in.string()}, in.parent_path(), kSeconds);
    CHECK_FALSE(check.timed_out);
    CHECK(check.result.exit_code == 1);
    CHECK(check.result.out.find(says) != std::string::npos);
  }
}

// ---- Memory bounds: what a file declares, and what --size asks for ----

namespace {

// A scanline EXR header (magic, version 2, the attributes OpenEXR writes, the end byte) of width x height pixels
// of the FLOAT channels B, G, R with `compression` (3: ZIP).
std::string exr_header(int32_t width, int32_t height, uint8_t compression) {
  std::string f;
  const auto put = [&f](const auto value) { f.append(reinterpret_cast<const char*>(&value), sizeof value); };
  const auto attribute = [&](const char* name, const char* type, int32_t size) {
    f.append(name, std::strlen(name) + 1);
    f.append(type, std::strlen(type) + 1);
    put(size);
  };
  put(uint32_t(20000630));  // magic number
  put(uint32_t(2));         // version 2, single-part scanline
  attribute("channels", "chlist", 3 * (2 + 16) + 1);
  for (const char* name : {"B", "G", "R"}) {
    f.append(name, 2);
    put(int32_t(2));   // FLOAT
    put(uint32_t(0));  // pLinear and 3 reserved bytes
    put(int32_t(1));   // x sampling
    put(int32_t(1));   // y sampling
  }
  f += '\0';
  attribute("compression", "compression", 1);
  f += char(compression);
  for (const char* window : {"dataWindow", "displayWindow"}) {
    attribute(window, "box2i", 16);
    for (const int32_t v : {0, 0, width - 1, height - 1}) put(v);
  }
  attribute("lineOrder", "lineOrder", 1);
  f += '\0';
  attribute("pixelAspectRatio", "float", 4);
  put(1.0f);
  attribute("screenWindowCenter", "v2f", 8);
  put(0.0f);
  put(0.0f);
  attribute("screenWindowWidth", "float", 4);
  put(1.0f);
  f += '\0';  // the end of the header
  return f;
}

// A 16384 x 16384 ZIP file of 3 FLOAT channels (3 GiB of pixels): the header, the table of its 1024 chunks of 16
// rows, every entry pointing at the one chunk that follows (row 0, `chunk_bytes` of data). With 29 bytes of data it
// is the 8,542-byte file a user found taking 3.16 GB; with 3.2 MB it could hold its pixels (ZIP decodes at most 1032 bytes from
// one), and only memory can refuse it.
std::string declared_3gib_exr(size_t chunk_bytes) {
  std::string f = exr_header(16384, 16384, 3);
  const uint64_t chunk_at = f.size() + 1024 * 8;
  for (int k = 0; k < 1024; ++k) f.append(reinterpret_cast<const char*>(&chunk_at), 8);
  const int32_t row = 0, size = int32_t(chunk_bytes);
  f.append(reinterpret_cast<const char*>(&row), 4);
  f.append(reinterpret_cast<const char*>(&size), 4);
  f.append(chunk_bytes, '\0');
  return f;
}

constexpr long kOneGiBInKiB = 1024 * 1024;

}  // namespace

TEST_CASE("check and filter: an 8,542-byte ZIP EXR declaring 16384x16384x3 floats is refused with peak RSS < 1 GB") {
  const fs::path dir = scratch("zip_bomb");
  const fs::path in = dir / "in";
  fs::create_directories(in);
  const std::string bytes = declared_3gib_exr(29);
  REQUIRE(bytes.size() == 8542);
  std::ofstream(in / "frame_0000.exr", std::ios::binary) << bytes;
  // Under an address-space limit of 2 GiB where it works (not under AddressSanitizer): a regression fails with
  // std::bad_alloc instead of taking 3 GB of a shared machine.
  for (const std::vector<std::string>& args : {std::vector<std::string>{"filter", "--in", in.string(), "--out",
                                                                        (dir / "out").string()},
                                               std::vector<std::string>{"check", "--in", in.string()}}) {
    INFO(args[0]);
    const BoundedRun run = run_rtdr_bounded(args, dir, kSeconds, uint64_t(2) << 30);
    CHECK_FALSE(run.timed_out);
    CHECK(run.result.exit_code == 1);
    const std::string said = args[0] == "check" ? run.result.out : rtdr::last_line(run.result.err);
    CHECK(said.find("16384x16384 pixels of 3 channels (3.00 GiB) cannot come from its 8542 bytes") !=
          std::string::npos);
    CHECK(run.max_rss_kib < kOneGiBInKiB);
    CHECK_FALSE(fs::exists(dir / "out"));
  }
}

TEST_CASE("filter: a ZIP EXR that could hold 3 GiB of pixels is refused by the memory budget (RLIMIT_AS 2 GiB)") {
  if (!kAddressLimitWorks) return;  // AddressSanitizer: no RLIMIT_AS, and the budget is the machine's
  const fs::path dir = scratch("zip_budget");
  const fs::path in = dir / "in";
  fs::create_directories(in);
  std::ofstream(in / "frame_0000.exr", std::ios::binary) << declared_3gib_exr(3'200'000);
  const BoundedRun run =
      run_rtdr_bounded({"filter", "--in", in.string(), "--out", (dir / "out").string()}, dir, kSeconds, uint64_t(2) << 30);
  require_refused_in_time(run, dir / "out", "reading its 16384x16384 pixels of 3 channels needs 3.00 GiB, more than the");
  CHECK(rtdr::last_line(run.result.err).find("(bound by RLIMIT_AS)") != std::string::npos);
  CHECK(run.max_rss_kib < kOneGiBInKiB);
}

TEST_CASE("render: a PNG texture declaring 16384x16384 pixels is refused by the memory budget (RLIMIT_AS 4 GiB)") {
  if (!kAddressLimitWorks) return;  // AddressSanitizer: no RLIMIT_AS, and the budget is the machine's
  const fs::path dir = scratch("png_budget");
  // A PNG's signature and IHDR chunk (length 13, width, height, 8 bits, RGBA, then a CRC no decoder gets to), and
  // nothing else: decoding it would take 32 bytes a pixel, 8 GiB.
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string("\0\0\0\x0dIHDR\0\0\x40\0\0\0\x40\0\x08\x06\0\0\0", 21) + "CRC!";
  std::ofstream(dir / "big.png", std::ios::binary) << png;
  json textured = cornell_with_buffer_file("scene.bin", dir / "scene.bin");
  textured["images"] = json::array({{{"uri", "big.png"}}});
  textured["textures"] = json::array({{{"source", 0}}});
  textured["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  const BoundedRun run =
      run_rtdr_bounded(render_args(write_scene(dir, textured), dir / "out"), dir, kSeconds, uint64_t(4) << 30);
  require_refused_in_time(run, dir / "out", "image #0 declares 16384x16384 pixels, whose decoding needs 8.00 GiB");
  CHECK(run.max_rss_kib < kOneGiBInKiB);
}

TEST_CASE("render, eval and bench: --size 16384x16384 is refused before any work, with the size and the estimate") {
  const fs::path dir = scratch("huge_size");
  // 8 GiB of address space where a limit works: a regression fails with std::bad_alloc, not the OOM killer. Without
  // one (AddressSanitizer), the estimate (hundreds of GiB) is beyond any machine that runs the suite.
  const uint64_t limit = uint64_t(8) << 30;
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"render", "--scene", "cornell", "--frames", "0", "--size", "16384x16384", "--out", (dir / "out").string()},
           {"render", "--scene", "cornell", "--gradients", "--frames", "0-1", "--size", "16384x16384", "--out",
            (dir / "out").string()},
           {"eval", "--scene", "cornell", "--methods", "svgf", "--frames", "0-1", "--size", "16384x16384", "--cache",
            (dir / "cache").string(), "--out", (dir / "out").string()},
           {"bench", "--stage", "trace", "--scenes", "cornell", "--size", "16384x16384", "--csv",
            (dir / "out").string()}}) {
    INFO(args[0] << " " << args[3]);
    const BoundedRun run = run_rtdr_bounded(args, dir, kSeconds, limit);
    require_refused_in_time(run, dir / "out", "--size 16384x16384: ");
    CHECK(rtdr::last_line(run.result.err).find(" would hold about ") != std::string::npos);
    CHECK(run.result.err.find('%') == std::string::npos);  // no progress: nothing was rendered
    CHECK_FALSE(fs::exists(dir / "cache"));
    CHECK(run.max_rss_kib < kOneGiBInKiB);
  }
}

// ---- Ids read from a file: render --gradients continuing from frame A-1 ----

namespace {

// Frames 0-1 of cornell with gradient samples in `dir`/out; frame 1 then changed by `change`.
fs::path gradient_sequence(const fs::path& dir, const std::function<void(Frame&)>& change) {
  const fs::path out = dir / "out";
  const RunResult r = render(dir, {"--scene", "cornell", "--gradients", "--frames", "0-1", "--size", "16x9", "--out",
                                   out.string()});
  REQUIRE(r.exit_code == 0);
  Frame frame = rtdr::read_exr((out / "frame_0001.exr").string());
  change(frame);
  rtdr::write_exr((out / "frame_0001.exr").string(), frame);
  return out;
}

// The first pixel that sees a surface.
size_t covered_pixel(const Frame& frame) {
  const std::vector<uint32_t>& instance = frame.uint_channel("id.instance").data;
  for (size_t i = 0; i < instance.size(); ++i)
    if (instance[i] != rtdr::kInvalidId) return i;
  FAIL("no pixel sees a surface");
  return 0;
}

}  // namespace

TEST_CASE("render --gradients: frame A-1 with ids beyond the scene is refused, naming the file, frame and pixel") {
  struct Damage {
    const char* what;
    std::function<void(Frame&)> change;
  };
  const std::vector<Damage> damages = {
      {"id.instance is 999", [](Frame& f) { f.uint_channel("id.instance").data[covered_pixel(f)] = 999; }},
      {"id.triangle is 4000000", [](Frame& f) { f.uint_channel("id.triangle").data[covered_pixel(f)] = 4000000; }},
      {"bary.U or bary.V is not finite", [](Frame& f) { f.float_channel("bary.V").data[covered_pixel(f)] = NAN; }},
      {"rng.seed_frame is 7, not a frame before 2", [](Frame& f) { f.uint_channel("rng.seed_frame").data[3] = 7; }},
      {"the luminance of direct or indirect is not finite",
       [](Frame& f) { f.float_channel("indirect.G").data[2] = INFINITY; }},
  };
  for (const Damage& d : damages) {
    INFO(d.what);
    const fs::path dir = scratch("bad_previous");
    const fs::path out = gradient_sequence(dir, d.change);
    const std::string before = read_text(out / "frame_0001.exr");
    const BoundedRun run = run_rtdr_bounded({"render", "--scene", "cornell", "--gradients", "--frames", "2", "--size",
                                             "16x9", "--out", out.string()},
                                            dir, kSeconds);
    INFO("stderr: " << run.result.err);
    CHECK_FALSE(run.timed_out);
    CHECK(run.result.exit_code == 1);  // not a crash
    const std::string error = rtdr::last_line(run.result.err);
    CHECK(error.rfind("rtdr: error: '" + (out / "frame_0001.exr").string() + "' (frame 1, which frame 2 continues): " +
                          d.what, 0) == 0);
    CHECK(error.find(" at pixel (") != std::string::npos);
    CHECK(files_in(out) == std::set<std::string>{"frame_0000.exr", "frame_0000.png", "frame_0001.exr", "frame_0001.png"});
    CHECK(read_text(out / "frame_0001.exr") == before);
    CHECK_FALSE(staging_left(dir));
  }
}

TEST_CASE("render --gradients: an untouched frame A-1 continues, to the bit of one render of the whole range") {
  const fs::path dir = scratch("good_previous");
  const fs::path out = gradient_sequence(dir, [](Frame&) {});
  REQUIRE(render(dir, {"--scene", "cornell", "--gradients", "--frames", "2", "--size", "16x9", "--out", out.string()})
              .exit_code == 0);
  REQUIRE(render(dir, {"--scene", "cornell", "--gradients", "--frames", "0-2", "--size", "16x9", "--out",
                       (dir / "whole").string()})
              .exit_code == 0);
  const Frame continued = rtdr::read_exr((out / "frame_0002.exr").string());
  const Frame whole = rtdr::read_exr((dir / "whole" / "frame_0002.exr").string());
  for (const char* channel : {"direct.R", "indirect.G", "gradient.prev_direct"})
    CHECK(continued.float_channel(channel).data == whole.float_channel(channel).data);
  CHECK(continued.uint_channel("gradient.source").data == whole.uint_channel("gradient.source").data);
  const std::vector<uint32_t>& source = continued.uint_channel("gradient.source").data;
  CHECK(std::count_if(source.begin(), source.end(), [](uint32_t j) { return j != rtdr::kInvalidId; }) > 0);
}

// ---- rtdr check runs exactly what filter runs, and every input error names its file ----

namespace {

// Frames 0-1 of cornell with gradient samples, as the input of asvgf, in `dir`/in; frame 1 changed by `change`.
fs::path asvgf_input(const fs::path& dir, const std::function<void(Frame&)>& change) {
  const fs::path in = dir / "in";
  REQUIRE(render(dir, {"--scene", "cornell", "--gradients", "--frames", "0-1", "--size", "16x9", "--out", in.string()})
              .exit_code == 0);
  for (const char* png : {"frame_0000.png", "frame_0001.png"}) fs::remove(in / png);
  Frame frame = rtdr::read_exr((in / "frame_0001.exr").string());
  change(frame);
  rtdr::write_exr((in / "frame_0001.exr").string(), frame);
  return in;
}

// Two gradient samples in stratum (0, 0): at (0, 0) and (2, 2), whatever the render put there.
void two_samples_in_a_stratum(Frame& f) {
  rtdr::UIntPlane& source = f.uint_channel("gradient.source");
  source.at(0, 0) = 5;
  source.at(1, 0) = rtdr::kInvalidId;
  source.at(2, 0) = rtdr::kInvalidId;
  source.at(0, 1) = rtdr::kInvalidId;
  source.at(1, 1) = rtdr::kInvalidId;
  source.at(2, 1) = rtdr::kInvalidId;
  source.at(0, 2) = rtdr::kInvalidId;
  source.at(1, 2) = rtdr::kInvalidId;
  source.at(2, 2) = 7;
}

}  // namespace

TEST_CASE("check --method asvgf refuses two gradient samples in one stratum, as filter does, both naming the file") {
  const fs::path dir = scratch("two_samples");
  const fs::path in = asvgf_input(dir, two_samples_in_a_stratum);
  const std::string problem = "stratum (0, 0) of 3x3 pixels holds two gradient samples, at (0, 0) and (2, 2)";
  const RunResult check = run_rtdr_args({"check", "--method", "asvgf", "--in", in.string()}, dir);
  CHECK(check.exit_code == 1);
  CHECK(check.out.find((in / "frame_0001.exr").string() + ": " + problem) != std::string::npos);
  require_refused(filter(in, dir / "out", {"--method", "asvgf"}), dir / "out",
                  (in / "frame_0001.exr").string() + ": " + problem);
}

TEST_CASE("check and filter agree on every damaged input: filter's refusal is one of check's lines") {
  struct Damage {
    const char* what;
    std::function<void(Frame&)> change;
  };
  const std::vector<Damage> damages = {
      {"untouched", [](Frame&) {}},
      {"two samples in a stratum", two_samples_in_a_stratum},
      {"stratum size 'three'", [](Frame& f) { f.attributes["rtdr.gradient.stratum_size"] = "three"; }},
      {"stratum size 0", [](Frame& f) { f.attributes["rtdr.gradient.stratum_size"] = "0"; }},
      {"no stratum size", [](Frame& f) { f.attributes.erase("rtdr.gradient.stratum_size"); }},
      {"no gradient layer", [](Frame& f) { f = without(without(f, "gradient.prev_direct"), "gradient.source"); }},
      {"NaN in gradient.prev_indirect", [](Frame& f) { f.float_channel("gradient.prev_indirect").data[4] = NAN; }},
      {"id.mesh as float",
       [](Frame& f) {
         const std::vector<uint32_t> ids = f.uint_channel("id.mesh").data;
         const auto attributes = f.attributes;
         f = without(f, "id.mesh");
         f.attributes = attributes;
         for (size_t k = 0; k < ids.size(); ++k) f.add_float("id.mesh").data[k] = float(ids[k]);
       }},
  };
  for (const Damage& d : damages) {
    INFO(d.what);
    const fs::path dir = scratch("agree");
    const fs::path in = asvgf_input(dir, d.change);
    const RunResult check = run_rtdr_args({"check", "--method", "asvgf", "--in", in.string()}, dir);
    const RunResult filtered = filter(in, dir / "out", {"--method", "asvgf"});
    INFO("check: " << check.out << check.err << "\nfilter: " << filtered.err);
    CHECK((check.exit_code == 0) == (filtered.exit_code == 0));
    if (filtered.exit_code == 0) continue;
    const std::string refusal = rtdr::last_line(filtered.err).substr(std::string("rtdr: error: ").size());
    CHECK(refusal.rfind((in / "frame_0001.exr").string() + ": ", 0) == 0);  // names the file: the frame
    CHECK(check.out.find(refusal + "\n") != std::string::npos);
  }
}

// ---- glTF URIs stay in the scene's folder ----

TEST_CASE("render: a glTF URI that climbs out of the scene's folder with ../ is refused, naming the folder") {
  const fs::path dir = scratch("uri_outside");
  fs::create_directories(dir / "scene");
  for (const std::string uri : {"../outside.bin", "../scene/../../outside.bin", "sub/../../outside.bin"}) {
    INFO(uri);
    fs::create_directories(dir / "scene" / "sub");
    const fs::path scene = write_scene(dir / "scene", cornell_with_buffer_file(uri, dir / "outside.bin"));
    require_refused_in_time(run_rtdr_bounded(render_args(scene, dir / "out"), dir, kSeconds), dir / "out",
                            "is outside the scene's folder '" + (dir / "scene").string() + "'");
  }
  // An absolute URI names a file below the scene's folder (tinygltf joins it to the folder): not found there.
  const fs::path absolute = write_scene(dir / "scene", cornell_with_buffer_file((dir / "outside.bin").string(), ""));
  require_refused_in_time(run_rtdr_bounded(render_args(absolute, dir / "out"), dir, kSeconds), dir / "out", "");
}

TEST_CASE("render: a URI with ../ inside the folder, and a symbolic link to a sibling folder, render") {
  const fs::path dir = scratch("uri_inside");
  fs::create_directories(dir / "scene" / "sub");
  const fs::path inside =
      write_scene(dir / "scene", cornell_with_buffer_file("sub/../scene.bin", dir / "scene" / "scene.bin"));
  require_finite_frames(run_rtdr_bounded(render_args(inside, dir / "a"), dir, kSeconds).result, dir / "a", 1);
  // Shared assets in a sibling folder, reached through a link the user made on purpose (docs/reliability.md).
  fs::create_directories(dir / "assets");
  fs::create_directory_symlink("../assets", dir / "scene" / "assets");
  const fs::path linked =
      write_scene(dir / "scene", cornell_with_buffer_file("assets/cornell.bin", dir / "assets" / "cornell.bin"),
                  "linked.gltf");
  require_finite_frames(run_rtdr_bounded(render_args(linked, dir / "b"), dir, kSeconds).result, dir / "b", 1);
}
