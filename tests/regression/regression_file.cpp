#include "regression_file.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "core/errors.hpp"
#include "forces/contact_force.hpp"
#include "forces/shape_force.hpp"
#include "forces/tether_force.hpp"
#include "forces/wall_force.hpp"

namespace invasim::regression {

namespace {

// Splits a line into whitespace-separated words; the caller knows the expected count.
struct Line {
  const std::string& path;
  int number;
  std::vector<std::string> words;

  [[noreturn]] void fail(const std::string& what) const {
    fail_input(path, ":", number, ": ", what);
  }
  void expect(std::size_t n) const {
    if (words.size() != n + 1)
      fail("'" + words[0] + "' takes " + std::to_string(n) + " values, got " +
           std::to_string(words.size() - 1));
  }
  double num(std::size_t k) const {
    char* end = nullptr;
    const double v = std::strtod(words[k].c_str(), &end);
    if (end == words[k].c_str() || *end != '\0')
      fail("'" + words[k] + "' is not a number (in '" + words[0] + "')");
    return v;
  }
  int integer(std::size_t k) const {
    const double v = num(k);
    if (!(std::abs(v) < 1e9) || v != std::floor(v))
      fail("'" + words[k] + "' is not an integer in (-1e9, 1e9) (in '" + words[0] + "')");
    return int(v);
  }
  Vec3 vec(std::size_t k) const { return Vec3(num(k), num(k + 1), num(k + 2)); }
};

// Parameters each term takes (all required).
const std::map<std::string, std::set<std::string>>& term_params() {
  static const std::map<std::string, std::set<std::string>> p = {
      {"contact", {"eps_cc", "eps_cv", "eps_vv", "alpha", "beta", "skin"}},
      {"wall", {"eps", "left", "right"}},
      {"shape", {"eps_v", "eps_a"}},
      {"tether", {"K"}}};
  return p;
}

}  // namespace

RegressionCase read_regression_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail_input("cannot open regression file '", path, "'");
  RegressionCase c;
  c.path = path;
  std::set<std::string> seen;
  BodySpec* body = nullptr;  // body whose vertex/face lines are being read
  std::size_t want_vertices = 0, want_faces = 0;
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    Line line{path, number, {}};
    std::istringstream words(text);
    for (std::string w; words >> w;) line.words.push_back(w);
    if (line.words.empty() || line.words[0][0] == '#') continue;
    const std::string& key = line.words[0];
    const bool in_body =
        body && (body->vertices.size() < want_vertices || body->faces.size() < want_faces);
    if (in_body && key != "vertex" && key != "face")
      line.fail("body incomplete: expected " + std::to_string(want_vertices) + " vertex and " +
                std::to_string(want_faces) + " face lines before '" + key + "'");
    if (key == "description") {
      const std::size_t at = text.find("description") + 11;
      c.description = at < text.size() ? text.substr(at + 1) : std::string();
    } else if (key == "term") {
      line.expect(1);
      if (!term_params().count(line.words[1]))
        line.fail("unknown term '" + line.words[1] + "' (allowed: contact, wall, shape, tether)");
      c.term = line.words[1];
    } else if (key == "box_lo" || key == "box_hi") {
      line.expect(3);
      (key == "box_lo" ? c.lo : c.hi) = line.vec(1);
    } else if (key == "periodic") {
      line.expect(3);
      for (int a = 0; a < 3; ++a) c.periodic[a] = line.integer(1 + a) != 0;
    } else if (key == "param") {
      line.expect(2);
      if (c.params.count(line.words[1])) line.fail("parameter '" + line.words[1] + "' repeated");
      c.params[line.words[1]] = line.num(2);
    } else if (key == "sphere") {
      line.expect(4);
      if (!c.bodies.empty()) line.fail("spheres must come before the bodies (site order)");
      c.spheres.push_back({line.num(1), line.vec(2)});
    } else if (key == "body") {
      line.expect(4);
      c.bodies.emplace_back();
      body = &c.bodies.back();
      if (line.integer(1) < 4 || line.integer(2) < 4)
        line.fail("a body needs at least 4 vertices and 4 faces, got " + line.words[1] + " and " +
                  line.words[2]);
      want_vertices = std::size_t(line.integer(1));
      want_faces = std::size_t(line.integer(2));
      body->vertex_diameter = line.num(3);
      body->ref_volume = line.num(4);
    } else if (key == "vertex") {
      line.expect(3);
      if (!body || body->vertices.size() >= want_vertices) line.fail("'vertex' outside a body");
      body->vertices.push_back(line.vec(1));
    } else if (key == "face") {
      line.expect(4);
      if (!body || body->faces.size() >= want_faces) line.fail("'face' outside a body");
      body->faces.push_back({line.integer(1), line.integer(2), line.integer(3)});
      body->ref_area.push_back(line.num(4));
    } else if (key == "tether") {
      line.expect(3);
      c.tethers.push_back({line.integer(1), line.integer(2), line.num(3)});
    } else if (key == "energy") {
      line.expect(1);
      c.energy = line.num(1);
    } else if (key == "virial") {
      line.expect(3);
      c.virial = line.vec(1);
    } else if (key == "force") {
      line.expect(4);
      if (line.integer(1) != int(c.forces.size()))
        line.fail("force lines must be in site order: expected site " +
                  std::to_string(c.forces.size()) + ", got " + line.words[1]);
      c.forces.push_back(line.vec(2));
    } else {
      line.fail("unknown keyword '" + key +
                "' (allowed: description, term, box_lo, box_hi, periodic, param, sphere, body, "
                "vertex, face, tether, energy, virial, force)");
    }
    if (key != "vertex" && key != "face" && key != "sphere" && key != "body" && key != "tether" &&
        key != "param" && key != "force" && !seen.insert(key).second)
      line.fail("'" + key + "' given twice");
  }
  for (const char* required : {"term", "box_lo", "box_hi", "periodic", "energy", "virial"})
    if (!seen.count(required)) fail_input(path, ": missing '", required, "'");
  if (body && (body->vertices.size() < want_vertices || body->faces.size() < want_faces))
    fail_input(path, ": the last body is incomplete");
  if (!c.tethers.empty() && c.term != "tether")
    fail_input(path, ": 'tether' lines are only allowed with 'term tether'");
  std::size_t n_sites = c.spheres.size();
  for (const BodySpec& b : c.bodies) n_sites += b.vertices.size();
  if (c.forces.size() != n_sites)
    fail_input(path, ": ", c.forces.size(), " force lines for ", n_sites, " sites");
  for (const std::string& p : term_params().at(c.term))
    if (!c.params.count(p)) fail_input(path, ": term '", c.term, "' needs 'param ", p, "'");
  for (const auto& [name, value] : c.params)
    if (!term_params().at(c.term).count(name))
      fail_input(path, ": unknown parameter '", name, "' = ", value, " for term '", c.term, "'");
  return c;
}

