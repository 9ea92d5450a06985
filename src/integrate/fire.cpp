#include "integrate/fire.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>

#include "core/deterministic_sum.hpp"
#include "core/errors.hpp"
#include "integrate/blowup_guard.hpp"

namespace invasim {

void FireParams::validate() const {
  require_positive("ftol", ftol);
  require_positive("dt", dt);
  require_positive("dt_max", dt_max);
  require_positive("dt_min", dt_min);
  if (!(alpha0 > 0 && alpha0 < 1)) fail_input("alpha0 = ", alpha0, " must be in (0, 1)");
  if (!(f_alpha > 0 && f_alpha <= 1)) fail_input("f_alpha = ", f_alpha, " must be in (0, 1]");
  if (!(f_inc >= 1)) fail_input("f_inc = ", f_inc, " must be >= 1");
  if (!(f_dec > 0 && f_dec < 1)) fail_input("f_dec = ", f_dec, " must be in (0, 1)");
}

Fire::Fire(const FireParams& params) : params_(params) {
  params_.validate();
}

namespace {
struct Sums {
  double power = 0, v2 = 0, f2 = 0, fmax2 = 0;
  Sums& operator+=(const Sums& o) {
    power += o.power;
    v2 += o.v2;
    f2 += o.f2;
    fmax2 = std::max(fmax2, o.fmax2);
    return *this;
  }
};
}  // namespace

FireResult Fire::minimize(System& sys, ForceField& ff, PressureWall* wall,
                          const FireControl* control) const {
  const FireParams& p = params_;
  Sites& s = sys.sites();
  const std::size_t n = s.size();
  // The piston's inertia in the minimiser (not the dynamics' M_w): one layer of sites over
  // the wall's area, m A / d^2 (mean site mass and diameter), or M_w if larger. The wall
  // touches ~A/d^2 contacts, so its stiffness grows with A; with M_w = m it would be the
  // fastest mode, FIRE's dt would be capped by its instability and the resets would stall
  // convergence (300 spheres at P = 1e-3 did not reach 1e-8 in 2e5 steps).
  double wall_mass = 0.0;
  if (wall) {
    wall->validate();
    if (n > 0) {
      const double d = deterministic_sum(n, 0.0, [&](std::size_t i) { return s.diameter[i]; }) / n;
      const double m = deterministic_sum(n, 0.0, [&](std::size_t i) { return s.mass[i]; }) / n;
      wall_mass = std::max(wall->mass, m * sys.box().wall_area() / (d * d));
    } else {
      wall_mass = wall->mass;
    }
  }
  double wall_v = 0.0;
  auto wall_force = [&]() {
    return wall->walls->left_wall_force() + wall->pressure * sys.box().wall_area();
  };
  const FireState* resume = control && control->resume ? &*control->resume : nullptr;
  if (!resume) {
#pragma omp parallel for schedule(static) if (parallel_light(n))
    for (std::size_t i = 0; i < n; ++i) s.vel[i].setZero();
  }
  double dt = resume ? resume->dt : p.dt, alpha = resume ? resume->alpha : p.alpha0;
  int n_positive = resume ? resume->n_positive : 0;
  if (resume && wall) wall_v = resume->wall_velocity;
  FireResult result;
  // The blow-up guard, its message prefixed with the iteration.
  auto guard = [&sys](std::uint64_t iteration) {
    try {
      check_blowup(sys);
    } catch (const SimulationError& e) {
      fail_simulation("FIRE iteration ", iteration, ": ", e.what());
    }
  };
  StepThreads own_threads;
  StepThreads& threads = control && control->threads ? *control->threads : own_threads;
  ff.compute(sys);
  for (result.steps = resume ? resume->steps : 0;; ++result.steps) {
    // 1 thread or all for this iteration, as measured (next to a busy core a team can be
    // several times slower than one thread); the same results either way.
    const MeasuredStep measured(threads);
    if (control && control->stop && control->stop()) {  // an iteration boundary
      result.stopped = true;
      result.state = FireState{dt, alpha, n_positive, result.steps, wall_v};
      return result;
    }
    Sums sum = deterministic_sum(n, Sums{}, [&](std::size_t i) {
      return Sums{s.force[i].dot(s.vel[i]), s.vel[i].squaredNorm(), s.force[i].squaredNorm(),
                  s.force[i].squaredNorm()};
    });
    double fw = 0.0;
    if (wall) {
      fw = wall_force();
      sum.power += fw * wall_v;
      sum.v2 += wall_v * wall_v;
      sum.f2 += fw * fw;
    }
    result.max_force = std::sqrt(sum.fmax2);
    const bool wall_ok = !wall || std::abs(fw) / sys.box().wall_area() < p.ftol;
    if ((result.max_force < p.ftol && wall_ok) || result.steps >= p.max_steps) {
      result.converged = result.max_force < p.ftol && wall_ok;
      break;
    }
    // Blow-up guard (integrate/blowup_guard.hpp) inside minimisations too: a
    // non-finite force, and every kDefaultEvery iterations a non-finite position or velocity
    // (a NaN position can give zero forces, and FIRE would "converge" on it).
    if (!std::isfinite(sum.f2) || result.steps % BlowupGuard::kDefaultEvery == 0) {
      guard(result.steps);
      if (!std::isfinite(sum.f2))
        fail_simulation("FIRE: a force became non-finite at step ", result.steps);
    }
    // At rest (the first step, or right after a reset) there is no uphill move to undo.
    const bool at_rest = sum.v2 == 0.0;
    if (sum.power > 0.0 || at_rest) {
      if (!at_rest && ++n_positive > p.n_delay) {
        dt = std::min(dt * p.f_inc, p.dt_max);
        alpha *= p.f_alpha;
      }
    } else {
      n_positive = 0;
      dt = std::max(dt * p.f_dec, p.dt_min);
      alpha = p.alpha0;
      // Step back half a step and stop (FIRE 2.0).
#pragma omp parallel for schedule(static) if (parallel_light(n))
      for (std::size_t i = 0; i < n; ++i) {
        s.pos[i] -= 0.5 * dt * s.vel[i];
        s.vel[i].setZero();
        sys.box().wrap(s.pos[i], s.image[i]);
      }
      if (wall) {
        sys.box().set_wall(0, false, sys.box().lo()[0] - 0.5 * dt * wall_v);
        wall_v = 0.0;
      }
      sum.v2 = 0.0;
    }
    // Semi-implicit Euler with FIRE velocity mixing, using |v| after the kick and |F| (the
    // forces are unchanged since sum.f2). One pass kicks and sums |v|^2 (each site is visited
    // once, in deterministic_sum's fixed blocks).
    double v2 = deterministic_sum(n, 0.0, [&](std::size_t i) {
      s.vel[i] += dt / s.mass[i] * s.force[i];
      return s.vel[i].squaredNorm();
    });
    if (wall) {
      wall_v += dt / wall_mass * fw;
      v2 += wall_v * wall_v;
    }
    const double ratio = sum.f2 > 0.0 ? std::sqrt(v2 / sum.f2) : 0.0;
#pragma omp parallel for schedule(static) if (parallel_light(n))
    for (std::size_t i = 0; i < n; ++i) {
      s.vel[i] = (1.0 - alpha) * s.vel[i] + alpha * ratio * s.force[i];
      s.pos[i] += dt * s.vel[i];
      sys.box().wrap(s.pos[i], s.image[i]);
    }
    if (wall) {
      wall_v = (1.0 - alpha) * wall_v + alpha * ratio * fw;
      sys.box().set_wall(0, false, sys.box().lo()[0] + dt * wall_v);
    }
    ff.compute(sys);
  }
#pragma omp parallel for schedule(static) if (parallel_light(n))
  for (std::size_t i = 0; i < n; ++i) s.vel[i].setZero();
  guard(result.steps);
  result.energy = ff.energy(sys);
  return result;
}

}  // namespace invasim
