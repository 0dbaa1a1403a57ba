// core/atomic_file.h: a single file appears whole or not at all, and a run's output folder (StagedOutputDir)
// receives every file at commit() or none.
#include "core/atomic_file.h"
#include "core/error.h"

#include "cli_fixtures.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

namespace fs = std::filesystem;
using rtdr::cli::files_in;
using rtdr::cli::read_text;

namespace {

fs::path scratch(const std::string& name) { return rtdr::cli::scratch("rtdr_atomic_file_test", name); }

}  // namespace

TEST_CASE("write_file_atomically: a writer that throws leaves neither the file nor its temporary") {
  const fs::path dir = scratch("throw");
  CHECK_THROWS_AS(rtdr::write_file_atomically((dir / "a.txt").string(),
                                              [](const std::string& tmp) {
                                                std::ofstream(tmp) << "half";
                                                throw std::runtime_error("disk full");
                                              }),
                  rtdr::Error);
  CHECK(files_in(dir).empty());
}

TEST_CASE("StagedOutputDir: files appear in a new --out folder, and its parents, only at commit()") {
  const fs::path dir = scratch("commit");
  const fs::path out = dir / "a" / "b";
  rtdr::StagedOutputDir staged(out.string());
  rtdr::write_text_file(staged.file("one.txt"), "1");
  rtdr::write_text_file(staged.file("two.txt"), "2");
  CHECK_FALSE(fs::exists(dir / "a"));  // the staging folder lies in dir, the deepest folder that exists
  CHECK(fs::path(staged.staging()).parent_path() == dir);
  staged.commit();
  CHECK(files_in(out) == std::set<std::string>{"one.txt", "two.txt"});
  CHECK(read_text(out / "two.txt") == "2");
  CHECK(files_in(dir) == std::set<std::string>{"a"});  // the staging folder is gone
}

TEST_CASE("StagedOutputDir: without commit() nothing appears, and nothing is created") {
  const fs::path dir = scratch("abandon");
  {
    rtdr::StagedOutputDir staged((dir / "new").string());
    rtdr::write_text_file(staged.file("frame_0000.exr"), "x");
  }
  CHECK(files_in(dir).empty());
}

TEST_CASE("StagedOutputDir: a rerun replaces files of the same name and keeps the others, and a failed one keeps all") {
  const fs::path out = scratch("rerun") / "out";
  fs::create_directories(out);
  rtdr::write_text_file((out / "keep.txt").string(), "old");
  rtdr::write_text_file((out / "same.txt").string(), "old");
  {
    rtdr::StagedOutputDir failed(out.string());
    rtdr::write_text_file(failed.file("same.txt"), "failed run");
  }
  CHECK(read_text(out / "same.txt") == "old");
  CHECK(files_in(out) == std::set<std::string>{"keep.txt", "same.txt"});
  rtdr::StagedOutputDir staged(out.string());
  rtdr::write_text_file(staged.file("same.txt"), "new");
  staged.commit();
  CHECK(read_text(out / "same.txt") == "new");
  CHECK(read_text(out / "keep.txt") == "old");
  CHECK(files_in(out) == std::set<std::string>{"keep.txt", "same.txt"});
}

TEST_CASE("StagedOutputDir: --out that is a file, or lies below one, is refused at once") {
  const fs::path dir = scratch("file");
  rtdr::write_text_file((dir / "f").string(), "x");
  CHECK_THROWS_AS(rtdr::StagedOutputDir((dir / "f").string()), rtdr::Error);
  CHECK_THROWS_AS(rtdr::StagedOutputDir((dir / "f" / "sub").string()), rtdr::Error);
  CHECK(files_in(dir) == std::set<std::string>{"f"});
}

TEST_CASE("StagedOutputDir: two runs into one folder stage apart") {
  const fs::path out = scratch("two") / "out";
  rtdr::StagedOutputDir a(out.string()), b(out.string());
  CHECK(a.staging() != b.staging());
  rtdr::write_text_file(a.file("a.txt"), "a");
  rtdr::write_text_file(b.file("b.txt"), "b");
  a.commit();
  b.commit();
  CHECK(files_in(out) == std::set<std::string>{"a.txt", "b.txt"});
}

TEST_CASE("StagedOutputDir: a commit that cannot move one file moves none, and --out keeps what it held") {
  // The defect: frame_0001.exr's name was taken by a folder; frame_0000.exr had already replaced the old one.
  const fs::path out = scratch("taken") / "out";
  fs::create_directories(out / "frame_0001.exr");
  rtdr::write_text_file((out / "frame_0000.exr").string(), "old 0");
  {
    rtdr::StagedOutputDir staged(out.string());
    rtdr::write_text_file(staged.file("frame_0000.exr"), "new 0");
    rtdr::write_text_file(staged.file("frame_0001.exr"), "new 1");
    rtdr::write_text_file(staged.file("frame_0002.exr"), "new 2");
    CHECK_THROWS_WITH(staged.commit(), Catch::Contains("frame_0001.exr': it is a folder"));
  }  // the run ends: its staging folder goes
  CHECK(read_text(out / "frame_0000.exr") == "old 0");
  CHECK(files_in(out) == std::set<std::string>{"frame_0000.exr", "frame_0001.exr"});
  CHECK(fs::is_directory(out / "frame_0001.exr"));
}

