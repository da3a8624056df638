#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace biovision_hri
{
/// A linear SVM trained with LIBLINEAR (Fan et al. 2008; Debian's liblinear, `#include <linear.h>`), as
/// the thesis (L390). The thesis gives C = 0.01 and nothing else ([gap]): the solver is LIBLINEAR's
/// default L2-regularised L2-loss dual (-s 1), with a bias feature of value 1 (-B 1; the features are
/// non-negative, so without a bias the hyperplane is forced through the origin). LIBLINEAR 2.3
/// regularises the bias term like any weight.
class LinearSvmTrainer
{
public:
  struct Parameters
  {
    double C = 0.01;               ///< soft-margin cost (thesis L390). > 0
    int solver = 1;                ///< LIBLINEAR solver_type (1 = L2R_L2LOSS_SVC_DUAL, 2 = primal, 3 = L1-loss dual)
    double bias = 1.0;             ///< value of the appended bias feature; <= 0 = none
    double epsilon = 0.1;          ///< stopping tolerance (LIBLINEAR's default for -s 1)
    double positive_weight = 1.0;  ///< C multiplier of the positive class (class imbalance). > 0
  };

  struct Result
  {
    std::vector<float> weights;  ///< one per feature column
    float bias = 0.f;            ///< w_bias * bias value
  };

  /// samples: N x D CV_32F rows; labels: N values, +1 or -1 (both must occur). Throws
  /// std::invalid_argument for mismatched sizes, other labels, a single class or a LIBLINEAR parameter
  /// error (check_parameter's message).
  static Result train(const cv::Mat& samples, const std::vector<int>& labels, const Parameters& parameters);
};
}  // namespace biovision_hri
