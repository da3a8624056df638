#include "biovision_v1/fourier_transform.hpp"

#include <fftw3.h>

#include <cstdint>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <tuple>

namespace biovision_v1
{
namespace
{
enum class Kind
{
  kRealForward,
  kComplexForward,
  kComplexInverse
};

struct Key
{
  int rows, cols;
  Kind kind;
  bool in_place;
  bool operator<(const Key& o) const
  {
    return std::tie(rows, cols, kind, in_place) < std::tie(o.rows, o.cols, o.kind, o.in_place);
  }
};

struct Entry
{
  std::shared_ptr<fftwf_plan_s> plan;
  std::int64_t last_use = 0;
  int executions = 0;     // since the plan was made, counted up to the measuring threshold only
  bool measured = false;  // an FFTW_MEASURE plan (or its making is under way)
};

// FFTW's planner (making and destroying plans) is not thread-safe; fftwf_execute_dft* is. Lock order:
// the planner's lock is never taken while the cache's is held, so a thread measuring a plan never stops
// the others from finding and executing the plans they have (a thread that needs a new plan waits).
std::mutex& plannerMutex()
{
  static std::mutex m;
  return m;
}

// BIOVISION_FFT_MEASURE_AFTER: the process's measuring threshold (0: estimated plans only), e.g. from a
// launch file's <env>; unset or not a number: kMeasureAfter.
int measureAfterFromEnvironment()
{
  const char* v = std::getenv("BIOVISION_FFT_MEASURE_AFTER");
  if (!v || !*v)
    return FourierTransform::kMeasureAfter;
  char* end = nullptr;
  const long n = std::strtol(v, &end, 10);
  return *end == '\0' && n >= 0 && n <= 1000000 ? static_cast<int>(n) : FourierTransform::kMeasureAfter;
}

struct Cache
{
  std::mutex mutex;
  std::map<Key, Entry> plans;
  std::int64_t uses = 0, made = 0, measured = 0;
  int measure_after = measureAfterFromEnvironment();
  int measure_budget = FourierTransform::kMaxMeasuredPlans, budget_used = 0;
  bool mayMeasure() const { return measure_after > 0 && budget_used < measure_budget; }
};

Cache& cache()
{
  plannerMutex();  // constructed first, so destroyed after the cache, whose plans' deleters lock it
  static Cache c;
  return c;
}

std::shared_ptr<fftwf_plan_s> makePlan(const Key& key, unsigned flags)
{
  std::lock_guard<std::mutex> lock(plannerMutex());
  // Plans are made on scratch arrays with fftwf_malloc's alignment (FFTW_MEASURE overwrites them);
  // execute() checks the caller's arrays match that alignment.
  const size_t n = static_cast<size_t>(key.rows) * key.cols;
  fftwf_complex* out = fftwf_alloc_complex(n);
  void* in = key.in_place ? static_cast<void*>(out) : fftwf_malloc(n * sizeof(fftwf_complex));
  fftwf_set_timelimit(FourierTransform::kMeasureTimeLimit);
  fftwf_plan p = nullptr;
  if (key.kind == Kind::kRealForward)
  {
    // Output rows W complex apart (the full spectrum's layout): FFTW writes columns 0..W/2 of each.
    const int n2[2] = {key.rows, key.cols};
    p = fftwf_plan_many_dft_r2c(2, n2, 1, static_cast<float*>(in), nullptr, 1, 0, out, n2, 1, 0, flags);
  }
  else
    p = fftwf_plan_dft_2d(key.rows, key.cols, static_cast<fftwf_complex*>(in), out,
                          key.kind == Kind::kComplexForward ? FFTW_FORWARD : FFTW_BACKWARD, flags);
  if (!key.in_place)
    fftwf_free(in);
  fftwf_free(out);
  if (!p)
    throw std::runtime_error("FourierTransform: FFTW could not plan a " + std::to_string(key.rows) + "x" +
                             std::to_string(key.cols) + " transform");
  return std::shared_ptr<fftwf_plan_s>(p, [](fftwf_plan q) {
    std::lock_guard<std::mutex> l(plannerMutex());
    fftwf_destroy_plan(q);
  });
}

// The plan to execute for key: a new size gets an FFTW_ESTIMATE plan at once (about 1 ms); a size
// executed measure_after times is planned again with FFTW_MEASURE (100-300 ms once, by the thread that
// crossed the count, while the others keep executing the estimated plan), which runs the bank's sizes
// 1.3-3.6x faster (fftw 3.3.10 here: 480x640 complex 2.4 -> 0.67 ms, 400x480 0.80 -> 0.45 ms), until
// measure_budget plans have been measured: recognition's crops come in ever new sizes, and measuring
// each that recurs took its CPU per frame from 39 to 289 ms in loop_bench.
std::shared_ptr<fftwf_plan_s> planFor(const Key& key)
{
  Cache& c = cache();
  std::shared_ptr<fftwf_plan_s> evicted, replaced;  // destroyed after the locks (their deleter locks)
  bool measure = false;
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    ++c.uses;
    auto it = c.plans.find(key);
    if (it != c.plans.end())
    {
      Entry& e = it->second;
      e.last_use = c.uses;
      if (e.measured || !c.mayMeasure())
        return e.plan;
      if (++e.executions < c.measure_after)  // never past the threshold: no overflow in a long run
        return e.plan;
      e.measured = true;  // this thread measures; the others keep the estimated plan meanwhile
      ++c.budget_used;
      measure = true;
    }
  }
  std::shared_ptr<fftwf_plan_s> plan;
  try
  {
    plan = makePlan(key, measure ? FFTW_MEASURE : FFTW_ESTIMATE);
  }
  catch (const std::exception&)
  {
    if (!measure)
      throw;
    // Measuring failed: give the budget back and keep the estimated plan (never measured again).
    std::lock_guard<std::mutex> lock(c.mutex);
    --c.budget_used;
    auto it = c.plans.find(key);
    if (it == c.plans.end())
      throw;
    return it->second.plan;
  }
  std::lock_guard<std::mutex> lock(c.mutex);
  ++c.made;
  c.measured += measure ? 1 : 0;
  auto it = c.plans.find(key);
  if (it != c.plans.end())
  {
    if (!measure)
    {
      evicted = std::move(plan);  // another thread made this size's plan meanwhile: use theirs
      return it->second.plan;
    }
    replaced = std::move(it->second.plan);
    it->second.plan = plan;
    it->second.measured = true;  // also when another thread re-made an evicted entry meanwhile
    return plan;
  }
  if (static_cast<int>(c.plans.size()) >= FourierTransform::kMaxPlans)
  {
    auto oldest = c.plans.begin();
    for (auto i = c.plans.begin(); i != c.plans.end(); ++i)
      if (i->second.last_use < oldest->second.last_use)
        oldest = i;
    evicted = std::move(oldest->second.plan);  // a thread still executing it holds its own reference
    c.plans.erase(oldest);
  }
  Entry e;
  e.plan = plan;
  e.last_use = c.uses;
  e.executions = 1;
  e.measured = measure;
  c.plans[key] = e;
  return plan;
}

// FFTW executes a plan on new arrays only with the alignment it was planned with (fftwf_malloc's).
bool usable(const cv::Mat& m)
{
  return m.isContinuous() && fftwf_alignment_of(reinterpret_cast<float*>(m.data)) == 0;
}

// dst as a continuous, aligned CV_32FC2 matrix of the given size (reallocated when it is not).
void prepareOutput(cv::Mat& dst, const cv::Size& size)
{
  dst.create(size, CV_32FC2);
  if (!usable(dst))
    dst = cv::Mat(size, CV_32FC2);
}

// One row of complex products; double intermediates round as cv::mulSpectrums does (a float product of
// floats is exact in double, so each part is rounded once, to float). Vectorised per clone.
__attribute__((target_clones("avx512f", "avx2", "default"))) void multiplyRow(const float* a, const float* b,
                                                                              float* out, int n)
{
  for (int i = 0; i < n; ++i)
  {
    const double ar = a[2 * i], ai = a[2 * i + 1], br = b[2 * i], bi = b[2 * i + 1];
    out[2 * i] = static_cast<float>(ar * br - ai * bi);
    out[2 * i + 1] = static_cast<float>(ar * bi + ai * br);
  }
}
}  // namespace

