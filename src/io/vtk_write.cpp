// Writers of the VTK XML snapshot files (.vtp, .pvd); readers are in vtk_read.cpp.
#include "io/vtk_format.hpp"

#include "io/text_format.hpp"
#include "io/xml.hpp"

namespace invasim {

namespace {

constexpr const char* kHeader =
    "<?xml version=\"1.0\"?>\n"
    "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
    "header_type=\"UInt64\">\n"
    "  <PolyData>\n";
constexpr const char* kFooter = "  </PolyData>\n</VTKFile>\n";

// Opens a DataArray element (the caller writes values and closes it).
void open_array(std::string& out, const char* indent, const char* type, const char* name,
                int components, long tuples = -1) {
  out += indent;
  out += "<DataArray type=\"";
  out += type;
  out += "\" Name=\"";
  out += name;
  out += '"';
  if (components != 1) {
    out += " NumberOfComponents=\"";
    text::append(out, components);
    out += '"';
  }
  if (tuples >= 0) {
    out += " NumberOfTuples=\"";
    text::append(out, std::int64_t(tuples));
    out += '"';
  }
  out += " format=\"ascii\">\n";
}
void close_array(std::string& out, const char* indent) {
  out += indent;
  out += "</DataArray>\n";
}

// One line of an array of 3-vectors: the indent, then " x y z".
void vec3_line(std::string& out, const char* indent, const Vec3& x) {
  text::append_xyz(out += indent, x);
  out += '\n';
}

// A DataArray of 3-vectors, one per line.
void vec3_array(std::string& out, const char* indent, const char* name,
                const std::vector<Vec3>& v) {
  open_array(out, indent, "Float64", name, 3);
  for (const Vec3& x : v) vec3_line(out, indent, x);
  close_array(out, indent);
}

// A DataArray of scalars, several per line.
template <typename T>
void scalar_array(std::string& out, const char* indent, const char* type, const char* name,
                  const std::vector<T>& v) {
  open_array(out, indent, type, name, 1);
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i % 8 == 0) out += indent;
    out += ' ';
    text::append(out, v[i]);
    if (i % 8 == 7 || i + 1 == v.size()) out += '\n';
  }
  close_array(out, indent);
}

// Cell connectivity and offsets (end index of each cell, VTK's convention).
void cell_arrays(std::string& out, const char* element, const std::vector<std::int64_t>& conn,
                 const std::vector<std::int64_t>& offsets) {
  out += "      <";
  out += element;
  out += ">\n";
  scalar_array(out, "        ", "Int64", "connectivity", conn);
  scalar_array(out, "        ", "Int64", "offsets", offsets);
  out += "      </";
  out += element;
  out += ">\n";
}

// Box, time and step as FieldData, so a .vtp alone is a complete frame.
void field_data(std::string& out, const Frame& f) {
  const char* in = "      ";
  out += "    <FieldData>\n";
  open_array(out, in, "Float64", "TimeValue", 1, 1);
  out += in;
  text::append(out, f.time);
  out += '\n';
  close_array(out, in);
  open_array(out, in, "UInt64", "step", 1, 1);
  out += in;
  text::append(out, f.step);
  out += '\n';
  close_array(out, in);
  for (const auto& [name, v] : {std::pair{"box_lo", f.box.lo()}, std::pair{"box_hi", f.box.hi()}}) {
    open_array(out, in, "Float64", name, 3, 1);
    vec3_line(out, in, v);
    close_array(out, in);
  }
  open_array(out, in, "Int32", "periodic", 3, 1);
  out += in;
  for (int a = 0; a < 3; ++a) out += f.box.periodic(a) ? " 1" : " 0";
  out += '\n';
  close_array(out, in);
  out += "    </FieldData>\n";
}

void piece_open(std::string& out, std::size_t points, std::size_t verts, std::size_t polys) {
  out += "    <Piece NumberOfPoints=\"";
  text::append(out, std::uint64_t(points));
  out += "\" NumberOfVerts=\"";
  text::append(out, std::uint64_t(verts));
  out += "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"";
  text::append(out, std::uint64_t(polys));
  out += "\">\n";
}

}  // namespace

std::string adipocytes_vtp_text(const Frame& f) {
  const MeshFrame& m = f.meshes;
  std::string out = kHeader;
  field_data(out, f);
  piece_open(out, m.points.size(), 0, m.triangles.size());
  out += "      <PointData Scalars=\"radius\">\n";
  scalar_array(out, "        ", "Float64", "radius", m.point_radius);
  out += "      </PointData>\n      <CellData Scalars=\"adipocyte\">\n";
  scalar_array(out, "        ", "Int32", "adipocyte", m.triangle_body);
  scalar_array(out, "        ", "Float64", "shape_parameter", m.triangle_shape);
  out += "      </CellData>\n      <Points>\n";
  vec3_array(out, "        ", "Points", m.points);
  out += "      </Points>\n";
  std::vector<std::int64_t> conn, offsets;
  for (const auto& t : m.triangles) {
    conn.insert(conn.end(), t.begin(), t.end());
    offsets.push_back(std::int64_t(conn.size()));
  }
  cell_arrays(out, "Polys", conn, offsets);
  out += "    </Piece>\n";
  out += kFooter;
  return out;
}

std::string spheres_vtp_text(const Frame& f) {
  const CellFrame& c = f.cells;
  std::string out = kHeader;
  field_data(out, f);
  piece_open(out, c.size(), c.size(), 0);
  out += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  scalar_array(out, "        ", "Float64", "radius", c.radius);
  vec3_array(out, "        ", "velocity", c.vel);
  vec3_array(out, "        ", "orientation", c.orient);
  if (!c.id.empty()) scalar_array(out, "        ", "UInt64", "id", c.id);
  out += "      </PointData>\n      <Points>\n";
  vec3_array(out, "        ", "Points", c.pos);
  out += "      </Points>\n";
  std::vector<std::int64_t> conn(c.size()), offsets(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) {
    conn[i] = std::int64_t(i);
    offsets[i] = std::int64_t(i + 1);
  }
  cell_arrays(out, "Verts", conn, offsets);
  out += "    </Piece>\n";
  out += kFooter;
  return out;
}

std::string pvd_text(const std::vector<PvdEntry>& entries) {
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const PvdEntry& e : entries) {
    out += "    <DataSet timestep=\"";
    text::append(out, e.time);
    out += "\" group=\"\" part=\"0\" file=\"";
    out += xml_escape(e.file);
    out += "\"/>\n";
  }
  out += "  </Collection>\n</VTKFile>\n";
  return out;
}

}  // namespace invasim
