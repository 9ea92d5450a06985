// Engine throughput in particle-steps per second (sites x steps / wall time).
//   (a) cancer cells only, N = 1500, 7000, 28000, packing fraction 0.65, Langevin, dt = 0.05,
//       fully periodic, purely repulsive and cohesive (beta = 1e-2);
//   (b) the full system: 28 adipocytes + 1500 cells, 128 adipocytes + 7000 cells.
// Each with 1 and 2 OpenMP threads. Usage: bench_engine [steps=2000]
// `bench_engine lammps-data N FILE` writes workload (a)'s relaxed start as a LAMMPS data file
// (types 1/2 = diameters 0.9/1.1) so compare_lammps.sh can time LAMMPS on the same state.
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "integrate/dynamics.hpp"
#include "integrate/fire.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Relaxes the random start a little so the timed run sees a realistic contact network.
void relax(System& sys, ForceField& ff) {
  FireParams fp;
  fp.ftol = 1e-3;
  fp.max_steps = 300;
  Fire(fp).minimize(sys, ff);
}

// Times workload (a); returns particle-steps per second.
double time_cancer(int n, double beta, int steps, std::uint64_t* builds = nullptr) {
  System sys = test::random_spheres(n, 0.65, false, 7);
  ForceField ff;
  ContactParams cp;
  cp.beta = beta;
  auto contacts = std::make_shared<ContactForce>(cp);
  ff.add(contacts);
  relax(sys, ff);
  Dynamics dyn(0.05);
  dyn.add(Method::langevin(sys.sites_of_kind(SiteKind::kCancer), 0.2, 1e-3));
  dyn.run(sys, ff, 50);  // warm up
  const auto builds0 = contacts->neighbor_list().builds();
  const auto t0 = std::chrono::steady_clock::now();
  dyn.run(sys, ff, steps);
  const double t = seconds_since(t0);
  if (builds) *builds = contacts->neighbor_list().builds() - builds0;
  return double(n) * steps / t;
}

void bench_cancer(int n, double beta, int steps, int threads) {
  omp_set_num_threads(threads);
  std::uint64_t builds = 0;
  const double rate = time_cancer(n, beta, steps, &builds);
  std::printf("| cancer only, beta=%-6g | %6d | %d | %10.3e | %5llu |\n", beta, n, threads, rate,
              (unsigned long long)builds);
}

void bench_full(int nx, int nyz, int n_cells, int steps, int threads) {
  omp_set_num_threads(threads);
  System sys = test::slab_system(nx, nyz, n_cells, 5.2, 0.6, 11);
  ForceField ff = test::standard_forces(1e-2, 1000.0, 1.0);
  relax(sys, ff);
  Dynamics dyn(0.05);
  dyn.add(Method::active(sys.sites_of_kind(SiteKind::kCancer), 0.2, 0.05, 25.0, 1e-3));
  dyn.add(Method::damped(sys.sites_of_kind(SiteKind::kVertex), 0.2));
  dyn.run(sys, ff, 50);
  const auto t0 = std::chrono::steady_clock::now();
  dyn.run(sys, ff, steps);
  const double t = seconds_since(t0);
  const int n = int(sys.n_sites());
  std::printf("| full: %3d adipocytes + %4d cells | %6d | %d | %10.3e | |\n",
              int(sys.bodies().size()), n_cells, n, threads, double(n) * steps / t);
}

}  // namespace

// Writes the relaxed cancer-only start of workload (a) in LAMMPS "atomic" data format.
int write_lammps_data(int n, const char* path) {
  System sys = test::random_spheres(n, 0.65, false, 7);
  ForceField ff;
  ff.add(std::make_shared<ContactForce>(ContactParams{}));
  relax(sys, ff);
  FILE* f = std::fopen(path, "w");
  if (!f) return 1;
  const Vec3 hi = sys.box().hi();
  std::fprintf(f, "invasim bench workload (a), N = %d\n\n%d atoms\n2 atom types\n\n", n, n);
  std::fprintf(f, "0 %.17g xlo xhi\n0 %.17g ylo yhi\n0 %.17g zlo zhi\n\nMasses\n\n1 1\n2 1\n\n",
               hi[0], hi[1], hi[2]);
  std::fprintf(f, "Atoms # atomic\n\n");
  for (int i = 0; i < n; ++i) {
    const Vec3& r = sys.sites().pos[i];
    std::fprintf(f, "%d %d %.17g %.17g %.17g\n", i + 1, sys.sites().diameter[i] < 1.0 ? 1 : 2, r[0],
                 r[1], r[2]);
  }
  std::fclose(f);
  return 0;
}

int main(int argc, char** argv) {
  if (argc == 4 && std::string(argv[1]) == "lammps-data")
    return write_lammps_data(std::atoi(argv[2]), argv[3]);
  if (argc == 4 && std::string(argv[1]) == "single") {  // one workload-(a) rate, for scripts
    std::printf("%.3e\n", time_cancer(std::atoi(argv[2]), 0.0, std::atoi(argv[3])));
    return 0;
  }
  const int steps = argc > 1 ? std::atoi(argv[1]) : 2000;
  std::printf("invasim engine benchmark, %d steps each\n", steps);
  std::printf("| workload | sites | threads | particle-steps/s | list builds |\n");
  std::printf("|---|---|---|---|---|\n");
  for (int threads : {1, 2})
    for (int n : {1500, 7000, 28000}) bench_cancer(n, 0.0, steps, threads);
  for (int threads : {1, 2})
    for (int n : {1500, 7000, 28000}) bench_cancer(n, 1e-2, steps, threads);
  for (int threads : {1, 2}) {
    bench_full(7, 2, 1500, steps, threads);
    bench_full(8, 4, 7000, steps, threads);
  }
  return 0;
}
