// Output layer: atomic files, extended XYZ and VTK snapshots (write, read back), the
// snapshot directory with its .pvd indexes and trajectory, restarts of a series.
#include <signal.h>
#include <sys/resource.h>

#include <catch2/catch.hpp>
#include <fstream>

#include "../io/io_test_support.hpp"
#include "core/range.hpp"
#include "io/atomic_file.hpp"
#include "io/io_error.hpp"
#include "io/snapshot_writer.hpp"
#include "io/text_format.hpp"
#include "io/vtk_format.hpp"
#include "io/xml.hpp"
#include "io/xyz_format.hpp"
#include "mesh/geometry.hpp"

using namespace invasim;
using Catch::Matchers::Contains;
using iotest::TempDir;

namespace {

std::vector<std::string> directory_listing(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

void write_plain(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

// Caps the size of files this process may write (RLIMIT_FSIZE) for its lifetime, so that a
// write fails half-way as on a full disk; SIGXFSZ is ignored so write() returns EFBIG.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    old_handler_ = signal(SIGXFSZ, SIG_IGN);
    rlimit lim = saved_;
    lim.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lim);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit saved_{};
  sighandler_t old_handler_;
};

}  // namespace

TEST_CASE("atomic write creates or replaces a file and leaves no temporary file") {
  TempDir dir("atomic");
  const auto target = dir / "out.txt";
  write_file_atomically(target, "first");
  CHECK(read_file(target) == "first");
  write_file_atomically(target, std::string(100000, 'x'));
  CHECK(read_file(target) == std::string(100000, 'x'));
  write_file_atomically(target, "");
  CHECK(read_file(target).empty());
  CHECK(directory_listing(dir.path()) == std::vector<std::string>{"out.txt"});
  CHECK(atomic_temp_path(target).string() == target.string() + ".tmp." + std::to_string(getpid()));
  append_file_synced(dir / "log.txt", "a");
  append_file_synced(dir / "log.txt", "b");
  CHECK(read_file(dir / "log.txt") == "ab");
  CHECK_THROWS_WITH(append_file_synced(dir / "none" / "log.txt", "a"),
                    "cannot append to '" + (dir / "none" / "log.txt").string() +
                        "': open failed: No such file or directory");
}

TEST_CASE("a failed atomic write leaves the old file whole and removes the temporary file") {
  TempDir dir("atomic_fail");
  const auto target = dir / "state.txt";
  write_plain(target, "old contents");

  SECTION("the disk fills up half-way through the write") {
    {
      FileSizeLimit limit(4096);
      CHECK_THROWS_WITH(write_file_atomically(target, std::string(1 << 20, 'n')),
                        Contains("cannot write '" + target.string() + "'") &&
                            Contains("write failed") && Contains("File too large"));
    }
    CHECK(read_file(target) == "old contents");
    CHECK(directory_listing(dir.path()) == std::vector<std::string>{"state.txt"});
  }
  SECTION("the directory does not exist") {
    const auto missing = dir / "no_such_dir" / "f.txt";
    CHECK_THROWS_AS(write_file_atomically(missing, "x"), IoError);
    CHECK_THROWS_WITH(write_file_atomically(missing, "x"),
                      Contains(missing.string()) && Contains("No such file or directory"));
    CHECK(directory_listing(dir.path()) == std::vector<std::string>{"state.txt"});
  }
  SECTION("the rename fails: the target is a non-empty directory") {
    const auto blocked = dir / "blocked";
    std::filesystem::create_directories(blocked / "inside");
    CHECK_THROWS_WITH(write_file_atomically(blocked, "x"),
                      Contains("'" + blocked.string() + "'") && Contains("rename"));
    CHECK(std::filesystem::is_directory(blocked / "inside"));
    CHECK(directory_listing(dir.path()) == std::vector<std::string>{"blocked", "state.txt"});
  }
}

