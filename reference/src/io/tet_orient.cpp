// The exact sign of det[b - a, c - a, d - a] on doubles, and the orientation
// repair every tet reader and generator applies (decision D38).
//
// A filter first: the determinant in floating point with the error bound of
// Shewchuk's orient3d stage A, (7 + 56 eps) eps times the permanent, which
// decides nearly every call. Otherwise exact arithmetic on expansions
// (sums of non-overlapping doubles): the differences are exact as two-term
// expansions, products and sums are exact, and the sign of an expansion is the
// sign of its largest component. Exactness needs no underflow or overflow:
// with coordinates 0 or of magnitude in [1e-50, 1e50] every quantity is a
// multiple of 2^-654 and below 2^520, well inside the double range.
// This file is compiled with -ffp-contract=off: a fused multiply-add would
// break the error-free transformations.
#include <cmath>
#include <vector>

#include "mrsv/tet_formats.h"

namespace mrsv {
namespace {

using Expansion = std::vector<double>;  // components by increasing magnitude, zeros removed

// a + b = x + y exactly, x = fl(a + b).
inline void twoSum(double a, double b, double* x, double* y) {
  *x = a + b;
  double bv = *x - a;
  double av = *x - bv;
  *y = (a - av) + (b - bv);
}

// a * b = x + y exactly, x = fl(a * b).
inline void twoProduct(double a, double b, double* x, double* y) {
  *x = a * b;
  *y = std::fma(a, b, -*x);
}

// e + f, both expansions (Shewchuk's fast-expansion-sum replaced by repeated
// growth: the expansions here have at most a few dozen components).
Expansion add(const Expansion& e, const Expansion& f) {
  Expansion h = e;
  for (double b : f) {
    Expansion g;
    g.reserve(h.size() + 1);
    double q = b;
    for (double component : h) {
      double sum, error;
      twoSum(q, component, &sum, &error);
      if (error != 0.0) g.push_back(error);
      q = sum;
    }
    if (q != 0.0) g.push_back(q);
    h.swap(g);
  }
  return h;
}

// e * b for a double b.
Expansion scale(const Expansion& e, double b) {
  Expansion h;
  if (e.empty() || b == 0.0) return h;
  double q, low;
  twoProduct(e[0], b, &q, &low);
  if (low != 0.0) h.push_back(low);
  for (size_t i = 1; i < e.size(); ++i) {
    double high, product_low;
    twoProduct(e[i], b, &high, &product_low);
    double sum, error;
    twoSum(q, product_low, &sum, &error);
    if (error != 0.0) h.push_back(error);
    double new_q;
    twoSum(high, sum, &new_q, &error);
    if (error != 0.0) h.push_back(error);
    q = new_q;
  }
  if (q != 0.0) h.push_back(q);
  return h;
}

Expansion multiply(const Expansion& e, const Expansion& f) {
  Expansion h;
  for (double b : f) h = add(h, scale(e, b));
  return h;
}

Expansion negate(Expansion e) {
  for (double& c : e) c = -c;
  return e;
}

Expansion difference(double a, double b) {
  double x, y;
  twoSum(a, -b, &x, &y);
  Expansion e;
  if (y != 0.0) e.push_back(y);
  if (x != 0.0) e.push_back(x);
  return e;
}

int exactSign(const std::array<double, 3>& a, const std::array<double, 3>& b,
              const std::array<double, 3>& c, const std::array<double, 3>& d) {
  Expansion u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = difference(b[k], a[k]);
    v[k] = difference(c[k], a[k]);
    w[k] = difference(d[k], a[k]);
  }
  // u . (v x w)
  auto minor = [&](int i, int j) {  // v_i w_j - v_j w_i
    return add(multiply(v[i], w[j]), negate(multiply(v[j], w[i])));
  };
  Expansion det = add(add(multiply(u[0], minor(1, 2)), multiply(u[1], minor(2, 0))),
                      multiply(u[2], minor(0, 1)));
  if (det.empty()) return 0;
  return det.back() > 0 ? 1 : -1;
}

}  // namespace

int orient3dSign(const std::array<double, 3>& a, const std::array<double, 3>& b,
                 const std::array<double, 3>& c, const std::array<double, 3>& d) {
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  const double vywz = vy * wz, vzwy = vz * wy;
  const double vzwx = vz * wx, vxwz = vx * wz;
  const double vxwy = vx * wy, vywx = vy * wx;
  const double det = ux * (vywz - vzwy) + uy * (vzwx - vxwz) + uz * (vxwy - vywx);
  const double permanent = std::fabs(ux) * (std::fabs(vywz) + std::fabs(vzwy)) +
                           std::fabs(uy) * (std::fabs(vzwx) + std::fabs(vxwz)) +
                           std::fabs(uz) * (std::fabs(vxwy) + std::fabs(vywx));
  constexpr double kEpsilon = 0x1p-53;  // half an ulp of 1
  constexpr double kBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;
  const double bound = kBound * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return exactSign(a, b, c, d);
}

bool orientTets(TetMesh* mesh, uint64_t* flipped, std::string* error) {
  *flipped = 0;
  const size_t n = mesh->positions.size();
  for (size_t t = 0; t < mesh->tets.size(); ++t) {
    auto& tet = mesh->tets[t];
    for (uint32_t v : tet)
      if (v >= n) {
        *error = "tet " + std::to_string(t) + " has vertex index " + std::to_string(v) +
                 " out of range (" + std::to_string(n) + " vertices)";
        return false;
      }
    int sign = orient3dSign(mesh->positions[tet[0]], mesh->positions[tet[1]],
                            mesh->positions[tet[2]], mesh->positions[tet[3]]);
    if (sign == 0) {
      *error = "tet " + std::to_string(t) + " (vertices " + std::to_string(tet[0]) + " " +
               std::to_string(tet[1]) + " " + std::to_string(tet[2]) + " " +
               std::to_string(tet[3]) + ") is degenerate: its four vertices lie in one plane";
      return false;
    }
    if (sign < 0) {
      std::swap(tet[2], tet[3]);
      ++*flipped;
    }
  }
  return true;
}

}  // namespace mrsv
