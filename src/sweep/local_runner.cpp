#include "sweep/local_runner.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <deque>
#include <fstream>
#include <memory>
#include <vector>

#include "core/errors.hpp"
#include "sweep/job_record.hpp"

namespace invasim::sweep {

namespace {

// A child running one job.
struct Child {
  pid_t pid = -1;
  std::string id;
  JobLock lock;
  std::unique_ptr<JobRecord> record;
};

// The runner's state: children, signal mask, tallies.
class Runner {
 public:
  Runner(const Workspace& ws, const LocalRunSettings& settings, std::ostream& out)
      : ws_(ws), settings_(settings), out_(out) {
    sigemptyset(&mask_);
    sigaddset(&mask_, SIGINT);
    sigaddset(&mask_, SIGTERM);
    sigaddset(&mask_, SIGHUP);  // a closed terminal: stopped like SIGTERM
    sigaddset(&mask_, SIGCHLD);
    pthread_sigmask(SIG_BLOCK, &mask_, &old_mask_);
  }
  ~Runner() { pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr); }

  // Runs the jobs in `ids`, `parallel` at a time with `threads` each.
  void run(std::deque<std::string> ids, int parallel, int threads) {
    while (!ids.empty() || !children_.empty()) {
      while (!stop_signal_ && static_cast<int>(children_.size()) < parallel && !ids.empty()) {
        const std::string id = ids.front();
        ids.pop_front();
        start(id, threads);
      }
      if (children_.empty()) break;
      wait_for_event();
    }
  }

  int stop_signal() const { return stop_signal_; }
  int done = 0, already_done = 0, busy = 0;
  std::vector<std::string> failed, interrupted;  // "id (log)"

 private:
  void start(const std::string& id, int threads) {
    const fs::path dir = ws_.job_dir(id);
    if (job_status(dir) == "done") {
      ++already_done;
      return;
    }
    auto lock = JobLock::try_acquire(dir);
    if (!lock) {
      ++busy;
      out_ << "sweep run: " << id << " is being run by another runner: skipped\n";
      return;
    }
    if (read_document(dir).value("status", "") == "done") {  // finished before we locked it
      ++already_done;
      return;
    }
    std::vector<std::string> args = ws_.run_arguments(id);
    args.insert(args.begin(), settings_.executable);
    args.push_back("--threads");
    args.push_back(std::to_string(threads));
    const fs::path log = dir / "run.log";
    {
      std::ofstream header(log, std::ios::app);
      header << "== " << utc_now() << " invasim sweep run:";
      for (const auto& a : args) header << ' ' << a;
      header << '\n';
    }
    std::vector<int> other_locks;
    for (const auto& c : children_) other_locks.push_back(c.lock.fd());
    const pid_t pid = ::fork();
    if (pid < 0) fail_input("sweep run: cannot start a process (fork failed)");
    if (pid == 0) exec_child(args, log, other_locks);
    Child child;
    child.pid = pid;
    child.id = id;
    child.lock = std::move(*lock);
    child.record = std::make_unique<JobRecord>(dir, pid);
    out_ << "sweep run: started " << label(id) << " (pid " << pid << ", log " << log.string()
         << ")\n"
         << std::flush;
    children_.push_back(std::move(child));
  }

  // In the forked child: the parent's signal mask undone, its own process group (a Ctrl-C at
  // the terminal reaches it once, through the runner), output to the job's log.
  [[noreturn]] void exec_child(const std::vector<std::string>& args, const fs::path& log,
                               const std::vector<int>& other_locks) {
    pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
    ::setpgid(0, 0);
    for (int fd : other_locks) ::close(fd);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::close(fd);
    }
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    // The runner's own binary, even if build/invasim was rebuilt (replaced) since the runner
    // started: every point of one `sweep run` runs the same program.
    ::execv("/proc/self/exe", argv.data());
    ::execv(argv[0], argv.data());
    _exit(127);
  }

