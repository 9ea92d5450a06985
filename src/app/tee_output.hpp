#pragma once
// Standard output and error of this process copied to a log file and to where they went
// before: a Slurm task's point writes its run.log (the point's record, appended over its
// attempts) and its slurm-%A_%a.out (where a cluster user looks first) alike. A thread copies
// a pipe to both; the destructor flushes, closes the pipe and restores the old descriptors,
// then waits for the copy of what is in the pipe (not for children that inherited it).
#include <atomic>
#include <string>
#include <thread>

namespace invasim::app {

class TeeOutput {
 public:
  // Appends to `log_path`; throws if it cannot be opened.
  explicit TeeOutput(const std::string& log_path);
  ~TeeOutput();
  TeeOutput(const TeeOutput&) = delete;
  TeeOutput& operator=(const TeeOutput&) = delete;

 private:
  int log_ = -1, saved_out_ = -1, saved_err_ = -1, pipe_read_ = -1;
  std::atomic<bool> restored_{false};  // the destructor has put the old descriptors back
  std::thread copier_;
};

}  // namespace invasim::app