namespace {

// The force term of a case (build_force adds the file name to its errors).
std::shared_ptr<Force> make_force(const RegressionCase& c, const System& sys) {
  const auto& p = c.params;
  if (c.term == "contact") {
    ContactParams cp;
    cp.eps_cc = p.at("eps_cc");
    cp.eps_cv = p.at("eps_cv");
    cp.eps_vv = p.at("eps_vv");
    cp.alpha = p.at("alpha");
    cp.beta = p.at("beta");
    cp.skin = p.at("skin");
    return std::make_shared<ContactForce>(cp);
  }
  if (c.term == "wall") {
    for (const char* side : {"left", "right"})
      if (p.at(side) != 0.0 && p.at(side) != 1.0)
        fail_input("param ", side, " = ", p.at(side), " must be 0 (no wall) or 1");
    return std::make_shared<WallForce>(p.at("eps"), p.at("left") != 0.0, p.at("right") != 0.0);
  }
  if (c.term == "shape") return std::make_shared<ShapeForce>(p.at("eps_v"), p.at("eps_a"));
  auto tether = std::make_shared<TetherForce>(p.at("K"));
  for (const TetherSpec& t : c.tethers) tether->add(sys, t.a, t.b, t.rest_length);
  return tether;
}

}  // namespace

System build_system(const RegressionCase& c) {
  try {
    System sys(Box(c.lo, c.hi, c.periodic), 1);
    for (const SphereSpec& s : c.spheres) sys.add_sphere(s.pos, s.diameter);
    for (const BodySpec& b : c.bodies) {
      auto topo = std::make_shared<const MeshTopology>(int(b.vertices.size()), b.faces);
      sys.add_mesh(topo, b.vertices, b.vertex_diameter, b.ref_area, b.ref_volume);
    }
    return sys;
  } catch (const InputError& e) {
    fail_input(c.path, ": ", e.what());
  }
}

std::shared_ptr<Force> build_force(const RegressionCase& c, const System& sys) {
  try {
    return make_force(c, sys);
  } catch (const InputError& e) {
    fail_input(c.path, ": ", e.what());
  }
}

}  // namespace invasim::regression
