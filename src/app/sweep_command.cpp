#include "app/sweep_command.hpp"

#include <fcntl.h>
#include <omp.h>
#include <sched.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "app/cli.hpp"
#include "app/error_report.hpp"
#include "app/options.hpp"
#include "app/sweep_analyze.hpp"
#include "app/tee_output.hpp"
#include "core/errors.hpp"
#include "core/stop_request.hpp"
#include "io/atomic_file.hpp"
#include "lua/lua_state.hpp"
#include "sweep/collect.hpp"
#include "sweep/init_workspace.hpp"
#include "sweep/job_record.hpp"
#include "sweep/local_runner.hpp"
#include "sweep/overrides.hpp"
#include "sweep/slurm.hpp"
#include "sweep/status.hpp"

namespace invasim::app {

namespace fs = std::filesystem;

namespace {

std::string sweep_help_text() {
  return R"(invasim sweep: parameter sweeps of a protocol (docs/sweeps.md)

Usage:
  invasim sweep init SPEC.lua [--workspace DIR] [--tiny] [--set KEY=VALUE]... [--take N]
                      [--max-points N]
        check the sweep spec and create (or grow) its signac-compatible workspace
        (default DIR: out/<spec name>, with --tiny out/tiny/<spec name>); --tiny uses the
        spec's CI size (its tiny = {...}), --set replaces a fixed parameter, --take N keeps
        the first N values of every axis and one seed; a spec of more than 10000 points is
        refused unless --max-points N allows N; DIR must be new, empty or a workspace of
        the same sweep (a grown spec adds its new points)
  invasim sweep run WS [--jobs N] [--threads T]
        run the points that are not done, N at a time with T threads each (default: fill
        the cores, N x T <= cores); interrupted points continue from their checkpoints;
        Ctrl-C / SIGTERM stop every run at its next checkpoint
  invasim sweep status WS
        pending / queued / running / done / failed / interrupted counts
  invasim sweep collect WS [-o FILE.csv]
        one row per point: state point, summary means and errors, tau_d, tau_r
        (default: standard output)
  invasim sweep submit WS --slurm [--partition P] [--time T] [--cpus-per-task C]
                        [--mem M] [--account A] [--qos Q] [--array-limit L]
                        [--max-array-size M] [--prep-time T] [--prep-mem M]
                        [--prep-cpus-per-task C] [--signal-before S] [--max-requeues N]
                        [--sbatch-arg ARG]... [--dry-run]
        run the points that are not done as Slurm job arrays of at most M tasks (default:
        the cluster's MaxArraySize), after the shared preparation, if any (--prep-*: its
        resources, default the points'); a point gets SIGTERM S seconds before its time
        limit (default 300), checkpoints and requeues itself up to N times (default 3)
  invasim sweep analyze WS [-o DIR] [--group K1,K2] [--temperature kT|T_c|kT_c_paper] ...
        collect into WS/results.csv and fit the master curve (scripts/master_curve.py;
        its options pass through, see --help there): fit tables and figures in DIR
        (default WS/analysis); P, beta, gamma default to the protocol's values
  invasim sweep job WS ID [--threads T] [--max-requeues N]
        run one point (ID: a job id, or prep) in this process, as the Slurm tasks do
)";
}

// The options of sweep subcommand `verb` (app/options.hpp).
ParsedOptions parse(const std::string& verb, const std::vector<std::string>& args,
                    const std::vector<std::string>& with_value,
                    const std::vector<std::string>& flags) {
  const std::string prefix = "invasim sweep " + verb + ": ";
  ParsedOptions p = parse_options(args, {with_value, flags, {"--sbatch-arg", "--set"}, prefix});
  if (p.version) throw UsageError(prefix + "--version goes alone: invasim --version");
  return p;
}

// --max-requeues N: an integer in [0, 1000] (0: a stopped point waits for sweep submit).
int requeue_count(const std::string& text) {
  return text == "0" ? 0 : positive_option("--max-requeues", text, 1000);
}

// The workspace argument: exactly one positional word after the verb (plus `extra` more).
std::vector<std::string> words(const std::string& verb, const ParsedOptions& p, std::size_t count,
                               const std::string& usage) {
  if (p.positional.size() != count)
    throw UsageError(
        "invasim sweep " + verb + ": expected " + usage +
        (p.positional.size() > count ? ", got also '" + p.positional[count] + "'" : ""));
  return p.positional;
}

int cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
}

std::string executable() {
  // After a rebuild replaced the binary, the link reads "PATH (deleted)": PATH is the new one.
  std::string path = fs::read_symlink("/proc/self/exe").string();
  const std::string deleted = " (deleted)";
  if (path.size() > deleted.size() && path.ends_with(deleted))
    path.resize(path.size() - deleted.size());
  return path;
}

int init(const std::vector<std::string>& args) {
  const ParsedOptions p =
      parse("init", args, {"--workspace", "--set", "--take", "--max-points"}, {"--tiny"});
  const auto spec_path = words("init", p, 1, "SPEC.lua")[0];
  sweep::SpecOverrides overrides;
  overrides.tiny = p.flag("--tiny");
  if (p.values.count("--set"))
    for (const auto& s : p.values.at("--set")) overrides.set.push_back(parse_override(s));
  if (auto take = p.value("--take")) overrides.take = positive_option("--take", *take, 1000000);
  sweep::SweepSpec spec = sweep::load_spec(spec_path);
  sweep::apply_spec_overrides(spec, overrides);
  const fs::path default_ws = overrides.tiny ? fs::path("out") / "tiny" : fs::path("out");
  const std::string ws =
      p.value("--workspace").value_or((default_ws / fs::path(spec_path).stem()).string());
  std::size_t max_points = sweep::kDefaultMaxPoints;
  if (auto m = p.value("--max-points")) max_points = positive_option("--max-points", *m, 100000000);
  const auto report = sweep::init_workspace(spec, ws, max_points);
  std::cout << "sweep init: " << ws << ": " << report.added << " new points, " << report.kept
            << " kept (" << report.added + report.kept << " in " << spec_path << ")"
            << (spec.has_prep ? ", with a shared preparation" : "") << "\nnext: invasim sweep run "
            << ws << "   or   invasim sweep submit " << ws << " --slurm\n";
  return 0;
}

int run(const std::vector<std::string>& args) {
  const ParsedOptions p = parse("run", args, {"--jobs", "--threads"}, {});
  const auto ws = sweep::Workspace::open(words("run", p, 1, "a workspace directory")[0]);
  const int n = cores();
  const auto jobs = p.value("--jobs"), threads = p.value("--threads");
  sweep::LocalRunSettings settings;
  settings.threads = threads ? positive_option("--threads", *threads) : 1;
  settings.jobs = jobs ? positive_option("--jobs", *jobs) : std::max(1, n / settings.threads);
  if (jobs && !threads) settings.threads = std::max(1, n / settings.jobs);
  if (settings.jobs * settings.threads > n)
    std::cout << "sweep run: note: " << settings.jobs << " jobs x " << settings.threads
              << " threads exceed the " << n << " cores\n";
  settings.executable = executable();
  std::cout << "sweep run: " << ws.root().string() << ": " << settings.jobs << " at a time, "
            << settings.threads << (settings.threads == 1 ? " thread" : " threads") << " each\n"
            << std::flush;
  return sweep::run_local(ws, settings, std::cout);
}

int collect(const std::vector<std::string>& args) {
  const ParsedOptions p = parse("collect", args, {"--output"}, {});
  const auto ws = sweep::Workspace::open(words("collect", p, 1, "a workspace directory")[0]);
  const auto output = p.value("--output");
  if (!output) {
    sweep::collect(ws, std::cout);
    return 0;
  }
  // The whole table first, then one atomic write: an error while collecting (a broken
  // point) or writing (a full disk) leaves the previous table as it was.
  std::ostringstream table;
  const int rows = sweep::collect(ws, table);
  write_file_atomically(*output, table.str());
  std::cerr << "sweep collect: " << rows << " rows in " << *output << '\n';
  return 0;
}

int submit(const std::vector<std::string>& args) {
  const ParsedOptions p =
      parse("submit", args,
            {"--partition", "--time", "--cpus-per-task", "--array-limit", "--max-array-size",
             "--sbatch-arg", "--mem", "--account", "--qos", "--prep-time", "--prep-mem",
             "--prep-cpus-per-task", "--signal-before", "--max-requeues"},
            {"--slurm", "--dry-run"});
  const auto ws = sweep::Workspace::open(words("submit", p, 1, "a workspace directory")[0]);
  if (!p.flag("--slurm"))
    throw UsageError("invasim sweep submit: say which batch system: --slurm (the only one so far)");
  sweep::SlurmOptions o;
  o.partition = p.value("--partition").value_or("");
  o.time = p.value("--time").value_or("");
  if (auto c = p.value("--cpus-per-task")) o.cpus_per_task = positive_option("--cpus-per-task", *c);
  if (auto l = p.value("--array-limit"))
    o.array_limit = positive_option("--array-limit", *l, 1000000);
  if (auto m = p.value("--max-array-size"))
    o.max_array_size = positive_option("--max-array-size", *m, 4000001);
  if (p.values.count("--sbatch-arg")) o.extra = p.values.at("--sbatch-arg");
  o.mem = p.value("--mem").value_or("");
  o.account = p.value("--account").value_or("");
  o.qos = p.value("--qos").value_or("");
  o.prep_time = p.value("--prep-time").value_or("");
  o.prep_mem = p.value("--prep-mem").value_or("");
  if (auto c = p.value("--prep-cpus-per-task"))
    o.prep_cpus_per_task = positive_option("--prep-cpus-per-task", *c);
  if (auto s = p.value("--signal-before"))
    o.signal_before = positive_option("--signal-before", *s, 65535);
  if (auto r = p.value("--max-requeues")) o.max_requeues = requeue_count(*r);
  sweep::check_slurm_options(o);
  o.dry_run = p.flag("--dry-run");
  o.executable = executable();
  return sweep::submit_slurm(ws, o, std::cout);
}

// One point in this process, output appended to its run.log.
int job(const std::vector<std::string>& args) {
  const ParsedOptions p = parse("job", args, {"--threads", "--max-requeues"}, {});
  const auto w = words("job", p, 2, "a workspace directory and a job id");
  const auto ws = sweep::Workspace::open(w[0]);
  const std::string& id = w[1];
  if (id != sweep::kPrepId && std::find(ws.ids().begin(), ws.ids().end(), id) == ws.ids().end())
    fail_input("sweep job: ", id, " is not a point of ", ws.root().string());
  if (id == sweep::kPrepId && !ws.has_prep())
    fail_input("sweep job: ", ws.root().string(), " has no shared preparation");
  const fs::path dir = ws.job_dir(id);
  const auto lock = sweep::JobLock::try_acquire(dir);
  if (!lock) {
    std::cerr << "sweep job: " << id << " is being run by another runner: skipped\n";
    return sweep::kJobBusyExitCode;
  }
  if (sweep::read_document(dir).value("status", "") == "done") {
    std::cout << "sweep job: " << id << " is done already\n";
    return 0;
  }
  const std::string own = sweep::current_slurm_job_id();
  if (const std::string other = sweep::running_slurm_job(dir, own); !other.empty()) {
    std::cerr << "sweep job: " << id << " is running as Slurm job " << other << " on "
              << sweep::read_document(dir).value("host", std::string("?"))
              << " (its lock did not reach here: a file system whose flock is not shared "
                 "across nodes): skipped\n";
    return sweep::kJobBusyExitCode;
  }
  std::vector<std::string> run_args = ws.run_arguments(id);
  if (auto threads = p.value("--threads")) {
    run_args.push_back("--threads");
    run_args.push_back(std::to_string(positive_option("--threads", *threads)));
  }
  // Under Slurm the output goes to the task's slurm-%A_%a.out as well as to run.log.
  const char* const slurm_job = std::getenv("SLURM_JOB_ID");
  std::optional<TeeOutput> tee;
  if (slurm_job) {
    std::cout << "sweep job: " << id << ": output also in " << (dir / "run.log").string() << '\n'
              << std::flush;
    tee.emplace((dir / "run.log").string());
  } else {
    std::cout << "sweep job: " << id << ": output in " << (dir / "run.log").string() << '\n'
              << std::flush;
    const int log = ::open((dir / "run.log").c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (log >= 0) {
      ::dup2(log, 1);
      ::dup2(log, 2);
      ::close(log);
    }
  }
  std::cout << "== " << utc_now() << " invasim sweep job:";
  for (const auto& a : run_args) std::cout << ' ' << a;
  std::cout << std::endl;
  sweep::JobRecord record(dir, ::getpid());
  int code = 0;
  try {
    Command command = parse_command_line(run_args);
    if (command.threads) omp_set_num_threads(*command.threads);
    // A stopped point continues with the sweep's command, not with `invasim run --resume`.
    command.options.continue_command =
        std::string(slurm_job ? "invasim sweep submit " : "invasim sweep run ") +
        ws.root().string() + (slurm_job ? " --slurm" : "");
    lua::LuaState state(command.options);
    state.run_file(command.options.script_path);
  } catch (const std::exception& e) {
    report_run_end(e, std::cerr);
    code = 1;
  }
  std::cout << std::flush;
  const std::string result = record.finish(code, stop_requested() != 0);
  if (id == sweep::kPrepId && result == "failed" && slurm_job)
    sweep::cancel_after_failed_prep(ws, slurm_job, std::cout);
  if (result == "interrupted" && p.value("--max-requeues"))
    sweep::requeue_stopped_point(ws, id, requeue_count(*p.value("--max-requeues")), std::cout);
  return result == "done" ? 0 : 1;
}

}  // namespace

int run_sweep_command(const std::vector<std::string>& args) {
  if (args.empty())
    throw UsageError(
        "invasim sweep: missing command (init, run, status, collect, submit, analyze or job)");
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::cout << sweep_help_text();
    return 0;
  }
  const std::string& verb = args[0];
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (std::find(rest.begin(), rest.end(), "--help") != rest.end() ||
      std::find(rest.begin(), rest.end(), "-h") != rest.end()) {
    std::cout << sweep_help_text();
    return 0;
  }
  if (verb == "init") return init(rest);
  if (verb == "run") return run(rest);
  if (verb == "status") {
    const ParsedOptions p = parse("status", rest, {}, {});
    return sweep::print_status(
        sweep::Workspace::open(words("status", p, 1, "a workspace directory")[0]), std::cout);
  }
  if (verb == "collect") return collect(rest);
  if (verb == "submit") return submit(rest);
  if (verb == "job") return job(rest);
  if (verb == "analyze") return sweep_analyze(rest);
  throw UsageError("unknown sweep command '" + verb +
                   "' (expected init, run, status, collect, submit, analyze or job)");
}

}  // namespace invasim::app
