#pragma once
// A progress line for the long tools: `label: 1200/4934 scans, 310/s, ETA 12 s`, rewritten in
// place on stderr at most twice a second, and only when stderr is a terminal (so CI logs, pipes
// and the summary line on stdout stay as they were). finish() ends the line.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace adaptive_perception::tools {

class Progress {
 public:
  /// `total` 0: unknown (no ETA). `unit`: what is counted ("scans", "frames").
  Progress(std::string label, long total, std::string unit)
      : label_(std::move(label)), unit_(std::move(unit)), total_(total),
        shown_(::isatty(STDERR_FILENO) == 1), start_(Clock::now()), last_(start_) {}
  ~Progress() { finish(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// `done` items so far.
  void update(long done) {
    if (!shown_) return;
    const Clock::time_point now = Clock::now();
    if (now - last_ < std::chrono::milliseconds(500) && done != total_) return;
    last_ = now;
    const double s = std::chrono::duration<double>(now - start_).count();
    const double rate = s > 0.0 ? done / s : 0.0;
    std::string line = label_ + ": " + std::to_string(done);
    if (total_ > 0) line += "/" + std::to_string(total_);
    char tail[96];
    if (total_ > 0 && rate > 0.0)
      std::snprintf(tail, sizeof(tail), " %s, %.1f/s, ETA %.0f s", unit_.c_str(), rate,
                    (total_ - done) / rate);
    else
      std::snprintf(tail, sizeof(tail), " %s, %.1f/s", unit_.c_str(), rate);
    std::fprintf(stderr, "\r%s%s\033[K", line.c_str(), tail);
    std::fflush(stderr);
    drawn_ = true;
    if (total_ > 0 && done >= total_) finish();
  }
  void finish() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_, unit_;
  long total_;
  bool shown_, drawn_ = false;
  Clock::time_point start_, last_;
};

}  // namespace adaptive_perception::tools
