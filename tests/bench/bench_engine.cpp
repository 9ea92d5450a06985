// Engine throughput in particle-steps per second (sites x steps / wall time).
//   (a) cancer cells only, N = 1500, 7000, 28000, packing fraction 0.65, Langevin, dt = 0.05,
//       fully periodic, purely repulsive and cohesive (beta = 1e-2);
//   (b) the full system: 28 adipocytes + 1500 cells, 128 adipocytes + 7000 cells.
// Each with 1 and 2 OpenMP threads. Usage: bench_engine [steps=2000]
// `bench_engine lammps-data N FILE` writes workload (a)'s relaxed start as a LAMMPS data file
// (types 1/2 = diameters 0.9/1.1) for LAMMPS on the same state (compare_lammps.sh, and
// cross_check_lammps.sh, whose Lua side reads it too).
// BENCH_CHUNK=n times the steps in runs of n steps (a production's operations cut it so).
// For scripts (OMP_NUM_THREADS sets the threads), each printing "<wall rate> <CPU rate>"
// (particle-steps per second of wall time and of the process's CPU time; on a loaded machine
// the CPU rate at 1 thread is the one to compare):
//   bench_engine single N STEPS [beta=0] [kT=1e-3]   workload (a) (list builds on stderr)
//   bench_engine full N_CELLS STEPS                  workload (b), N_CELLS = 1500 or 7000
//   bench_engine free N STEPS                        N free active particles, no forces (a light
//                                                    step, like test_dynamics' orientation runs)
// `single` also prints the last list build's candidates and entries per site on stderr.
#include <omp.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/wait_policy.hpp"
#include "integrate/dynamics.hpp"
#include "integrate/fire.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// CPU time of the whole process (all threads), in seconds.
double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Particle-steps per second of wall time and of CPU time.
struct Rate {
  double wall = 0.0, cpu = 0.0;
};

// True if the environment variable `name` is set to `other`, false if unset or `usual`;
// any other value stops the benchmark with a message naming both.
bool env_choice(const char* name, const std::string& usual, const std::string& other) {
  const char* v = std::getenv(name);
  if (!v || v == usual) return false;
  if (v == other) return true;
  std::fprintf(stderr, "%s = '%s': expected '%s' or '%s'\n", name, v, usual.c_str(), other.c_str());
  std::exit(2);
}

// BENCH_STEP_THREADS=all: every step with all threads (integrate/step_threads.hpp), instead of
// the measured choice between 1 thread and all.
void apply_step_threads_env(Dynamics& dyn) {
  if (env_choice("BENCH_STEP_THREADS", "auto", "all"))
    dyn.step_threads().set_mode(StepThreads::Mode::kAll);
}

// BENCH_CONTACT_KERNEL=full: the contact kernel's full rows (each pair twice) instead of the
// half rows (forces/contact_force.hpp), for A/B comparisons of the two drivers.
void apply_contact_kernel_env(ContactForce& contacts) {
  if (env_choice("BENCH_CONTACT_KERNEL", "half", "full"))
    contacts.set_kernel(ContactKernel::kFullRows);
}

// Times `steps` steps of dyn on sys (prints the steps run with all threads on stderr).
Rate time_steps(System& sys, ForceField& ff, Dynamics& dyn, int steps) {
  // BENCH_CHUNK=n: the steps in runs of n (as a production's operations every n steps cut them;
  // each run stores the sites in the engine order and back, docs/performance.md "Sites in cell
  // order"); default: one run.
  const char* chunk_env = std::getenv("BENCH_CHUNK");
  const int chunk = chunk_env ? std::max(1, std::atoi(chunk_env)) : steps;
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds();
  for (int done = 0; done < steps; done += chunk) dyn.run(sys, ff, std::min(chunk, steps - done));
  const double cpu = cpu_seconds() - c0, wall = seconds_since(t0);
  const double work = double(sys.n_sites()) * steps;
  std::fprintf(
      stderr, "steps with all threads: %llu of %llu\n",
      (unsigned long long)dyn.step_threads().team_steps(),
      (unsigned long long)(dyn.step_threads().team_steps() + dyn.step_threads().serial_steps()));
  return {work / wall, work / cpu};
}

// Relaxes the random start a little so the timed run sees a realistic contact network.
void relax(System& sys, ForceField& ff) {
  FireParams fp;
  fp.ftol = 1e-3;
  fp.max_steps = 300;
  Fire(fp).minimize(sys, ff);
}

// Candidates tested and entries kept per site by the last list build (on stderr).
void print_list_stats(const System& sys, const VerletList& list) {
  double entries = 0.0;
  for (std::size_t i = 0; i < sys.n_sites(); ++i) entries += list.count(i);
  std::fprintf(stderr, "list: %.1f candidates, %.1f entries per site\n",
               double(list.candidates()) / double(sys.n_sites()), entries / double(sys.n_sites()));
}

