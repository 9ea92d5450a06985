// A point's wall_seconds counts every attempt (sweep/job_record.hpp): the heartbeat writes the
// running attempt's time to attempt_seconds, a killed attempt's (one that never recorded its
// end) is added by the next, and a recorded end replaces it by the whole attempt.
#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <thread>

#include <unistd.h>

#include "sweep/job_record.hpp"
#include "sweep/workspace.hpp"

using namespace invasim::sweep;
namespace fs = std::filesystem;

namespace {

fs::path fresh_job_dir(const char* name) {
  const fs::path dir =
      fs::temp_directory_path() / ("invasim_job_record_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST_CASE("job record: a killed attempt's heartbeat time is added by the next attempt") {
  const fs::path dir = fresh_job_dir("killed");
  write_document(dir,
                 Json{{"status", "running"}, {"wall_seconds", 50.0}, {"attempt_seconds", 100.0}});
  {
    JobRecord record(dir, 1234, std::chrono::milliseconds(20));
    const Json doc = read_document(dir);
    CHECK(doc["wall_seconds"].get<double>() == 150.0);
    CHECK(doc["status"] == "running");
    CHECK(doc["attempts"] == 1);
    // The heartbeat writes this attempt's time so far.
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
    const Json beat = read_document(dir);
    REQUIRE(beat.contains("attempt_seconds"));
    CHECK(beat["attempt_seconds"].get<double>() > 0.1);
    CHECK(beat["wall_seconds"].get<double>() == 150.0);
  }  // destroyed without finish(): the attempt was killed; its heartbeat time stays
  const double left = read_document(dir)["attempt_seconds"].get<double>();
  CHECK(left > 0.1);
  JobRecord next(dir, 1235, std::chrono::seconds(60));
  CHECK(read_document(dir)["wall_seconds"].get<double>() == Approx(150.0 + left).epsilon(1e-12));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  CHECK(next.finish(0, false) == "done");
  const Json end = read_document(dir);
  CHECK(end["status"] == "done");
  CHECK_FALSE(end.contains("attempt_seconds"));
  CHECK(end["wall_seconds"].get<double>() >= 150.0 + left + 0.05);
  CHECK(end["attempts"] == 2);
  fs::remove_all(dir.parent_path());
}

TEST_CASE("job record: the runner's end for a dead child replaces the heartbeat's time") {
  const fs::path dir = fresh_job_dir("dead_child");
  write_document(dir,
                 Json{{"status", "running"}, {"wall_seconds", 10.0}, {"attempt_seconds", 7.0}});
  CHECK(record_end(dir, 9, false, 8.0) == "failed");
  const Json doc = read_document(dir);
  CHECK(doc["wall_seconds"].get<double>() == 18.0);
  CHECK_FALSE(doc.contains("attempt_seconds"));
  fs::remove_all(dir.parent_path());
}
