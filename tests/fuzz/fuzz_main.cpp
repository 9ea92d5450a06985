// invasim_fuzz: a seeded random-mutation fuzzer for the readers of hostile input,
// in-process, with no libFuzzer dependency.
//   invasim_fuzz run TARGET [--seconds S] [--runs N] [--seed N] [--timeout S]
//                           [--findings DIR] [--corpus DIR]
//   invasim_fuzz replay TARGET PATH...   every file (directories: every file inside) must run
//                                        without a finding; the seeds are replayed too
//   invasim_fuzz seeds TARGET DIR        writes the generated seed corpus
// A finding is an exception that is not one of the project's error types, a crash signal
// (SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL), or an input that runs longer than --timeout
// seconds of CPU time (a hang); the input is saved to the findings directory (crash-/timeout-/
// exception-<target>-<hash>) for tests/fuzz/regression/<target>/. The address space is limited
// (INVASIM_FUZZ_MEMORY_MB, default 4096), so an allocation sized by a crafted count throws
// std::bad_alloc: a finding too.
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/fnv1a.hpp"
#include "lua/lua_state.hpp"
#include "mutate.hpp"
#include "targets.hpp"

namespace fs = std::filesystem;
using namespace invasim;
using namespace invasim::fuzz;

namespace {

// The input being run, for the signal handlers (which may only use async-signal-safe calls).
const std::string* g_input = nullptr;
char g_findings[4096] = ".";
char g_target[64] = "target";

void write_str(int fd, const char* s) {
  if (::write(fd, s, std::strlen(s)) < 0) return;
}

// Saves the current input as <findings>/<kind>-<target>-<pid> and exits 1.
[[noreturn]] void die_with_input(const char* kind) {
  char path[4300];
  std::snprintf(path, sizeof path, "%s/%s-%s-%d", g_findings, kind, g_target, int(::getpid()));
  write_str(2, "\ninvasim_fuzz: FINDING: ");
  write_str(2, kind);
  if (g_input) {
    const int fd = ::open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      if (::write(fd, g_input->data(), g_input->size()) < 0) write_str(2, " (not saved)");
      ::close(fd);
      write_str(2, "; input saved as ");
      write_str(2, path);
    }
  }
  write_str(2, "\n");
  ::_exit(1);
}

extern "C" void on_signal(int sig) {
  die_with_input(sig == SIGPROF   ? "timeout"
                 : sig == SIGSEGV ? "crash-SIGSEGV"
                 : sig == SIGABRT ? "crash-SIGABRT"
                 : sig == SIGBUS  ? "crash-SIGBUS"
                 : sig == SIGFPE  ? "crash-SIGFPE"
                                  : "crash-signal");
}

void install_handlers() {
  // The crash handlers run on their own stack: a stack overflow is a SIGSEGV too.
  static std::vector<char> alt(1 << 16);
  stack_t ss{};
  ss.ss_sp = alt.data();
  ss.ss_size = alt.size();
  sigaltstack(&ss, nullptr);
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sa.sa_flags = SA_ONSTACK;
  for (int sig : {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL, SIGPROF}) sigaction(sig, &sa, nullptr);
}

// Caps the address space (default 4096 MB), so that a runaway allocation is a finding, not the
// OOM killer. Not under AddressSanitizer, which reserves terabytes of shadow address space up
// front (a cap makes its mmap fail before main) and bounds allocations itself.
void limit_memory() {
#if defined(__SANITIZE_ADDRESS__)
  return;
#endif
  const char* env = std::getenv("INVASIM_FUZZ_MEMORY_MB");
  const rlim_t mb = env ? rlim_t(std::atol(env)) : 4096;
  if (mb == 0) return;
  rlimit r{mb << 20, mb << 20};
  setrlimit(RLIMIT_AS, &r);
}

void arm(double seconds) {
  itimerval t{};
  t.it_value.tv_sec = long(seconds);
  t.it_value.tv_usec = long((seconds - double(long(seconds))) * 1e6);
  setitimer(ITIMER_PROF, &t, nullptr);  // CPU time: a loaded machine is not a hang
}

// The outcome of one input: "" (accepted or refused with a project error) or a finding.
struct Outcome {
  std::string finding;
  std::string message;  // the project error's message (for the corpus' novelty test)
};

Outcome run_one(const Target& target, const std::string& input, double timeout) {
  Outcome out;
  g_input = &input;
  arm(timeout);
  try {
    target.run(input);
  } catch (const InputError& e) {
    out.message = e.what();
  } catch (const SimulationError& e) {
    out.message = e.what();
  } catch (const lua::ScriptError& e) {
    out.message = e.what();
  } catch (const std::exception& e) {
    out.finding = std::string("exception: ") + e.what();
  } catch (...) {
    out.finding = "exception: unknown";
  }
  arm(0);
  g_input = nullptr;
  return out;
}

