// The a-priori values' disagreement with the data per link (a_priori_disagreement.hpp).

#include "modelgen/estimation/a_priori_disagreement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace modelgen {
namespace {

// Row j's a-priori value, or nullopt when a standard parameter in it has none.
std::optional<double> regrouped_a_priori(const Eigen::MatrixXd& K, Eigen::Index j,
                                         const std::vector<std::optional<double>>& a_priori,
                                         double small) {
  double sum = 0;
  for (Eigen::Index k = 0; k < K.cols(); ++k) {
    if (std::abs(K(j, k)) <= small) continue;
    const auto& value = a_priori[static_cast<std::size_t>(k)];
    if (!value) return std::nullopt;
    sum += K(j, k) * *value;
  }
  return sum;
}

}  // namespace

std::vector<std::vector<BaseDisagreement>> a_priori_disagreement(
    const std::vector<std::array<int, 10>>& body_params, const Eigen::MatrixXd& K,
    const std::vector<std::optional<double>>& a_priori, const Eigen::VectorXd& beta_hat,
    const Eigen::VectorXd& std_dev, const std::vector<std::string>& base_names, double threshold) {
  const auto rows = static_cast<std::size_t>(K.rows());
  if (a_priori.size() != static_cast<std::size_t>(K.cols()) ||
      static_cast<std::size_t>(beta_hat.size()) != rows ||
      static_cast<std::size_t>(std_dev.size()) != rows || base_names.size() != rows) {
    throw std::invalid_argument("a_priori_disagreement: sizes do not match K");
  }
  const double small = 1e-10 * std::max(K.cwiseAbs().maxCoeff(), 1e-300);
  std::vector<std::optional<BaseDisagreement>> row(rows);
  for (Eigen::Index j = 0; j < K.rows(); ++j) {
    const std::optional<double> value = regrouped_a_priori(K, j, a_priori, small);
    if (!value || !(std_dev[j] > 0)) continue;
    const BaseDisagreement d{base_names[static_cast<std::size_t>(j)], *value, beta_hat[j],
                             std_dev[j]};
    if (std::abs(d.z()) > threshold) row[static_cast<std::size_t>(j)] = d;
  }
  std::vector<std::vector<BaseDisagreement>> out;
  for (const auto& index : body_params) {
    std::vector<BaseDisagreement> list;
    for (std::size_t j = 0; j < rows; ++j) {
      if (!row[j]) continue;
      const bool enters = std::any_of(index.begin(), index.end(), [&](int k) {
        return k >= 0 && std::abs(K(static_cast<Eigen::Index>(j), k)) > small;
      });
      if (enters) list.push_back(*row[j]);
    }
    std::stable_sort(list.begin(), list.end(), [](const auto& a, const auto& b) {
      return std::abs(a.z()) > std::abs(b.z());
    });
    out.push_back(std::move(list));
  }
  return out;
}

std::vector<std::string> disagreement_words(const std::vector<BaseDisagreement>& list,
                                            std::size_t count) {
  std::vector<std::string> out;
  char text[96];
  for (std::size_t i = 0; i < list.size() && i < count; ++i) {
    std::snprintf(text, sizeof text, "%s %+.1f sd", list[i].name.c_str(), list[i].z());
    out.emplace_back(text);
  }
  return out;
}

}  // namespace modelgen
