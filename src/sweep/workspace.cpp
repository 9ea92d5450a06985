#include "sweep/workspace.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace invasim::sweep {

Json read_document(const fs::path& job_dir) {
  const fs::path path = job_dir / "signac_job_document.json";
  if (!fs::exists(path)) return Json{{"status", "pending"}};
  return read_json(path);
}

void write_document(const fs::path& job_dir, const Json& document) {
  write_file_atomically(job_dir / "signac_job_document.json", document.dump(2) + "\n");
}

JobLock::~JobLock() {
  if (fd_ >= 0) ::close(fd_);
}

std::optional<JobLock> JobLock::try_acquire(const fs::path& job_dir) {
  const int fd = ::open((job_dir / "run.lock").c_str(), O_RDWR | O_CREAT, 0644);
  if (fd < 0) fail_input("cannot open ", (job_dir / "run.lock").string());
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    return std::nullopt;
  }
  return JobLock(fd);
}

std::string job_status(const fs::path& job_dir) {
  const std::string status = read_document(job_dir).value("status", "pending");
  if (status != "running") return status;
  return JobLock::try_acquire(job_dir) ? "interrupted" : "running";
}

Workspace Workspace::open(const fs::path& root) {
  const fs::path config = root / kConfig;
  if (!fs::exists(config))
    fail_input(root.string(), " is not a sweep workspace (no ", kConfig,
               "); create one with: invasim sweep init SPEC.lua --workspace ", root.string());
  const Json c = read_json(config);
  Workspace ws;
  ws.root_ = fs::absolute(root).lexically_normal();
  ws.protocol_ = c.at("protocol").get<std::string>();
  ws.ids_ = c.at("points").get<std::vector<std::string>>();
  ws.has_prep_ = c.contains("prep") && !c.at("prep").is_null();
  if (ws.has_prep_) ws.prep_set_ = c.at("prep").at("set");
  return ws;
}

fs::path Workspace::job_dir(const std::string& id) const {
  return id == kPrepId ? root_ / "prep" : root_ / "workspace" / id;
}

Json Workspace::statepoint(const std::string& id) const {
  if (id == kPrepId) return prep_set_;
  return read_json(job_dir(id) / "signac_statepoint.json");
}

std::vector<std::string> Workspace::run_arguments(const std::string& id) const {
  const fs::path dir = job_dir(id);
  if (fs::exists(dir / "resume.txt")) return {"run", "--resume", dir.string()};
  std::vector<std::string> args = {"run", protocol_, "--out", dir.string()};
  const Json point = statepoint(id);
  for (const auto& item : point.items()) {
    args.push_back("--set");
    args.push_back(item.key() + "=" + set_text(item.value()));
  }
  if (id != kPrepId && has_prep_) {
    args.push_back("--from");
    args.push_back(job_dir(kPrepId).string());
  }
  return args;
}

}  // namespace invasim::sweep
