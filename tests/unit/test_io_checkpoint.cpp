// Checkpoints: the container (typed sections, exact doubles, refusal of damaged files with a
// message naming the problem) and the System / tether / barostat sections (bit-for-bit).
#include <bit>
#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>

#include "../io/io_test_support.hpp"
#include "checkpoint/checkpoint_file.hpp"
#include "checkpoint/state_checkpoint.hpp"
#include "core/fnv1a.hpp"
#include "integrate/dynamics.hpp"
#include "io/atomic_file.hpp"
#include "io/crc32.hpp"
#include "test_support.hpp"

using namespace invasim;
using Catch::Matchers::Contains;
using iotest::TempDir;

namespace {

// Bitwise equality of doubles (distinguishes -0.0 from 0.0 and compares NaN payloads).
bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}
bool same_bits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (!same_bits(a[i][k], b[i][k])) return false;
  return true;
}

void write_plain(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

// A small checkpoint with one section of every type.
CheckpointWriter every_type() {
  CheckpointWriter w;
  w.put_bytes("raw", std::string("a\0b", 3));
  w.put_string("name", "invasim run 7");
  w.put_f64("neg_zero", -0.0);
  w.put_f64("nan", std::bit_cast<double>(std::uint64_t(0x7ff8000000000123)));
  w.put_f64("denormal", 4.9e-324);
  w.put_u64("big", 0xFEDCBA9876543210ull);
  w.put_i64("negative", -42);
  w.put_f64s("f64s", {1.0 / 3.0, -1e300, 0.1});
  w.put_i32s("i32s", {-1, 0, 2147483647, -2147483647 - 1});
  w.put_u64s("u64s", {0, ~0ull});
  w.put_vec3s("vec3s", {Vec3(0.1, 0.2, 0.3), Vec3(-1, 1e-310, 7)});
  w.put_vec3is("vec3is", {Vec3i(-3, 0, 5)});
  w.put_f64s("empty", {});
  return w;
}

}  // namespace

TEST_CASE("CRC-32 matches the standard check value") {
  CHECK(crc32("123456789") == 0xCBF43926u);
  CHECK(crc32("") == 0u);
  CHECK(crc32("56789", crc32("1234")) == 0xCBF43926u);
}

// The checkpoint format does not depend on who computes the checksum: these 437 bytes (and
// their trailer, Python's zlib.crc32 of the bytes before it) were written by the hand-written
// CRC-32 that zlib replaced, and are written the same now.
TEST_CASE("checkpoint container: a fixed checkpoint's bytes and CRC-32 trailer are unchanged") {
  const std::string bytes = every_type().bytes();
  REQUIRE(bytes.size() == 437);
  std::uint32_t stored = 0;
  for (int k = 0; k < 4; ++k) stored |= std::uint32_t(std::uint8_t(bytes[433 + k])) << (8 * k);
  CHECK(stored == 0x86b1928eu);
  CHECK(crc32(std::string_view(bytes).substr(0, 433)) == stored);
  CHECK(fnv1a64_hex(bytes) == "fc3dc9b0e1838e6c");
  // Format version 3 changed only the version field (offset 11): set back to 2, with the
  // trailer of then, these are the bytes version 2 wrote (CRC 0x2ebedb11 from the hand-written
  // CRC-32 and Python's zlib.crc32 alike).
  REQUIRE(kCheckpointVersion == 3);
  REQUIRE(bytes[11] == 3);
  std::string v2 = bytes;
  v2[11] = 2;
  CHECK(crc32(std::string_view(v2).substr(0, 433)) == 0x2ebedb11u);
  for (int k = 0; k < 4; ++k) v2[433 + k] = char((0x2ebedb11u >> (8 * k)) & 0xff);
  CHECK(fnv1a64_hex(v2) == "4fc568bbdb8208ea");
}

