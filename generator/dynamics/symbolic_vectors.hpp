// 3-vectors and 3x3 matrices of DAG expressions and the few operations the symbolic dynamics
// need; every operation folds constants as it builds, so exact geometry disappears at once.
#pragma once

#include <array>

#include "generator/symbolic/expr.hpp"

namespace modelgen::gen {

using V3 = std::array<ExprId, 3>;
using M3 = std::array<ExprId, 9>;  // row-major

class VectorAlgebra {
 public:
  explicit VectorAlgebra(ExprGraph& g) : g_(g) {}

  V3 zero() const { return {g_.zero(), g_.zero(), g_.zero()}; }
  V3 vector(const std::array<double, 3>& v) {
    return {g_.constant(v[0]), g_.constant(v[1]), g_.constant(v[2])};
  }
  M3 matrix(const std::array<double, 9>& m) {
    M3 out;
    for (int i = 0; i < 9; ++i) out[i] = g_.constant(m[i]);
    return out;
  }
  V3 add(const V3& a, const V3& b) {
    return {g_.add(a[0], b[0]), g_.add(a[1], b[1]), g_.add(a[2], b[2])};
  }
  // Each component as an atom computed once (a customized Newton-Euler intermediate variable).
  V3 share(const V3& a) { return {g_.share(a[0]), g_.share(a[1]), g_.share(a[2])}; }
  V3 scale(ExprId s, const V3& a) { return {g_.mul(s, a[0]), g_.mul(s, a[1]), g_.mul(s, a[2])}; }
  ExprId dot(const V3& a, const V3& b) {
    return g_.add({g_.mul(a[0], b[0]), g_.mul(a[1], b[1]), g_.mul(a[2], b[2])});
  }
  V3 cross(const V3& a, const V3& b) {
    return {g_.sub(g_.mul(a[1], b[2]), g_.mul(a[2], b[1])),
            g_.sub(g_.mul(a[2], b[0]), g_.mul(a[0], b[2])),
            g_.sub(g_.mul(a[0], b[1]), g_.mul(a[1], b[0]))};
  }
  V3 mul(const M3& m, const V3& v) {
    V3 out;
    for (int r = 0; r < 3; ++r) {
      out[r] = g_.add({g_.mul(m[3 * r], v[0]), g_.mul(m[3 * r + 1], v[1]), g_.mul(m[3 * r + 2], v[2])});
    }
    return out;
  }
  V3 mul_transposed(const M3& m, const V3& v) {
    V3 out;
    for (int c = 0; c < 3; ++c) {
      out[c] = g_.add({g_.mul(m[c], v[0]), g_.mul(m[3 + c], v[1]), g_.mul(m[6 + c], v[2])});
    }
    return out;
  }
  M3 mul(const M3& a, const M3& b) {
    M3 out;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        out[3 * r + c] = g_.add({g_.mul(a[3 * r], b[c]), g_.mul(a[3 * r + 1], b[3 + c]),
                                 g_.mul(a[3 * r + 2], b[6 + c])});
      }
    }
    return out;
  }

 private:
  ExprGraph& g_;
};

}  // namespace modelgen::gen
