// Readers of the VTK XML snapshot files this layer writes (.vtp, .pvd), on the parsed XML of
// io/xml.hpp (pugixml).
#include "io/vtk_format.hpp"

#include <cmath>
#include <cstring>
#include <optional>

#include "io/atomic_file.hpp"
#include "io/io_error.hpp"
#include "io/text_format.hpp"
#include "io/xml.hpp"

namespace invasim {

namespace {

// The value of attribute `key` of `node`, or nullopt.
std::optional<std::string_view> attr(pugi::xml_node node, const char* key) {
  const pugi::xml_attribute a = node.attribute(key);
  if (!a) return std::nullopt;
  return std::string_view(a.value());
}

bool named(pugi::xml_node node, const char* name) {
  return std::strcmp(node.name(), name) == 0;
}

std::string cat_count(const char* text, long n) {
  return text + std::to_string(n);
}

// `v` as an integer in [lo, hi], or nullopt (NaN, fractions and values out of range, which
// would be undefined behaviour to convert).
std::optional<std::int64_t> integral(double v, double lo, double hi) {
  if (!(v >= lo && v <= hi) || v != std::floor(v)) return std::nullopt;
  return std::int64_t(v);
}

}  // namespace

std::vector<PvdEntry> read_pvd(const std::filesystem::path& path) {
  return parse_pvd(read_file(path), quoted(path));
}

std::vector<PvdEntry> parse_pvd(std::string_view text, const std::string& origin) {
  const XmlDocument xml(text, origin);
  const pugi::xml_node root = xml.root();
  const auto type = attr(root, "type");
  const pugi::xml_node coll = root.child("Collection");
  if (!named(root, "VTKFile") || type != "Collection" || !coll)
    fail_io(origin, ": not a VTK collection (.pvd) file");
  std::vector<PvdEntry> out;
  for (pugi::xml_node d : coll.children("DataSet")) {
    const auto t = attr(d, "timestep");
    const auto file = attr(d, "file");
    const auto time = t ? text::parse<double>(*t) : std::nullopt;
    if (!time || !file)
      fail_io(origin, ": line ", xml.line(d), ": DataSet needs a numeric timestep and a file");
    out.push_back({*time, std::string(*file)});
  }
  return out;
}

namespace {

// Parses one DataArray; checks its size against `tuples` (if >= 0).
VtpData::Array parse_array(const XmlDocument& xml, pugi::xml_node e, long tuples) {
  const std::string& origin = xml.origin();
  VtpData::Array a;
  const std::string label(attr(e, "Name").value_or("(unnamed)"));
  if (const auto t = attr(e, "type")) a.type = *t;
  if (attr(e, "format") != "ascii")
    fail_io(origin, ": line ", xml.line(e), ": DataArray ", label, " is not in ascii format");
  if (const auto c = attr(e, "NumberOfComponents")) {
    const auto n = text::parse<int>(*c);
    if (!n || *n < 1) fail_io(origin, ": line ", xml.line(e), ": bad NumberOfComponents");
    a.components = *n;
  }
  // A stated NumberOfTuples must agree with the count the caller expects: it never replaces
  // it (a Points array claiming 0 tuples of a 5-point Piece would leave points unread).
  if (const auto nt = attr(e, "NumberOfTuples")) {
    const auto n = text::parse<long>(*nt);
    if (!n || *n < 0 || (tuples >= 0 && *n != tuples))
      fail_io(origin, ": line ", xml.line(e), ": DataArray ", label, " NumberOfTuples=\"", *nt,
              "\"", tuples >= 0 ? cat_count(" where the Piece declares ", tuples) : "",
              " is not a valid count");
    tuples = *n;
  }
  const std::string data = xml_text(e);
  std::vector<std::string_view> tok;
  text::split_whitespace(data, tok);
  a.values.reserve(tok.size());
  for (auto t : tok) {
    const auto v = text::parse<double>(t);
    if (!v)
      fail_io(origin, ": line ", xml.line(e), ": DataArray ", label, ": '", t, "' is not a number");
    a.values.push_back(*v);
  }
  // Compared by division: tuples x components could overflow.
  if (tuples >= 0 && (a.values.size() % std::size_t(a.components) != 0 ||
                      a.values.size() / std::size_t(a.components) != std::size_t(tuples)))
    fail_io(origin, ": line ", xml.line(e), ": DataArray ", label, " has ", a.values.size(),
            " values, expected ", tuples, " x ", a.components);
  return a;
}

void parse_named_arrays(const XmlDocument& xml, pugi::xml_node parent, long tuples,
                        std::map<std::string, VtpData::Array>& out) {
  if (!parent) return;
  for (pugi::xml_node e : parent.children("DataArray")) {
    const auto name = attr(e, "Name");
    if (!name) fail_io(xml.origin(), ": line ", xml.line(e), ": DataArray without a Name");
    out[std::string(*name)] = parse_array(xml, e, tuples);
  }
}

std::vector<std::int64_t> to_indices(const VtpData::Array& a, const std::string& what,
                                     const std::string& origin) {
  std::vector<std::int64_t> out;
  out.reserve(a.values.size());
  for (double v : a.values) {
    const auto i = integral(v, 0, 9.0e18);
    if (!i) fail_io(origin, ": ", what, " holds a non-index value ", v);
    out.push_back(*i);
  }
  return out;
}

// Connectivity and offsets of a Verts / Polys element with `count` cells.
void parse_cells(const XmlDocument& xml, pugi::xml_node piece, const char* element, long count,
                 std::vector<std::int64_t>& conn, std::vector<std::int64_t>& offsets) {
  const std::string& origin = xml.origin();
  const pugi::xml_node e = piece.child(element);
  if (!e) {
    if (count > 0) fail_io(origin, ": Piece declares ", count, " ", element, " but has none");
    return;
  }
  std::map<std::string, VtpData::Array> arrays;
  parse_named_arrays(xml, e, -1, arrays);
  if (!arrays.count("connectivity") || !arrays.count("offsets"))
    fail_io(origin, ": ", element, " needs connectivity and offsets arrays");
  conn = to_indices(arrays["connectivity"], std::string(element) + " connectivity", origin);
  offsets = to_indices(arrays["offsets"], std::string(element) + " offsets", origin);
  if (long(offsets.size()) != count)
    fail_io(origin, ": ", element, ": ", offsets.size(), " offsets for ", count, " cells");
  std::int64_t prev = 0;
  for (std::int64_t o : offsets) {
    if (o < prev || o > std::int64_t(conn.size()))
      fail_io(origin, ": ", element, ": offsets are not increasing within the connectivity");
    prev = o;
  }
  if (!offsets.empty() && offsets.back() != std::int64_t(conn.size()))
    fail_io(origin, ": ", element, ": the last offset does not end the connectivity");
}

long count_attr(pugi::xml_node piece, const char* key, const std::string& origin) {
  const auto v = attr(piece, key);
  if (!v) return 0;
  const auto n = text::parse<long>(*v);
  if (!n || *n < 0) fail_io(origin, ": Piece ", key, "=\"", *v, "\" is not a count");
  return *n;
}

// Box, time and step from the FieldData written by field_data().
void frame_header_from_vtp(const VtpData& vtp, const std::string& origin, Frame& f) {
  auto field = [&](const char* name, std::size_t n) -> const std::vector<double>& {
    const auto it = vtp.field_data.find(name);
    if (it == vtp.field_data.end() || it->second.values.size() != n)
      fail_io(origin, ": FieldData ", name, " (", n, " values) is missing");
    return it->second.values;
  };
  const auto& lo = field("box_lo", 3);
  const auto& hi = field("box_hi", 3);
  const auto& per = field("periodic", 3);
  try {
    f.box = Box(Vec3(lo[0], lo[1], lo[2]), Vec3(hi[0], hi[1], hi[2]),
                {per[0] != 0, per[1] != 0, per[2] != 0});
  } catch (const InputError& e) {
    fail_io(origin, ": ", e.what());
  }
  f.time = field("TimeValue", 1)[0];
  const double step = field("step", 1)[0];
  const auto s = integral(step, 0, 9.0e18);
  if (!s) fail_io(origin, ": FieldData step ", step, " is not a step number");
  f.step = std::uint64_t(*s);
}

}  // namespace

VtpData parse_vtp(std::string_view text, const std::string& origin) {
  const XmlDocument xml(text, origin);
  const pugi::xml_node root = xml.root();
  const pugi::xml_node poly = root.child("PolyData");
  if (!named(root, "VTKFile") || attr(root, "type") != "PolyData" || !poly)
    fail_io(origin, ": not a VTK PolyData (.vtp) file");
  const auto pieces = poly.children("Piece");
  const auto n_pieces = std::distance(pieces.begin(), pieces.end());
  if (n_pieces != 1) fail_io(origin, ": expected one Piece, found ", n_pieces);
  const pugi::xml_node piece = *pieces.begin();
  VtpData out;
  parse_named_arrays(xml, poly.child("FieldData"), -1, out.field_data);
  const long n_points = count_attr(piece, "NumberOfPoints", origin);
  const long n_verts = count_attr(piece, "NumberOfVerts", origin);
  const long n_polys = count_attr(piece, "NumberOfPolys", origin);
  if (count_attr(piece, "NumberOfLines", origin) || count_attr(piece, "NumberOfStrips", origin))
    fail_io(origin, ": lines and strips are not supported");
  const pugi::xml_node pts_array = piece.child("Points").child("DataArray");
  if (!pts_array) fail_io(origin, ": Piece has no Points DataArray");
  const VtpData::Array p = parse_array(xml, pts_array, n_points);
  if (p.components != 3) fail_io(origin, ": Points must have 3 components");
  for (long i = 0; i < n_points; ++i)
    out.points.emplace_back(p.values[3 * i], p.values[3 * i + 1], p.values[3 * i + 2]);
  parse_named_arrays(xml, piece.child("PointData"), n_points, out.point_data);
  parse_named_arrays(xml, piece.child("CellData"), n_verts + n_polys, out.cell_data);
  parse_cells(xml, piece, "Verts", n_verts, out.vert_connectivity, out.vert_offsets);
  parse_cells(xml, piece, "Polys", n_polys, out.poly_connectivity, out.poly_offsets);
  if (n_points > 2147483647L) fail_io(origin, ": ", n_points, " points exceed the limit 2^31 - 1");
  for (auto c : {&out.vert_connectivity, &out.poly_connectivity})
    for (std::int64_t i : *c)
      if (i >= n_points) fail_io(origin, ": connectivity refers to point ", i, " of ", n_points);
  return out;
}

VtpData read_vtp(const std::filesystem::path& path) {
  return parse_vtp(read_file(path), quoted(path));
}

Frame mesh_frame_from_vtp(const VtpData& vtp, const std::string& origin) {
  Frame f;
  frame_header_from_vtp(vtp, origin, f);
  MeshFrame& m = f.meshes;
  m.points = vtp.points;
  std::int64_t start = 0;
  for (std::int64_t end : vtp.poly_offsets) {
    if (end - start != 3)
      fail_io(origin, ": a poly with ", end - start, " points is not a triangle");
    const auto* c = &vtp.poly_connectivity[start];
    m.triangles.push_back({int(c[0]), int(c[1]), int(c[2])});
    start = end;
  }
  const auto body = vtp.cell_data.find("adipocyte");
  const auto shape = vtp.cell_data.find("shape_parameter");
  if (body == vtp.cell_data.end() || shape == vtp.cell_data.end())
    fail_io(origin, ": CellData needs the arrays adipocyte and shape_parameter");
  // One value per triangle: the file's CellData counts Verts too.
  if (body->second.values.size() != m.triangles.size() ||
      shape->second.values.size() != m.triangles.size())
    fail_io(origin, ": CellData adipocyte and shape_parameter need one value per triangle (",
            m.triangles.size(), ")");
  for (double b : body->second.values) {
    const auto k = integral(b, 0, 2147483647.0);
    if (!k) fail_io(origin, ": CellData adipocyte holds ", b, ", not a body index");
    m.triangle_body.push_back(int(*k));
  }
  m.triangle_shape = shape->second.values;
  const auto radius = vtp.point_data.find("radius");  // optional: 0 when absent
  m.point_radius = radius != vtp.point_data.end() && radius->second.components == 1
                       ? radius->second.values
                       : std::vector<double>(m.points.size(), 0.0);
  return f;
}

Frame cell_frame_from_vtp(const VtpData& vtp, const std::string& origin) {
  Frame f;
  frame_header_from_vtp(vtp, origin, f);
  CellFrame& c = f.cells;
  auto array = [&](const char* name, int components) -> const std::vector<double>& {
    const auto it = vtp.point_data.find(name);
    if (it == vtp.point_data.end() || it->second.components != components)
      fail_io(origin, ": PointData needs the array ", name, " with ", components, " components");
    return it->second.values;
  };
  const auto& radius = array("radius", 1);
  const auto& vel = array("velocity", 3);
  const auto& orient = array("orientation", 3);
  c.pos = vtp.points;
  c.radius = radius;
  for (std::size_t i = 0; i < c.pos.size(); ++i) {
    c.vel.emplace_back(vel[3 * i], vel[3 * i + 1], vel[3 * i + 2]);
    c.orient.emplace_back(orient[3 * i], orient[3 * i + 1], orient[3 * i + 2]);
  }
  return f;
}

}  // namespace invasim
