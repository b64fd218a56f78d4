#include "cli/progress_line.h"

#include <unistd.h>

#include <cstdio>

namespace offsetopt::cli {

namespace {

double seconds_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

ProgressLine::ProgressLine(bool enabled, std::chrono::steady_clock::time_point start, double delay_seconds)
    : enabled_(enabled), delay_seconds_(delay_seconds), start_(start), last_draw_(start) {}

ProgressLine::~ProgressLine() { clear(); }

bool ProgressLine::stderr_is_terminal() { return isatty(fileno(stderr)) == 1; }

void ProgressLine::update(const std::string& stage, double fraction) {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  bool found = false;
  for (auto it = stages_.begin(); it != stages_.end(); ++it)
    if (it->first == stage) {
      found = true;
      if (fraction >= 1.0) stages_.erase(it);
      else it->second = fraction;
      break;
    }
  if (!found && fraction < 1.0) stages_.emplace_back(stage, fraction);
  draw_locked(false);
}

void ProgressLine::print_line(const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  clear_locked();
  std::fprintf(stderr, "%s\n", line.c_str());
}

void ProgressLine::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  clear_locked();
}

void ProgressLine::clear_locked() {
  if (!shown_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  shown_ = false;
}

// At most five draws a second; nothing before delay_seconds.
void ProgressLine::draw_locked(bool force) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = seconds_between(start_, now);
  if (elapsed < delay_seconds_ || stages_.empty()) return;
  if (!force && shown_ && seconds_between(last_draw_, now) < 0.2) return;
  std::string text = " ";
  for (const auto& [stage, fraction] : stages_) {
    text += text.size() > 1 ? " · " : " ";
    text += stage;
    if (fraction >= 0.0) text += " " + std::to_string(static_cast<int>(100.0 * fraction)) + "%";
  }
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "  (%.1f s)", elapsed);
  text += seconds;
  std::fprintf(stderr, "\r\033[K%s", text.c_str());
  std::fflush(stderr);
  last_draw_ = now;
  shown_ = true;
}

}  // namespace offsetopt::cli