TEST_CASE("move_all_or_nothing: a move that fails undoes every move before it") {
  const fs::path dir = scratch("undo");
  fs::create_directories(dir / "from");
  fs::create_directories(dir / "to");
  std::vector<rtdr::FileMove> moves;
  for (int k = 0; k < 4; ++k) {
    const std::string name = "f" + std::to_string(k);
    rtdr::write_text_file((dir / "from" / name).string(), "new " + name);
    if (k % 2 == 0) rtdr::write_text_file((dir / "to" / name).string(), "old " + name);  // f0, f2 replace files
    // f3 goes into a folder the moves create.
    moves.push_back({(dir / "from" / name).string(), (dir / "to" / (k == 3 ? "new_folder/" : "") / name).string()});
  }
  // Six renames: f0 aside, f0, f1, f2 aside, f2, f3. Each in turn fails, as a vanished disk would make it.
  for (int fail_at = 1; fail_at <= 6; ++fail_at) {
    INFO("the rename that fails: " << fail_at);
    int renames = 0;
    const auto failing = [&](const std::string& from, const std::string& to) {
      if (++renames == fail_at) throw std::runtime_error("injected failure");
      fs::rename(from, to);
    };
    CHECK_THROWS_WITH(rtdr::move_all_or_nothing(moves, (dir / "backup").string(), failing),
                      Catch::Contains("injected failure"));
    for (int k = 0; k < 4; ++k) {
      const std::string name = "f" + std::to_string(k);
      CHECK(read_text(dir / "from" / name) == "new " + name);
      if (k % 2 == 0) CHECK(read_text(dir / "to" / name) == "old " + name);
    }
    CHECK(files_in(dir / "to") == std::set<std::string>{"f0", "f2"});
  }
}

TEST_CASE("move_all_or_nothing: checks every destination before the first move") {
  const fs::path dir = scratch("check_first");
  rtdr::write_text_file((dir / "a").string(), "a");
  rtdr::write_text_file((dir / "b").string(), "b");
  rtdr::write_text_file((dir / "file").string(), "a file, not a folder");
  CHECK_THROWS_WITH(rtdr::move_all_or_nothing({{(dir / "a").string(), (dir / "a2").string()},
                                               {(dir / "b").string(), (dir / "file" / "b").string()}},
                                              (dir / "backup").string()),
                    Catch::Contains("is a file, not a folder"));
  CHECK(files_in(dir) == std::set<std::string>{"a", "b", "file"});
}

TEST_CASE("StagedOutputDir: staged folders are merged into --out's folders of the same name") {
  const fs::path out = scratch("folders") / "out";
  fs::create_directories(out / "frames");
  rtdr::write_text_file((out / "frames" / "keep.exr").string(), "old");
  rtdr::write_text_file((out / "frames" / "same.exr").string(), "old");
  rtdr::StagedOutputDir staged(out.string());
  fs::create_directories(fs::path(staged.staging()) / "frames");
  rtdr::write_text_file(staged.file("frames/same.exr"), "new");
  rtdr::write_text_file(staged.file("frames/added.exr"), "new");
  staged.commit();
  CHECK(files_in(out / "frames") == std::set<std::string>{"added.exr", "keep.exr", "same.exr"});
  CHECK(read_text(out / "frames" / "same.exr") == "new");
  CHECK(read_text(out / "frames" / "keep.exr") == "old");
}

TEST_CASE("StagingFolder: random names, a lock held while it lives, and stale folders removed by the next one") {
  const fs::path dir = scratch("staging");
  std::set<std::string> names;
  {
    rtdr::StagingFolder a(dir.string(), ".stage-"), b(dir.string(), ".stage-");
    names = files_in(dir);
    CHECK(names.size() == 4);  // two folders, two lock files
    CHECK(a.path() != b.path());
    CHECK(fs::exists(a.path() + ".lock"));
    // Both are alive: neither is stale.
    CHECK(rtdr::StagingFolder::remove_stale(dir.string(), ".stage-") == 0);
  }
  CHECK(files_in(dir).empty());  // each removes itself and its lock
  // A dead run's folder: its lock file exists, but no process holds it.
  fs::create_directories(dir / ".stage-0123456789abcdef-0" / "sub");
  std::ofstream(dir / ".stage-0123456789abcdef-0.lock");
  // Another program's folder of the same prefix, without a lock file, and another prefix: left alone.
  fs::create_directories(dir / ".stage-no-lock");
  fs::create_directories(dir / ".other-1");
  std::ofstream(dir / ".other-1.lock");
  rtdr::StagingFolder c(dir.string(), ".stage-");
  CHECK_FALSE(fs::exists(dir / ".stage-0123456789abcdef-0"));
  CHECK_FALSE(fs::exists(dir / ".stage-0123456789abcdef-0.lock"));
  CHECK(fs::exists(dir / ".stage-no-lock"));
  CHECK(fs::exists(dir / ".other-1.lock"));
  // A staging name does not depend on the pid: a folder left with this process's pid in its name blocks nothing.
  CHECK(fs::path(c.path()).filename().string().find(std::to_string(::getpid())) == std::string::npos);
}
