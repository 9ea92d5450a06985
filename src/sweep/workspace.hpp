#pragma once
// A sweep workspace, laid out so that signac (schema version 2) opens it as a project:
//   WS/.signac/config                       schema_version = 2
//   WS/workspace/<id>/signac_statepoint.json the state point (its MD5 is <id>)
//   WS/workspace/<id>/signac_job_document.json status, exit code, wall time, version, ...
//   WS/workspace/<id>/...                    the run directory of `invasim run --out`
//   WS/prep/                                 the shared preparation's run directory
//   WS/invasim_sweep.json                    protocol, spec, preparation and point list
// docs/sweeps.md describes every file.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/json.hpp"
#include "sweep/python_json.hpp"
#include "sweep/spec.hpp"

namespace invasim::sweep {

namespace fs = std::filesystem;

// The name of the shared preparation among job ids (its directory is WS/prep).
inline const std::string kPrepId = "prep";
// The workspace's configuration file, WS/invasim_sweep.json.
inline const char* const kConfig = "invasim_sweep.json";

class Workspace {
 public:
  // Opens an initialised workspace; InputError naming WS if it is none.
  static Workspace open(const fs::path& root);

  const fs::path& root() const { return root_; }
  const std::string& protocol() const { return protocol_; }
  const std::vector<std::string>& ids() const { return ids_; }  // the state points, in order
  bool has_prep() const { return has_prep_; }

  // WS/workspace/<id>, or WS/prep for kPrepId.
  fs::path job_dir(const std::string& id) const;
  Json statepoint(const std::string& id) const;

  // The `invasim` arguments that run (or, with a resume.txt, continue) job `id`:
  // run PROTOCOL --out DIR --set k=v ... [--from WS/prep], or run --resume DIR.
  std::vector<std::string> run_arguments(const std::string& id) const;

 private:
  fs::path root_;
  std::string protocol_;
  std::vector<std::string> ids_;
  bool has_prep_ = false;
  Json prep_set_;
};

// Job documents (signac_job_document.json): status is one of pending, submitted, running,
// done, failed, interrupted.
Json read_document(const fs::path& job_dir);
void write_document(const fs::path& job_dir, const Json& document);  // atomic (rename)

// An exclusive lock on a job (flock on DIR/run.lock), held by whoever runs it; child
// processes inherit it. Not copyable.
class JobLock {
 public:
  ~JobLock();
  JobLock(JobLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  // Takes the lock if nobody holds it.
  static std::optional<JobLock> try_acquire(const fs::path& job_dir);

 private:
  explicit JobLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

// The status of a job as the documents and locks tell it: a "running" job whose lock nobody
// holds (its runner was killed) is "interrupted".
std::string job_status(const fs::path& job_dir);

}  // namespace invasim::sweep