  std::string label(const std::string& id) const {
    if (id == kPrepId) return "the shared preparation";
    const Json point = ws_.statepoint(id);
    std::string text(id, 0, 8);
    text += " (";
    for (auto it = point.begin(); it != point.end(); ++it) {
      if (it != point.begin()) text += ' ';
      text += it.key();
      text += '=';
      text += set_text(it.value());
    }
    text += ')';
    return text;
  }

  void wait_for_event() {
    siginfo_t info{};
    if (sigwaitinfo(&mask_, &info) < 0) return;  // EINTR: look again
    if (info.si_signo == SIGCHLD) {
      reap();
      return;
    }
    const bool first = !stop_signal_;
    const int signal = info.si_signo == SIGHUP ? SIGTERM : info.si_signo;
    stop_signal_ = signal;
    out_ << "sweep run: "
         << (info.si_signo == SIGINT   ? "SIGINT"
             : info.si_signo == SIGHUP ? "SIGHUP"
                                       : "SIGTERM")
         << (first ? ": stopping the running jobs at their next checkpoint (no new job starts)"
                   : " again: passed on to the jobs, which stop at once")
         << '\n'
         << std::flush;
    for (const auto& c : children_) ::kill(c.pid, signal);
  }

  void reap() {
    for (;;) {
      int status = 0;
      const pid_t pid = ::waitpid(-1, &status, WNOHANG);
      if (pid <= 0) return;
      for (auto it = children_.begin(); it != children_.end(); ++it) {
        if (it->pid != pid) continue;
        const bool signalled = WIFSIGNALED(status);
        const int code = signalled ? 128 + WTERMSIG(status) : WEXITSTATUS(status);
        const std::string result = it->record->finish(code, stop_signal_ != 0 || signalled);
        const std::string entry = label(it->id) + ": " + it->record->log_path().string();
        if (result == "done")
          done += it->id == kPrepId ? 0 : 1;
        else if (result == "interrupted")
          interrupted.push_back(entry);
        else
          failed.push_back(entry + " (exit status " + std::to_string(code) + ")");
        out_ << "sweep run: " << result << ": " << label(it->id) << '\n' << std::flush;
        children_.erase(it);
        break;
      }
    }
  }

  const Workspace& ws_;
  const LocalRunSettings& settings_;
  std::ostream& out_;
  sigset_t mask_{}, old_mask_{};
  std::vector<Child> children_;
  int stop_signal_ = 0;
};

}  // namespace

int run_local(const Workspace& ws, const LocalRunSettings& settings, std::ostream& out) {
  Runner runner(ws, settings, out);
  if (ws.has_prep() && job_status(ws.job_dir(kPrepId)) != "done") {
    runner.run({kPrepId}, 1, settings.threads);
    if (job_status(ws.job_dir(kPrepId)) != "done") {
      out << "sweep run: the shared preparation is not done (" << job_status(ws.job_dir(kPrepId))
          << ", log " << (ws.job_dir(kPrepId) / "run.log").string()
          << "): no point can start from it\n";
      return 1;
    }
  }
  std::deque<std::string> ids(ws.ids().begin(), ws.ids().end());
  if (!runner.stop_signal()) runner.run(ids, settings.jobs, settings.threads);
  int pending = 0;
  for (const auto& id : ws.ids())
    if (job_status(ws.job_dir(id)) != "done") ++pending;
  out << "sweep run: " << runner.done << " done now, " << runner.already_done << " done before, "
      << runner.failed.size() << " failed, " << runner.interrupted.size() << " interrupted, "
      << runner.busy << " running elsewhere; " << ws.ids().size() - pending << " of "
      << ws.ids().size() << " points done\n";
  for (const auto& f : runner.failed) out << "  failed: " << f << '\n';
  for (const auto& i : runner.interrupted)
    out << "  interrupted (continue with sweep run): " << i << '\n';
  return runner.failed.empty() && runner.interrupted.empty() && !runner.stop_signal() ? 0 : 1;
}

}  // namespace invasim::sweep
