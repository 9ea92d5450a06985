// Hostile files: every reader of a user-named file bounds its recursion, counts and
// sizes and refuses non-regular files, with an IoError naming the file and the problem, instead
// of crashing, hanging or allocating without bound. Each case was a crash or hang before.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <ctime>

#include "../io/io_test_support.hpp"
#include "checkpoint/checkpoint_file.hpp"
#include "checkpoint/lua_data.hpp"
#include "checkpoint/state_checkpoint.hpp"
#include "io/atomic_file.hpp"
#include "io/crc32.hpp"
#include "io/regular_file.hpp"
#include "io/vtk_format.hpp"

using namespace invasim;
using Catch::Matchers::Contains;
using iotest::TempDir;

namespace {

std::string nested(const char* outer, int depth) {
  std::string s = std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"") + outer + "\">";
  for (int i = 0; i < depth; ++i) s += "<a>";
  for (int i = 0; i < depth; ++i) s += "</a>";
  return s + "</VTKFile>\n";
}

// A checkpoint with the little-endian integer at the start of section `name`'s payload
// replaced (`bytes` wide) and the length and CRC recomputed, as a crafted file would be.
std::string crafted(std::string file, const std::string& name, std::uint64_t value, int bytes) {
  const std::size_t at = file.find(name);
  REQUIRE(at != std::string::npos);
  const std::size_t payload = at + name.size() + 1 + 8;
  for (int k = 0; k < bytes; ++k) file[payload + k] = char((value >> (8 * k)) & 0xFF);
  const std::uint32_t crc = crc32(std::string_view(file).substr(0, file.size() - 4));
  for (int k = 0; k < 4; ++k) file[file.size() - 4 + k] = char((crc >> (8 * k)) & 0xFF);
  return file;
}

std::string system_checkpoint() {
  CheckpointWriter w;
  write_system(w, iotest::sample_system());
  return w.bytes();
}

}  // namespace

TEST_CASE("hostile VTK: deeply nested XML is refused with the file, line and limit") {
  for (const char* type : {"PolyData", "Collection"}) {
    const std::string text = nested(type, 200000);  // recursion depth of a naive reader
    CHECK_THROWS_WITH(parse_vtp(text, "'deep.vtp'"),
                      Contains("'deep.vtp': line 2: XML elements nested deeper than 64 levels"));
    CHECK_THROWS_WITH(parse_pvd(text, "'deep.pvd'"), Contains("nested deeper than 64"));
  }
  CHECK_THROWS_WITH(parse_vtp(nested("PolyData", 60), "'ok.vtp'"), Contains("not a VTK PolyData"));
}

TEST_CASE("hostile VTK: a DataArray's NumberOfTuples cannot contradict the Piece (was SIGSEGV)") {
  const Frame frame = frame_from_system(iotest::sample_system());
  std::string text = spheres_vtp_text(frame);
  const std::size_t points = text.find("NumberOfPoints=\"");
  REQUIRE(points != std::string::npos);
  text.replace(points, text.find('"', points + 16) + 1 - points, "NumberOfPoints=\"50000000\"");
  const std::size_t array = text.find("<DataArray", text.find("<Points>"));
  const std::size_t data = text.find('>', array) + 1;
  text.erase(data, text.find("</DataArray>", data) - data);  // no values at all
  text.insert(array + 10, " NumberOfTuples=\"0\"");
  // A Points DataArray stating 0 tuples was believed, and 50000000 points read past its end.
  CHECK_THROWS_WITH(parse_vtp(text, "'cells.vtp'"),
                    Contains("NumberOfTuples=\"0\" where the Piece declares 50000000"));
}

TEST_CASE("hostile VTK: values that would be undefined to convert are refused") {
  const Frame frame = frame_from_system(iotest::sample_system());
  std::string text = adipocytes_vtp_text(frame);
  const std::size_t body = text.find("Name=\"adipocyte\"");
  REQUIRE(body != std::string::npos);
  const std::size_t data = text.find_first_not_of(" \n", text.find('>', body) + 1);
  text.replace(data, text.find_first_of(" \n<", data) - data, "1e300");
  const VtpData vtp = parse_vtp(text, "'meshes.vtp'");
  CHECK_THROWS_WITH(mesh_frame_from_vtp(vtp, "'meshes.vtp'"),
                    Contains("CellData adipocyte holds 1e+300, not a body index"));
}

