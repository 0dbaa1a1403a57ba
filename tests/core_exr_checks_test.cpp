// Tests of core/exr_checks.cpp, the checks read_exr makes before OpenEXR allocates: the expansion bounds against
// what zlib really achieves on the most compressible frame there is (all zeros), which read_exr still reads; the
// plausibility rule on the numbers of an 8,542-byte file that took 3.16 GB and of a file that could hold its pixels; and the
// memory budget, passed in.
#include "core/exr_checks.h"

#include "core/error.h"
#include "core/exr_io.h"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>

namespace fs = std::filesystem;
using namespace rtdr;

TEST_CASE("exr checks: ZIP's bound (1032) is above what zlib reaches on a frame of zeros, which still reads") {
  const fs::path path = fs::temp_directory_path() / ("rtdr_exr_checks_zeros_" + std::to_string(::getpid()) + ".exr");
  Frame zeros(512, 512);
  for (const char* name : {"a.R", "a.G", "a.B", "b.R", "b.G", "b.B", "c.X", "c.Y"}) zeros.add_float(name, 0.0f);
  write_exr(path.string(), zeros);  // ZIP (core/exr_io.h)
  const double stored = 512.0 * 512.0 * 8 * 4;
  const double ratio = stored / double(fs::file_size(path));
  INFO("8 MiB of zeros in " << fs::file_size(path) << " bytes: " << ratio << " to 1");
  CHECK(ratio > 100.0);                                // zeros do compress: the bound is not loose by orders
  CHECK(ratio < double(exr_max_expansion(3)));         // and ZIP stays below its bound
  CHECK(read_exr(path.string()).float_channel("b.G").data.size() == size_t(512 * 512));  // so it is read
  fs::remove(path);
}

TEST_CASE("exr checks: each compression's bound, from its decoder (exr_checks.cpp), and unknown ones") {
  CHECK(exr_max_expansion(0) == 1);
  CHECK(exr_max_expansion(1) == 64);    // RLE: 128 bytes from 2
  CHECK(exr_max_expansion(2) == 1032);  // ZIPS: deflate
  CHECK(exr_max_expansion(3) == 1032);  // ZIP
  CHECK(exr_max_expansion(4) == 454);   // PIZ: 510 bytes from 9 bits
  CHECK(exr_max_expansion(5) == 1376);  // PXR24: deflate of 3 bytes that become 4
  CHECK(exr_max_expansion(7) == 11);    // B44A: 32 bytes from 3
  CHECK(exr_max_expansion(9) == 65536);
  CHECK(exr_max_expansion(10) == 0);
  CHECK(exr_compression_name(3) == "ZIP");
  CHECK(exr_compression_name(12) == "unknown (12)");
}

TEST_CASE("exr checks: 3 GiB of pixels cannot come from 8542 ZIP bytes, can from 3.2 MB, and must fit the budget") {
  const ExrDeclared image{16384, 16384, 3, 12, 3};  // 3 FLOAT channels, ZIP
  const MemoryBudget plenty{uint64_t(64) << 30, "MemAvailable"};
  CHECK_THROWS_WITH(require_plausible_exr("x.exr", image, 8542, plenty),
                    "cannot read EXR file 'x.exr': its 16384x16384 pixels of 3 channels (3.00 GiB) cannot come from "
                    "its 8542 bytes: ZIP compression decodes at most 1032 bytes from each (core/exr_checks.cpp); "
                    "truncated or damaged");
  // 3 GiB / 1032 = 3,121,342.5 bytes: the least a ZIP file can hold them in.
  CHECK_THROWS_AS(require_plausible_exr("x.exr", image, 3'121'341, plenty), Error);
  CHECK_NOTHROW(require_plausible_exr("x.exr", image, 3'121'343, plenty));
  // The planes read_exr makes: 4 bytes per value, 3 GiB here.
  const MemoryBudget tight{uint64_t(2) << 30, "the cgroup's memory limit"};
  CHECK_THROWS_WITH(require_plausible_exr("x.exr", image, 3'200'000, tight),
                    "cannot read EXR file 'x.exr': reading its 16384x16384 pixels of 3 channels needs 3.00 GiB, more than the "
                    "2.00 GiB of memory available (bound by the cgroup's memory limit)");
  CHECK_NOTHROW(require_plausible_exr("x.exr", image, 3'200'000, {uint64_t(3) << 30, "MemAvailable"}));
  // HALF channels store 2 bytes and become 4 in memory: the file bound counts 2, the budget 4.
  const ExrDeclared half{16384, 16384, 3, 6, 0};  // uncompressed
  CHECK_NOTHROW(require_plausible_exr("h.exr", half, uint64_t(16384) * 16384 * 6, {uint64_t(3) << 30, "MemAvailable"}));
  CHECK_THROWS_WITH(require_plausible_exr("h.exr", half, uint64_t(16384) * 16384 * 6 - 1, plenty),
                    Catch::Contains("it is uncompressed, but its"));
}
