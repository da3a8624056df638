#include "biovision_hri/linear_svm_trainer.hpp"

#include <stdexcept>
#include <string>

#include <linear.h>

namespace biovision_hri
{
namespace
{
void quiet(const char*)
{
}
}  // namespace

LinearSvmTrainer::Result LinearSvmTrainer::train(const cv::Mat& samples, const std::vector<int>& labels,
                                                 const Parameters& parameters)
{
  if (samples.empty() || samples.type() != CV_32FC1)
    throw std::invalid_argument("LinearSvmTrainer: samples must be a non-empty CV_32FC1 matrix");
  if (static_cast<int>(labels.size()) != samples.rows)
    throw std::invalid_argument("LinearSvmTrainer: " + std::to_string(labels.size()) + " labels for " +
                                std::to_string(samples.rows) + " samples");
  bool has_pos = false, has_neg = false;
  for (int y : labels)
  {
    if (y != 1 && y != -1)
      throw std::invalid_argument("LinearSvmTrainer: labels must be +1 or -1, got " + std::to_string(y));
    (y > 0 ? has_pos : has_neg) = true;
  }
  if (!has_pos || !has_neg)
    throw std::invalid_argument("LinearSvmTrainer: both classes are needed");

  const int n = samples.rows, d = samples.cols;
  const bool with_bias = parameters.bias > 0;
  const int per_row = d + (with_bias ? 1 : 0) + 1;  // features, bias, terminator
  std::vector<feature_node> nodes(static_cast<size_t>(n) * per_row);
  std::vector<feature_node*> rows(n);
  std::vector<double> y(n);
  for (int i = 0; i < n; ++i)
  {
    feature_node* row = nodes.data() + static_cast<size_t>(i) * per_row;
    rows[i] = row;
    y[i] = labels[i];
    const float* x = samples.ptr<float>(i);
    for (int j = 0; j < d; ++j)
      row[j] = feature_node{j + 1, x[j]};
    if (with_bias)
      row[d] = feature_node{d + 1, parameters.bias};
    row[per_row - 1] = feature_node{-1, 0.0};
  }
  problem prob{};
  prob.l = n;
  prob.n = d + (with_bias ? 1 : 0);
  prob.y = y.data();
  prob.x = rows.data();
  prob.bias = with_bias ? parameters.bias : -1.0;

  int weight_label[2] = {1, -1};
  double weight[2] = {parameters.positive_weight, 1.0};
  parameter param{};
  param.solver_type = parameters.solver;
  param.eps = parameters.epsilon;
  param.C = parameters.C;
  param.nr_weight = 2;
  param.weight_label = weight_label;
  param.weight = weight;
  param.p = 0.1;
  param.init_sol = nullptr;
  if (const char* error = check_parameter(&prob, &param))
    throw std::invalid_argument(std::string("LinearSvmTrainer: LIBLINEAR refuses the parameters: ") + error);

  set_print_string_function(&quiet);
  model* m = ::train(&prob, &param);
  Result result;
  result.weights.resize(d);
  // LIBLINEAR orders classes by first appearance; get_decfun_coef gives w for label[0] vs the rest.
  const double sign = (m->label[0] == 1) ? 1.0 : -1.0;
  for (int j = 0; j < d; ++j)
    result.weights[j] = static_cast<float>(sign * get_decfun_coef(m, j + 1, 0));
  result.bias = with_bias ? static_cast<float>(sign * get_decfun_bias(m, 0)) : 0.f;
  free_and_destroy_model(&m);
  return result;
}
}  // namespace biovision_hri
