#include "sweep/slurm.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <regex>
#include <sstream>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "sweep/job_record.hpp"
#include "sweep/status.hpp"

namespace invasim::sweep {

namespace {

// A path inside single quotes for the shell; paths holding a quote are refused.
std::string quoted(const std::string& text) {
  if (text.find('\'') != std::string::npos)
    fail_input("sweep submit: the path ", text,
               " holds a single quote, which the sbatch script cannot quote");
  return "'" + text + "'";
}

// The #SBATCH lines of a script: the points' (prep = false) or the preparation's resources.
std::string header(const SlurmOptions& o, const std::string& name, const std::string& output,
                   bool prep) {
  const int cpus = prep && o.prep_cpus_per_task > 0 ? o.prep_cpus_per_task : o.cpus_per_task;
  const std::string& time = prep && !o.prep_time.empty() ? o.prep_time : o.time;
  const std::string& mem = prep && !o.prep_mem.empty() ? o.prep_mem : o.mem;
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "#SBATCH --job-name=" << name << '\n'
    << "#SBATCH --cpus-per-task=" << cpus << '\n'
    << "#SBATCH --output=" << output << '\n';
  if (!o.partition.empty()) s << "#SBATCH --partition=" << o.partition << '\n';
  if (!time.empty()) s << "#SBATCH --time=" << time << '\n';
  if (!mem.empty()) s << "#SBATCH --mem=" << mem << '\n';
  if (!o.account.empty()) s << "#SBATCH --account=" << o.account << '\n';
  if (!o.qos.empty()) s << "#SBATCH --qos=" << o.qos << '\n';
  // The time limit's warning: SIGTERM to the batch shell (exec'd into invasim) S seconds
  // before the limit, so the run checkpoints; the point then requeues itself.
  s << "#SBATCH --signal=B:TERM@" << o.signal_before << '\n' << "#SBATCH --requeue\n";
  for (const auto& e : o.extra) s << "#SBATCH " << e << '\n';
  return s.str();
}

bool matches(const std::string& text, const char* pattern) {
  return std::regex_match(text, std::regex(pattern));
}

// Runs `sbatch --parsable [dependency] SCRIPT`; returns the job id.
std::string sbatch(const fs::path& script, const std::string& dependency) {
  std::ostringstream text_of_command;
  text_of_command << "sbatch --parsable";
  if (!dependency.empty())
    text_of_command << " --dependency=afterok:" << dependency << " --kill-on-invalid-dep=yes";
  text_of_command << ' ' << quoted(script.string()) << " 2>&1";
  const std::string command = text_of_command.str();
  auto [status, text] = run_command(command);
  if (status == -1) fail_input("sweep submit: cannot run sbatch");
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  if (status != 0) fail_input("sweep submit: ", command, " failed: ", text);
  const std::string id = text.substr(0, text.find(';'));  // "123" or "123;cluster"
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    fail_input("sweep submit: sbatch --parsable printed '", text, "', not a job id");
  return id;
}

// The cluster's MaxArraySize (`scontrol show config`): array indices run 0..MaxArraySize-1,
// so an array holds at most that many tasks; 1001, Slurm's default, when it cannot be read.
int cluster_max_array_size() {
  std::istringstream lines(run_command("scontrol show config 2>/dev/null").text);
  int size = 0;
  for (std::string line; std::getline(lines, line);)
    if (std::sscanf(line.c_str(), " MaxArraySize = %d", &size) == 1) break;
  return size > 0 ? size : 1001;
}

void mark_submitted(const fs::path& dir, const std::string& slurm_id) {
  Json doc = read_document(dir);
  doc["status"] = "submitted";
  doc.erase("cancelled");  // an earlier array's cancellation no longer applies
  doc["slurm_job_id"] = slurm_id;
  doc["submitted_at"] = utc_now();
  write_document(dir, doc);
}

}  // namespace

int submit_slurm(const Workspace& ws, const SlurmOptions& o, std::ostream& out) {
  const auto queue = slurm_queue();
  std::vector<std::string> ids;
  for (const auto& id : ws.ids()) {
    const std::string status = effective_status(ws.job_dir(id), queue);
    if (status != "done" && status != "queued" && status != "running") ids.push_back(id);
  }
  const std::string prep_status =
      ws.has_prep() ? effective_status(ws.job_dir(kPrepId), queue) : "done";
  if (ids.empty()) {
    out << "sweep submit: nothing to submit (every point is done, queued or running)\n";
    return 0;
  }
  const fs::path slurm_dir = ws.root() / "slurm";
  fs::create_directories(slurm_dir);
  int k = 1;
  while (fs::exists(slurm_dir / ("submit-" + std::to_string(k)))) ++k;
  const fs::path dir = slurm_dir / ("submit-" + std::to_string(k));
  fs::create_directories(dir);
  const std::string exe = quoted(o.executable), root = quoted(ws.root().string());
  const std::string threads = "--threads \"${SLURM_CPUS_PER_TASK:-1}\"";
  const bool need_prep =
      prep_status != "done" && prep_status != "queued" && prep_status != "running";
  if (need_prep) {
    std::ostringstream script;
    script << header(o, "invasim-prep", (dir / "slurm-%j.out").string(), true)
           << "# the shared preparation every point starts from (--from "
           << ws.job_dir(kPrepId).string() << ")\nexec " << exe << " sweep job " << root << ' '
           << kPrepId << ' ' << threads << " --max-requeues " << o.max_requeues << '\n';
    write_file_atomically(dir / "prep.sbatch", script.str());
  }
  const std::size_t chunk =
      static_cast<std::size_t>(o.max_array_size > 0 ? o.max_array_size : cluster_max_array_size());
  std::vector<std::vector<std::string>> arrays;
  for (std::size_t first = 0; first < ids.size(); first += chunk)
    arrays.emplace_back(ids.begin() + first, ids.begin() + std::min(ids.size(), first + chunk));
  std::vector<fs::path> scripts;
  for (std::size_t j = 0; j < arrays.size(); ++j) {
    std::string suffix;  // "" for a single array, else "-<j+1>"
    if (arrays.size() > 1) suffix.append("-").append(std::to_string(j + 1));
    const fs::path points = dir / ("points" + suffix + ".txt");
    std::string list;  // atomic and checked like the scripts: a cut list would drop points
    for (const auto& id : arrays[j]) list.append(id).append("\n");
    write_file_atomically(points, list);
    std::ostringstream script;
    script << header(o, "invasim-sweep", (dir / "slurm-%A_%a.out").string(), false)
           << "#SBATCH --array=0-" << arrays[j].size() - 1;
    if (o.array_limit > 0) script << '%' << o.array_limit;
    script << "\n# array task i runs the state point on line i + 1 of "
           << points.filename().string() << "\nid=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" "
           << quoted(points.string()) << ")\nexec " << exe << " sweep job " << root << " \"$id\" "
           << threads << " --max-requeues " << o.max_requeues << '\n';
    scripts.push_back(dir / ("array" + suffix + ".sbatch"));
    write_file_atomically(scripts.back(), script.str());
  }
  if (o.dry_run) {
    out << "sweep submit: wrote " << (need_prep ? (dir / "prep.sbatch").string() + " and " : "")
        << scripts.size() << " array script(s) in " << dir.string() << " (" << ids.size()
        << " points, at most " << chunk << " per array); --dry-run: nothing submitted\n";
    return 0;
  }
  std::string prep_job;
  if (need_prep) {
    prep_job = sbatch(dir / "prep.sbatch", "");
    mark_submitted(ws.job_dir(kPrepId), prep_job);
    out << "sweep submit: shared preparation: Slurm job " << prep_job << '\n';
  } else if (prep_status == "queued" || prep_status == "running") {
    prep_job = read_document(ws.job_dir(kPrepId)).value("slurm_job_id", "");
  }
  Json log = fs::exists(slurm_dir / "submissions.json") ? read_json(slurm_dir / "submissions.json")
                                                        : Json::array();
  for (std::size_t j = 0; j < arrays.size(); ++j) {
    const std::string array_job = sbatch(scripts[j], prep_job);
    for (std::size_t i = 0; i < arrays[j].size(); ++i)
      mark_submitted(ws.job_dir(arrays[j][i]), array_job + "_" + std::to_string(i));
    log.push_back({{"submitted_at", utc_now()},
                   {"directory", dir.string()},
                   {"array_job", array_job},
                   {"prep_job", prep_job.empty() ? Json(nullptr) : Json(prep_job)},
                   {"points", arrays[j]}});
    write_file_atomically(slurm_dir / "submissions.json", log.dump(2) + "\n");
    out << "sweep submit: " << arrays[j].size() << " points as Slurm job array " << array_job
        << (prep_job.empty() ? "" : " (after job " + prep_job + ")") << "; script "
        << scripts[j].string() << '\n';
  }
  return 0;
}

int cancel_after_failed_prep(const Workspace& ws, const std::string& prep_job, std::ostream& out) {
  const fs::path log_path = ws.root() / "slurm" / "submissions.json";
  if (prep_job.empty() || !fs::exists(log_path)) return 0;
  const Json log = read_json(log_path);
  const std::string note = "the shared preparation failed (Slurm job " + prep_job + ", log " +
                           (ws.job_dir(kPrepId) / "run.log").string() + ")";
  int returned = 0;
  for (const auto& submission : log) {
    if (submission.value("prep_job", Json()) != Json(prep_job)) continue;
    const std::string array = submission.value("array_job", "");
    if (!array.empty()) {
      const std::string command = "scancel " + array + " > /dev/null 2>&1";
      if (std::system(command.c_str()) != 0)
        out << "sweep job: scancel " << array << " failed (the array may have ended already)\n";
    }
    for (const auto& id : submission.value("points", std::vector<std::string>{})) {
      Json doc = read_document(ws.job_dir(id));
      if (doc.value("status", "") != "submitted" ||
          doc.value("slurm_job_id", "").rfind(array + "_", 0) != 0)
        continue;
      doc["status"] = "pending";
      doc["cancelled"] = note;
      write_document(ws.job_dir(id), doc);
      ++returned;
    }
    out << "sweep job: " << note << ": cancelled job array " << array << "; " << returned
        << " points pending again (fix the cause, then sweep submit)\n";
  }
  return returned;
}

void check_slurm_options(const SlurmOptions& o) {
  const char* time = R"((\d+)|(\d+:\d+)|(\d+:\d+:\d+)|(\d+-\d+)|(\d+-\d+:\d+)|(\d+-\d+:\d+:\d+))";
  const char* mem = R"(\d+[KMGT]?)";
  const char* name = R"([A-Za-z0-9_.-]+)";
  const auto check = [](const std::string& value, const char* pattern, const char* option,
                        const char* form) {
    if (!value.empty() && !matches(value, pattern))
      fail_input("sweep submit: ", option, " '", value, "' is not ", form);
  };
  const char* time_form = "a Slurm time (M, M:S, H:M:S, D-H, D-H:M or D-H:M:S)";
  const char* mem_form = "a memory size (digits with an optional K, M, G or T)";
  check(o.time, time, "--time", time_form);
  check(o.prep_time, time, "--prep-time", time_form);
  check(o.mem, mem, "--mem", mem_form);
  check(o.prep_mem, mem, "--prep-mem", mem_form);
  check(o.account, name, "--account", "an account name (letters, digits, _ - .)");
  check(o.qos, name, "--qos", "a QOS name (letters, digits, _ - .)");
  check(o.partition, name, "--partition", "a partition name (letters, digits, _ - .)");
}

bool requeue_stopped_point(const Workspace& ws, const std::string& id, int max_requeues,
                           std::ostream& out) {
  const std::string slurm_id = current_slurm_job_id();
  if (slurm_id.empty()) return false;
  const fs::path dir = ws.job_dir(id);
  Json doc = read_document(dir);
  const int used = doc.value("requeues", 0);
  if (used >= max_requeues) {
    out << "sweep job: " << id << " was stopped and has used its " << max_requeues
        << " requeues: it stays interrupted (sweep submit continues it)\n";
    return false;
  }
  // The document first: Slurm ends this process as soon as the requeue is taken.
  doc["status"] = "submitted";
  doc["requeues"] = used + 1;
  doc["slurm_job_id"] = slurm_id;
  write_document(dir, doc);
  out << "sweep job: " << id << " stopped by a signal: requeued as Slurm job " << slurm_id
      << " (requeue " << used + 1 << " of " << max_requeues << ")\n"
      << std::flush;
  const std::string command = "scontrol requeue " + slurm_id + " 2>&1";
  if (std::system(command.c_str()) != 0) {
    doc["status"] = "interrupted";
    doc["requeues"] = used;
    write_document(dir, doc);
    out << "sweep job: " << command << " failed: the point stays interrupted\n";
    return false;
  }
  return true;
}

}  // namespace invasim::sweep