TEST_CASE("ensure_directory creates parents and names a path that is not a directory") {
  TempDir dir("mkdir");
  ensure_directory(dir / "a/b/c");
  CHECK(std::filesystem::is_directory(dir / "a/b/c"));
  ensure_directory(dir / "a/b/c");  // exists: no-op
  write_plain(dir / "file", "x");
  CHECK_THROWS_WITH(ensure_directory(dir / "file"),
                    Contains("cannot create directory '" + (dir / "file").string() + "'"));
  CHECK_THROWS_WITH(ensure_directory(dir / "file/sub"), Contains((dir / "file/sub").string()));
  CHECK_THROWS_WITH(read_file(dir / "nothing"),
                    Contains("cannot read '" + (dir / "nothing").string() + "'"));
}

TEST_CASE("extended XYZ: the documented header and an exact round trip") {
  const System sys = iotest::sample_system();
  const Frame f = frame_from_system(sys);
  REQUIRE(f.cells.size() == 20);
  const std::string text = xyz_frame_text(f);
  const std::size_t nl = text.find('\n');
  CHECK(text.substr(0, nl) == "20");
  const std::string comment = text.substr(nl + 1, text.find('\n', nl + 1) - nl - 1);
  CHECK(comment ==
        "Lattice=\"12 0 0 0 10 0 0 0 10\" Origin=\"0 0 0\" "
        "Properties=species:S:1:pos:R:3:radius:R:1:velo:R:3:orient:R:3 pbc=\"F T T\" "
        "Time=60.00000000000001 Step=1200");
  const auto kv = parse_xyz_comment(comment);
  CHECK(kv.at("pbc") == "F T T");
  CHECK(kv.at("Step") == "1200");

  const Frame back = parse_xyz(text, "test");
  CHECK(back.step == 1200);
  CHECK(back.time == sys.time);
  CHECK(back.box.lo() == sys.box().lo());
  CHECK(back.box.hi() == sys.box().hi());
  CHECK(back.box.periodic() == sys.box().periodic());
  CHECK(back.cells.pos == f.cells.pos);  // exact: shortest round-trip decimal form
  CHECK(back.cells.vel == f.cells.vel);
  CHECK(back.cells.orient == f.cells.orient);
  CHECK(back.cells.radius == f.cells.radius);
  CHECK(f.cells.radius[0] == 0.45);
  CHECK(f.cells.radius[1] == 0.55);
  for (const Vec3& r : f.cells.pos) {  // wrapped on the periodic axes
    CHECK(r[1] >= 0.0);
    CHECK(r[1] < 10.0);
    CHECK(r[2] >= 0.0);
    CHECK(r[2] < 10.0);
  }
  for (std::size_t i = 0; i < f.cells.size(); ++i)
    CHECK(text.find("\nC " + format_number(f.cells.pos[i][0]) + " ") != std::string::npos);
}

