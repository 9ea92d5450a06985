#include "sweep/init_workspace.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <unordered_set>

#include "core/errors.hpp"
#include "core/names.hpp"
#include "io/atomic_file.hpp"
#include "sweep/workspace.hpp"

namespace invasim::sweep {

namespace {

// Test hook (docs/reliability.md): INVASIM_TEST_KILL_SWEEP_INIT_AFTER=N makes `sweep init`
// SIGKILL itself once it has written N job directories, as a user's kill would midway.
void kill_after_jobs_hook(int written) {
  static const char* env = std::getenv("INVASIM_TEST_KILL_SWEEP_INIT_AFTER");
  if (env && std::atoi(env) == written) ::raise(SIGKILL);
}

// The temporary directory names of init: a new workspace's sibling, a grown one's staging.
std::string temporary_prefix(const fs::path& root) {
  return cat(".", root.filename().string(), ".init.");
}
const std::string kStagingPrefix = ".init.";

// Removes, in `dir`, the directories named PREFIX<pid> whose process is gone (a killed init).
void remove_stale(const fs::path& dir, const std::string& prefix) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::atol(digits.c_str());
    if (pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
      fs::remove_all(entry.path());
  }
}

// The spec's shared preparation as the configuration records it (null without one).
Json prep_of(const SweepSpec& spec) {
  return spec.has_prep ? Json{{"set", spec.prep_set}} : Json(nullptr);
}

// The spec file as the configuration records it: absolute and normalised.
std::string recorded_spec_path(const SweepSpec& spec) {
  return fs::absolute(spec.path).lexically_normal().string();
}

// A job directory's document before its run: pending.
void write_pending(const fs::path& dir) {
  write_document(dir, Json{{"status", "pending"}});
}

// Refuses a spec with more points than `max_points`, before anything is made or written.
void check_point_count(const SweepSpec& spec, std::size_t max_points) {
  const std::size_t count = spec.point_count();
  if (count > max_points)
    fail_input("sweep init: ", spec.path, " has ",
               count == std::numeric_limits<std::size_t>::max() ? std::string("more than 2^64")
                                                                : std::to_string(count),
               " points (", spec.point_count_factors(), "), more than the limit of ", max_points,
               " points per workspace: nothing written; give --max-points ", count,
               " to write them all, or --take N to keep the first N values of every axis");
}

// Refuses a directory that exists but is not a workspace (no invasim_sweep.json).
void check_new_workspace_target(const fs::path& root) {
  if (!fs::exists(root)) return;
  if (!fs::is_directory(root))
    fail_input("sweep init: ", root.string(),
               " exists and is not a directory: choose another --workspace");
  if (fs::exists(root / "resume.txt") || fs::exists(root / "params.json"))
    fail_input("sweep init: ", root.string(),
               " is a run directory (it holds resume.txt or params.json), not a sweep workspace: "
               "choose another --workspace");
  if (!fs::is_empty(root))
    fail_input("sweep init: ", root.string(), " is not empty and is not a sweep workspace (no ",
               kConfig, "): choose a new or empty --workspace");
}

std::string names_text(const std::set<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : ", ") + n;
  return text.empty() ? "none" : text;
}

// The parameters every point of `spec` gives: its fixed ones and its axes.
std::set<std::string> point_keys(const SweepSpec& spec) {
  std::set<std::string> keys;
  for (const auto& item : spec.fixed.items()) keys.insert(item.key());
  for (const auto& axis : spec.product) keys.insert(axis.first);
  for (const auto& zip : spec.zips)
    for (const auto& axis : zip) keys.insert(axis.first);
  return keys;
}

// Refuses adding the points of `spec` to the workspace `root` (configuration `old`, points
// `ids`) unless they belong to the same sweep: same protocol, same preparation, the same
// parameters in every point and the same values of the spec's fixed parameters.
void check_same_sweep(const SweepSpec& spec, const Json& old, const fs::path& root,
                      const std::vector<std::string>& ids) {
  const std::string old_spec = old.value("spec", std::string("its first spec"));
  const bool same_file = old_spec == recorded_spec_path(spec);
  const std::string refused =
      cat("sweep init: ", root.string(), " holds the points of ", old_spec, ", another sweep than ",
          spec.path, same_file ? " as given now (--set, --tiny and --take change it)" : "", ": ");
  const std::string advice =
      "; a workspace holds one sweep (a grown spec may add values to its axes and seeds): "
      "choose another --workspace";
  if (old.at("protocol") != spec.protocol)
    fail_input(refused, "its protocol is ", old.at("protocol").get<std::string>(), ", not ",
               spec.protocol, advice);
  const Json prep = prep_of(spec);
  const Json old_prep = old.contains("prep") ? old.at("prep") : Json(nullptr);
  if (python_dumps(old_prep) != python_dumps(prep))
    fail_input(refused, "the shared preparation differs from the one its points started from (",
               python_dumps(old_prep), " there, ", python_dumps(prep), " in ", spec.path, ")",
               advice);
  const std::set<std::string> keys = point_keys(spec);
  for (const auto& id : ids) {
    const fs::path statepoint = root / "workspace" / id / "signac_statepoint.json";
    if (!fs::exists(statepoint)) continue;
    const Json point = read_json(statepoint);
    std::set<std::string> old_keys;
    for (const auto& item : point.items()) old_keys.insert(item.key());
    if (old_keys != keys) {
      std::set<std::string> only_old, only_new;
      std::set_difference(old_keys.begin(), old_keys.end(), keys.begin(), keys.end(),
                          std::inserter(only_old, only_old.end()));
      std::set_difference(keys.begin(), keys.end(), old_keys.begin(), old_keys.end(),
                          std::inserter(only_new, only_new.end()));
      fail_input(refused, "its points give other parameters (only there: ", names_text(only_old),
                 "; only in ", spec.path, ": ", names_text(only_new), ")", advice);
    }
    for (const auto& item : spec.fixed.items())
      if (python_dumps(point.at(item.key())) != python_dumps(item.value()))
        fail_input(refused, "its point ", id, " has ", item.key(), " = ",
                   python_dumps(point.at(item.key())), ", ", spec.path, " fixes ", item.key(),
                   " = ", python_dumps(item.value()), advice);
  }
}

