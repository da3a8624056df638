#include "biovision_recognition/lda_hash_trainer.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

namespace biovision_recognition
{
namespace
{
using MatrixD = Eigen::MatrixXd;

/// Leading `rank` eigenpairs of D^T D / rows, descending.
void leadingEigenpairs(const LdaHashTrainer::Matrix& d, int rank, int exact_limit, int iterations, unsigned seed,
                       Eigen::VectorXd& values, MatrixD& vectors)
{
  const Eigen::Index n = d.cols();
  const double inv_rows = 1.0 / static_cast<double>(d.rows());
  if (n <= exact_limit)
  {
    const MatrixD cov = (d.transpose() * d).cast<double>() * inv_rows;
    Eigen::SelfAdjointEigenSolver<MatrixD> eig(cov);
    const Eigen::Index r = std::min<Eigen::Index>(rank, n);
    values = eig.eigenvalues().reverse().head(r);
    vectors = eig.eigenvectors().rowwise().reverse().leftCols(r);
    return;
  }
  // Randomised subspace iteration on the covariance, in float for the big products.
  const Eigen::Index l = std::min<Eigen::Index>(n, rank + 32);
  std::mt19937 rng(seed);
  std::normal_distribution<float> gauss;
  Eigen::MatrixXf q(n, l);
  for (Eigen::Index i = 0; i < q.size(); ++i)
    q.data()[i] = gauss(rng);
  for (int it = 0; it <= iterations; ++it)
  {
    const Eigen::MatrixXf dq = d * q;              // rows x l
    const Eigen::MatrixXf y = d.transpose() * dq;  // n x l
    Eigen::HouseholderQR<Eigen::MatrixXf> qr(y);
    q = qr.householderQ() * Eigen::MatrixXf::Identity(n, l);
  }
  const MatrixD b = (d * q).cast<double>();
  const MatrixD small = b.transpose() * b * inv_rows;
  Eigen::SelfAdjointEigenSolver<MatrixD> eig(small);
  const Eigen::Index r = std::min<Eigen::Index>(rank, l);
  values = eig.eigenvalues().reverse().head(r);
  vectors = q.cast<double>() * eig.eigenvectors().rowwise().reverse().leftCols(r);
}
}  // namespace

DescriptorModel LdaHashTrainer::train(const Matrix& pa, const Matrix& pb, const Matrix& na, const Matrix& nb) const
{
  if (pa.rows() != pb.rows() || na.rows() != nb.rows() || pa.cols() != pb.cols() || na.cols() != nb.cols())
    throw std::invalid_argument("LdaHashTrainer: the pair matrices disagree in size");
  return trainOnDifferences(pa, pa - pb, na, na - nb);
}

DescriptorModel LdaHashTrainer::trainOnDifferences(const Matrix& pa, const Matrix& dp, const Matrix& na,
                                                   const Matrix& dn) const
{
  if (pa.rows() != dp.rows() || na.rows() != dn.rows() || pa.cols() != dp.cols() || pa.cols() != na.cols() ||
      na.cols() != dn.cols())
    throw std::invalid_argument("LdaHashTrainer: the pair matrices disagree in size");
  const int bits = parameters_.bits;
  if (pa.rows() < 2 * bits || na.rows() < 2 * bits)
    throw std::invalid_argument("LdaHashTrainer: need at least 2 * bits positive and negative pairs");
  if (parameters_.whitening_rank < bits || pa.cols() < bits)
    throw std::invalid_argument("LdaHashTrainer: whitening_rank and the feature count must be >= bits");

  // 1. Regularised Sigma_N^-1/2 on the leading eigenpairs.
  Eigen::VectorXd lambda;
  MatrixD u;
  leadingEigenpairs(dn, parameters_.whitening_rank, parameters_.exact_limit, parameters_.power_iterations,
                    parameters_.seed, lambda, u);
  const double floor = parameters_.ridge * std::max(lambda(0), 1e-30);
  const Eigen::VectorXd inv_sqrt = (lambda.array().max(0.0) + floor).rsqrt();
  const MatrixD w = inv_sqrt.asDiagonal() * u.transpose();  // rank x n

  // 2. Smallest eigenvectors of the whitened positive covariance.
  const MatrixD zp = dp.cast<double>() * w.transpose();  // pairs x rank
  const MatrixD sp = zp.transpose() * zp / static_cast<double>(dp.rows());
  Eigen::SelfAdjointEigenSolver<MatrixD> eig(sp);  // ascending
  const Eigen::VectorXd s = eig.eigenvalues().head(bits).array().max(1e-12);
  const MatrixD v = eig.eigenvectors().leftCols(bits);
  const MatrixD p = s.array().rsqrt().matrix().asDiagonal() * v.transpose() * w;

  DescriptorModel model;
  model.projection = p.cast<float>();
  // b = a - difference, so P b = P a - P difference.
  const Matrix ya = pa * model.projection.transpose(), yb = ya - dp * model.projection.transpose();
  const Matrix za = na * model.projection.transpose(), zb = za - dn * model.projection.transpose();
  model.thresholds = thresholds(ya, yb, za, zb);
  return model;
}

Eigen::VectorXf LdaHashTrainer::thresholds(const Matrix& ya, const Matrix& yb, const Matrix& za, const Matrix& zb) const
{
  const int k = std::max(2, parameters_.threshold_candidates);
  Eigen::VectorXf t(ya.cols());
  std::vector<long> pos_delta(k + 1), neg_delta(k + 1);
  for (Eigen::Index b = 0; b < ya.cols(); ++b)
  {
    const float lo = std::min({ya.col(b).minCoeff(), yb.col(b).minCoeff(), za.col(b).minCoeff(), zb.col(b).minCoeff()});
    const float hi = std::max({ya.col(b).maxCoeff(), yb.col(b).maxCoeff(), za.col(b).maxCoeff(), zb.col(b).maxCoeff()});
    const double step = (hi - lo) / (k - 1);
    if (!(step > 0))
    {
      t(b) = lo;
      continue;
    }
    // Candidate c = lo + c * step separates a pair (u, v) iff min(u,v) <= c < max(u,v) (bit = value > t).
    auto first = [&](float value) { return static_cast<long>(std::ceil((value - lo) / step - 1e-9)); };
    std::fill(pos_delta.begin(), pos_delta.end(), 0);
    std::fill(neg_delta.begin(), neg_delta.end(), 0);
    auto add = [&](std::vector<long>& delta, float u, float v) {
      const long from = std::max(0L, first(std::min(u, v)));
      const long to = std::min<long>(k, first(std::max(u, v)));  // exclusive
      if (from < to)
      {
        ++delta[from];
        --delta[to];
      }
    };
    for (Eigen::Index i = 0; i < ya.rows(); ++i)
      add(pos_delta, ya(i, b), yb(i, b));
    for (Eigen::Index i = 0; i < za.rows(); ++i)
      add(neg_delta, za(i, b), zb(i, b));
    long pos_split = 0, neg_split = 0, best = -1;
    int best_c = 0;
    for (int c = 0; c < k; ++c)
    {
      pos_split += pos_delta[c];
      neg_split += neg_delta[c];
      const long correct = (static_cast<long>(ya.rows()) - pos_split) + neg_split;
      if (correct > best)
      {
        best = correct;
        best_c = c;
      }
    }
    t(b) = static_cast<float>(lo + best_c * step);
  }
  return t;
}
}  // namespace biovision_recognition
