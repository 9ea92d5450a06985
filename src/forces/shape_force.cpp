#include "forces/shape_force.hpp"

#include "core/parallel.hpp"

#include "core/deterministic_sum.hpp"
#include "core/errors.hpp"
#include "core/team_barrier.hpp"
#include "forces/shape_kernel.hpp"

namespace invasim {

ShapeForce::ShapeForce(double eps_v, double eps_a) : eps_v_(eps_v), eps_a_(eps_a) {
  require_non_negative("eps_v", eps_v);
  require_non_negative("eps_a", eps_a);
}

double body_shape_energy(const MeshBody& body, const Vec3* x, double eps_v, double eps_a,
                         Vec3* grad) {
  thread_local ShapeKernel kernel;
  thread_local std::vector<Vec3> g;
  g.resize(std::size_t(body.n_vertices()));
  const double energy = kernel.evaluate(body, x, eps_v, eps_a, g.data());
  if (grad)
    for (int v = 0; v < body.n_vertices(); ++v) grad[v] += g[v];
  return energy;
}

void ShapeForce::prepare_team(System& sys, const ForceFlags&) {
  per_body_.resize(sys.bodies().size());
}

ForceResult ShapeForce::add_forces_team(System& sys, const ForceFlags& flags) {
  const auto& bodies = sys.bodies();
  const int nb = int(bodies.size());
  Sites& s = sys.sites();
  thread_local std::vector<Vec3> x, grad;  // one body's vertices and energy gradient
  thread_local ShapeKernel kernel;
  // Bodies are independent (each writes only its own vertices); dynamic, so that a thread
  // slowed by another process on its core takes fewer.
#pragma omp for schedule(dynamic, 1) nowait
  for (int b = 0; b < nb; ++b) {
    const MeshBody& body = bodies[b];
    const int nv = body.n_vertices();
    x.resize(nv);
    grad.resize(nv);
    sys.body_vertices(b, x.data());
    ForceResult r;
    r.energy = kernel.evaluate(body, x.data(), eps_v_, eps_a_, grad.data());
    const Vec3& c = kernel.centroid();
    for (int v = 0; v < nv; ++v) {
      s.force[sys.body_slot(b, v)] -= grad[v];
      r.virial -= (x[v] - c).cwiseProduct(grad[v]);
    }
    per_body_[b] = r;
  }
  team_barrier();
  ForceResult out;
  if (!team_leader()) return out;
  if (flags.energy)
    out.energy = block_sum(nb, 0.0, [&](std::size_t b) { return per_body_[b].energy; });
  if (flags.virial)
    out.virial =
        block_sum(nb, Vec3(Vec3::Zero()), [&](std::size_t b) { return per_body_[b].virial; });
  return out;
}

}  // namespace invasim