// Times workload (a) at temperature kT.
Rate time_cancer(int n, double beta, int steps, std::uint64_t* builds = nullptr, double kT = 1e-3) {
  System sys = test::random_spheres(n, 0.65, false, 7);
  ForceField ff;
  ContactParams cp;
  cp.beta = beta;
  auto contacts = std::make_shared<ContactForce>(cp);
  apply_contact_kernel_env(*contacts);
  ff.add(contacts);
  relax(sys, ff);
  Dynamics dyn(0.05);
  apply_step_threads_env(dyn);
  dyn.add(Method::langevin(sys.sites_of_kind(SiteKind::kCancer), 0.2, kT));
  dyn.run(sys, ff, 50);  // warm up
  const auto builds0 = contacts->neighbor_list().builds();
  const Rate rate = time_steps(sys, ff, dyn, steps);
  if (builds) *builds = contacts->neighbor_list().builds() - builds0;
  if (builds) print_list_stats(sys, contacts->neighbor_list());
  return rate;
}

void bench_cancer(int n, double beta, int steps, int threads) {
  omp_set_num_threads(threads);
  std::uint64_t builds = 0;
  const Rate rate = time_cancer(n, beta, steps, &builds);
  std::printf("| cancer only, beta=%-6g | %6d | %d | %10.3e | %10.3e | %5llu |\n", beta, n, threads,
              rate.wall, rate.cpu, (unsigned long long)builds);
  std::fflush(stdout);
}

// Times workload (b): nx x nyz x nyz adipocytes and n_cells cells.
Rate time_full(int nx, int nyz, int n_cells, int steps, int* n_bodies = nullptr,
               int* n_sites = nullptr) {
  System sys = test::slab_system(nx, nyz, n_cells, 5.2, 0.6, 11);
  ForceField ff = test::standard_forces(1e-2, 1000.0, 1.0);
  apply_contact_kernel_env(dynamic_cast<ContactForce&>(*ff.terms().front()));
  relax(sys, ff);
  Dynamics dyn(0.05);
  apply_step_threads_env(dyn);
  dyn.add(Method::active(sys.sites_of_kind(SiteKind::kCancer), 0.2, 0.05, 25.0, 1e-3));
  dyn.add(Method::damped(sys.sites_of_kind(SiteKind::kVertex), 0.2));
  dyn.run(sys, ff, 50);
  if (n_bodies) *n_bodies = int(sys.bodies().size());
  if (n_sites) *n_sites = int(sys.n_sites());
  return time_steps(sys, ff, dyn, steps);
}

// Times N free active particles (no force terms: the step is the drift and the kick alone).
Rate time_free(int n, int steps) {
  System sys = test::free_particles(n, 1.0, 5);
  ForceField ff;
  Dynamics dyn(0.05);
  apply_step_threads_env(dyn);
  auto method = Method::active(test::all_sites(sys), 0.2, 0.02, 25.0);
  method->randomize_orientations(sys);
  dyn.add(method);
  dyn.run(sys, ff, 50);
  return time_steps(sys, ff, dyn, steps);
}

void bench_full(int nx, int nyz, int n_cells, int steps, int threads) {
  omp_set_num_threads(threads);
  int bodies = 0, n = 0;
  const Rate rate = time_full(nx, nyz, n_cells, steps, &bodies, &n);
  std::printf("| full: %3d adipocytes + %4d cells | %6d | %d | %10.3e | %10.3e | |\n", bodies,
              n_cells, n, threads, rate.wall, rate.cpu);
  std::fflush(stdout);
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
  use_passive_wait_policy_by_default(argv);  // as invasim does
  if (argc == 4 && std::string(argv[1]) == "lammps-data")
    return write_lammps_data(std::atoi(argv[2]), argv[3]);
  if (argc >= 4 && argc <= 6 && std::string(argv[1]) == "single") {  // workload (a), for scripts
    const double beta = argc > 4 ? std::atof(argv[4]) : 0.0;
    const double kT = argc > 5 ? std::atof(argv[5]) : 1e-3;
    std::uint64_t builds = 0;
    const Rate r = time_cancer(std::atoi(argv[2]), beta, std::atoi(argv[3]), &builds, kT);
    std::printf("%.3e %.3e\n", r.wall, r.cpu);
    std::fprintf(stderr, "list builds: %llu\n", (unsigned long long)builds);
    return 0;
  }
  if (argc == 4 && std::string(argv[1]) == "full") {  // workload (b), for scripts
    const int n_cells = std::atoi(argv[2]);
    if (n_cells != 1500 && n_cells != 7000) {
      std::fprintf(stderr, "bench_engine full: N_CELLS = %d, expected 1500 or 7000\n", n_cells);
      return 2;
    }
    const Rate r = n_cells == 1500 ? time_full(7, 2, 1500, std::atoi(argv[3]))
                                   : time_full(8, 4, 7000, std::atoi(argv[3]));
    std::printf("%.3e %.3e\n", r.wall, r.cpu);
    return 0;
  }
  if (argc == 4 && std::string(argv[1]) == "free") {  // free particles, for scripts
    const Rate r = time_free(std::atoi(argv[2]), std::atoi(argv[3]));
    std::printf("%.3e %.3e\n", r.wall, r.cpu);
    return 0;
  }
  const int steps = argc > 1 ? std::atoi(argv[1]) : 2000;
  std::printf("invasim engine benchmark, %d steps each\n", steps);
  std::printf("| workload | sites | threads | particle-steps/s (wall) | (CPU) | list builds |\n");
  std::printf("|---|---|---|---|---|---|\n");
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
