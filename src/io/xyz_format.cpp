#include "io/xyz_format.hpp"

#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/io_error.hpp"
#include "io/text_format.hpp"

namespace invasim {

namespace {

// Reads lines one at a time from a text, counting them for error messages.
class LineReader {
 public:
  LineReader(std::string_view text, const std::string& origin) : text_(text), origin_(origin) {}
  bool at_end() const { return pos_ >= text_.size(); }
  std::size_t line_number() const { return line_; }
  std::string_view next() {
    if (at_end()) fail_io(origin_, ": unexpected end of file after line ", line_);
    const std::size_t end = text_.find('\n', pos_);
    std::string_view line = text_.substr(pos_, end == std::string_view::npos ? end : end - pos_);
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    ++line_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }

 private:
  std::string_view text_;
  const std::string& origin_;
  std::size_t pos_ = 0, line_ = 0;
};

std::size_t parse_count(std::string_view line, const LineReader& in, const std::string& origin) {
  std::vector<std::string_view> tok;
  text::split_whitespace(line, tok);
  const auto n = tok.size() == 1 ? text::parse<std::size_t>(tok[0]) : std::nullopt;
  if (!n) fail_io(origin, ": line ", in.line_number(), ": expected the number of particles");
  return *n;
}

// Parses a whitespace-separated list of exactly `n` numbers from a comment value.
std::vector<double> parse_numbers(const std::string& value, std::size_t n, const char* key,
                                  const std::string& origin) {
  std::vector<std::string_view> tok;
  text::split_whitespace(value, tok);
  std::vector<double> out;
  for (auto t : tok)
    if (auto v = text::parse<double>(t)) out.push_back(*v);
  if (out.size() != n || tok.size() != n)
    fail_io(origin, ": ", key, "=\"", value, "\" must hold ", n, " numbers");
  return out;
}

// Column layout from the Properties value: the first column of each named property.
struct Columns {
  int species = -1, pos = -1, radius = -1, velo = -1, orient = -1;
  int count = 0;
};

Columns parse_properties(const std::string& value, const std::string& origin) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t colon = value.find(':', start);
    fields.push_back(value.substr(start, colon == std::string::npos ? colon : colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  if (fields.size() % 3 != 0)
    fail_io(origin, ": Properties=", value, " is not a list of name:type:columns triples");
  Columns c;
  for (std::size_t k = 0; k < fields.size(); k += 3) {
    const auto n = text::parse<int>(fields[k + 2]);
    if (!n || *n < 1) fail_io(origin, ": Properties=", value, ": bad column count for ", fields[k]);
    // A row's numbers are allocated from the count before any row is read: bounded.
    constexpr int kMaxColumns = 1024;
    if (*n > kMaxColumns - c.count)
      fail_io(origin, ": Properties=", value, ": more than ", kMaxColumns, " columns in all");
    const std::string& name = fields[k];
    auto expect = [&](int want, int& slot) {
      if (*n != want)
        fail_io(origin, ": property ", name, " has ", *n, " columns, expected ", want);
      slot = c.count;
    };
    if (name == "species") expect(1, c.species);
    if (name == "pos") expect(3, c.pos);
    if (name == "radius") expect(1, c.radius);
    if (name == "velo") expect(3, c.velo);
    if (name == "orient") expect(3, c.orient);
    c.count += *n;
  }
  if (c.pos < 0) fail_io(origin, ": Properties=", value, " has no pos column");
  return c;
}

Box parse_box(const std::map<std::string, std::string>& kv, const std::string& origin) {
  const auto lattice = kv.find("Lattice");
  if (lattice == kv.end()) fail_io(origin, ": the comment line has no Lattice=\"...\"");
  const std::vector<double> m = parse_numbers(lattice->second, 9, "Lattice", origin);
  for (int i : {1, 2, 3, 5, 6, 7})
    if (m[i] != 0.0) fail_io(origin, ": Lattice is not orthorhombic (off-diagonal entries)");
  Vec3 lo = Vec3::Zero();
  if (auto o = kv.find("Origin"); o != kv.end()) {
    const std::vector<double> v = parse_numbers(o->second, 3, "Origin", origin);
    lo = Vec3(v[0], v[1], v[2]);
  }
  std::array<bool, 3> periodic{true, true, true};
  if (auto p = kv.find("pbc"); p != kv.end()) {
    std::vector<std::string_view> tok;
    text::split_whitespace(p->second, tok);
    if (tok.size() != 3) fail_io(origin, ": pbc=\"", p->second, "\" must hold 3 flags");
    for (int a = 0; a < 3; ++a) {
      if (tok[a] != "T" && tok[a] != "F")
        fail_io(origin, ": pbc=\"", p->second, "\": flags must be T or F");
      periodic[a] = tok[a] == "T";
    }
  }
  try {
    return Box(lo, lo + Vec3(m[0], m[4], m[8]), periodic);
  } catch (const InputError& e) {
    fail_io(origin, ": ", e.what());
  }
}

}  // namespace

std::string xyz_frame_text(const Frame& frame) {
  const CellFrame& c = frame.cells;
  const Vec3 L = frame.box.lengths();
  const Vec3& lo = frame.box.lo();
  std::string out;
  out.reserve(64 * (c.size() + 4));
  text::append(out, std::uint64_t(c.size()));
  out += "\nLattice=\"";
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      if (a + b > 0) out += ' ';
      text::append(out, a == b ? L[a] : 0.0);
    }
  out += "\" Origin=\"";
  for (int a = 0; a < 3; ++a) {
    if (a) out += ' ';
    text::append(out, lo[a]);
  }
  out += "\" Properties=";
  out += kXyzProperties;
  if (!c.id.empty()) out += ":id:I:1";
  out += " pbc=\"";
  for (int a = 0; a < 3; ++a) {
    if (a) out += ' ';
    out += frame.box.periodic(a) ? 'T' : 'F';
  }
  out += "\" Time=";
  text::append(out, frame.time);
  out += " Step=";
  text::append(out, frame.step);
  out += '\n';
  for (std::size_t i = 0; i < c.size(); ++i) {
    out += 'C';
    text::append_xyz(out, c.pos[i]);
    out += ' ';
    text::append(out, c.radius[i]);
    text::append_xyz(out, c.vel[i]);
    text::append_xyz(out, c.orient[i]);
    if (!c.id.empty()) {
      out += ' ';
      text::append(out, c.id[i]);
    }
    out += '\n';
  }
  return out;
}

std::map<std::string, std::string> parse_xyz_comment(std::string_view line) {
  std::map<std::string, std::string> kv;
  std::size_t i = 0;
  auto space = [&](std::size_t k) { return line[k] == ' ' || line[k] == '\t'; };
  while (i < line.size()) {
    while (i < line.size() && space(i)) ++i;
    const std::size_t key_start = i;
    while (i < line.size() && line[i] != '=' && !space(i)) ++i;
    const std::string key(line.substr(key_start, i - key_start));
    if (i >= line.size() || line[i] != '=') {  // a bare word: a flag without a value
      if (!key.empty()) kv[key] = "";
      continue;
    }
    ++i;
    std::size_t value_start = i, value_end;
    if (i < line.size() && line[i] == '"') {
      value_start = ++i;
      while (i < line.size() && line[i] != '"') ++i;
      value_end = i;
      if (i < line.size()) ++i;
    } else {
      while (i < line.size() && !space(i)) ++i;
      value_end = i;
    }
    kv[key] = std::string(line.substr(value_start, value_end - value_start));
  }
  return kv;
}

Frame parse_xyz(std::string_view text, const std::string& origin, std::size_t index) {
  LineReader in(text, origin);
  for (std::size_t skip = 0; skip < index; ++skip) {
    if (in.at_end()) fail_io(origin, ": has only ", skip, " frames, frame ", index, " requested");
    const std::size_t n = parse_count(in.next(), in, origin);
    for (std::size_t k = 0; k < n + 1; ++k) in.next();
  }
  if (in.at_end()) fail_io(origin, ": no frame ", index, " (empty file or too few frames)");
  const std::size_t n = parse_count(in.next(), in, origin);
  const std::size_t count_line = in.line_number();
  const auto kv = parse_xyz_comment(in.next());
  Frame f;
  f.box = parse_box(kv, origin);
  const auto props = kv.find("Properties");
  const Columns col =
      parse_properties(props == kv.end() ? "species:S:1:pos:R:3" : props->second, origin);
  if (auto t = kv.find("Time"); t != kv.end()) {
    const auto v = text::parse<double>(t->second);
    if (!v) fail_io(origin, ": Time=", t->second, " is not a number");
    f.time = *v;
  }
  if (auto s = kv.find("Step"); s != kv.end()) {
    const auto v = text::parse<std::uint64_t>(s->second);
    if (!v) fail_io(origin, ": Step=", s->second, " is not a non-negative integer");
    f.step = *v;
  }
  CellFrame& c = f.cells;
  std::vector<std::string_view> tok;
  std::vector<double> num(col.count);
  auto rows_text = [](std::size_t rows) {
    return std::to_string(rows) + (rows == 1 ? " row" : " rows");
  };
  const std::string says = std::to_string(n) + (n == 1 ? " particle" : " particles");
  auto fewer_rows = [&](std::size_t rows, const char* where) {
    fail_io(origin, ": line ", count_line, " says ", says, ", but the frame has ", rows_text(rows),
            " (", where, in.line_number(), ")");
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (in.at_end()) fewer_rows(i, "the file ends after line ");
    text::split_whitespace(in.next(), tok);
    if (col.count > 1 && tok.size() == 1 && text::parse<std::size_t>(tok[0]))
      fewer_rows(i, "the next frame's count line is line ");
    if (int(tok.size()) != col.count)
      fail_io(origin, ": line ", in.line_number(), ": ", tok.size(), " columns, expected ",
              col.count);
    for (int k = 0; k < col.count; ++k) {
      if (k == col.species) continue;
      const auto v = text::parse<double>(tok[k]);
      if (!v)
        fail_io(origin, ": line ", in.line_number(), ": column ", k + 1, " '", tok[k],
                "' is not a number");
      num[k] = *v;
    }
    auto vec = [&](int first) {
      return first < 0 ? Vec3(Vec3::Zero()) : Vec3(num[first], num[first + 1], num[first + 2]);
    };
    c.pos.push_back(vec(col.pos));
    c.radius.push_back(col.radius < 0 ? 0.5 : num[col.radius]);
    c.vel.push_back(vec(col.velo));
    c.orient.push_back(vec(col.orient));
  }
  // What follows the rows: nothing (blank lines), or the next frame's count line.
  LineReader rest = in;
  std::size_t extra = 0, first_extra = 0;
  while (!rest.at_end()) {
    text::split_whitespace(rest.next(), tok);
    if (tok.empty()) continue;
    if (tok.size() == 1 && text::parse<std::size_t>(tok[0])) break;  // the next frame
    if (extra++ == 0) first_extra = rest.line_number();
  }
  if (extra > 0)
    fail_io(origin, ": line ", count_line, " says ", says, ", but the frame has ",
            rows_text(n + extra), " (", extra, " more from line ", first_extra, ")");
  return f;
}

Frame read_xyz(const std::filesystem::path& path, std::size_t index) {
  return parse_xyz(read_file(path), quoted(path), index);
}

}  // namespace invasim
