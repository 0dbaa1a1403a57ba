// A progress bar with an ETA on the terminal, for long work (reference frames, evaluation runs).
// On a terminal it redraws one line on stderr; when stderr is not a terminal (CI logs, pipes) it prints a
// plain line at every 10% instead, so logs stay short.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace rtdr {

class ProgressBar {
 public:
  ProgressBar(std::string label, uint64_t total);
  ~ProgressBar();  // finishes the line

  // Adds `amount` units of work done. Thread-safe; cheap when nothing needs redrawing.
  void advance(uint64_t amount = 1);

 private:
  void draw(uint64_t done, bool final);

  std::string label_;
  uint64_t total_;
  std::atomic<uint64_t> done_{0};
  std::chrono::steady_clock::time_point start_;
  std::mutex draw_mutex_;
  std::chrono::steady_clock::time_point last_draw_;
  int last_decile_ = -1;
  bool terminal_;
};

}  // namespace rtdr
