#include "earc/util/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace earc {

Progress::Progress(std::string label, std::size_t total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled && isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

Progress::~Progress() { finish(); }

void Progress::tick(std::size_t n) {
  done_ += n;
  if (enabled_) draw(false);
}

void Progress::setStatus(const std::string& status) {
  std::lock_guard lock(mutex_);
  status_ = status;
}

void Progress::addToTotal(std::size_t more) {
  std::lock_guard lock(mutex_);
  total_ += more;
}

void Progress::finish() {
  if (!enabled_ || finished_) return;
  draw(true);
  std::fputc('\n', stderr);
  finished_ = true;
}

void Progress::draw(bool force) {
  std::lock_guard lock(mutex_);
  auto now = std::chrono::steady_clock::now();
  // Redraw at most ten times a second: a terminal is slow and so are we if we flood it.
  if (!force && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  std::size_t done = done_.load();
  double frac = total_ ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
  if (frac > 1.0) frac = 1.0;
  constexpr int kWidth = 30;
  int filled = static_cast<int>(frac * kWidth);
  double elapsed = std::chrono::duration<double>(now - start_).count();
  double eta = frac > 0 ? elapsed / frac - elapsed : 0.0;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\r%s [%s] %zu/%zu %5.1fs eta %5.1fs %s\033[K", label_.c_str(), bar.c_str(), done,
               total_, elapsed, eta, status_.c_str());
  std::fflush(stderr);
}

}  // namespace earc
