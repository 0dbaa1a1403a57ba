// trace/render_key.h: every rendered frame carries its full render key, its provenance and the checksum of its
// planes; key_mismatch and checksum_mismatch tell a frame apart from the one asked for; a scene is identified by
// its content (Scene::content_hash), external buffers included.
#include "trace/render_key.h"

#include "cli_fixtures.h"
#include "core/parallel.h"
#include "scenes/gltf_loader.h"
#include "trace/gradients.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

namespace fs = std::filesystem;
using namespace rtdr;

namespace {

fs::path scratch(const std::string& name) { return cli::scratch("rtdr_render_key_test", name); }

// Decodes base64 (RFC 4648, with padding), for moving a shipped scene's embedded buffer into a file of its own.
std::string base64_decode(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    const size_t v = alphabet.find(c);
    if (v == std::string::npos) continue;  // '=' and anything else
    bits = (bits << 6) | uint32_t(v);
    if ((count += 6) >= 8) out += char((bits >> (count -= 8)) & 0xFF);
  }
  return out;
}

// cornell with its one buffer in `dir`/cornell.bin instead of a data: URI.
fs::path cornell_with_external_buffer(const fs::path& dir) {
  nlohmann::json scene = nlohmann::json::parse(cli::read_text(fs::path(RTDR_SOURCE_DIR) / "scenes" / "cornell.gltf"));
  REQUIRE(scene["buffers"].size() == 1);
  const std::string uri = scene["buffers"][0]["uri"];
  std::ofstream(dir / "cornell.bin", std::ios::binary) << base64_decode(uri.substr(uri.find(',') + 1));
  scene["buffers"][0]["uri"] = "cornell.bin";
  std::ofstream(dir / "cornell.gltf") << scene.dump();
  return dir / "cornell.gltf";
}

struct ThreadCountGuard {
  ~ThreadCountGuard() { set_thread_count(0); }
};

}  // namespace

TEST_CASE("a rendered frame's header holds its full key, its provenance and the checksum of its planes") {
  const Scene scene = load_scene("cornell");
  RenderSettings settings;
  settings.spp = 2;
  settings.seed = 7;
  const Frame frame = render_frame(scene, 3, 16, 9, settings);
  const Attributes key = render_key(scene, 3, 16, 9, settings);
  CHECK(key.at("rtdr.scene") == "cornell");
  CHECK(key.at("rtdr.scene.hash") == scene.content_hash);
  CHECK(key.at("rtdr.frame") == "3");
  CHECK(key.at("rtdr.size") == "16x9");
  CHECK(key.at("rtdr.spp") == "2");
  CHECK(key.at("rtdr.seed") == "7");
  CHECK(key.at("rtdr.max_bounces") == "1");
  CHECK(key.at("rtdr.regularized_roughness") == "0.300000012");  // 0.3f, exactly
  CHECK(key.at("rtdr.shading_samples") == "0");
  CHECK(key.at("rtdr.gradients") == "0");
  CHECK(key_mismatch(frame, key).empty());
  CHECK(checksum_mismatch(frame).empty());
  CHECK(frame.attributes.at("rtdr.checksum") == frame_checksum(frame));
  CHECK_THAT(frame.attributes.at("rtdr.build"), Catch::Contains("Embree"));
  CHECK_FALSE(frame.attributes.at("rtdr.cpu").empty());
  // The provenance is recorded, not keyed: a frame of another build or processor is the same frame.
  Frame elsewhere = frame;
  elsewhere.attributes["rtdr.build"] = "another build";
  elsewhere.attributes["rtdr.cpu"] = "another processor";
  CHECK(key_mismatch(elsewhere, key).empty());
}

