#include "services/convert/plant_samples.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace ambid::convert {
namespace {

void append_rows(const Eigen::MatrixXd& m, Eigen::Index begin, Eigen::Index count, std::vector<double>& out) {
  for (Eigen::Index k = begin; k < begin + count; ++k)
    for (Eigen::Index j = 0; j < m.cols(); ++j) out.push_back(m(k, j));
}

Eigen::MatrixXd take_rows(std::vector<double>& values, Eigen::Index rows, std::size_t cols) {
  Eigen::MatrixXd m(rows, Eigen::Index(cols));
  for (Eigen::Index k = 0; k < rows; ++k)
    for (std::size_t j = 0; j < cols; ++j) m(k, Eigen::Index(j)) = values[std::size_t(k) * cols + j];
  values.erase(values.begin(), values.begin() + std::ptrdiff_t(std::size_t(rows) * cols));
  return m;
}

std::string size_mismatch(const char* field, std::size_t got, std::size_t expected) {
  std::ostringstream s;
  s << field << " holds " << got << " values, expected " << expected;
  return s.str();
}

}  // namespace

bus::PlantSamples sample_batch(const Experiment& e, Eigen::Index begin, Eigen::Index count, const std::string& plant_id,
                               std::uint64_t seq, double time_offset) {
  if (begin < 0 || count < 1 || begin + count > e.samples())
    throw Error("sample batch: rows " + std::to_string(begin) + "+" + std::to_string(count) + " outside the " +
                std::to_string(e.samples()) + " samples");
  bus::PlantSamples b;
  b.plant_id = plant_id;
  b.seq = seq;
  b.t0 = e.t(begin) + time_offset;
  b.sample_time = e.sample_time;
  b.count = std::uint32_t(count);
  b.y_names = e.y_names;
  b.u_names = e.u_names;
  b.r_names = e.r_names;
  append_rows(e.y, begin, count, b.y);
  append_rows(e.u, begin, count, b.u);
  if (e.has_excitation()) append_rows(e.r, begin, count, b.r);
  return b;
}

SampleWindow::SampleWindow(Experiment header, Eigen::Index samples, Eigen::Index settle)
    : header_(std::move(header)), samples_(samples), settle_(settle) {
  if (samples_ < 2) throw Error("sample window: at least 2 samples, got " + std::to_string(samples_));
  if (settle_ < 0) throw Error("sample window: settle samples must be >= 0, got " + std::to_string(settle_));
}

std::string SampleWindow::check(const bus::PlantSamples& b) const {
  if (b.y_names != header_.y_names || b.u_names != header_.u_names || b.r_names != header_.r_names)
    return "signal names differ from the configured plant's";
  if (!(std::abs(b.sample_time - header_.sample_time) <= kSamplingTolerance * header_.sample_time))
    return "sample time " + std::to_string(b.sample_time) + " s, expected " + std::to_string(header_.sample_time);
  if (b.count < 1) return "empty batch";
  const std::size_t n = b.count;
  if (b.y.size() != n * b.y_names.size()) return size_mismatch("y", b.y.size(), n * b.y_names.size());
  if (b.u.size() != n * b.u_names.size()) return size_mismatch("u", b.u.size(), n * b.u_names.size());
  if (b.r.size() != n * b.r_names.size()) return size_mismatch("r", b.r.size(), n * b.r_names.size());
  if (!std::isfinite(b.t0)) return "t0 is not finite";
  for (const auto* values : {&b.y, &b.u, &b.r})
    for (double v : *values)
      if (!std::isfinite(v)) return "a sample value is not finite";
  return {};
}

SampleWindow::Result SampleWindow::add(const bus::PlantSamples& b) {
  if (std::string reason = check(b); !reason.empty()) return {Outcome::rejected, reason};
  Result result{Outcome::added, {}};
  const bool contiguous =
      started_ && b.seq == next_seq_ && std::abs(b.t0 - next_t_) <= kSamplingTolerance * header_.sample_time;
  if (!contiguous) {
    if (started_ || b.seq != 0)
      result = {Outcome::restarted, b.seq == 0
                                        ? "a new record starts"
                                        : "batch " + std::to_string(b.seq) + " does not follow the previous one"};
    clear();
    if (b.seq == 0) to_drop_ = settle_;
  }
  started_ = true;
  next_seq_ = b.seq + 1;
  next_t_ = b.t0 + b.count * b.sample_time;
  const std::size_t drop = std::size_t(std::min<Eigen::Index>(to_drop_, b.count));
  to_drop_ -= Eigen::Index(drop);
  for (std::size_t k = drop; k < b.count; ++k) t_.push_back(b.t0 + double(k) * b.sample_time);
  y_.insert(y_.end(), b.y.begin() + std::ptrdiff_t(drop * b.y_names.size()), b.y.end());
  u_.insert(u_.end(), b.u.begin() + std::ptrdiff_t(drop * b.u_names.size()), b.u.end());
  r_.insert(r_.end(), b.r.begin() + std::ptrdiff_t(drop * b.r_names.size()), b.r.end());
  return result;
}

Experiment SampleWindow::take() {
  if (!full())
    throw Error("sample window: " + std::to_string(t_.size()) + " of " + std::to_string(samples_) + " samples");
  Experiment e = header_;
  e.t = Eigen::Map<const Eigen::VectorXd>(t_.data(), samples_);
  t_.erase(t_.begin(), t_.begin() + samples_);
  e.y = take_rows(y_, samples_, header_.y_names.size());
  e.u = take_rows(u_, samples_, header_.u_names.size());
  e.r = take_rows(r_, samples_, header_.r_names.size());
  return e;
}

void SampleWindow::clear() {
  to_drop_ = 0;
  t_.clear();
  y_.clear();
  u_.clear();
  r_.clear();
  started_ = false;
}

}  // namespace ambid::convert
