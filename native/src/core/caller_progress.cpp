#include "anisomesh/core/caller_progress.h"

namespace anisomesh {

CallerProgress::CallerProgress(size_t n, std::function<bool(double)> report, double offset, double scale)
    : fraction_(n), caller_(std::this_thread::get_id()), report_(std::move(report)), offset_(offset), scale_(scale) {
  for (auto& f : fraction_) f.store(0.0);
}

std::function<bool(double)> CallerProgress::task(size_t k) {
  return [this, k](double f) {
    fraction_[k].store(f);
    if (std::this_thread::get_id() == caller_) report();
    return !stop_.load();
  };
}

std::function<void()> CallerProgress::poll() {
  return [this] { report(); };
}

void CallerProgress::report() {
  if (stop_.load() || fraction_.empty()) return;
  double sum = 0.0;
  for (const auto& x : fraction_) sum += x.load();
  if (!report_(offset_ + scale_ * sum / static_cast<double>(fraction_.size()))) stop_.store(true);
}

}  // namespace anisomesh
