// The point-cloud functions (nearest frame, blended frames) and the tube domain.
#include "coxmesh/oracle/point_cloud.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>

#include "coxmesh/lattice/simplex.h"
#include "coxmesh/util/parallel_for.h"

namespace coxmesh {

std::uint64_t SampleModel::next_serial() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

namespace {

// The oracle evaluates F and then the tube at each lattice vertex (ImplicitOracle::evaluate): F's
// query has found the nearest sample already, so each thread remembers its squared distance for
// the last point, and the tube reuses it instead of a query of its own (the same value: the same
// kd-tree and the same arithmetic find the same minimum).
struct LastNearest {
  std::uint64_t model = 0;  // SampleModel::serial; 0: nothing remembered
  std::array<double, SampleTree::kFixedMaxDimension> x;
  double distance2 = 0;
};
thread_local LastNearest last_nearest;

void remember_nearest(const SampleModel& model, const double* x, double distance2) {
  const int d = model.tree->dimension();
  if (d > SampleTree::kFixedMaxDimension) return;
  last_nearest.model = model.serial;
  std::copy(x, x + d, last_nearest.x.begin());
  last_nearest.distance2 = distance2;
}

double nearest_distance2(const SampleModel& model, const double* x) {
  const int d = model.tree->dimension();
  if (last_nearest.model == model.serial && std::equal(x, x + d, last_nearest.x.begin())) return last_nearest.distance2;
  double d2;
  model.tree->nearest(x, &d2);
  return d2;
}

class NearestFrameFunction final : public ImplicitFunction {
 public:
  explicit NearestFrameFunction(std::shared_ptr<const SampleModel> model) : model_(std::move(model)) {}
  int ambient_dimension() const override { return model_->frames.d; }
  int codimension() const override { return model_->frames.k; }
  void evaluate(const double* x, double* value) const override {
    const SampleFrames& fr = model_->frames;
    double d2;
    const std::uint32_t q = model_->tree->nearest(x, &d2);
    remember_nearest(*model_, x, d2);
    const double* c = fr.centers.data() + static_cast<std::size_t>(q) * fr.d;
    const double* u = fr.frame(q);
    for (int j = 0; j < fr.k; ++j) {
      double s = 0;
      for (int t = 0; t < fr.d; ++t) s += u[j * fr.d + t] * (x[t] - c[t]);
      value[j] = s;
    }
  }

 private:
  std::shared_ptr<const SampleModel> model_;
};

class BlendedFrameFunction final : public ImplicitFunction {
 public:
  BlendedFrameFunction(std::shared_ptr<const SampleModel> model, double width)
      : model_(std::move(model)), inv_w2_(1 / (width * width)), reach2_(9 * width * width) {
    // Each sample's point and frame side by side, in the tree's order: the samples a query finds
    // are read from a few nearby rows instead of two scattered arrays.
    const SampleFrames& fr = model_->frames;
    const SampleTree& tree = *model_->tree;
    const std::size_t n = tree.size(), row = static_cast<std::size_t>(fr.k + 1) * fr.d;
    rows_.resize(n * row);
    for (std::size_t at = 0; at < n; ++at) {
      const std::uint32_t i = tree.sample_at(static_cast<std::uint32_t>(at));
      std::copy(tree.point(i), tree.point(i) + fr.d, rows_.begin() + at * row);
      std::copy(fr.frame(i), fr.frame(i) + fr.k * fr.d, rows_.begin() + at * row + fr.d);
    }
  }
  int ambient_dimension() const override { return model_->frames.d; }
  int codimension() const override { return model_->frames.k; }
  void evaluate(const double* x, double* value) const override {
    const int d = model_->frames.d, k = model_->frames.k;
    const SampleTree& tree = *model_->tree;
    std::array<std::uint32_t, kBlend> at;
    std::array<double, kBlend> d2;
    int count = tree.nearest_within_by_position(x, reach2_, kBlend, at.data(), d2.data());
    if (count == 0)
      count = tree.nearest_within_by_position(x, std::numeric_limits<double>::infinity(), 1, at.data(), d2.data());
    remember_nearest(*model_, x, d2[0]);
    std::array<double, kMaxDimension> sum{};
    double total = 0;
    const std::size_t row = static_cast<std::size_t>(k + 1) * d;
    for (int i = 0; i < count; ++i) {
      // Weights relative to the nearest sample's: the same ratios, and no underflow far away.
      const double theta = std::exp(-(d2[i] - d2[0]) * inv_w2_);
      const double* p = rows_.data() + at[i] * row;
      const double* u = p + d;
      for (int j = 0; j < k; ++j) {
        double s = 0;
        for (int t = 0; t < d; ++t) s += u[j * d + t] * (x[t] - p[t]);
        sum[j] += theta * s;
      }
      total += theta;
    }
    for (int j = 0; j < k; ++j) value[j] = sum[j] / total;
  }

 private:
  static constexpr int kBlend = 32;
  std::shared_ptr<const SampleModel> model_;
  double inv_w2_, reach2_;
  std::vector<double> rows_;  // by position in the tree: the sample (d), then its frame (k × d)
};

class TubeDomain final : public ImplicitFunction {
 public:
  TubeDomain(std::shared_ptr<const SampleModel> model, double radius) : model_(std::move(model)), radius_(radius) {}
  int ambient_dimension() const override { return model_->tree->dimension(); }
  int codimension() const override { return 1; }
  void evaluate(const double* x, double* value) const override {
    value[0] = std::sqrt(nearest_distance2(*model_, x)) - radius_;
  }

 private:
  std::shared_ptr<const SampleModel> model_;
  double radius_;
};

}  // namespace

FunctionPtr nearest_frame_function(std::shared_ptr<const SampleModel> model) {
  return std::make_shared<NearestFrameFunction>(std::move(model));
}

FunctionPtr blended_frame_function(std::shared_ptr<const SampleModel> model, double width) {
  if (!(width > 0) || !std::isfinite(width)) throw InputError("the blending width must be positive");
  return std::make_shared<BlendedFrameFunction>(std::move(model), width);
}

FunctionPtr tube_domain(std::shared_ptr<const SampleModel> model, double radius) {
  if (!(radius > 0) || !std::isfinite(radius)) throw InputError("the tube radius must be positive");
  return std::make_shared<TubeDomain>(std::move(model), radius);
}

double median_spacing(const SampleTree& tree, int threads) {
  const std::size_t n = tree.size();
  if (n < 2) return 0;
  std::vector<double> nearest(n);
  constexpr std::size_t kBlock = 512;
  WorkerPool(std::max(threads, 1)).run((n + kBlock - 1) / kBlock, [&](std::size_t block, int) {
    for (std::size_t at = block * kBlock; at < std::min(n, (block + 1) * kBlock); ++at) {
      const std::size_t i = tree.sample_at(static_cast<std::uint32_t>(at));  // (nearby queries one after another)
      std::array<std::uint32_t, 2> index;
      std::array<double, 2> d2;
      tree.nearest_within(tree.point(i), std::numeric_limits<double>::infinity(), 2, index.data(), d2.data());
      nearest[at] = d2[1];  // d2[0] = 0: the sample itself (the median needs no order)
    }
  });
  std::nth_element(nearest.begin(), nearest.begin() + n / 2, nearest.end());
  return std::sqrt(nearest[n / 2]);
}

}  // namespace coxmesh
