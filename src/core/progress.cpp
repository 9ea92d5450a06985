#include "core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace invasim {

namespace {

double steady_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

std::string printf_string(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

}  // namespace

Progress::Progress(ProgressOptions options, std::ostream& out, bool live, Clock clock)
    : options_(std::move(options)),
      out_(out),
      live_(live),
      clock_(clock ? std::move(clock) : Clock(&steady_seconds)),
      start_time_(clock_()),
      step_(options_.start_step) {}

Progress::Progress(ProgressOptions options)
    : Progress(std::move(options), std::cerr, isatty(STDERR_FILENO) != 0) {}

Progress::~Progress() {
  if (live_ && last_width_ > 0 && !finished_) {
    out_ << '\n';
    out_.flush();
  }
}

std::string Progress::format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  if (seconds > 100 * 86400.0) return printf_string("%.3g years", seconds / (365.25 * 86400.0));
  const long long s = std::llround(seconds);
  char buffer[48];
  if (s >= 3600)
    std::snprintf(buffer, sizeof buffer, "%lld:%02lld:%02lld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buffer, sizeof buffer, "%lld:%02lld", s / 60, s % 60);
  return buffer;
}

std::string Progress::line(long long step, std::optional<double> time, double now,
                           bool done) const {
  std::string text = options_.label.empty() ? "" : options_.label + ": ";
  text += "step " + std::to_string(step);
  const long long total = options_.total;
  if (total > 0) {
    text += '/';
    text += std::to_string(total);
    const double percent = 100.0 * std::clamp(double(step) / double(total), 0.0, 1.0);
    text += " (" + printf_string("%.1f", percent) + "%)";
  }
  if (time) text += "  t = " + printf_string("%.6g", *time);
  const double elapsed = now - start_time_;
  const long long steps_done = step - options_.start_step;
  const char* const ended = stopped_ ? "  stopped after " : "  done in ";
  if (elapsed > 0 && steps_done > 0) {
    const double rate = double(steps_done) / elapsed;
    text += "  " + printf_string(rate >= 100 ? "%.0f" : "%.3g", rate) + " steps/s";
    if (done)
      text += ended + format_duration(elapsed);
    else if (total > 0)
      text += "  ETA " + format_duration(double(std::max(total - step, 0LL)) / rate);
  } else if (done) {
    text += ended + format_duration(std::max(elapsed, 0.0));
  }
  return text;
}

void Progress::print(const std::string& text) {
  if (live_) {
    // Pad with spaces to wipe the tail of a longer previous line.
    const std::size_t pad = last_width_ > text.size() ? last_width_ - text.size() : 0;
    out_ << '\r' << text << std::string(pad, ' ');
    last_width_ = text.size();
  } else {
    out_ << text << '\n';
  }
  out_.flush();
}

std::string Progress::eta_warning(long long step, double now) const {
  constexpr double kYear = 365.25 * 86400.0;
  const double elapsed = now - start_time_;
  const long long steps_done = step - options_.start_step;
  if (options_.total <= 0 || elapsed <= 0 || steps_done <= 0) return "";
  const double rate = double(steps_done) / elapsed;
  const double remaining = double(std::max(options_.total - step, 0LL));
  if (!(remaining / rate > kYear)) return "";
  return (options_.label.empty() ? "" : options_.label + ": ") + "warning: at " +
         printf_string(rate >= 100 ? "%.0f" : "%.3g", rate) + " steps/s the remaining " +
         printf_string("%.6g", remaining) + " steps take " + format_duration(remaining / rate) +
         ", more than a year; check the number of steps";
}

void Progress::update(long long step, std::optional<double> time) {
  if (finished_) return;
  step_ = step;
  if (time) time_ = time;
  const double now = clock_();
  if (!eta_warned_) {
    if (std::string warning = eta_warning(step, now); !warning.empty()) {
      eta_warned_ = true;
      if (live_ && last_width_ > 0) out_ << '\n';
      out_ << warning << '\n';
      last_width_ = 0;
      out_.flush();
    }
  }
  const double period = live_ ? options_.live_interval : options_.every_seconds;
  if (last_print_ && now - *last_print_ < period) return;
  last_print_ = now;
  print(line(step_, time_, now, false));
}

void Progress::stop() {
  if (finished_) return;
  stopped_ = true;
  finish();
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  print(line(step_, time_, clock_(), true));
  if (live_) {
    out_ << '\n';
    out_.flush();
  }
}

}  // namespace invasim
