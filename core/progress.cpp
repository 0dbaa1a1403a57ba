#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace rtdr {
namespace {

std::string format_seconds(double s) {
  char text[32];
  if (s < 60.0) std::snprintf(text, sizeof text, "%.0fs", s);
  else std::snprintf(text, sizeof text, "%dm%02ds", int(s) / 60, int(s) % 60);
  return text;
}

}  // namespace

ProgressBar::ProgressBar(std::string label, uint64_t total)
    : label_(std::move(label)), total_(std::max<uint64_t>(total, 1)), start_(std::chrono::steady_clock::now()),
      last_draw_(start_), terminal_(::isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() { draw(done_.load(), true); }

void ProgressBar::advance(uint64_t amount) {
  const uint64_t done = done_.fetch_add(amount) + amount;
  const auto now = std::chrono::steady_clock::now();
  // Redraw at most 10 times a second; skip when another thread is drawing.
  if (now - last_draw_ < std::chrono::milliseconds(100)) return;
  std::unique_lock<std::mutex> lock(draw_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  last_draw_ = now;
  draw(done, false);
}

void ProgressBar::draw(uint64_t done, bool final) {
  const double fraction = std::min(1.0, double(done) / double(total_));
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  if (terminal_) {
    constexpr int kWidth = 30;
    const int filled = int(fraction * kWidth);
    std::fprintf(stderr, "\r%s [%s%s] %3.0f%%  %s elapsed, ETA %s  ", label_.c_str(), std::string(size_t(filled), '#').c_str(),
                 std::string(size_t(kWidth - filled), '.').c_str(), 100.0 * fraction, format_seconds(elapsed).c_str(),
                 format_seconds(eta).c_str());
    if (final) std::fputc('\n', stderr);
  } else {
    const int decile = int(fraction * 10.0);
    if (decile == last_decile_ && !final) return;
    if (final && decile == last_decile_) return;
    last_decile_ = decile;
    std::fprintf(stderr, "%s %3.0f%%  %s elapsed, ETA %s\n", label_.c_str(), 100.0 * fraction,
                 format_seconds(elapsed).c_str(), format_seconds(eta).c_str());
  }
  std::fflush(stderr);
}

}  // namespace rtdr