// The run identity's hash (core/fnv1a.hpp): the published FNV-1a 64 test vectors.
TEST_CASE("FNV-1a 64 matches the reference values") {
  CHECK(fnv1a64("") == 0xcbf29ce484222325ULL);
  CHECK(fnv1a64("a") == 0xaf63dc4c8601ec8cULL);
  CHECK(fnv1a64("foobar") == 0x85944171f73967e8ULL);
  CHECK(fnv1a64_hex("") == "cbf29ce484222325");
  CHECK(fnv1a64_hex("foobar") == "85944171f73967e8");
}

TEST_CASE("checkpoint container: every section type round-trips bit for bit") {
  const CheckpointWriter w = every_type();
  const std::string bytes = w.bytes();
  CHECK(bytes.substr(0, 11) == "INVASIMCKPT");
  const CheckpointReader r = CheckpointReader::parse(bytes, "mem");
  CHECK(r.version() == kCheckpointVersion);
  CHECK(r.names().size() == w.n_sections());
  CHECK(r.names().front() == "raw");
  CHECK(r.get_bytes("raw") == std::string("a\0b", 3));
  CHECK(r.get_string("name") == "invasim run 7");
  CHECK(same_bits(r.get_f64("neg_zero"), -0.0));
  CHECK(same_bits(r.get_f64("nan"), std::bit_cast<double>(std::uint64_t(0x7ff8000000000123))));
  CHECK(same_bits(r.get_f64("denormal"), 4.9e-324));
  CHECK(r.get_u64("big") == 0xFEDCBA9876543210ull);
  CHECK(r.get_i64("negative") == -42);
  CHECK(same_bits(r.get_f64s("f64s"), {1.0 / 3.0, -1e300, 0.1}));
  CHECK(r.get_i32s("i32s") == std::vector<int>{-1, 0, 2147483647, -2147483647 - 1});
  CHECK(r.get_u64s("u64s") == std::vector<std::uint64_t>{0, ~0ull});
  CHECK(same_bits(r.get_vec3s("vec3s"), {Vec3(0.1, 0.2, 0.3), Vec3(-1, 1e-310, 7)}));
  CHECK(r.get_vec3is("vec3is") == std::vector<Vec3i>{Vec3i(-3, 0, 5)});
  CHECK(r.get_f64s("empty").empty());
  CHECK(r.type("vec3s") == SectionType::kVec3Array);
}

TEST_CASE("checkpoint container: missing sections, wrong types, duplicate names") {
  const CheckpointReader r = CheckpointReader::parse(every_type().bytes(), "'run.ckpt'");
  CHECK_THROWS_AS(r.get_f64("absent"), IoError);
  CHECK_THROWS_WITH(r.get_f64("absent"), "checkpoint 'run.ckpt': no section 'absent'");
  CHECK_THROWS_WITH(r.get_u64("f64s"),
                    "checkpoint 'run.ckpt': section 'f64s' holds f64 array, not u64");
  CheckpointWriter w;
  w.put_u64("x", 1);
  CHECK_THROWS_WITH(w.put_f64("x", 1.0), Contains("section 'x' is written twice"));
}

