#include "palpa/mat/fit_residual.hpp"

#include <algorithm>
#include <cmath>

namespace palpa::mat {

FitResidual fit_residual(const MatBody& body, const BodyGrid& grid, const MaterialDefaults& defaults) {
  FitResidual res;
  const auto samples = skeleton_samples(grid, defaults);
  std::array<double, kSkeletonChannels> sk{};
  std::array<double, 3> top{};
  std::array<double, 3> bottom{};
  for (int i = 0; i < grid.rows; ++i) {
    for (int j = 0; j < grid.cols; ++j) {
      const auto k = static_cast<std::size_t>(i * grid.cols + j);
      const double u = body.u_params()[static_cast<std::size_t>(i)];
      const double v = body.v_params()[static_cast<std::size_t>(j)];
      body.skeleton().evaluate(u, v, sk);
      for (std::size_t c = 0; c < kSkeletonChannels; ++c) {
        res.skeleton[c] = std::max(res.skeleton[c], std::abs(sk[c] - samples[k * kSkeletonChannels + c]));
      }
      double n[3] = {0.0, 0.0, 0.0};
      skeleton_normal(body.skeleton(), u, v, n);
      body.top().evaluate(u, v, top);
      body.bottom().evaluate(u, v, bottom);
      double dt = 0.0;
      double db = 0.0;
      for (std::size_t c = 0; c < 3; ++c) {
        const double r = grid.radius[k] * n[c];
        dt += std::pow(top[c] - (grid.medial[k][c] + r), 2);
        db += std::pow(bottom[c] - (grid.medial[k][c] - r), 2);
      }
      res.top = std::max(res.top, std::sqrt(dt));
      res.bottom = std::max(res.bottom, std::sqrt(db));
    }
  }
  return res;
}

}  // namespace palpa::mat
