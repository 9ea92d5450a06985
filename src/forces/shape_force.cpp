#include "forces/shape_force.hpp"
#include "core/parallel.hpp"

#include "core/deterministic_sum.hpp"
#include "core/errors.hpp"
#include "core/team_barrier.hpp"
#include "mesh/geometry.hpp"

namespace invasim {

ShapeForce::ShapeForce(double eps_v, double eps_a) : eps_v_(eps_v), eps_a_(eps_a) {
  require_non_negative("eps_v", eps_v);
  require_non_negative("eps_a", eps_a);
}

double body_shape_energy(const MeshBody& body, const Vec3* x, double eps_v, double eps_a,
                         Vec3* grad) {
  const MeshTopology& topo = *body.topology;
  const double v = mesh_volume(topo, x);
  const double dv = 1.0 - v / body.ref_volume;
  double energy = 0.5 * eps_v * dv * dv;
  if (grad) add_volume_gradient(topo, x, -eps_v * dv / body.ref_volume, grad);
  const auto& faces = topo.faces();
  for (int k = 0; k < topo.n_faces(); ++k) {
    const auto& f = faces[k];
    const Vec3 &a = x[f[0]], &b = x[f[1]], &c = x[f[2]];
    const Vec3 nrm = (b - a).cross(c - a);
    const double twice_area = nrm.norm();
    const double da = 1.0 - 0.5 * twice_area / body.ref_area[k];
    energy += 0.5 * eps_a * da * da;
    if (grad && twice_area > 0.0) {
      // d|n|/da = (b - c) x n_hat, cyclic; area = |n| / 2.
      const Vec3 nh = nrm / twice_area;
      const double scale = -eps_a * da / body.ref_area[k] * 0.5;
      grad[f[0]] += scale * (b - c).cross(nh);
      grad[f[1]] += scale * (c - a).cross(nh);
      grad[f[2]] += scale * (a - b).cross(nh);
    }
  }
  return energy;
}

ForceResult ShapeForce::add_forces(System& sys, const ForceFlags& flags) {
  return add_forces_in_own_region(sys, flags);
}

void ShapeForce::prepare_team(System& sys, const ForceFlags&) {
  per_body_.resize(sys.bodies().size());
}

ForceResult ShapeForce::add_forces_team(System& sys, const ForceFlags& flags) {
  const auto& bodies = sys.bodies();
  const int nb = int(bodies.size());
  Sites& s = sys.sites();
  thread_local std::vector<Vec3> x, grad;  // one body's vertices and energy gradient
  // Bodies are independent (each writes only its own vertices); dynamic, so that a thread
  // slowed by another process on its core takes fewer.
#pragma omp for schedule(dynamic, 1) nowait
  for (int b = 0; b < nb; ++b) {
    const MeshBody& body = bodies[b];
    const int nv = body.n_vertices();
    x.resize(nv);
    grad.assign(nv, Vec3::Zero());
    sys.body_vertices(b, x.data());
    ForceResult r;
    r.energy = body_shape_energy(body, x.data(), eps_v_, eps_a_, grad.data());
    const Vec3 c = vertex_centroid(nv, x.data());
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
