// eval/frame_cache.h: an entry is found by the whole render key, however long the scene's name; an entry is used
// only when its header holds that key, its planes their checksum and every float is finite, and is rendered again
// otherwise; writes are staged inside the cache and appear whole; what a dead run staged is removed; a gradient
// sequence is rendered in the runs gradient_runs cuts, which a plan's jobs follow (eval/render_plan.h).
#include "eval/frame_cache.h"

#include "cli_fixtures.h"
#include "core/atomic_file.h"
#include "core/exr_io.h"
#include "scenes/gltf_loader.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

namespace fs = std::filesystem;
using namespace rtdr;

namespace {

fs::path scratch(const std::string& name) { return cli::scratch("rtdr_frame_cache_test", name); }

RenderSettings with_spp(int spp) {
  RenderSettings s;
  s.spp = spp;
  return s;
}

// Every file below `dir`, as paths relative to it.
std::set<std::string> tree(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) names.insert(fs::relative(e.path(), dir).string());
  return names;
}

bool staging_in(const fs::path& dir) {
  for (const std::string& name : cli::files_in(dir))
    if (name.rfind(".rtdr-cache-staging-", 0) == 0) return true;
  return false;
}

}  // namespace

TEST_CASE("a scene name of any length keys the whole render key: a reference is never a 1-spp frame") {
  // The defect: a 160-character stem filled a fixed char name[160] that held the whole key, so its tail (the
  // hash, size, spp and seed) was cut off and the 1-spp inputs were found as the references.
  const fs::path dir = scratch("long_name");
  const std::string stem(200, 'r');
  fs::copy_file(fs::path(RTDR_SOURCE_DIR) / "scenes" / "cornell.gltf", dir / (stem + ".gltf"));
  const Scene scene = load_scene((dir / (stem + ".gltf")).string());
  FrameCache cache((dir / "cache").string(), scene);
  const std::string input = cache.path(render_key(scene, 0, 12, 8, with_spp(1)));
  const std::string reference = cache.path(render_key(scene, 0, 12, 8, with_spp(4)));
  CHECK(input != reference);
  CHECK(fs::path(input).parent_path().filename().string().size() < 100);  // the readable part is cut, not the hash
  bool hit = true;
  const Frame a = cache.get(0, 12, 8, with_spp(1), &hit);
  CHECK_FALSE(hit);
  const Frame b = cache.get(0, 12, 8, with_spp(4), &hit);
  CHECK_FALSE(hit);
  CHECK(b.attributes.at("rtdr.spp") == "4");
  CHECK(cache.get(0, 12, 8, with_spp(4), &hit).attributes.at("rtdr.checksum") == b.attributes.at("rtdr.checksum"));
  CHECK(hit);
  CHECK(a.attributes.at("rtdr.checksum") != b.attributes.at("rtdr.checksum"));
}

TEST_CASE("every setting of the tracer is in the key") {
  const Scene scene = load_scene("cornell");
  const FrameCache cache(scratch("settings").string(), scene);
  const RenderSettings base;
  const std::string path = cache.path(render_key(scene, 2, 12, 8, base));
  RenderSettings s = base;
  s.trace.max_bounces = 0;
  CHECK(cache.path(render_key(scene, 2, 12, 8, s)) != path);
  s = base;
  s.trace.regularized_roughness = 0.0f;
  CHECK(cache.path(render_key(scene, 2, 12, 8, s)) != path);
  s = base;
  s.trace.shading_samples = 64;
  CHECK(cache.path(render_key(scene, 2, 12, 8, s)) != path);
  s = base;
  s.seed = 1;
  CHECK(cache.path(render_key(scene, 2, 12, 8, s)) != path);
  CHECK(cache.path(render_key(scene, 2, 12, 8, base)) == path);
  CHECK(cache.path(render_key(scene, 3, 12, 8, base)) != path);
  CHECK(fs::path(cache.path(render_key(scene, 3, 12, 8, base))).parent_path() == fs::path(path).parent_path());
}

