#include "setup/compression.hpp"

#include <cmath>

#include "core/errors.hpp"
#include "setup/test_hooks.hpp"

namespace invasim {

void CompressionParams::validate() const {
  if (!(target_phi > 0.0 && target_phi < 1.0))
    fail_input("compress: target phi = ", target_phi, " must be in (0, 1)");
  if (!(step > 0.0 && step < 1.0)) fail_input("compress: step = ", step, " must be in (0, 1)");
  fire.validate();
}

CompressionReport compress_to_phi(System& sys, ForceField& ff, const CompressionParams& params,
                                  const CompressionCallback& on_step,
                                  const CompressionReport& so_far, const CompressionStop& stop) {
  params.validate();
  const Fire fire(params.fire);
  CompressionReport report = so_far;
  report.stopped = false;
  report.fire_state.reset();
  StepThreads threads;  // one measured thread count for all the steps' minimisations
  FireControl control;
  control.stop = stop;
  control.threads = &threads;
  control.resume = so_far.fire_state;  // a step's FIRE to finish first (scaling done)
  double phi = packing_fractions(sys).total;
  if (!control.resume && phi > params.target_phi)
    fail_input("compress: the packing fraction is already ", phi, ", above the target ",
               params.target_phi, "; use rescale to expand");
  if (!control.resume && !(phi > 0.0))
    fail_input("compress: the packing fraction is ", phi,
               " (no cancer cells and no adipocytes with a volume V_i): there is nothing to "
               "compress");
  while (control.resume || phi < params.target_phi * (1.0 - 1e-12)) {
    if (!control.resume) {
      if (report.steps >= params.max_steps)
        fail_simulation("compress: target phi = ", params.target_phi, " not reached after ",
                        report.steps, " steps (phi = ", phi, ")");
      const double next = std::min(phi * (1.0 + params.step), params.target_phi);
      sys.scale(Vec3::Constant(std::cbrt(phi / next)), true);
      inject_nan_at_compression_step(sys, report.steps + 1);  // test hooks, off by default
      pause_at_compression_step(report.steps + 1);
    }
    const FireResult r = fire.minimize(sys, ff, nullptr, &control);
    control.resume.reset();
    if (r.stopped) {
      report.stopped = true;
      report.fire_state = r.state;
      phi = packing_fractions(sys).total;
      break;
    }
    ++report.steps;
    report.fire_steps += r.steps;
    report.converged = report.converged && r.converged;
    report.max_force = r.max_force;
    phi = packing_fractions(sys).total;
    report.phi = phi;
    report.box_lengths = sys.box().lengths();
    if (on_step && !on_step(report) && phi < params.target_phi * (1.0 - 1e-12)) {
      report.stopped = true;
      break;
    }
  }
  report.phi = phi;
  report.box_lengths = sys.box().lengths();
  return report;
}

FireResult rescale_to_phi_a(System& sys, ForceField& ff, double phi_a, const FireParams& fire,
                            const FireControl* control) {
  if (!(phi_a > 0.0 && phi_a < 1.0)) fail_input("rescale: phi_a = ", phi_a, " must be in (0, 1)");
  const double now = packing_fractions(sys).adipocyte;
  if (!(now > 0.0))
    fail_input("rescale: the adipocyte packing fraction is ", now,
               " (no adipocytes): no box reaches phi_a = ", phi_a);
  sys.scale(Vec3::Constant(std::cbrt(now / phi_a)), true);
  return Fire(fire).minimize(sys, ff, nullptr, control);
}

}  // namespace invasim
