#include "cli/progress.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <sys/resource.h>
#include <unistd.h>

namespace pcl_ncut_seg {
namespace tool {

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled) {
  if (!enabled_)
    return;
  if (const char* delay = std::getenv("PCL_NCUT_SEG_PROGRESS_DELAY")) {
    double v = 0;
    if (toDouble(delay, v) && v >= 0)
      delay_ = v;
  }
  thread_ = std::thread([this] { run(); });
}

ProgressBar::~ProgressBar() {
  if (!enabled_)
    return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  std::lock_guard<std::mutex> lock(mutex_);
  draw(true);
}

void ProgressBar::update(const char* phase, double fraction) {
  if (!enabled_)
    return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (phase_ != phase) { // a new phase (the last one ended, or is left without an end)
    draw(true);
    phase_ = phase;
    start_ = std::chrono::steady_clock::now();
    known_ = false;
  }
  fraction_ = std::clamp(fraction, 0.0, 1.0);
  const bool was_known = known_;
  if (fraction > 0.0 && fraction < 1.0)
    known_ = true;
  if (fraction >= 1.0) {
    draw(true);
    phase_.clear();
    return;
  }
  // Redraw now rather than wait for the thread when the bar changes kind or is stale, so that
  // what is shown does not depend on how the phase's time falls against the thread's period.
  const auto now = std::chrono::steady_clock::now();
  if (!drawn_ || known_ != was_known || now - last_draw_ >= std::chrono::milliseconds(100))
    draw(false);
}

std::function<void(const char*, double)> ProgressBar::callback() {
  return [this](const char* phase, double fraction) { update(phase, fraction); };
}

void ProgressBar::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, std::chrono::milliseconds(100));
    if (!stop_)
      draw(false);
  }
}

// Called with mutex_ held.
void ProgressBar::draw(bool final_clear) {
  if (final_clear) {
    if (drawn_)
      std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    drawn_ = false;
    return;
  }
  if (phase_.empty())
    return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed < delay_)
    return;
  const int width = 30;
  std::string bar(width, ' ');
  char percent[16] = "    ";
  if (known_) {
    const int filled = static_cast<int>(fraction_ * width);
    std::fill(bar.begin(), bar.begin() + filled, '#');
    std::snprintf(percent, sizeof(percent), "%3d%%", static_cast<int>(fraction_ * 100));
  } else { // no fraction known: a marker that moves, so the user sees it is alive
    const int pos = static_cast<int>(elapsed * 10) % (2 * (width - 3));
    const int at = pos < width - 3 ? pos : 2 * (width - 3) - pos;
    bar.replace(static_cast<std::size_t>(at), 3, "<=>");
  }
  std::fprintf(stderr, "\r%-5s [%s] %s %6.1f s\033[K", phase_.c_str(), bar.c_str(), percent,
               elapsed);
  std::fflush(stderr);
  drawn_ = true;
  last_draw_ = std::chrono::steady_clock::now();
}

bool progressWanted(const Flags& flags) {
  return !flags.has("-quiet") && ::isatty(STDERR_FILENO);
}

std::uint64_t peakMemoryBytes() {
  struct rusage usage;
  if (::getrusage(RUSAGE_SELF, &usage) != 0)
    return 0;
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u; // kilobytes on Linux
}

} // namespace tool
} // namespace pcl_ncut_seg