// A pending job: its state point and job document in `dir` (created).
void write_job(const fs::path& dir, const Json& point) {
  fs::create_directories(dir);
  write_file_atomically(dir / "signac_statepoint.json", python_dumps(point));
  write_pending(dir);
}

Json config_of(const SweepSpec& spec, const std::vector<std::string>& ids) {
  return {{"protocol", spec.protocol},
          {"spec", recorded_spec_path(spec)},
          {"prep", prep_of(spec)},
          {"points", ids}};
}

// A new workspace, built in a temporary sibling and renamed into place.
InitReport create(const SweepSpec& spec, const fs::path& root) {
  const fs::path tmp = root.parent_path() / (temporary_prefix(root) + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp / ".signac");
  fs::create_directories(tmp / "workspace");
  write_file_atomically(tmp / ".signac" / "config", "schema_version = 2\n");
  InitReport report;
  std::vector<std::string> ids;  // in the spec's order, for the configuration
  std::unordered_set<std::string> written;
  for (const Json& point : spec.points()) {
    const std::string id = signac_id(point);
    if (!written.insert(id).second) continue;
    write_job(tmp / "workspace" / id, point);
    ids.push_back(id);
    ++report.added;
    kill_after_jobs_hook(report.added);
  }
  if (spec.has_prep) {
    fs::create_directories(tmp / "prep");
    write_pending(tmp / "prep");
  }
  write_file_atomically(tmp / kConfig, config_of(spec, ids).dump(2) + "\n");
  fs::rename(tmp, root);  // root is absent or an empty directory
  return report;
}

// The new points of a grown spec, built in WS/.init.PID, moved into WS/workspace/ one by one;
// then the configuration that lists them replaces the old one.
InitReport grow(const SweepSpec& spec, const fs::path& root, std::vector<std::string> ids) {
  const fs::path staging = root / (kStagingPrefix + std::to_string(::getpid()));
  fs::remove_all(staging);
  InitReport report;
  std::unordered_set<std::string> listed_ids(ids.begin(), ids.end());
  std::vector<std::string> staged;  // in the spec's order
  std::unordered_set<std::string> staged_ids;
  for (const Json& point : spec.points()) {
    const std::string id = signac_id(point);
    const fs::path dir = root / "workspace" / id;
    const bool listed = listed_ids.count(id) > 0;
    if (listed && fs::exists(dir / "signac_statepoint.json")) {
      ++report.kept;
      continue;
    }
    if (staged_ids.count(id)) continue;
    if (fs::exists(dir)) {
      // Moved in by an init killed before it wrote the configuration (or listed without a
      // state point): list it, keeping what it holds.
      if (!fs::exists(dir / "signac_statepoint.json"))
        write_file_atomically(dir / "signac_statepoint.json", python_dumps(point));
      if (!fs::exists(dir / "signac_job_document.json")) write_pending(dir);
      if (listed_ids.insert(id).second) ids.push_back(id);
      ++report.added;
      continue;
    }
    write_job(staging / id, point);
    staged.push_back(id);
    staged_ids.insert(id);
  }
  fs::create_directories(root / "workspace");
  for (const auto& id : staged) {
    fs::rename(staging / id, root / "workspace" / id);
    if (listed_ids.insert(id).second) ids.push_back(id);
    ++report.added;
    kill_after_jobs_hook(report.added);
  }
  fs::remove_all(staging);
  if (spec.has_prep && !fs::exists(root / "prep" / "signac_job_document.json")) {
    fs::create_directories(root / "prep");
    write_pending(root / "prep");
  }
  write_file_atomically(root / kConfig, config_of(spec, ids).dump(2) + "\n");
  return report;
}

}  // namespace

InitReport init_workspace(const SweepSpec& spec, const fs::path& root_in, std::size_t max_points) {
  fs::path root = fs::absolute(root_in).lexically_normal();
  if (root.filename().empty()) root = root.parent_path();  // "ws/"
  check_point_count(spec, max_points);
  remove_stale(root.parent_path(), temporary_prefix(root));
  if (!fs::exists(root / kConfig)) {
    check_new_workspace_target(root);
    fs::create_directories(root.parent_path());
    return create(spec, root);
  }
  remove_stale(root, kStagingPrefix);
  const Json old = read_json(root / kConfig);
  const auto ids = old.at("points").get<std::vector<std::string>>();
  check_same_sweep(spec, old, root, ids);
  return grow(spec, root, ids);
}

}  // namespace invasim::sweep
