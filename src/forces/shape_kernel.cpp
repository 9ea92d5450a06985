#include "forces/shape_kernel.hpp"

#include <cmath>

#include "mesh/geometry.hpp"

namespace invasim {

double ShapeKernel::evaluate(const MeshBody& body, const Vec3* x, double eps_v, double eps_a,
                             Vec3* grad) {
  const MeshTopology& topo = *body.topology;
  const int nv = topo.n_vertices(), nf = topo.n_faces();
  const int *i0 = topo.face_corner(0).data(), *i1 = topo.face_corner(1).data(),
            *i2 = topo.face_corner(2).data();
  const double* ref_area = body.ref_area.data();
  const std::size_t n = std::size_t(nf);
  // Per face: six_v's term and 1 - a_k / a_k0; per corner (m n + k): the corner's position
  // (px, py, pz) and the gradient (gx, gy, gz).
  buffer_.resize(20 * n);
  double *six_v_term = buffer_.data(), *da = six_v_term + n;
  double *gx = da + n, *gy = gx + 3 * n, *gz = gy + 3 * n;
  double *px = gz + 3 * n, *py = px + 3 * n, *pz = py + 3 * n;
  vx_.resize(std::size_t(nv));
  vy_.resize(std::size_t(nv));
  vz_.resize(std::size_t(nv));
  double *X = vx_.data(), *Y = vy_.data(), *Z = vz_.data();
  for (int v = 0; v < nv; ++v) {
    X[v] = x[v][0];
    Y[v] = x[v][1];
    Z[v] = x[v][2];
  }
  centroid_ = vertex_centroid(nv, x);
  const double cx = centroid_[0], cy = centroid_[1], cz = centroid_[2];
  // V = (1/6) sum_f u . (v x w) about the centroid c (u, v, w the corners less c).
#pragma omp simd
  for (int k = 0; k < nf; ++k) {
    px[k] = X[i0[k]], py[k] = Y[i0[k]], pz[k] = Z[i0[k]];
    px[n + k] = X[i1[k]], py[n + k] = Y[i1[k]], pz[n + k] = Z[i1[k]];
    px[2 * n + k] = X[i2[k]], py[2 * n + k] = Y[i2[k]], pz[2 * n + k] = Z[i2[k]];
    six_v_term[k] =
        triple_product(px[k] - cx, py[k] - cy, pz[k] - cz, px[n + k] - cx, py[n + k] - cy,
                       pz[n + k] - cz, px[2 * n + k] - cx, py[2 * n + k] - cy, pz[2 * n + k] - cz);
  }
  double six_v = 0.0;
  for (int k = 0; k < nf; ++k) six_v += six_v_term[k];  // in face order
  const double dv = 1.0 - (six_v / 6.0) / body.ref_volume;
  const double s = (-eps_v * dv / body.ref_volume) / 6.0;
  // Each corner's gradient: s times dV/du = (v x w) (cyclic), plus, for a face of non-zero
  // area |n| / 2 with n = (p1 - p0) x (p2 - p0), -eps_a da / (2 a_k0) times
  // d|n|/dp0 = (p1 - p2) x n / |n| (cyclic).
#pragma omp simd
  for (int k = 0; k < nf; ++k) {
    const double p0[3] = {px[k], py[k], pz[k]};
    const double p1[3] = {px[n + k], py[n + k], pz[n + k]};
    const double p2[3] = {px[2 * n + k], py[2 * n + k], pz[2 * n + k]};
    const double ux = p0[0] - cx, uy = p0[1] - cy, uz = p0[2] - cz;
    const double vx = p1[0] - cx, vy = p1[1] - cy, vz = p1[2] - cz;
    const double wx = p2[0] - cx, wy = p2[1] - cy, wz = p2[2] - cz;
    const double ex = p1[0] - p0[0], ey = p1[1] - p0[1], ez = p1[2] - p0[2];
    const double fx = p2[0] - p0[0], fy = p2[1] - p0[1], fz = p2[2] - p0[2];
    const double nx = ey * fz - ez * fy, ny = ez * fx - ex * fz, nz = ex * fy - ey * fx;
    const double twice_area = twice_triangle_area(ex, ey, ez, fx, fy, fz);
    const double d = 1.0 - 0.5 * twice_area / ref_area[k];
    da[k] = d;
    const bool has_area = twice_area > 0.0;
    const double scale = has_area ? -eps_a * d / ref_area[k] * 0.5 / twice_area : 0.0;
    const double hx = scale * nx, hy = scale * ny, hz = scale * nz;  // scale n / |n|
    const double gx0 = p1[0] - p2[0], gy0 = p1[1] - p2[1], gz0 = p1[2] - p2[2];
    const double mx = p0[0] - p1[0], my = p0[1] - p1[1], mz = p0[2] - p1[2];
    gx[k] = s * (vy * wz - vz * wy) + (gy0 * hz - gz0 * hy);
    gy[k] = s * (vz * wx - vx * wz) + (gz0 * hx - gx0 * hz);
    gz[k] = s * (vx * wy - vy * wx) + (gx0 * hy - gy0 * hx);
    gx[n + k] = s * (wy * uz - wz * uy) + (fy * hz - fz * hy);
    gy[n + k] = s * (wz * ux - wx * uz) + (fz * hx - fx * hz);
    gz[n + k] = s * (wx * uy - wy * ux) + (fx * hy - fy * hx);
    gx[2 * n + k] = s * (uy * vz - uz * vy) + (my * hz - mz * hy);
    gy[2 * n + k] = s * (uz * vx - ux * vz) + (mz * hx - mx * hz);
    gz[2 * n + k] = s * (ux * vy - uy * vx) + (mx * hy - my * hx);
  }
  double energy = 0.5 * eps_v * dv * dv;
  for (int k = 0; k < nf; ++k) energy += 0.5 * eps_a * da[k] * da[k];  // in face order
  // Each vertex sums its corners (face k, corner m: entry m n + k) in face order.
  const int* offsets = topo.corner_offsets().data();
  const std::pair<int, int>* corners = topo.corners().data();
  for (int v = 0; v < nv; ++v) {
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (int m = offsets[v]; m < offsets[v + 1]; ++m) {
      const std::size_t at = std::size_t(corners[m].second) * n + std::size_t(corners[m].first);
      sx += gx[at];
      sy += gy[at];
      sz += gz[at];
    }
    grad[v] = Vec3(sx, sy, sz);
  }
  return energy;
}

}  // namespace invasim
