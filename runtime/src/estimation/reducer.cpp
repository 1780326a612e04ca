// The Reducer's storage: rows appended below each group's factor, reduced by Householder QR when
// the block is full, factors merged across threads.

#include "runtime/src/estimation/reducer.hpp"

#include "runtime/src/estimation/row_reduction.hpp"

namespace modelgen::detail {

void Reducer::merge(Reducer&& other) {
  for (int g = 0; g < groups(); ++g) {
    Group& theirs = other.groups_[static_cast<std::size_t>(g)];
    if (theirs.rows == 0) continue;
    reduce(theirs);
    const Eigen::Index w = theirs.width();
    const auto entry = [&](Eigen::Index i, int k) {
      const int p = theirs.position[static_cast<std::size_t>(k)];
      return p < 0 ? 0.0 : theirs.S(i, p);
    };
    const auto rhs = [&](Eigen::Index i) { return theirs.S(i, 0); };
    append<kColumns>(g, w, entry, rhs, false);
    Group& ours = groups_[static_cast<std::size_t>(g)];
    ours.rows += theirs.rows;
    ours.y_squared += theirs.y_squared;
    for (int k = 0; k < params_; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      ours.column_max[kk] = std::max(ours.column_max[kk], theirs.column_max[kk]);
    }
  }
  other.groups_.clear();
}

void Reducer::reduce_all() {
  for (Group& g : groups_) reduce(g);
}

void Reducer::compact() {
  for (Group& g : groups_) {
    reduce(g);
    if (g.capacity() > 0) g.S.conservativeResize(g.width(), Eigen::NoChange);
  }
}

int Reducer::first_non_finite() {
  reduce_all();
  for (int g = 0; g < groups(); ++g) {
    const Group& group = groups_[static_cast<std::size_t>(g)];
    if (!group.S.topRows(group.width()).allFinite()) return g;
  }
  return -1;
}

double Reducer::residual_norm(int g, const Eigen::VectorXd& beta) {
  Group& group = groups_[static_cast<std::size_t>(g)];
  reduce(group);
  const Eigen::Index w = group.width();
  // R_g [beta; -1] has the norm of W_g beta - y_g.
  Eigen::VectorXd r = -group.S.col(0).head(w);
  for (Eigen::Index p = 1; p < w; ++p) {
    r += group.S.col(p).head(w) * beta[group.columns[static_cast<std::size_t>(p)]];
  }
  return r.norm();
}

void Reducer::grow(Group& g, Eigen::Index capacity) {
  const Eigen::Index w = g.width();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(w + capacity, w);
  S.topRows(w + g.pending) = g.S.topRows(w + g.pending);
  g.S.swap(S);
}

void Reducer::add_column(Group& g, int k) {
  const Eigen::Index w = g.width();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(w + 1 + g.capacity(), w + 1);
  S.topLeftCorner(w, w) = g.S.topLeftCorner(w, w);
  S.block(w + 1, 0, g.pending, w) = g.S.block(w, 0, g.pending, w);
  g.S.swap(S);
  g.position[static_cast<std::size_t>(k)] = static_cast<int>(w);
  g.columns.push_back(k);
}

void Reducer::reduce(Group& g) {
  if (g.pending == 0) return;
  const Eigen::Index w = g.width(), ld = g.S.rows();
  fold_rows(g.S.data(), ld, g.S.data() + w, ld, g.pending, w);
  g.pending = 0;
}

}  // namespace modelgen::detail