TEST_CASE("checkpoint files are written atomically and refused when damaged") {
  TempDir dir("ckpt");
  const auto path = dir / "run.ckpt";
  every_type().write(path);
  const std::string good = read_file(path);
  CHECK(CheckpointReader::read(path).get_i64("negative") == -42);
  const std::string where = "checkpoint '" + path.string() + "': ";

  SECTION("truncated at every length") {
    for (std::size_t n = 0; n < good.size(); ++n) {
      write_plain(path, good.substr(0, n));
      INFO("length " << n);
      CHECK_THROWS_AS(CheckpointReader::read(path), IoError);
      if (n == 0)
        CHECK_THROWS_WITH(CheckpointReader::read(path), where + "the file is empty");
      else if (n < kCheckpointHeaderSize)
        CHECK_THROWS_WITH(CheckpointReader::read(path), Contains(where + "truncated: "));
      else
        CHECK_THROWS_WITH(CheckpointReader::read(path), where + "truncated: " + std::to_string(n) +
                                                            " of " + std::to_string(good.size()) +
                                                            " bytes");
    }
  }
  SECTION("extended") {
    write_plain(path, good + "x");
    CHECK_THROWS_WITH(CheckpointReader::read(path), Contains(where + "corrupt: "));
  }
  SECTION("a flipped bit anywhere") {
    for (std::size_t byte = 0; byte < good.size(); ++byte) {
      std::string bad = good;
      bad[byte] = char(bad[byte] ^ (1 << (byte % 8)));
      INFO("byte " << byte);
      CHECK_THROWS_AS(CheckpointReader::parse(bad, "x"), IoError);
    }
    std::string bad = good;
    bad[good.size() / 2] ^= 0x10;  // inside the payloads
    write_plain(path, bad);
    CHECK_THROWS_WITH(
        CheckpointReader::read(path),
        Contains(where + "checksum mismatch (stored 0x") && Contains("the file is corrupt"));
  }
  SECTION("wrong magic") {
    std::string bad = good;
    bad.replace(0, 11, "INVASIMCKPX");
    write_plain(path, bad);
    CHECK_THROWS_WITH(CheckpointReader::read(path),
                      where +
                          "not an invasim checkpoint (wrong magic: it does not start with "
                          "\"INVASIMCKPT\")");
    write_plain(path, "hello");
    CHECK_THROWS_WITH(CheckpointReader::read(path), Contains("wrong magic"));
  }
  SECTION("wrong version") {
    std::string bad = good;
    bad[11] = 4;
    write_plain(path, bad);
    CHECK_THROWS_WITH(CheckpointReader::read(path),
                      where + "format version 4 is not supported (this build reads version 3)");
    // Version 2 (the Dynamics in positional arrays) is refused with the version it needs.
    bad[11] = 2;
    write_plain(path, bad);
    CHECK_THROWS_WITH(CheckpointReader::read(path),
                      where +
                          "format version 2 is not supported (this build reads version 3; "
                          "version 2 stored the Dynamics as positional arrays: continue it with "
                          "an invasim that reads version 2, or start that run again)");
    // Version 1 (before checkpoints carried their run's identity) is refused with the reason.
    bad[11] = 1;
    write_plain(path, bad);
    CHECK_THROWS_WITH(CheckpointReader::read(path),
                      where +
                          "format version 1 is not supported (this build reads version 3; older "
                          "checkpoints do not record the run that wrote them, so they cannot be "
                          "continued: start that run again)");
  }
  SECTION("missing file") {
    CHECK_THROWS_WITH(CheckpointReader::read(dir / "none.ckpt"),
                      Contains("cannot read '" + (dir / "none.ckpt").string() + "'"));
  }
}

namespace {

void check_same_system(const System& a, const System& b) {
  CHECK(a.box().lo() == b.box().lo());
  CHECK(a.box().hi() == b.box().hi());
  CHECK(a.box().periodic() == b.box().periodic());
  CHECK(a.box().version() == b.box().version());
  CHECK(a.seed() == b.seed());
  CHECK(a.step == b.step);
  CHECK(same_bits(a.time, b.time));
  const Sites &s = a.sites(), &t = b.sites();
  CHECK(same_bits(s.pos, t.pos));
  CHECK(same_bits(s.vel, t.vel));
  CHECK(same_bits(s.force, t.force));
  CHECK(same_bits(s.orient, t.orient));
  CHECK(s.image == t.image);
  CHECK(same_bits(s.diameter, t.diameter));
  CHECK(same_bits(s.mass, t.mass));
  CHECK(s.body == t.body);
  CHECK(s.kind == t.kind);
  REQUIRE(a.bodies().size() == b.bodies().size());
  for (std::size_t k = 0; k < a.bodies().size(); ++k) {
    const MeshBody &x = a.bodies()[k], &y = b.bodies()[k];
    CHECK(x.first_site == y.first_site);
    CHECK(x.topology->n_vertices() == y.topology->n_vertices());
    CHECK(x.topology->faces() == y.topology->faces());
    CHECK(same_bits(x.ref_area, y.ref_area));
    CHECK(same_bits(x.ref_volume, y.ref_volume));
    CHECK(same_bits(x.outer_volume, y.outer_volume));
  }
}

}  // namespace