TEST_CASE("hostile checkpoint: a crafted box version is restored without a loop (was a hang)") {
  const std::string file =
      crafted(system_checkpoint(), "system.box.version", 0x7FFFFFFFFFFFFFFFull, 8);
  // CPU time of this process, not wall time (a loaded machine stretches the latter): the
  // loop of 2^63 replays this guards against would take forever.
  const std::clock_t start = std::clock();
  const System sys = read_system(CheckpointReader::parse(file, "'crafted.ckpt'"));
  CHECK(sys.box().version() == 0x7FFFFFFFFFFFFFFFull);
  CHECK(double(std::clock() - start) / CLOCKS_PER_SEC < 5.0);
}

TEST_CASE("hostile checkpoint: a topology's vertex count is bounded by the stored sites") {
  const std::string file =
      crafted(system_checkpoint(), "system.topologies.n_vertices", 0x7FFFFFFF, 4);
  CHECK_THROWS_WITH(read_system(CheckpointReader::parse(file, "'crafted.ckpt'")),
                    Contains("checkpoint 'crafted.ckpt': section 'system.topologies.n_vertices': "
                             "topology 0 has 2147483647 vertices, outside [0, "));
}

TEST_CASE("hostile checkpoint: the protocol state is parsed as data, never run") {
  const std::string origin = "checkpoint 'x.ckpt': section 'extra'";
  // What protocols/lib/resume.lua's serialize writes comes back with its subtypes.
  const LuaDatum d = parse_lua_data(
      "{[1]=-9223372036854775807,[2]=0x1.8p+1,[3]=-0x0p+0,[4]=\"a\\\"b\\\nc\\0011\\0\","
      "[\"k\"]={[true]=false,[false]=math.huge},[\"m\"]=-math.huge,[\"n\"]=0/0,"
      "[\"big\"]=9223372036854775808}",
      origin);
  REQUIRE(d.kind == LuaDatum::Kind::kTable);
  REQUIRE(d.entries.size() == 8);
  CHECK(d.entries[0].second.kind == LuaDatum::Kind::kInteger);
  CHECK(d.entries[0].second.integer == -9223372036854775807LL);
  CHECK(d.entries[1].second.number == 3.0);
  CHECK(std::signbit(d.entries[2].second.number));
  CHECK(d.entries[3].second.string == std::string("a\"b\nc\0011\0", 8));
  CHECK(d.entries[4].second.entries[1].second.number == HUGE_VAL);
  CHECK(d.entries[6].second.number != d.entries[6].second.number);
  CHECK(d.entries[7].second.kind == LuaDatum::Kind::kNumber);  // overflows: a float, as in Lua
  // Code that would loop or allocate forever is not data.
  CHECK_THROWS_WITH(parse_lua_data("(function() while true do end end)()", origin),
                    Contains(origin + ": line 1 (offset 0): unexpected character '('"));
  CHECK_THROWS_WITH(parse_lua_data("{[1]=(\"x\"):rep(1 << 40)}", origin),
                    Contains("unexpected character '('"));
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "{[1]=";
  CHECK_THROWS_WITH(parse_lua_data(deep, origin), Contains("tables nested deeper than 100 levels"));
  CHECK_THROWS_WITH(parse_lua_data("{[0/0]=1}", origin), Contains("a table key is NaN"));
}

TEST_CASE("hostile files: a FIFO, a directory or a device is refused before it blocks") {
  TempDir dir("hostile_fifo");
  const auto fifo = dir / "state.ckpt";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);  // no writer: an open() for reading would block
  CHECK_THROWS_WITH(read_file(fifo), Contains("cannot read '" + fifo.string() +
                                              "': it is a FIFO (named pipe), not a regular file"));
  CHECK_THROWS_WITH(CheckpointReader::read(fifo), Contains("FIFO"));
  CHECK_THROWS_WITH(read_vtp(fifo), Contains("FIFO"));
  CHECK_THROWS_WITH(read_pvd(dir.path()), Contains("it is a directory"));
  CHECK_THROWS_WITH(read_file("/dev/zero"), Contains("it is a character device"));
  CHECK_THROWS_WITH(require_regular_file(fifo, "protocol file"),
                    Contains("cannot read protocol file '" + fifo.string() + "': it is a FIFO"));
}