TEST_CASE("key_mismatch names the first keyed attribute that differs, is missing or is not expected") {
  const Scene scene = load_scene("cornell");
  const RenderSettings settings;
  const Frame plain = render_frame(scene, 0, 8, 6, settings);
  RenderSettings references = settings;
  references.spp = 64;
  CHECK(key_mismatch(plain, render_key(scene, 0, 8, 6, references)) == "rtdr.spp is 1, not 64");
  CHECK(key_mismatch(plain, render_key(scene, 1, 8, 6, settings)) == "rtdr.frame is 0, not 1");
  CHECK(key_mismatch(plain, render_key(scene, 1, 8, 6, settings), {"rtdr.frame"}).empty());
  Frame bare = plain;
  bare.attributes.erase("rtdr.max_bounces");
  CHECK(key_mismatch(bare, render_key(scene, 0, 8, 6, settings)) == "rtdr.max_bounces is missing");
  // A frame with gradient samples is not the plain frame of the same settings, nor the other way round.
  const GradientParams params;
  const Frame gradients = render_frame_with_gradients(scene, 0, 8, 6, settings, params, nullptr);
  CHECK(key_mismatch(gradients, render_key(scene, 0, 8, 6, settings, &params)).empty());
  CHECK(key_mismatch(gradients, render_key(scene, 0, 8, 6, settings)) == "rtdr.gradients is 1, not 0");
  CHECK(key_mismatch(plain, render_key(scene, 0, 8, 6, settings, &params)) == "rtdr.gradient.light_cdf is missing");
  // An attribute the key does not have, but a keyed name: a frame of a newer rtdr with one setting more.
  Frame newer = plain;
  newer.attributes["rtdr.some_future_setting"] = "2";
  CHECK(key_mismatch(newer, render_key(scene, 0, 8, 6, settings)) == "rtdr.some_future_setting = 2 is not expected");
}

TEST_CASE("checksum_mismatch: any changed value, channel or size since rendering, a NaN too, is told apart") {
  const Frame frame = render_frame(load_scene("cornell"), 0, 8, 6, {});
  REQUIRE(checksum_mismatch(frame).empty());
  Frame nudged = frame;
  float& v = nudged.float_channel("direct.R").data[17];
  v = std::nextafter(v, 1e9f);  // one ulp
  CHECK_THAT(checksum_mismatch(nudged), Catch::Contains("changed since it was rendered"));
  Frame nan = frame;
  nan.float_channel("indirect.G").data[0] = std::numeric_limits<float>::quiet_NaN();
  CHECK_FALSE(checksum_mismatch(nan).empty());
  Frame positive_zero = frame;  // bits, not values: -0 is not 0
  positive_zero.add_float("extra", 0.0f);
  Frame negative_zero = frame;
  negative_zero.add_float("extra", -0.0f);
  CHECK(frame_checksum(positive_zero) != frame_checksum(negative_zero));
  Frame dropped = cli::without(frame, "albedo.G");
  dropped.attributes = frame.attributes;
  CHECK_FALSE(checksum_mismatch(dropped).empty());
  Frame id = frame;
  id.uint_channel("id.mesh").data[3] ^= 1u;
  CHECK_FALSE(checksum_mismatch(id).empty());
  Frame unstamped = frame;
  unstamped.attributes.erase("rtdr.checksum");
  CHECK(checksum_mismatch(unstamped) == "rtdr.checksum is missing");
}

TEST_CASE("the header, checksum included, is the same for 1 and 2 threads") {
  ThreadCountGuard guard;
  const Scene scene = load_scene("pillars");
  RenderSettings settings;
  settings.spp = 2;
  set_thread_count(1);
  const Frame one = render_frame(scene, 10, 24, 14, settings);
  set_thread_count(2);
  const Frame two = render_frame(scene, 10, 24, 14, settings);
  CHECK(one.attributes == two.attributes);
}

TEST_CASE("a scene is identified by its content: the file and every buffer it loads, not its name") {
  const fs::path dir = scratch("content");
  const Scene shipped = load_scene("cornell");
  CHECK(shipped.content_hash.size() == 16);
  CHECK(load_scene("cornell").content_hash == shipped.content_hash);
  // The same name in another folder, one byte more (a space the JSON ignores): another scene.
  fs::create_directories(dir / "other");
  std::ofstream(dir / "other" / "cornell.gltf") << cli::read_text(fs::path(RTDR_SOURCE_DIR) / "scenes" / "cornell.gltf")
                                                 << " ";
  const Scene copy = load_scene((dir / "other" / "cornell.gltf").string());
  CHECK(copy.name == shipped.name);
  CHECK(copy.content_hash != shipped.content_hash);
  // An external buffer: changing one byte of cornell.bin changes the hash though the .gltf is the same file.
  fs::create_directories(dir / "external");
  const fs::path gltf = cornell_with_external_buffer(dir / "external");
  const std::string before = load_scene(gltf.string()).content_hash;
  std::string bin = cli::read_text(dir / "external" / "cornell.bin");
  bin[5] = char(bin[5] ^ 1);
  std::ofstream(dir / "external" / "cornell.bin", std::ios::binary) << bin;
  CHECK(load_scene(gltf.string()).content_hash != before);
}
