#include "biovision_stereo/iterative_spatial_filter.hpp"

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "avx512_clone.hpp"
#include "biovision_common/parallel_arena.hpp"

namespace biovision_stereo
{
namespace
{
// One row of one slice: the over-relaxed update, freezing and the count of costs that moved. Branch-free
// on 32-bit lanes only (float costs, float 0/1 frozen marks, int count), so that it vectorises.
inline int updateRow(float* cost, const float* mean, const float* inv_norm, float* frozen, int w, float r, float th)
{
  int moved = 0;
  for (int x = 0; x < w; ++x)
  {
    const float before = cost[x];
    const float after = before + r * (mean[x] * inv_norm[x] - before);
    const bool keep = (frozen[x] != 0.f) | (inv_norm[x] == 0.f);
    cost[x] = keep ? before : after;
    frozen[x] = (keep | ((before < th) & (after < th))) ? 1.f : 0.f;
    moved += (!keep & (std::abs(after - before) > 1e-3f)) ? 1 : 0;
  }
  return moved;
}

// The same row compiled for AVX-512, AVX2 (no FMA: the same bits) and the baseline instruction set.
__attribute__((target("avx2"), flatten)) int updateRowAvx2(float* cost, const float* mean, const float* inv_norm,
                                                           float* frozen, int w, float r, float th)
{
  return updateRow(cost, mean, inv_norm, frozen, w, r, th);
}

BIOVISION_STEREO_AVX512_CLONE int updateRowAvx512(float* cost, const float* mean, const float* inv_norm, float* frozen,
                                                  int w, float r, float th)
{
  return updateRow(cost, mean, inv_norm, frozen, w, r, th);
}

__attribute__((flatten)) int updateRowGeneric(float* cost, const float* mean, const float* inv_norm, float* frozen,
                                              int w, float r, float th)
{
  return updateRow(cost, mean, inv_norm, frozen, w, r, th);
}

const cv::Mat& binomial()
{
  static const cv::Mat kernel = (cv::Mat_<float>(1, 3) << 0.25f, 0.5f, 0.25f);
  return kernel;
}
}  // namespace

IterativeSpatialFilter::IterativeSpatialFilter(double relaxation, double stable_cost, double changing_fraction,
                                               int max_iterations)
  : relaxation_(static_cast<float>(relaxation)),
    stable_cost_(static_cast<float>(stable_cost)),
    changing_fraction_(changing_fraction),
    max_iterations_(max_iterations)
{
}

void IterativeSpatialFilter::setSimd(CostSimd simd)
{
  requireCostSimd(simd);
  simd_ = simd;
}

void IterativeSpatialFilter::weights(const CostVolume& costs, const cv::Mat& barriers, cv::Mat& weight,
                                     cv::Mat& inv_norm) const
{
  const cv::Size size = costs.size();
  if (!barriers.empty() && (barriers.size() != size || barriers.type() != CV_8UC1))
    throw std::invalid_argument("IterativeSpatialFilter: barriers must be CV_8UC1 of the volume's size");
  weight = cv::Mat(size, CV_32F, cv::Scalar(1.f));
  if (!barriers.empty())
    weight.setTo(0.f, barriers);
  cv::sepFilter2D(weight, inv_norm, CV_32F, binomial(), binomial(), cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
  for (int y = 0; y < size.height; ++y)
  {
    float* n = inv_norm.ptr<float>(y);
    for (int x = 0; x < size.width; ++x)
      n[x] = n[x] > 1e-6f ? 1.f / n[x] : 0.f;
  }
}

void IterativeSpatialFilter::apply(CostVolume& costs, const cv::Mat& barriers) const
{
  cv::Mat weight, inv_norm;
  weights(costs, barriers, weight, inv_norm);
  const cv::Size size = costs.size();
  const size_t total = size_t(size.area()) * costs.disparities();
  const size_t slice = size_t(size.area());
  frozen_.assign(slice * costs.disparities(), 0.f);  // no allocation once the capacity is there
  const auto update = simd_ == CostSimd::kAvx512 ? updateRowAvx512
                      : simd_ == CostSimd::kAvx2 ? updateRowAvx2
                                                 : updateRowGeneric;
  for (int it = 0; it < max_iterations_; ++it)
  {
    std::atomic<size_t> changed{0};
    biovision_common::parallelFor(cv::Range(0, costs.disparities()), [&](const cv::Range& ks) {
      cv::Mat masked, mean;
      size_t moved = 0;
      for (int k = ks.start; k < ks.end; ++k)
      {
        cv::Mat& c = costs.slice(k);
        cv::multiply(c, weight, masked);
        cv::sepFilter2D(masked, mean, CV_32F, binomial(), binomial(), cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
        for (int y = 0; y < size.height; ++y)
          moved += update(c.ptr<float>(y), mean.ptr<float>(y), inv_norm.ptr<float>(y),
                          frozen_.data() + slice * k + size_t(y) * size.width, size.width, relaxation_, stable_cost_);
      }
      changed += moved;
    });
    if (changed < changing_fraction_ * total)
      break;
  }
}

void IterativeSpatialFilter::applyReference(CostVolume& costs, const cv::Mat& barriers) const
{
  cv::Mat weight, inv_norm;
  weights(costs, barriers, weight, inv_norm);
  const cv::Size size = costs.size();
  const size_t total = size_t(size.area()) * costs.disparities();
  std::vector<cv::Mat> frozen(costs.disparities());
  for (cv::Mat& f : frozen)
    f = cv::Mat::zeros(size, CV_8U);
  const float r = relaxation_, th = stable_cost_;
  for (int it = 0; it < max_iterations_; ++it)
  {
    size_t changed = 0;
    cv::Mat masked, mean;
    for (int k = 0; k < costs.disparities(); ++k)
    {
      cv::Mat& c = costs.slice(k);
      cv::multiply(c, weight, masked);
      cv::sepFilter2D(masked, mean, CV_32F, binomial(), binomial(), cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
      for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x)
        {
          float& cost = c.at<float>(y, x);
          uchar& f = frozen[k].at<uchar>(y, x);
          const float before = cost, n = inv_norm.at<float>(y, x);
          const float after = before + r * (mean.at<float>(y, x) * n - before);
          if (f || n == 0.f)
          {
            f = 1;
            continue;
          }
          cost = after;
          if (before < th && after < th)
            f = 1;
          if (std::abs(after - before) > 1e-3f)
            ++changed;
        }
    }
    if (changed < changing_fraction_ * total)
      break;
  }
}
}  // namespace biovision_stereo
