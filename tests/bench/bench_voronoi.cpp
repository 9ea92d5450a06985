// Time per evaluation of the Voronoi measurement (measure_voronoi) on the paper's two system
// sizes: 28 adipocytes + 1500 cancer cells and 128 + 7000, each placed de-mixed and dilute
// (docs/model.md, protocol step 1) and compressed to phi = 0.72 with loose minimisations, which
// gives a dense configuration of realistic structure (box ~ 17 and ~ 28).
// Prints wall and CPU time per evaluation. Usage: bench_voronoi [evaluations=20]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "measure/voronoi.hpp"
#include "mesh/geometry.hpp"
#include "setup/compression.hpp"
#include "setup/placement.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The paper's de-mixed dilute start (phi = 0.01, x ranges scaled from L0 = 70) compressed to
// phi = 0.72; the minimiser stops early (ftol 1e-2, 300 steps per compression step).
System compressed_system(int n_a, int n_c, std::uint64_t seed) {
  const double v_cells = n_c * M_PI / 6.0 * 0.5 * (0.9 * 0.9 * 0.9 + 1.1 * 1.1 * 1.1);
  const MeshShape shape = icosphere(1);
  std::vector<Vec3> x;
  for (const Vec3& v : shape.vertices) x.push_back(2.0 * v);
  const double v_body = union_volume(*shape.topology, x.data(), 2.0, 0.05);
  const double L0 = std::cbrt((v_cells + n_a * v_body) / 0.01);
  System sys(Box(Vec3::Zero(), Vec3::Constant(L0), {false, true, true}), seed);
  MeshPlacement mp;
  mp.n = n_a;
  mp.x = {16.0 / 70.0 * L0, 68.0 / 70.0 * L0 - 3.0};
  SpherePlacement sp;
  sp.n = n_c;
  sp.x = {2.0 / 70.0 * L0, 12.0 / 70.0 * L0};
  place_random(sys, mp, sp);
  ForceField ff = test::standard_forces(0.0, 1e3, 1.0);
  CompressionParams cp;
  cp.target_phi = 0.72;
  cp.fire.ftol = 1e-2;
  cp.fire.max_steps = 300;
  compress_to_phi(sys, ff, cp);
  return sys;
}

// Times measure_voronoi on one system; prints a table row (wall and CPU seconds, so that a
// loaded machine can be recognised).
void bench(int n_a, int n_c, int evaluations) {
  auto t0 = std::chrono::steady_clock::now();
  const System sys = compressed_system(n_a, n_c, 3);
  const double setup = seconds_since(t0);
  // First evaluation from the automatic margin, then the same with the accepted margin passed
  // back (what an observer does in a time series), then the radical variant.
  t0 = std::chrono::steady_clock::now();
  VoronoiMeasurement m = measure_voronoi(sys);
  const double first = seconds_since(t0);
  VoronoiOptions opt;
  opt.margin = m.tessellation.margin;
  t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  for (int k = 0; k < evaluations; ++k) m = measure_voronoi(sys, opt);
  const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC / evaluations;
  const double wall = seconds_since(t0) / evaluations;
  opt.radical = true;
  t0 = std::chrono::steady_clock::now();
  const VoronoiMeasurement r = measure_voronoi(sys, opt);
  const double radical = seconds_since(t0);
  const VoronoiTessellation& t = m.tessellation;
  std::printf(
      "| %3d + %4d | %5.2f x %5.2f | %6zu | %6zu | %4zu | %4.2f | %d | %6.4f | %6.4f | %6.4f | "
      "%6.4f "
      "| %.12g | %.12g | %5.3f | %5.3f | %5.3f | %.12g |\n",
      n_a, n_c, sys.box().length(0), sys.box().length(1), sys.n_sites(), t.n_points, t.n_added,
      t.margin, t.refinements, first, wall, cpu, radical, m.interface_area, m.max_interface_area,
      m.interface_ratio, m.mean_local_phi_a, m.std_local_phi_a, r.interface_area);
  std::fflush(stdout);
  std::fprintf(stderr, "(setup of %d + %d: %.1f s)\n", n_a, n_c, setup);
}

}  // namespace

int main(int argc, char** argv) {
  const int evaluations = argc > 1 ? std::atoi(argv[1]) : 20;
  std::printf(
      "| N_a + N_c  | L_x x L_y     | sites  | points | added | margin | passes | first (s) | "
      "wall/eval (s) | CPU/eval (s) | radical (s) | A_t | A_t^max | ratio | <phi_a,i> | "
      "Delta phi_a | radical A_t |\n");
  bench(28, 1500, evaluations);
  bench(128, 7000, evaluations);
  return 0;
}