TEST_CASE("XYZ reader: frames of a trajectory and clear errors") {
  System sys = iotest::sample_system(3);
  const std::string a = xyz_frame_text(frame_from_system(sys));
  sys.step = 1300;
  const std::string b = xyz_frame_text(frame_from_system(sys));
  CHECK(parse_xyz(a + b, "traj", 1).step == 1300);
  CHECK(parse_xyz(a + b, "traj", 0).step == 1200);
  CHECK_THROWS_WITH(parse_xyz(a + b, "traj", 2), Contains("traj: no frame 2"));
  CHECK_THROWS_WITH(parse_xyz("2\nProperties=species:S:1:pos:R:3\nC 0 0 0\n", "f.xyz"),
                    Contains("f.xyz: the comment line has no Lattice"));
  CHECK_THROWS_WITH(parse_xyz("1\nLattice=\"1 0 0 0 1 0 0 0 1\"\nC 0 0\n", "f.xyz"),
                    Contains("f.xyz: line 3: 3 columns, expected 4"));
  CHECK_THROWS_WITH(parse_xyz("1\nLattice=\"1 1 0 0 1 0 0 0 1\"\nC 0 0 0\n", "f.xyz"),
                    Contains("not orthorhombic"));
  // Column counts are bounded before a row's numbers are allocated (the sum would overflow an
  // int; 2e9 columns alone would take 16 GB).
  for (const char* junk : {"junk:R:2147483647", "junk:R:2000000000", "a:R:1000:b:R:1000"})
    CHECK_THROWS_WITH(parse_xyz(std::string("1\nLattice=\"1 0 0 0 1 0 0 0 1\" "
                                            "Properties=species:S:1:pos:R:3:") +
                                    junk + "\nC 0 0 0\n",
                                "f.xyz"),
                      Contains("more than 1024 columns in all"));
  CHECK_THROWS_WITH(parse_xyz("2\nLattice=\"1 0 0 0 1 0 0 0 1\"\nC 0 0 0\n", "f.xyz"),
                    Contains("f.xyz: line 1 says 2 particles, but the frame has 1 row (the "
                             "file ends after line 3)"));
  // A count line that disagrees with the rows: more rows, or the next frame's count line early.
  const std::string head = "2\nLattice=\"1 0 0 0 1 0 0 0 1\"\n";
  CHECK_THROWS_WITH(
      parse_xyz(head + "C 0 0 0\nC 0 0 0\nC 0 0 0\n", "f.xyz"),
      "f.xyz: line 1 says 2 particles, but the frame has 3 rows (1 more from line 5)");
  CHECK_THROWS_WITH(parse_xyz(head + "C 0 0 0\n" + head + "C 0 0 0\nC 0 0 0\n", "f.xyz"),
                    "f.xyz: line 1 says 2 particles, but the frame has 1 row (the next frame's "
                    "count line is line 4)");
  CHECK(parse_xyz(head + "C 0 0 0\nC 0 0 0\n\n\n", "f.xyz").cells.size() == 2);  // blank lines
  CHECK(parse_xyz(head + "C 0 0 0\nC 0 0 0\n" + head + "C 0 0 0\nC 0 0 0\n", "f.xyz", 1)
            .cells.size() == 2);
  // Plain extended XYZ from elsewhere: default radius, pbc T T T, any column order.
  const Frame other = parse_xyz(
      "1\nLattice=\"2 0 0 0 3 0 0 0 4\" Properties=pos:R:3:species:S:1\n0.5 1 1.5 Si\n", "o");
  CHECK(other.cells.pos[0] == Vec3(0.5, 1, 1.5));
  CHECK(other.cells.radius[0] == 0.5);
  CHECK(other.box.periodic() == std::array<bool, 3>{true, true, true});
}

TEST_CASE("adipocyte .vtp: whole meshes in the box, per-triangle data, exact round trip") {
  const System sys = iotest::sample_system();
  const Frame f = frame_from_system(sys);
  const MeshFrame& m = f.meshes;
  REQUIRE(m.points.size() == 84);
  REQUIRE(m.triangles.size() == 160);
  CHECK(m.n_bodies() == 2);
  std::vector<Vec3> x(42);
  for (int b = 0; b < 2; ++b) {
    sys.body_vertices(b, x.data());
    const MeshTopology& topo = *sys.bodies()[b].topology;
    const double shape = shape_parameter(mesh_area(topo, x.data()), mesh_volume(topo, x.data()));
    // Points of body b: its unwrapped vertices shifted by whole periods, centroid in the box.
    const Vec3 shift = m.points[42 * b] - x[0];
    for (int v = 0; v < 42; ++v) CHECK((m.points[42 * b + v] - x[v] - shift).norm() < 1e-12);
    for (int a = 1; a < 3; ++a) CHECK(std::abs(std::remainder(shift[a], 10.0)) < 1e-12);
    CHECK(shift == (b == 0 ? Vec3(0, 0, 0) : Vec3(0, -10, 10)));  // body 1: one period back
    const Vec3 c = vertex_centroid(42, &m.points[42 * b]);
    CHECK(c[1] >= 0.0);
    CHECK(c[1] < 10.0);
    CHECK(c[2] >= 0.0);
    CHECK(c[2] < 10.0);
    for (int k = 0; k < 80; ++k) {
      CHECK(m.triangle_body[80 * b + k] == b);
      CHECK(m.triangle_shape[80 * b + k] == shape);
      for (int j = 0; j < 3; ++j) CHECK(m.triangles[80 * b + k][j] == 42 * b + topo.faces()[k][j]);
    }
  }
  // Body 1 straddles the y and z edges: its points leave the box, the mesh stays whole.
  double max_y = 0.0;
  for (int v = 42; v < 84; ++v) max_y = std::max(max_y, m.points[v][1]);
  CHECK(max_y > 10.0);

  const std::string text = adipocytes_vtp_text(f);
  const VtpData vtp = parse_vtp(text, "a.vtp");
  CHECK(vtp.cell_data.at("adipocyte").type == "Int32");
  CHECK(vtp.cell_data.at("shape_parameter").type == "Float64");
  const Frame back = mesh_frame_from_vtp(vtp, "a.vtp");
  CHECK(back.meshes.points == m.points);
  CHECK(back.meshes.triangles == m.triangles);
  CHECK(back.meshes.triangle_body == m.triangle_body);
  CHECK(back.meshes.triangle_shape == m.triangle_shape);
  CHECK(back.meshes.point_radius == m.point_radius);
  CHECK(m.point_radius == std::vector<double>(84, 1.0));
  CHECK(back.box.lo() == f.box.lo());
  CHECK(back.box.hi() == f.box.hi());
  CHECK(back.box.periodic() == f.box.periodic());
  CHECK(back.step == 1200);
  CHECK(back.time == sys.time);
}

