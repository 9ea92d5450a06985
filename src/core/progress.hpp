#pragma once
// Progress of a long run. On a terminal: one live line rewritten in place with '\r',
//   step 1200/10000 (12.0%)  t = 60  1530 steps/s  ETA 0:05
// elsewhere (CI, Slurm logs): the same text as plain lines, the first update, then at most one
// every `every_seconds`, and a last line from finish() ("done in 0:06" instead of the ETA) or
// stop() ("stopped after 0:06").
// An ETA beyond a year is also said once, on a line of its own, at the first update.
// The clock and the stream are injectable for tests.
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>

namespace invasim {

struct ProgressOptions {
  long long total = 0;          // steps in the run; 0 when unknown (no percentage, no ETA)
  long long start_step = 0;     // step at construction (for steps/s of a continued run)
  double every_seconds = 10.0;  // plain mode: seconds between lines (<= 0: every update)
  double live_interval = 0.2;   // live mode: seconds between redraws
  std::string label;            // optional prefix, "label: step ..."
};

class Progress {
 public:
  using Clock = std::function<double()>;  // monotonic seconds

  // Reports to `out`; `live` selects the '\r' line. The clock defaults to steady_clock.
  Progress(ProgressOptions options, std::ostream& out, bool live, Clock clock = {});
  // Reports to stderr, live when stderr is a terminal.
  explicit Progress(ProgressOptions options);
  // Ends a live line left open (no finish()) so that later output starts on a new line.
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Records that `step` is done (simulated time `time` if given) and prints when due.
  void update(long long step, std::optional<double> time = std::nullopt);
  // Prints the final line (and ends the live line). Later calls do nothing.
  void finish();
  // finish() for a run cut short by a signal: "stopped after 0:06" instead of "done in 0:06".
  void stop();

  // The text of one report at wall-clock `now` (no '\r' or newline).
  std::string line(long long step, std::optional<double> time, double now, bool done) const;

  // "0:05", "12:34", "1:02:03"; beyond 100 days "3.2e+03 years".
  static std::string format_duration(double seconds);

  // The warning printed once, at the first update that gives an ETA beyond a year (
  // e.g. --set steps=9223372036854775807), or "" if there is none at wall-clock `now`.
  std::string eta_warning(long long step, double now) const;

  long long step() const { return step_; }
  long long total() const { return options_.total; }
  bool finished() const { return finished_; }

 private:
  void print(const std::string& text);

  ProgressOptions options_;
  std::ostream& out_;
  bool live_;
  Clock clock_;
  double start_time_;
  std::optional<double> last_print_;
  long long step_;
  std::optional<double> time_;
  std::size_t last_width_ = 0;
  bool finished_ = false;
  bool stopped_ = false;
  bool eta_warned_ = false;
};

}  // namespace invasim
