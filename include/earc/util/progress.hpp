// A progress line for long jobs: redrawn in place on a terminal (stderr),
// silent otherwise so logs and CI output stay clean. Thread-safe tick().
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace earc {

class Progress {
 public:
  Progress(std::string label, std::size_t total, bool enabled = true);
  ~Progress();
  void tick(std::size_t n = 1);
  void setStatus(const std::string& status);  // short text shown after the bar
  void addToTotal(std::size_t more);          // what is known only once the job has begun
  void finish();

 private:
  void draw(bool force);
  std::string label_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  bool enabled_;
  bool finished_ = false;
  std::string status_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace earc