TEST_CASE("sphere .vtp round trip and malformed VTK files refused with the line") {
  const Frame f = frame_from_system(iotest::sample_system());
  const VtpData vtp = parse_vtp(spheres_vtp_text(f), "s.vtp");
  CHECK(vtp.vert_offsets.size() == 20);
  CHECK(vtp.vert_offsets.back() == 20);
  CHECK(vtp.poly_offsets.empty());
  CHECK(vtp.point_data.at("velocity").components == 3);
  CHECK(vtp.point_data.at("orientation").components == 3);
  const Frame back = cell_frame_from_vtp(vtp, "s.vtp");
  CHECK(back.cells.pos == f.cells.pos);
  CHECK(back.cells.vel == f.cells.vel);
  CHECK(back.cells.orient == f.cells.orient);
  CHECK(back.cells.radius == f.cells.radius);

  std::string bad = spheres_vtp_text(f);
  bad.erase(bad.find("</Points>"), 9);
  CHECK_THROWS_WITH(parse_vtp(bad, "s.vtp"), Contains("s.vtp: line") && Contains("malformed XML"));
  CHECK_THROWS_WITH(parse_vtp(pvd_text({}), "c.pvd"), Contains("c.pvd: not a VTK PolyData"));
  CHECK_THROWS_WITH(mesh_frame_from_vtp(vtp, "s.vtp"), Contains("adipocyte and shape_parameter"));
  CHECK(xml_escape("a<b & \"c\"") == "a&lt;b &amp; &quot;c&quot;");
  // A snapshot cut short (a crash while copying it) is refused with the file and the line.
  const std::string text = spheres_vtp_text(f);
  CHECK_THROWS_WITH(parse_vtp(text.substr(0, text.size() / 2), "'s.vtp'"),
                    Contains("'s.vtp': line ") && Contains("malformed XML") &&
                        Contains("; the text ends inside an element (a truncated file?)"));
}

TEST_CASE("XML documents: entities, comments, and malformed XML with its line and offset") {
  const XmlDocument doc("<a k='&lt;1&gt;'>x &amp; y<!-- c --><b/> z</a>", "t");
  CHECK(std::string(doc.root().attribute("k").value()) == "<1>");
  CHECK(xml_text(doc.root()) == "x & y z");
  CHECK(doc.line(doc.root().child("b")) == 1);
  const XmlDocument lines("<?xml version=\"1.0\"?>\n<a>\n  <b/>\n</a>\n", "t");
  CHECK(lines.line(lines.root().child("b")) == 3);
  CHECK_THROWS_AS(XmlDocument("<a>\n<b>\n</a>", "'x.vtp'"), IoError);
  CHECK_THROWS_WITH(XmlDocument("<a>\n<b>\n</a>", "'x.vtp'"),
                    "'x.vtp': line 3 (offset 10): malformed XML: Start-end tags mismatch");
  CHECK_THROWS_WITH(XmlDocument("", "'x.vtp'"),
                    "'x.vtp': line 1 (offset 0): malformed XML: No document element found");
  CHECK_THROWS_WITH(XmlDocument("<a/>\n<b/>", "'x.vtp'"),
                    Contains("'x.vtp': line 2") && Contains("content after the root element"));
  CHECK_THROWS_WITH(XmlDocument("<a k=1/>", "'x.vtp'"), Contains("malformed XML"));
}

