#include "sweep/local_runner.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <deque>
#include <vector>

#include "core/errors.hpp"
#include "sweep/job_record.hpp"
#include "sweep/status.hpp"

namespace invasim::sweep {

namespace {

// "abcdef12 (key=value ...)", or "the shared preparation".
std::string point_label(const Workspace& ws, const std::string& id) {
  if (id == kPrepId) return "the shared preparation";
  const Json point = ws.statepoint(id);
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

// Why a point that is not done is not: its status as the documents and locks tell, with its
// log (failed, interrupted) or its holder (running elsewhere).
std::string unfinished_reason(const Workspace& ws, const std::string& id,
                              const std::map<std::string, std::string>& queue) {
  const fs::path dir = ws.job_dir(id);
  const std::string status = effective_status(dir, queue);
  const Json doc = read_document(dir);
  const std::string log = (dir / "run.log").string();
  if (status == "failed")
    return "failed (exit status " + std::to_string(doc.value("exit_code", -1)) + "; log " + log +
           ")";
  if (status == "interrupted") return "interrupted (continue with sweep run; log " + log + ")";
  if (status == "running") {
    const std::string slurm = doc.value("slurm_job_id", "");
    return "running elsewhere (" + (slurm.empty() ? "" : "Slurm job " + slurm + ", ") + "pid " +
           std::to_string(doc.value("pid", -1)) + " on " + doc.value("host", std::string("?")) +
           " since " + doc.value("started_at", std::string("?")) + "; log " + log + ")";
  }
  if (status == "submitted" || status == "queued") return status + " to Slurm";
  return "not started (" + status + ")";
}

// A child running one job (`invasim sweep job`, which holds the job's lock and records it).
struct Child {
  pid_t pid = -1;
  std::string id;
  std::chrono::steady_clock::time_point start;
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
  int done = 0, already_done = 0;

 private:
  void start(const std::string& id, int threads) {
    const fs::path dir = ws_.job_dir(id);
    if (job_status(dir) == "done") {
      ++already_done;
      return;
    }
    if (!JobLock::try_acquire(dir)) {  // held elsewhere: reported at the end
      out_ << "sweep run: " << label(id) << " is being run by another runner: skipped\n";
      return;
    }
    const std::vector<std::string> args = {settings_.executable,   "sweep", "job",
                                           ws_.root().string(),    id,      "--threads",
                                           std::to_string(threads)};
    const fs::path log = dir / "run.log";
    const pid_t pid = ::fork();
    if (pid < 0) fail_input("sweep run: cannot start a process (fork failed)");
    if (pid == 0) exec_child(args, log);
    children_.push_back(Child{pid, id, std::chrono::steady_clock::now()});
    out_ << "sweep run: started " << label(id) << " (pid " << pid << ", log " << log.string()
         << ")\n"
         << std::flush;
  }

  // In the forked child: the parent's signal mask undone, its own process group (a Ctrl-C at
  // the terminal reaches it once, through the runner; a killed runner leaves it running to
  // its end), output to the job's log.
  [[noreturn]] void exec_child(const std::vector<std::string>& args, const fs::path& log) {
    pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
    ::setpgid(0, 0);
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

  std::string label(const std::string& id) const { return point_label(ws_, id); }

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
        const fs::path dir = ws_.job_dir(it->id);
        std::string result;
        if (!signalled && code == kJobBusyExitCode) {
          result = "skipped (another runner took it first)";
        } else {
          result = read_document(dir).value("status", "pending");
          if (result == "running") {  // the child died before it could record its end
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - it->start).count();
            result = record_end(dir, code, stop_signal_ != 0 || signalled, seconds);
          }
          if (result == "done" && it->id != kPrepId) ++done;
        }
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
  const auto unfinished = [&ws] {
    std::vector<std::string> ids;
    for (const auto& id : ws.ids())
      if (job_status(ws.job_dir(id)) != "done") ids.push_back(id);
    return ids;
  };
  if (ws.has_prep() && job_status(ws.job_dir(kPrepId)) != "done" && !unfinished().empty()) {
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
  const std::vector<std::string> left = unfinished();
  out << "sweep run: " << runner.done << " done now, " << runner.already_done << " done before; "
      << ws.ids().size() - left.size() << " of " << ws.ids().size() << " points done";
  if (left.empty()) {
    out << '\n';
    return 0;
  }
  out << "; " << left.size() << " not done:\n";
  const auto queue = slurm_queue();
  for (const auto& id : left)
    out << "  " << point_label(ws, id) << ": " << unfinished_reason(ws, id, queue) << '\n';
  return 1;
}

}  // namespace invasim::sweep
