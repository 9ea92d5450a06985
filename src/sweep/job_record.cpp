#include "sweep/job_record.hpp"

#include <cstdlib>

#include "invasim_version.hpp"

namespace invasim::sweep {

JobRecord::JobRecord(const fs::path& job_dir, int pid, std::chrono::duration<double> heartbeat)
    : dir_(job_dir), start_(std::chrono::steady_clock::now()) {
  Json doc = read_document(dir_);
  // An attempt killed before it recorded its end left its time in attempt_seconds.
  if (doc.contains("attempt_seconds") && doc["attempt_seconds"].is_number()) {
    doc["wall_seconds"] = doc.value("wall_seconds", 0.0) + doc["attempt_seconds"].get<double>();
  }
  doc.erase("attempt_seconds");
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
  heartbeat_ = std::thread([this, heartbeat] {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, heartbeat, [this] { return stopping_; })) {
      try {
        Json d = read_document(dir_);
        d["attempt_seconds"] = elapsed();
        write_document(dir_, d);
      } catch (const std::exception&) {
        // A heartbeat that cannot write loses at most this attempt's time, never the run.
      }
    }
  });
}

JobRecord::~JobRecord() {
  stop_heartbeat();
}

void JobRecord::stop_heartbeat() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (heartbeat_.joinable()) heartbeat_.join();
}

double JobRecord::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
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
  doc.erase("attempt_seconds");  // the heartbeat's part of `seconds`
  doc["finished_at"] = utc_now();
  write_document(job_dir, doc);
  return status;
}

std::string JobRecord::finish(int exit_code, bool stopped) {
  stop_heartbeat();
  return record_end(dir_, exit_code, stopped, elapsed());
}

}  // namespace invasim::sweep