TEST_CASE("a System with cells, 2 adipocytes and tethers is restored bit for bit") {
  TempDir dir("ckpt_system");
  const System sys = iotest::sample_system();
  REQUIRE(sys.box().version() == 2);
  TetherForce tethers(0.7);
  iotest::sample_tethers(sys, tethers);
  PressureWall wall;
  wall.pressure = 1.3e-3;
  wall.mass = 2.5;
  wall.gamma = 0.2;
  wall.kT = 1.0 / 7.0;
  wall.velocity = -1.0 / 3.0;
  wall.force = 0.017;

  CheckpointWriter w;
  write_system(w, sys);
  write_tethers(w, tethers);
  write_pressure_wall(w, wall);
  w.write(dir / "state.ckpt");
  const CheckpointReader r = CheckpointReader::read(dir / "state.ckpt");

  const System back = read_system(r);
  check_same_system(sys, back);
  // One topology object shared by both adipocytes (they use the same mesh).
  CHECK(back.bodies()[0].topology.get() == back.bodies()[1].topology.get());
  CHECK(r.get_i32s("system.topologies.n_vertices") == std::vector<int>{42});

  TetherForce t2(0.0);
  read_tethers(r, back, t2);
  CHECK(t2.stiffness() == 0.7);
  REQUIRE(t2.tethers().size() == 2);
  CHECK(t2.tethers()[1].a == 1);
  CHECK(t2.tethers()[1].b == 0);
  CHECK(same_bits(t2.tethers()[1].rest_length, 5.0 / 3.0));
  CHECK_THROWS_WITH(read_tethers(r, back, t2), Contains("already holds 2 tethers"));

  PressureWall w2;
  w2.walls = std::make_shared<WallForce>();
  read_pressure_wall(r, w2);
  CHECK(same_bits(w2.velocity, -1.0 / 3.0));
  CHECK(w2.pressure == 1.3e-3);
  CHECK(w2.mass == 2.5);
  CHECK(same_bits(w2.kT, 1.0 / 7.0));
  CHECK(w2.force == 0.017);
  CHECK(w2.walls != nullptr);

  CHECK_THROWS_WITH(read_system(r, "other"), Contains("no section 'other.box.lo'"));
}

TEST_CASE("a restored System runs on exactly like the original") {
  System a = iotest::sample_system();
  CheckpointWriter w;
  write_system(w, a);
  System b = read_system(CheckpointReader::parse(w.bytes(), "mem"));
  auto run = [](System& sys) {
    ForceField ff = test::standard_forces();
    auto tethers = std::make_shared<TetherForce>(0.5);
    iotest::sample_tethers(sys, *tethers);
    ff.add(tethers);
    Dynamics dyn(0.01);
    dyn.add(Method::langevin(sys.sites_of_kind(SiteKind::kCancer), 0.2, 0.05));
    dyn.add(Method::damped(sys.sites_of_kind(SiteKind::kVertex), 0.2));
    dyn.run(sys, ff, 20);
  };
  run(a);
  run(b);
  check_same_system(a, b);
}

TEST_CASE("sites slightly beyond a wall (allowed during a run) are restored") {
  System sys = iotest::sample_system(4);
  sys.sites().pos[0][0] = -0.2;  // validate() allows up to one diameter beyond the wall
  sys.sites().pos[1][0] = 12.1;
  CheckpointWriter w;
  write_system(w, sys);
  const System back = read_system(CheckpointReader::parse(w.bytes(), "mem"));
  check_same_system(sys, back);
}
