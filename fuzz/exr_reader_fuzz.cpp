// libFuzzer harness for the EXR frame reader (core/exr_io.h) and the checks a filter runs on what it reads
// (app/sequence.h read_filter_input: every channel a method reads present, of its type and finite). Each input is one
// .exr file; the seeds (fuzz/corpus/exr_reader_fuzz/) are 2x2 frames written by fuzz/make_seeds.py.
//
// read_exr promises a one-line rtdr::Error for every bad file. A finding is anything else: a crash, a
// sanitizer report, a hang, or any other exception escaping (libFuzzer reports the abort it causes).
// A frame that reads is also written back and read again: core/exr_io.h promises a bit-exact round trip,
// so a difference is a finding too.
#include "fuzz/harness.h"

#include "app/sequence.h"
#include "core/error.h"
#include "filters/method.h"
#include "filters/svgf/svgf.h"
#include "core/exr_io.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

// Bitwise equality of two planes (NaN payloads included, which == would not compare).
template <class T>
bool same_plane(const rtdr::Plane<T>& a, const rtdr::Plane<T>& b) {
  return a.width == b.width && a.height == b.height && a.data.size() == b.data.size() &&
         std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(T)) == 0;
}

// Writes `frame`, reads it back, and aborts when any channel changed.
void check_round_trip(const rtdr::Frame& frame, const std::string& path) {
  rtdr::write_exr(path, frame);
  const rtdr::Frame back = rtdr::read_exr(path);
  bool same = back.float_channels().size() == frame.float_channels().size() &&
              back.uint_channels().size() == frame.uint_channels().size();
  for (const auto& [name, plane] : frame.float_channels())
    same = same && back.float_channels().count(name) && same_plane(plane, back.float_channel(name));
  for (const auto& [name, plane] : frame.uint_channels())
    same = same && back.uint_channels().count(name) && same_plane(plane, back.uint_channel(name));
  if (!same) {
    std::fprintf(stderr, "finding: write_exr then read_exr changed the frame (%dx%d)\n", frame.width(), frame.height());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static rtdr::fuzz::InputFile input("frame_0000.exr"), output("round_trip.exr");
  const std::string& path = input.write(data, size);
  try {
    // The reader alone: a frame that reads must survive a round trip, whatever its layers hold.
    check_round_trip(rtdr::read_exr(path), output.path());
    // A filter's view of it: every channel a method reads present, of its type and finite. EAW's inputs are
    // SVGF's plus `position`: every channel any method reads (filters/svgf/svgf.h svgf_input_channels).
    static const rtdr::InputChannels channels = rtdr::svgf_input_channels(rtdr::method_options("eaw"));
    rtdr::SequenceShape shape;
    rtdr::read_filter_input(path, shape, channels);
  } catch (const rtdr::Error& e) {  // the promised outcome for a bad file
    rtdr::fuzz::expected_error(e);
  }
  return 0;
}
