// Cost of the protocol's compress stage (init + compress to phi = 0.72 in 3 % steps with FIRE
// to ftol = 1e-3, then a final FIRE to 1e-6; cohesion off), as protocols/lib/init.lua and
// lib/compress.lua build it: FIRE iterations, CPU time per iteration, and the time split
// between the force terms and the minimiser's own loops (each force term is timed through a
// wrapper). CPU time (user + system of this process) is reported besides wall time because
// the machine may be shared.
//   bench_compression [system=paper|reduced|large] [threads=1] [verbose=0|1] [key=value...]
// where key is a FIRE parameter (dt, dt_max, alpha0, f_alpha, f_inc, f_dec, n_delay) to try
// instead of the engine's default, for both the compression and the final FIRE.
#include <omp.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "forces/contact_force.hpp"
#include "forces/shape_force.hpp"
#include "forces/wall_force.hpp"
#include "integrate/fire.hpp"
#include "setup/compression.hpp"
#include "setup/placement.hpp"

using namespace invasim;

namespace {

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// A force term that forwards to another and accumulates the CPU time spent in it.
class TimedForce : public Force {
 public:
  explicit TimedForce(std::shared_ptr<Force> inner) : inner_(std::move(inner)) {}
  std::string name() const override { return inner_->name(); }
  ForceResult add_forces(System& sys, const ForceFlags& flags) override {
    const double t0 = cpu_seconds();
    const ForceResult r = inner_->add_forces(sys, flags);
    seconds += cpu_seconds() - t0;
    return r;
  }
  void invalidate_caches() override { inner_->invalidate_caches(); }
  double seconds = 0.0;

 private:
  std::shared_ptr<Force> inner_;
};

struct Preset {
  int n_a, n_c;
  double L0;
};

// The presets of protocols/lib/presets.lua.
Preset preset(const std::string& name) {
  if (name == "paper") return {28, 1500, 70.0};
  if (name == "reduced") return {8, 400, 46.0};
  if (name == "large") return {128, 7000, 116.0};
  std::fprintf(stderr, "bench_compression: system must be paper, reduced or large, got '%s'\n",
               name.c_str());
  std::exit(2);
}

// The init stage's de-mixed start (protocols/lib/init.lua, seed 1).
System init_system(const Preset& p) {
  const double L = p.L0, s = L / 70.0;
  System sys(Box(Vec3::Zero(), Vec3::Constant(L), {false, true, true}), 1);
  MeshPlacement mp;
  mp.n = p.n_a;
  mp.x = {16.0 * s, std::min(68.0 * s, L - 3.0)};
  SpherePlacement sp;
  sp.n = p.n_c;
  sp.x = {2.0 * s, 12.0 * s};
  place_random(sys, mp, sp);
  return sys;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string system = argc > 1 ? argv[1] : "paper";
  const int threads = argc > 2 ? std::atoi(argv[2]) : 1;
  const bool verbose = argc > 3 && std::atoi(argv[3]) != 0;
  omp_set_num_threads(threads);
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = cpu_seconds();
  System sys = init_system(preset(system));
  const double init_cpu = cpu_seconds() - cpu0;

  ContactParams cp;
  cp.beta = 0.0;  // cohesion off while compressing (lib/compress.lua)
  auto walls = std::make_shared<TimedForce>(std::make_shared<WallForce>());
  auto contacts = std::make_shared<TimedForce>(std::make_shared<ContactForce>(cp));
  auto shape = std::make_shared<TimedForce>(std::make_shared<ShapeForce>(1e3, 1.0));
  ForceField ff;  // the order of lib/init.lua: walls, contacts, shape
  ff.add(walls);
  ff.add(contacts);
  ff.add(shape);

  CompressionParams c;
  c.target_phi = 0.72;
  c.fire.ftol = 1e-3;
  for (int a = 4; a < argc; ++a) {
    const char* eq = std::strchr(argv[a], '=');
    if (!eq) {
      std::fprintf(stderr, "bench_compression: expected key=value, got '%s'\n", argv[a]);
      return 2;
    }
    const std::string key(argv[a], std::size_t(eq - argv[a]));
    const double v = std::atof(eq + 1);
    if (key == "dt")
      c.fire.dt = v;
    else if (key == "dt_max")
      c.fire.dt_max = v;
    else if (key == "alpha0")
      c.fire.alpha0 = v;
    else if (key == "f_alpha")
      c.fire.f_alpha = v;
    else if (key == "f_inc")
      c.fire.f_inc = v;
    else if (key == "f_dec")
      c.fire.f_dec = v;
    else if (key == "n_delay")
      c.fire.n_delay = int(v);
    else {
      std::fprintf(stderr, "bench_compression: unknown FIRE parameter '%s'\n", key.c_str());
      return 2;
    }
  }
  const double t_comp = cpu_seconds();
  std::uint64_t last = 0;
  const CompressionReport r = compress_to_phi(sys, ff, c, [&](const CompressionReport& rep) {
    if (verbose)
      std::printf("step %3zu phi %.4f iterations %llu\n", rep.steps, rep.phi,
                  (unsigned long long)(rep.fire_steps - last));
    last = rep.fire_steps;
    return true;
  });
  const double comp_cpu = cpu_seconds() - t_comp;
  FireParams final_fire = c.fire;
  final_fire.ftol = 1e-6;
  const double t_final = cpu_seconds();
  const FireResult f = Fire(final_fire).minimize(sys, ff);
  const double final_cpu = cpu_seconds() - t_final;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double total_cpu = cpu_seconds() - cpu0;
  const double forces = walls->seconds + contacts->seconds + shape->seconds;
  const std::uint64_t iterations = r.fire_steps + f.steps;

  std::printf("system %s, %zu sites, %d thread(s)\n", system.c_str(), sys.n_sites(), threads);
  std::printf("compression: %zu steps, %llu FIRE iterations, %.2f s CPU; converged %d\n", r.steps,
              (unsigned long long)r.fire_steps, comp_cpu, int(r.converged));
  std::printf(
      "final FIRE:  %llu iterations, %.2f s CPU, max force %.3e, energy %.9e, "
      "converged %d\n",
      (unsigned long long)f.steps, final_cpu, f.max_force, f.energy, int(f.converged));
  std::printf("phi %.6f, box %.6f %.6f %.6f\n", packing_fractions(sys).total,
              sys.box().lengths()[0], sys.box().lengths()[1], sys.box().lengths()[2]);
  std::printf(
      "total: %.2f s CPU (init %.2f), %.2f s wall; %llu iterations, %.1f us CPU per "
      "iteration\n",
      total_cpu, init_cpu, wall, (unsigned long long)iterations,
      1e6 * (comp_cpu + final_cpu) / double(iterations));
  std::printf(
      "split of the minimisation CPU: contacts %.1f %%, shape %.1f %%, walls %.1f %%, "
      "FIRE loops and the rest %.1f %%\n",
      100 * contacts->seconds / (comp_cpu + final_cpu),
      100 * shape->seconds / (comp_cpu + final_cpu), 100 * walls->seconds / (comp_cpu + final_cpu),
      100 * (comp_cpu + final_cpu - forces) / (comp_cpu + final_cpu));
  return 0;
}
