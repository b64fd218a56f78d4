// A live progress line on stderr for long runs (issue 22): the stages running and the fraction of
// each done, e.g. "  skeleton 70% · basis 42%  (6.1 s)", rewritten in place ("\r", erase to the
// end of the line). Shown only when stderr is a terminal, and only once the run has lasted
// `delay_seconds`: short runs, pipes and log files see nothing of it. It is the CLI's own: the
// library reports (stage, fraction) through OptimizeOptions::on_stage_progress and prints nothing.
// Safe to call from two threads (the basis reports from its own).
#pragma once
#include <chrono>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace offsetopt::cli {

class ProgressLine {
 public:
  // enabled: false turns every call into a plain pass-through (print_line still prints). Seconds
  // count from `start` (the command's start, as the other progress lines do).
  ProgressLine(bool enabled, std::chrono::steady_clock::time_point start, double delay_seconds = 2.0);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // fraction in [0, 1): running (shown as a percentage); < 0: running, fraction unknown;
  // >= 1: finished (removed from the line).
  void update(const std::string& stage, double fraction);
  // A normal line on stderr (newline added): the live line is cleared first and drawn again at
  // the next update.
  void print_line(const std::string& line);
  // Erases the live line (before the final messages).
  void clear();

  // Whether stderr is a terminal (the condition for enabling it).
  static bool stderr_is_terminal();

 private:
  void draw_locked(bool force);
  void clear_locked();

  bool enabled_;
  double delay_seconds_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  std::vector<std::pair<std::string, double>> stages_;  // in the order they started
  bool shown_ = false;
  std::mutex mutex_;
};

}  // namespace offsetopt::cli
