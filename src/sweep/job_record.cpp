#include "sweep/job_record.hpp"

#include <unistd.h>

#include <cstdlib>
#include <ctime>

#include "invasim_version.hpp"

namespace invasim::sweep {

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

namespace {

std::string host_name() {
  char name[256] = {};
  ::gethostname(name, sizeof name - 1);
  return name;
}

}  // namespace

JobRecord::JobRecord(const fs::path& job_dir, int pid)
    : dir_(job_dir), start_(std::chrono::steady_clock::now()) {
  Json doc = read_document(dir_);
  doc["status"] = "running";
  doc.erase("cancelled");  // set when an earlier Slurm array was cancelled
  doc["pid"] = pid;
  doc["host"] = host_name();
  doc["started_at"] = utc_now();
  doc["attempts"] = doc.value("attempts", 0) + 1;
  doc["invasim_version"] = kInvasimVersion;
  doc["git_revision"] = kInvasimGitRevision;
  doc["log"] = log_path().string();
  if (const std::string slurm = current_slurm_job_id(); !slurm.empty()) doc["slurm_job_id"] = slurm;
  write_document(dir_, doc);
}

std::string current_slurm_job_id() {
  const char* array_job = std::getenv("SLURM_ARRAY_JOB_ID");
  const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* job = std::getenv("SLURM_JOB_ID");
  if (array_job && task) return std::string(array_job) + "_" + task;
  return job ? std::string(job) : std::string();
}

std::string record_end(const fs::path& job_dir, int exit_code, bool stopped, double seconds) {
  Json doc = read_document(job_dir);
  const std::string status = exit_code == 0 ? "done" : stopped ? "interrupted" : "failed";
  doc["status"] = status;
  doc["exit_code"] = exit_code;
  doc["wall_seconds"] = doc.value("wall_seconds", 0.0) + seconds;
  doc["finished_at"] = utc_now();
  write_document(job_dir, doc);
  return status;
}

std::string JobRecord::finish(int exit_code, bool stopped) {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return record_end(dir_, exit_code, stopped, seconds);
}

}  // namespace invasim::sweep
