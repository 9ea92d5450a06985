#pragma once
// The lock of a run directory: an exclusive flock(2) on DIR/.lock, taken before a run writes
// or deletes any file of DIR and held until the process ends. A second run into DIR (new,
// --overwrite or --resume) finds it taken and is refused. The kernel releases an flock when
// its holder dies, even by SIGKILL, so a lock never outlives its run. The lock file records
// its holder (pid, host, start time in UTC) for the refusal message; it is rewritten in
// place, not by rename, because the lock belongs to the file's inode (docs/reliability.md,
// "Run directories").
#include <filesystem>
#include <optional>
#include <string>

namespace invasim {

// Takes the lock of `dir` (which must exist) for the rest of this process's life; taking it
// again in the same process succeeds. Returns nullopt on success, or the holder recorded in
// the lock file ("pid 123 on host h, started 2026-01-02T03:04:05Z") if another process holds
// it. The lock file is created if missing but not written: a run refused after taking the
// lock (its directory holds another run) leaves it as it was. Throws IoError if the lock file
// cannot be opened or locked for another reason.
std::optional<std::string> lock_run_directory(const std::filesystem::path& dir);

// Records this process (pid, host, start time) in the lock file of `dir`, whose lock it must
// hold (lock_run_directory). Throws IoError if it cannot be written.
void record_run_lock_holder(const std::filesystem::path& dir);

// Now as an ISO 8601 UTC time stamp ("2026-01-02T03:04:05Z"), and this machine's host name
// ("unknown" if it has none): what lock files and job documents record of their holder.
std::string utc_now();
std::string host_name();

}  // namespace invasim