TEST_CASE("an entry that is not the frame asked for is rendered again and replaced") {
  const fs::path dir = scratch("invalid");
  const Scene scene = load_scene("cornell");
  FrameCache cache(dir.string(), scene);
  const RenderSettings references = with_spp(4);
  const Frame good = cache.get(1, 12, 8, references);
  const std::string entry = cache.path(render_key(scene, 1, 12, 8, references));
  REQUIRE(fs::exists(entry));
  const auto corrupt_then_get = [&](const std::function<void()>& corrupt) {
    corrupt();
    bool hit = true;
    const Frame again = cache.get(1, 12, 8, references, &hit);
    CHECK_FALSE(hit);
    CHECK(again.attributes.at("rtdr.checksum") == good.attributes.at("rtdr.checksum"));  // the same frame, rendered
    CHECK(checksum_mismatch(read_exr(entry)).empty());  // and the entry replaced by it
    cache.get(1, 12, 8, references, &hit);
    CHECK(hit);
  };
  SECTION("another key's frame at its path (a hash collision, or a copy)") {
    corrupt_then_get([&] { write_exr(entry, cache.get(1, 12, 8, with_spp(1))); });
  }
  SECTION("a NaN written into it, header untouched") {
    corrupt_then_get([&] {
      Frame f = read_exr(entry);
      f.float_channel("indirect.R").data[5] = std::numeric_limits<float>::quiet_NaN();
      write_exr(entry, f);
    });
  }
  SECTION("a finite value changed, header untouched") {
    corrupt_then_get([&] {
      Frame f = read_exr(entry);
      f.float_channel("direct.G").data[0] += 1.0f;
      write_exr(entry, f);
    });
  }
  SECTION("a truncated file") {
    corrupt_then_get([&] {
      const std::string bytes = cli::read_text(entry);
      std::ofstream(entry, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
    });
  }
  SECTION("a frame of an older rtdr, without a key") {
    corrupt_then_get([&] {
      Frame f = read_exr(entry);
      f.attributes.clear();
      write_exr(entry, f);
    });
  }
}

TEST_CASE("a frame rendered by rtdr render, written anywhere, is the cache's entry when moved into place") {
  // The contract that lets other machines fill the cache: the header render_frame stamps is the entry's key.
  const fs::path dir = scratch("foreign");
  const Scene scene = load_scene("cornell");
  FrameCache cache((dir / "cache").string(), scene);
  const Frame rendered = render_frame(scene, 4, 12, 8, with_spp(2));
  const std::string entry = cache.path(render_key(scene, 4, 12, 8, with_spp(2)));
  fs::create_directories(fs::path(entry).parent_path());
  write_exr(entry, rendered);
  bool hit = false;
  CHECK(cache.get(4, 12, 8, with_spp(2), &hit).attributes == rendered.attributes);
  CHECK(hit);
}

TEST_CASE("cache writes are staged inside the cache, appear whole, and what a dead run staged is removed") {
  const fs::path dir = scratch("staging");
  const Scene scene = load_scene("cornell");
  fs::create_directories(dir);
  // What a killed run leaves: a staging folder with a partial frame, and its lock file, which no process holds.
  fs::create_directories(dir / ".rtdr-cache-staging-dead");
  std::ofstream(dir / ".rtdr-cache-staging-dead" / "frame_0000.exr") << "half a frame";
  std::ofstream(dir / ".rtdr-cache-staging-dead.lock");
  // A live run's staging folder, whose lock this process holds, and a folder of that prefix with no lock file.
  auto live = std::make_unique<StagingFolder>(dir.string(), ".rtdr-cache-staging-");
  fs::create_directories(dir / ".rtdr-cache-staging-unlocked");
  {
    FrameCache cache(dir.string(), scene);
    cache.get(0, 12, 8, {});
    CHECK_FALSE(fs::exists(dir / ".rtdr-cache-staging-dead"));
    CHECK_FALSE(fs::exists(dir / ".rtdr-cache-staging-dead.lock"));
    CHECK(fs::exists(live->path()));
    CHECK(fs::exists(dir / ".rtdr-cache-staging-unlocked"));
  }
  live.reset();
  fs::remove(dir / ".rtdr-cache-staging-unlocked");
  CHECK_FALSE(staging_in(dir));  // each run's own staging folder goes with it
  // Only whole entries: one folder, one frame.
  const std::set<std::string> entries = tree(dir);
  REQUIRE(entries.size() == 2);
  CHECK_THAT(*entries.rbegin(), Catch::EndsWith("frame_0000.exr"));
}

TEST_CASE("gradient_runs cuts a gradient sequence where the cache must render it, asking once per frame") {
  // The frames the cache holds, and how often each was asked about.
  std::set<int> held;
  std::map<int, int> asked;
  const auto runs = [&](int first, int last) {
    asked.clear();
    std::vector<std::pair<int, int>> out;
    for (const GradientRun& r : gradient_runs(first, last, [&](int f) { return ++asked[f], held.count(f) > 0; }))
      out.push_back({r.first, r.last});
    for (const auto& [f, n] : asked) CHECK(n == 1);
    return out;
  };
  using Runs = std::vector<std::pair<int, int>>;
  held = {};
  CHECK(runs(0, 4) == Runs{{0, 4}});
  CHECK(runs(3, 5) == Runs{{0, 5}});  // frame 3 needs 2, 1 and 0: rendered from the start
  held = {0, 1, 2, 3, 4, 5};
  CHECK(runs(2, 5).empty());
  CHECK(asked.size() == 4);  // a warm range asks nothing before it
  held = {0, 1, 2, 4, 5};
  CHECK(runs(2, 5) == Runs{{3, 3}});  // a hole: frame 3 from the cached 2; 4 and 5 are kept
  held = {1, 4};
  CHECK(runs(3, 7) == Runs{{2, 3}, {5, 7}});  // back to the latest cached frame before the range, then after 4
  held = {0, 5};
  CHECK(runs(2, 3) == Runs{{1, 3}});
}

TEST_CASE("gradient_frames renders what gradient_runs lists, each frame from the one before, and keeps the rest") {
  const fs::path dir = scratch("gradient_frames");
  const Scene scene = load_scene("pillars");
  FrameCache cache(dir.string(), scene);
  const GradientParams params;
  const auto entry = [&](int f) { return cache.path(render_key(scene, f, 16, 12, {}, &params)); };
  const std::vector<Frame> cold = cache.gradient_frames(2, 4, 16, 12, {}, params);  // renders 0 to 4
  for (int f = 0; f <= 4; ++f) REQUIRE(fs::exists(entry(f)));
  fs::remove(entry(3));
  const auto kept2 = cli::file_id(entry(2)), kept4 = cli::file_id(entry(4));
  const std::vector<Frame> again = cache.gradient_frames(2, 4, 16, 12, {}, params);
  CHECK(cli::file_id(entry(2)) == kept2);  // read, not rendered
  CHECK(cli::file_id(entry(4)) == kept4);
  REQUIRE(fs::exists(entry(3)));  // rendered from the cached frame 2: the same frame as from the start
  REQUIRE(again.size() == 3);
  for (size_t k = 0; k < 3; ++k)
    CHECK(again[k].attributes.at("rtdr.checksum") == cold[k].attributes.at("rtdr.checksum"));
}