void FourierTransform::multiplySpectra(const cv::Mat& a, const cv::Mat& b, cv::Mat& product)
{
  if (a.type() != CV_32FC2 || b.type() != CV_32FC2 || a.size() != b.size() || a.empty())
    throw std::invalid_argument("FourierTransform::multiplySpectra: needs two non-empty CV_32FC2 spectra of one size");
  if (product.data != a.data && product.data != b.data)
    prepareOutput(product, a.size());
  for (int y = 0; y < a.rows; ++y)
    multiplyRow(a.ptr<float>(y), b.ptr<float>(y), product.ptr<float>(y), a.cols);
}

void FourierTransform::forward(const cv::Mat& src_in, cv::Mat& spectrum)
{
  if (src_in.empty() || (src_in.type() != CV_32FC1 && src_in.type() != CV_32FC2))
    throw std::invalid_argument("FourierTransform::forward: needs a non-empty CV_32FC1 or CV_32FC2 image");
  const cv::Mat src = usable(src_in) ? src_in : src_in.clone();
  const int h = src.rows, w = src.cols;
  if (src.type() == CV_32FC2)
  {
    const bool in_place = spectrum.data == src.data && spectrum.size() == src.size() && spectrum.type() == CV_32FC2;
    if (!in_place)
      prepareOutput(spectrum, src.size());
    const auto plan = planFor({h, w, Kind::kComplexForward, in_place});
    fftwf_execute_dft(plan.get(), reinterpret_cast<fftwf_complex*>(src.data),
                      reinterpret_cast<fftwf_complex*>(spectrum.data));
    return;
  }
  // Written into spectrum's own buffer when nothing else holds it (a fresh spectrum per call was a third
  // of BioBin's page faults); never src's buffer: a real image is not its own spectrum.
  releaseIfShared(spectrum);
  if (spectrum.data == src.data)
    spectrum.release();
  cv::Mat& out = spectrum;
  prepareOutput(out, src.size());
  const auto plan = planFor({h, w, Kind::kRealForward, false});
  fftwf_execute_dft_r2c(plan.get(), reinterpret_cast<float*>(src.data), reinterpret_cast<fftwf_complex*>(out.data));
  // The other half: X[y][x] = conj(X[-y mod H][W - x]) for x > W/2 (those sources are all in the computed half).
  for (int y = 0; y < h; ++y)
  {
    cv::Vec2f* row = out.ptr<cv::Vec2f>(y);
    const cv::Vec2f* mirror = out.ptr<cv::Vec2f>((h - y) % h);
    for (int x = w / 2 + 1; x < w; ++x)
      row[x] = cv::Vec2f(mirror[w - x][0], -mirror[w - x][1]);
  }
}

