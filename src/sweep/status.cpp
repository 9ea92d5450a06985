#include "sweep/status.hpp"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace invasim::sweep {

CommandOutput run_command(const std::string& command) {
  CommandOutput out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return out;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe)) out.text += buffer;
  out.status = ::pclose(pipe);
  return out;
}

std::map<std::string, std::string> slurm_queue() {
  std::map<std::string, std::string> queue;
  if (std::system("command -v squeue >/dev/null 2>&1") != 0) return queue;
  std::istringstream lines(run_command("squeue -h -r -o '%i %T' 2>/dev/null").text);
  for (std::string line, id, state; std::getline(lines, line);)
    if (std::istringstream(line) >> id >> state) queue[id] = state;
  return queue;
}

std::string effective_status(const fs::path& job_dir,
                             const std::map<std::string, std::string>& queue) {
  const Json doc = read_document(job_dir);
  const std::string recorded = doc.value("status", "pending");
  const auto it = queue.find(doc.value("slurm_job_id", ""));
  // A Slurm task the queue still holds is running or queued, whatever a lock on a shared file
  // system (where flock may not reach across nodes) says.
  if ((recorded == "running" || recorded == "submitted") && it != queue.end())
    return it->second == "RUNNING" || it->second == "COMPLETING" ? "running" : "queued";
  if (recorded == "submitted") return "pending";  // it left the queue without starting
  return job_status(job_dir);
}

std::string running_slurm_job(const fs::path& job_dir, const std::string& own_slurm_id) {
  const Json doc = read_document(job_dir);
  const std::string other = doc.value("slurm_job_id", "");
  if (doc.value("status", "") != "running" || other.empty() || other == own_slurm_id) return "";
  const auto queue = slurm_queue();
  const auto it = queue.find(other);
  return it != queue.end() && (it->second == "RUNNING" || it->second == "COMPLETING") ? other : "";
}

int print_status(const Workspace& ws, std::ostream& out) {
  const auto queue = slurm_queue();
  std::map<std::string, int> counts;
  std::vector<std::string> failed;
  std::map<std::string, int> cancelled;  // why -> points
  for (const auto& id : ws.ids()) {
    const std::string status = effective_status(ws.job_dir(id), queue);
    ++counts[status];
    const Json doc = read_document(ws.job_dir(id));
    if (status == "failed") failed.push_back(id + ": " + doc.value("log", ""));
    if (status == "pending" && doc.contains("cancelled")) ++cancelled[doc.value("cancelled", "")];
  }
  out << ws.root().string() << ": " << ws.ids().size() << " points of " << ws.protocol() << '\n';
  if (ws.has_prep())
    out << "  shared preparation: " << effective_status(ws.job_dir(kPrepId), queue) << '\n';
  for (const char* name : {"pending", "queued", "running", "done", "failed", "interrupted"})
    out << "  " << name << ": " << counts[name] << '\n';
  for (const auto& f : failed) out << "  failed: " << f << '\n';
  for (const auto& [why, n] : cancelled)
    out << "  cancelled: " << n << " pending points whose Slurm array was cancelled: " << why
        << "; fix the cause, then sweep submit\n";
  return 0;
}

}  // namespace invasim::sweep