TEST_CASE("snapshot writer: frame files, .pvd indexes, and a restarted series") {
  TempDir dir("snapshots");
  System sys = iotest::sample_system();
  SnapshotOptions opt;
  opt.trajectory = true;
  {
    SnapshotWriter w(dir / "snaps", opt);
    for (std::uint64_t step : {0, 1000, 2000}) {
      sys.step = step;
      sys.time = 0.05 * double(step);
      w.write(sys);
    }
  }
  const auto snaps = dir / "snaps";
  CHECK(directory_listing(snaps) ==
        std::vector<std::string>{
            "adipocytes.pvd", "adipocytes_000000000.vtp", "adipocytes_000001000.vtp",
            "adipocytes_000002000.vtp", "cells_000000000.xyz", "cells_000001000.xyz",
            "cells_000002000.xyz", "spheres.pvd", "spheres_000000000.vtp", "spheres_000001000.vtp",
            "spheres_000002000.vtp", "trajectory.xyz"});
  const auto pvd = read_pvd(snaps / "adipocytes.pvd");
  REQUIRE(pvd.size() == 3);
  CHECK(pvd[1].file == "adipocytes_000001000.vtp");
  CHECK(pvd[1].time == 50.0);
  CHECK(read_xyz(snaps / "cells_000001000.xyz").step == 1000);
  CHECK(read_xyz(snaps / "trajectory.xyz", 2).step == 2000);

  // A run restarted from step 1000: entries from step 1000 on are replaced.
  {
    SnapshotWriter w(snaps, opt);
    sys.step = 1000;
    sys.time = 50.5;
    w.write(sys);
  }
  const auto sph = read_pvd(snaps / "spheres.pvd");
  REQUIRE(sph.size() == 2);
  CHECK(sph[0].file == "spheres_000000000.vtp");
  CHECK(sph[1].time == 50.5);
  CHECK(read_xyz(snaps / "trajectory.xyz", 0).step == 0);
  CHECK(read_xyz(snaps / "trajectory.xyz", 1).step == 1000);
  CHECK(read_xyz(snaps / "trajectory.xyz", 1).time == 50.5);
  CHECK_THROWS_WITH(read_xyz(snaps / "trajectory.xyz", 2), Contains("no frame 2"));

  CHECK(SnapshotWriter::frame_file_name("cells", 1200, "xyz") == "cells_000001200.xyz");
  CHECK(SnapshotWriter::frame_file_name("cells", 12345678901, "xyz") == "cells_12345678901.xyz");
  CHECK(SnapshotWriter::step_of_file_name("adipocytes_000001200.vtp") == 1200);
  CHECK(SnapshotWriter::step_of_file_name("adipocytes.vtp") == -1);
}

TEST_CASE("trajectory truncation drops an incomplete last frame") {
  TempDir dir("traj");
  const auto path = dir / "t.xyz";
  System sys = iotest::sample_system(2);
  std::string text = xyz_frame_text(frame_from_system(sys));
  sys.step = 1300;
  const std::string second = xyz_frame_text(frame_from_system(sys));
  write_plain(path, text + second.substr(0, second.size() / 2));
  truncate_xyz_trajectory(path, 5000);
  CHECK(read_file(path) == text);
  truncate_xyz_trajectory(path, 1200);
  CHECK(read_file(path).empty());
  truncate_xyz_trajectory(dir / "none.xyz", 0);  // missing: no-op
  CHECK(!std::filesystem::exists(dir / "none.xyz"));
}