// The message with digits and quoted text removed: one "kind" of refusal.
std::string message_kind(const std::string& m) {
  std::string k;
  bool in_quote = false;
  for (char c : m.substr(0, 200)) {
    if (c == '\'') in_quote = !in_quote;
    if (!in_quote && !(c >= '0' && c <= '9')) k += c;
  }
  return k;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string hex(std::uint64_t v) {
  char b[20];
  std::snprintf(b, sizeof b, "%016llx", (unsigned long long)v);
  return b;
}

void save_finding(const std::string& kind, const std::string& input) {
  const fs::path p = fs::path(g_findings) / (kind + "-" + g_target + "-" + hex(fnv1a64(input)));
  std::ofstream(p, std::ios::binary) << input;
  std::cerr << "invasim_fuzz: FINDING: " << kind << "; input saved as " << p.string() << "\n";
}

int usage() {
  std::cerr << "usage: invasim_fuzz run TARGET [--seconds S] [--runs N] [--seed N] [--timeout S]"
               " [--findings DIR] [--corpus DIR]\n"
               "       invasim_fuzz replay TARGET PATH...\n"
               "       invasim_fuzz seeds TARGET DIR\n"
               "targets: checkpoint, vtk, set, keywords\n";
  return 2;
}

// The files named by paths (a directory: the regular files inside, less dotfiles and
// README.md). A path that does not exist is an error, not an empty input: a mistyped corpus
// path must not replay as nothing.
std::vector<fs::path> files_in(const std::vector<std::string>& paths) {
  std::vector<fs::path> out;
  for (const auto& p : paths) {
    if (!fs::exists(p)) throw std::runtime_error("corpus path '" + p + "' does not exist");
    if (fs::is_directory(p)) {
      for (const auto& e : fs::directory_iterator(p))
        if (e.is_regular_file() && e.path().filename().string()[0] != '.' &&
            e.path().filename() != "README.md")
          out.push_back(e.path());
    } else {
      out.push_back(p);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return usage();
  const std::string mode = argv[1];
  Target target;
  try {
    target = make_target(argv[2]);
  } catch (const std::exception& e) {
    std::cerr << "invasim_fuzz: " << e.what() << "\n";
    return 2;
  }
  std::snprintf(g_target, sizeof g_target, "%s", argv[2]);
  double seconds = 10, timeout = 10;
  long long runs = -1;
  std::uint64_t seed = 1;
  std::string corpus_dir;
  std::vector<std::string> rest;
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    try {
      if (a == "--seconds")
        seconds = std::stod(value());
      else if (a == "--runs")
        runs = std::stoll(value());
      else if (a == "--seed")
        seed = std::stoull(value());
      else if (a == "--timeout")
        timeout = std::stod(value());
      else if (a == "--findings")
        std::snprintf(g_findings, sizeof g_findings, "%s", value().c_str());
      else if (a == "--corpus")
        corpus_dir = value();
      else
        rest.push_back(a);
    } catch (const std::exception& e) {
      std::cerr << "invasim_fuzz: bad option " << a << ": " << e.what() << "\n";
      return 2;
    }
  }
  fs::create_directories(g_findings);
  install_handlers();
  limit_memory();

  if (mode == "seeds") {
    if (rest.size() != 1) return usage();
    fs::create_directories(rest[0]);
    for (std::size_t k = 0; k < target.seeds.size(); ++k)
      std::ofstream(fs::path(rest[0]) / ("seed-" + std::to_string(k)), std::ios::binary)
          << target.seeds[k];
    return 0;
  }
  if (mode == "replay") {
    int findings = 0;
    std::size_t n = 0;
    for (const auto& s : target.seeds) findings += !run_one(target, s, timeout).finding.empty();
    std::vector<fs::path> files;
    try {
      files = files_in(rest);
    } catch (const std::exception& e) {
      std::cerr << "invasim_fuzz replay: " << e.what() << "\n";
      return 2;
    }
    for (const fs::path& p : files) {
      const std::string input = read_all(p);
      const Outcome o = run_one(target, input, timeout);
      ++n;
      if (!o.finding.empty()) {
        std::cerr << "invasim_fuzz: " << p.string() << ": " << o.finding << "\n";
        ++findings;
      }
    }
    std::cout << "invasim_fuzz replay " << g_target << ": " << target.seeds.size() << " seeds and "
              << n << " regression inputs, " << findings << " findings\n";
    return findings ? 1 : 0;
  }
  if (mode != "run") return usage();

  std::vector<std::string> corpus = target.seeds;
  if (!corpus_dir.empty()) try {
      for (const fs::path& p : files_in({corpus_dir})) corpus.push_back(read_all(p));
    } catch (const std::exception& e) {
      std::cerr << "invasim_fuzz run: " << e.what() << "\n";
      return 2;
    }
  std::set<std::string> kinds;
  Mutator mutator(seed);
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  long long execs = 0, findings = 0;
  double next_report = 10;
  while ((runs < 0 || execs < runs) && (runs >= 0 || elapsed() < seconds)) {
    const std::string& base = corpus[std::size_t(mutator.rng()() % corpus.size())];
    std::string input = mutator.mutate(base, corpus, target.dictionary);
    if (target.fixup && mutator.rng()() % 10 != 0) target.fixup(input);
    const Outcome o = run_one(target, input, timeout);
    ++execs;
    if (!o.finding.empty()) {
      ++findings;
      save_finding("exception", input);
      std::cerr << "  " << o.finding << "\n";
      continue;
    }
    // Keep inputs that reach a new kind of answer (a cheap stand-in for coverage).
    const std::string kind = message_kind(o.message);
    if (kinds.insert(kind).second && corpus.size() < 5000) corpus.push_back(std::move(input));
    if (elapsed() > next_report) {
      std::cerr << "invasim_fuzz " << g_target << ": " << execs << " execs, " << corpus.size()
                << " corpus, " << kinds.size() << " kinds of answer, " << findings << " findings, "
                << elapsed() << " s\n";
      next_report += 60;
    }
  }
  std::cout << "invasim_fuzz " << g_target << ": " << execs << " execs in " << elapsed()
            << " s (seed " << seed << "), " << corpus.size() << " corpus inputs, " << kinds.size()
            << " kinds of answer, " << findings << " findings\n";
  return findings ? 1 : 0;
}
