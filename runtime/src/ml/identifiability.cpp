// Rank, condition number and null-space directions of a column-scaled Jacobian (Swevers et al.
// 2002, section 4.2), from the singular values of its triangular QR factor.

#include "modelgen/ml/identifiability.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace modelgen {
namespace {

// Components of a unit null-space vector (on unit-norm columns): at least kMoved, the
// parameter moves along the direction and is not identifiable (below, rounding of an exact
// null space); at least kNamed, it is named with its component.
constexpr double kMoved = 1e-6;
constexpr double kNamed = 0.1;

}  // namespace

Identifiability identifiability(const Eigen::MatrixXd& J, const std::vector<std::string>& names,
                                double tolerance) {
  const Eigen::Index U = J.cols();
  Identifiability out;
  out.identifiable.assign(U, true);
  Eigen::VectorXd scale = J.colwise().norm().transpose();
  std::vector<Eigen::Index> live;
  for (Eigen::Index u = 0; u < U; ++u) {
    if (scale[u] > 0 && std::isfinite(scale[u])) {
      live.push_back(u);
    } else {
      out.identifiable[u] = false;
      out.directions.push_back(names[u] + " has no effect on the fitted torques");
    }
  }
  Eigen::MatrixXd Js(J.rows(), static_cast<Eigen::Index>(live.size()));
  for (size_t c = 0; c < live.size(); ++c) Js.col(c) = J.col(live[c]) / scale[live[c]];
  // Singular values of J equal those of R in J = Q R: a small SVD whatever the rows.
  Eigen::MatrixXd R;
  if (Js.rows() > Js.cols()) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(Js);
    R = qr.matrixQR().topRows(Js.cols()).triangularView<Eigen::Upper>();
  } else {
    R = Js;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(R, Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  const double largest = sv.size() > 0 ? sv[0] : 0.0;
  out.rank = 0;
  for (Eigen::Index k = 0; k < sv.size(); ++k) {
    if (sv[k] > tolerance * largest) ++out.rank;
  }
  out.condition_number = out.rank == static_cast<int>(U) && sv.size() > 0
                             ? largest / sv[sv.size() - 1]
                             : std::numeric_limits<double>::infinity();
  for (Eigen::Index k = out.rank; k < sv.size(); ++k) {
    const Eigen::VectorXd v = svd.matrixV().col(k);
    std::vector<Eigen::Index> order(v.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](Eigen::Index a, Eigen::Index b) { return std::abs(v[a]) > std::abs(v[b]); });
    std::ostringstream text;
    text.precision(2);
    // Every parameter the direction moves is undetermined; the dominant ones are named with
    // their components, the others (moved by less than kNamed) after them.
    int listed = 0;
    std::vector<std::string> also;
    for (const Eigen::Index c : order) {
      if (std::abs(v[c]) < kMoved) break;
      out.identifiable[live[c]] = false;
      if (listed == 0 || std::abs(v[c]) >= kNamed) {
        text << (listed++ > 0 ? ", " : "") << names[live[c]] << " (" << v[c] << ")";
      } else {
        also.push_back(names[live[c]]);
      }
    }
    text << (listed > 1 ? " cannot be told apart" : " cannot be determined")
         << " by these data (singular value " << sv[k] / std::max(largest, 1e-300)
         << " of the largest, columns scaled to unit norm)";
    if (!also.empty()) {
      text << "; with them";
      for (const std::string& name : also) text << " " << name;
      text << (also.size() > 1 ? " are" : " is") << " undetermined too";
    }
    text << "; excite the robot differently or make one of them known";
    out.directions.push_back(text.str());
  }
  return out;
}

}  // namespace modelgen
