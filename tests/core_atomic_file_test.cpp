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