void FourierTransform::releaseIfShared(cv::Mat& m)
{
  if (m.u && CV_XADD(&m.u->refcount, 0) > 1)  // an atomic read: other threads may release their views
    m.release();
}

void FourierTransform::inverseUnscaled(const cv::Mat& spectrum_in, cv::Mat& dst)
{
  if (spectrum_in.empty() || spectrum_in.type() != CV_32FC2)
    throw std::invalid_argument("FourierTransform::inverseUnscaled: needs a non-empty CV_32FC2 spectrum");
  const cv::Mat spectrum = usable(spectrum_in) ? spectrum_in : spectrum_in.clone();
  const bool in_place = dst.data == spectrum.data && dst.size() == spectrum.size() && dst.type() == CV_32FC2;
  if (!in_place)
    prepareOutput(dst, spectrum.size());
  const auto plan = planFor({spectrum.rows, spectrum.cols, Kind::kComplexInverse, in_place});
  fftwf_execute_dft(plan.get(), reinterpret_cast<fftwf_complex*>(spectrum.data),
                    reinterpret_cast<fftwf_complex*>(dst.data));
}

std::string FourierTransform::backend()
{
  return std::string("fftw3f ") + fftwf_version;
}

long FourierTransform::plansMade()
{
  std::lock_guard<std::mutex> lock(cache().mutex);
  return cache().made;
}

long FourierTransform::plansMeasured()
{
  std::lock_guard<std::mutex> lock(cache().mutex);
  return cache().measured;
}

void FourierTransform::setMeasurePolicy(int after_executions, int max_measured_plans)
{
  std::lock_guard<std::mutex> lock(cache().mutex);
  cache().measure_after = after_executions;
  cache().measure_budget = max_measured_plans;
  cache().budget_used = 0;
}
int FourierTransform::warmUp(const std::function<void()>& run, int max_runs)
{
  Cache& c = cache();
  int calls = 0;
  bool pending = true;
  while (pending && calls < max_runs)
  {
    std::int64_t since = 0;
    {
      std::lock_guard<std::mutex> lock(c.mutex);
      since = c.uses;
    }
    run();
    ++calls;
    // Again while a plan this run used is still an estimated one that will be measured.
    std::lock_guard<std::mutex> lock(c.mutex);
    pending = false;
    for (const auto& [key, entry] : c.plans)
      pending = pending || (entry.last_use > since && !entry.measured && c.mayMeasure());
  }
  return calls;
}
}  // namespace biovision_v1
