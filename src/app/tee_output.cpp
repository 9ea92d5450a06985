#include "app/tee_output.hpp"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace invasim::app {

TeeOutput::TeeOutput(const std::string& log_path) {
  log_ = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (log_ < 0) fail_input("cannot open ", log_path, " for appending");
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    ::close(log_);
    fail_input("cannot make a pipe for ", log_path);
  }
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  saved_out_ = ::fcntl(1, F_DUPFD_CLOEXEC, 3);
  saved_err_ = ::fcntl(2, F_DUPFD_CLOEXEC, 3);
  pipe_read_ = fds[0];
  ::dup2(fds[1], 1);
  ::dup2(fds[1], 2);
  ::close(fds[1]);
  copier_ = std::thread([this] {
    char buffer[8192];
    std::optional<std::chrono::steady_clock::time_point> restored_at;
    for (;;) {
      // Once this process has restored its descriptors, the pipe is read while data comes,
      // and left at the first quiet 100 ms or after 2 s: a background child a protocol
      // started (os.execute("... &")) holds a write end, whose end of file may never come.
      pollfd ready{pipe_read_, POLLIN, 0};
      const int polled = ::poll(&ready, 1, 100);
      if (polled < 0 && errno == EINTR) continue;
      if (restored_.load()) {
        if (!restored_at) restored_at = std::chrono::steady_clock::now();
        if (polled == 0 ||
            std::chrono::steady_clock::now() - *restored_at > std::chrono::seconds(2))
          break;
      }
      if (polled == 0) continue;
      const ssize_t n = ::read(pipe_read_, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      write_all(log_, {buffer, std::size_t(n)});  // a write error loses only the copy
      write_all(saved_out_, {buffer, std::size_t(n)});
    }
  });
}

TeeOutput::~TeeOutput() {
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  // The pipe's last write ends go with the old descriptors back in place: the copier reads
  // what is left, then end of file.
  ::dup2(saved_out_, 1);
  ::dup2(saved_err_, 2);
  restored_.store(true);
  copier_.join();
  ::close(pipe_read_);
  ::close(saved_out_);
  ::close(saved_err_);
  ::close(log_);
}

}  // namespace invasim::app
