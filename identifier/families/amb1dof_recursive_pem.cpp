#include "identifier/families/amb1dof_recursive_pem.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {
namespace {

const std::string kRecursivePemWho = "recursive prediction-error identification";
constexpr int kThetaGain = 12;  // first K column of theta (K(i, j) at kThetaGain + 3 i + j)
using Theta = Amb1dofRecursivePem::Parameters;

// The model's [v; w] from theta's [v; c] (amb1dof_recursive_pem.hpp): w2 = c2 - v5 i1o + v8 u1o,
// w3 = c3 - v7 i2o + v9 u2o.
Eigen::Matrix<double, 12, 12> coil_offset_map(const Amb1dofCoilOperatingPoint& op) {
  Eigen::Matrix<double, 12, 12> map = Eigen::Matrix<double, 12, 12>::Identity();
  map(10, 4) = -op.i1;
  map(10, 7) = op.u1;
  map(11, 6) = -op.i2;
  map(11, 8) = op.u2;
  return map;
}

// The model [v, w] and the gain of theta -> the batch predictor's 28 parameters (x0 = 0: the
// hold does not use it).
pem::Parameters batch_parameters(const Eigen::Matrix<double, 12, 1>& model, const Theta& theta) {
  pem::Parameters out = pem::Parameters::Zero();
  out.head<pem::kModel>() = model;
  out.tail<12>() = theta.tail<12>();
  return out;
}

// The batch method's scales (amb1dof_prediction_error.cpp): v by |v|, w by the size of the
// rows' terms, K by |K| or a thousandth of the state-to-output ratio.
Theta parameter_scale(const Theta& theta, const Eigen::Vector3d& spread) {
  const Eigen::Vector4d xs(spread(0), spread(0) * std::sqrt(std::abs(theta(0))), spread(1), spread(2));
  Theta s;
  s.head<9>() = theta.head<9>().cwiseAbs();
  s.segment<3>(9) << std::abs(theta(0)) * spread(0), std::abs(theta(4)) * spread(1), std::abs(theta(6)) * spread(2);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j)
      s(kThetaGain + 3 * i + j) = std::max(std::abs(theta(kThetaGain + 3 * i + j)), 1e-3 * xs(i) / spread(j));
  return s;
}

Eigen::Vector4d at_rest(const Eigen::Vector3d& y) { return {y(0), 0.0, y(1), y(2)}; }

}  // namespace

Amb1dofRecursivePem::Amb1dofRecursivePem(const PemWarmStart& start, const Eigen::Vector3d& spread, double sample_time,
                                         const Amb1dofCoilOperatingPoint& operating_point,
                                         const Amb1dofRecursivePemOptions& options)
    : options_(options),
      sample_time_(sample_time),
      model_map_(coil_offset_map(operating_point)),
      ud_([&] {
        if (!start.v.allFinite() || (start.v.array() == 0.0).any() || !start.offset.allFinite() ||
            !start.predictor_gain.allFinite())
          throw Error(kRecursivePemWho + ": the start's v1..v9 must be finite and non-zero, its w and K finite");
        if (!spread.allFinite() || !(spread.minCoeff() > 0.0))
          throw Error(kRecursivePemWho + ": the spread of every output must be finite and > 0");
        if (!(options.prior_relative_sigma > 0.0)) throw Error(kRecursivePemWho + ": prior_relative_sigma must be > 0");
        Eigen::VectorXd prior = Eigen::VectorXd::Ones(kParameters);
        prior.head<9>().setConstant(options.prior_relative_sigma * options.prior_relative_sigma);
        return UdCovariance(prior);
      }()),
      window_ud_(ud_),
      window_prior_ud_(ud_),
      lambda_(spread.cwiseAbs2()),
      s1_(options.prior_weight_samples),
      forgetting_(options.startup_forgetting) {
  if (!(sample_time > 0.0) || !std::isfinite(sample_time))
    throw Error(kRecursivePemWho + ": sample time must be finite and > 0");
  if (!(options.forgetting > 0.0 && options.forgetting <= 1.0) ||
      !(options.startup_forgetting > 0.0 && options.startup_forgetting <= 1.0))
    throw Error(kRecursivePemWho + ": forgetting factors must be in (0, 1]");
  if (!(options.offset_random_walk >= 0.0)) throw Error(kRecursivePemWho + ": offset_random_walk must be >= 0");
  if (!(options.startup_samples >= 1.0) || options.relinearise_samples < 1 || !(options.prior_weight_samples >= 1.0) ||
      !(options.jump_samples >= 1.0))
    throw Error(kRecursivePemWho +
                ": startup_samples, relinearise_samples, prior_weight_samples and jump_samples must be >= 1");
  if (!(options.jump_threshold > 0.0)) throw Error(kRecursivePemWho + ": jump_threshold must be > 0");
  if (!(options.commit_threshold > 0.0)) throw Error(kRecursivePemWho + ": commit_threshold must be > 0");
  if (!(options.max_held_radius > 0.0)) throw Error(kRecursivePemWho + ": max_held_radius must be > 0");
  if (!model_map_.allFinite()) throw Error(kRecursivePemWho + ": the operating point's i1, i2, u1, u2 must be finite");
  theta_.head<9>() = start.v;
  theta_.segment<3>(9) = start.offset - model_map_.bottomLeftCorner<3, 9>() * start.v;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) theta_(kThetaGain + 3 * i + j) = start.predictor_gain(i, j);
  scale_ = parameter_scale(theta_, spread);
  checked_ = theta_;
  start_window(1.0);
  relinearise();
  if (projections_ > 0) throw InsufficientData(kRecursivePemWho + ": the predictor of the start is unstable");
}

Eigen::Matrix<double, 4, 3> Amb1dofRecursivePem::predictor_gain() const {
  return pem::gain_of(batch_parameters(model_of(estimate()), estimate()));
}

Eigen::Matrix<double, 9, 9> Amb1dofRecursivePem::covariance() const {
  const Eigen::MatrixXd P = ud_.covariance();
  const Eigen::Matrix<double, 9, 1> s = scale_.head<9>();
  // s1_ and s2_ include the start's weight as samples; the ratio is that of the data's weights.
  return (s2_ > 0.0 ? s2_ / s1_ : 1.0) * (s.asDiagonal() * P.topLeftCorner<9, 9>() * s.asDiagonal());
}

void Amb1dofRecursivePem::restart(const Eigen::Vector3d& y) {
  x_ = at_rest(y);
  w_.setZero();
  drift_.setZero();
  quiet_ = static_cast<int>(options_.jump_samples) * 4;
  // The first start has no predictor to warm up: its theta is the prior, forgotten fast anyway.
  // The length is taken at the next sample, from the predictor a projection has settled on.
  if (started_) warmup_ = -1;
  started_ = true;
}

int Amb1dofRecursivePem::warmup_samples() const {
  // The predictor's state error from the restart decays like radius^n.
  const double memory = options_.forgetting < 1.0 ? 1.0 / (1.0 - options_.forgetting) : options_.startup_samples;
  const double n = std::log(options_.restart_decay) / std::log(predictor_radius_);
  return static_cast<int>(std::ceil(std::clamp(std::isfinite(n) ? n : memory, 1.0, memory)));
}

void Amb1dofRecursivePem::begin_window(double carry) {
  if (!options_.window_estimates) throw Error(kRecursivePemWho + ": per-window estimates need window_estimates");
  if (!(carry > 0.0 && carry <= 1.0))
    throw Error(kRecursivePemWho + ": carry must be in (0, 1], got " + std::to_string(carry));
  if (pending_.head<9>().cwiseAbs().maxCoeff() > options_.commit_threshold) {
    // The held theta moves to the long-memory estimate if its predictor's spectral radius is
    // below options.max_held_radius, else to its v and c with the held K; if that predictor is
    // unstable the held theta stays (the state goes on: it is the held theta's) and the move is
    // counted a projection.
    const Theta held = theta_, target = estimate();
    theta_ = target;
    bool stable = linearise_at_theta() && predictor_radius_ < options_.max_held_radius;
    if (!stable) {
      theta_.tail<12>() = held.tail<12>();
      stable = linearise_at_theta();
    }
    if (stable) {
      pending_ = (target - theta_).cwiseQuotient(scale_);
      checked_ = theta_;
      reference_model_ = model_of(theta_);
      hold_ << reference_.Ad, reference_.Bd;
      ++commits_;
    } else {
      ++projections_;
      theta_ = held;
      linearise_at_theta();
    }
  }
  start_window(carry);
}

double Amb1dofRecursivePem::window_surprise() const {
  if (!options_.window_estimates) throw Error(kRecursivePemWho + ": window_surprise needs window_estimates");
  const Theta deviation = (window_origin_ - window_prior_).cwiseQuotient(scale_) + window_step_;
  const Eigen::VectorXd variances = window_prior_ud_.variances();
  return deviation.head<9>().cwiseAbs().cwiseQuotient(variances.head<9>().cwiseSqrt()).maxCoeff();
}

void Amb1dofRecursivePem::hold_at(const Amb1dofRecursivePem& plain) {
  if (!options_.window_estimates || plain.options_.window_estimates)
    throw Error(kRecursivePemWho + ": hold_at holds a window estimator at a plain one's estimate");
  const Amb1dofRecursivePemOptions options = options_;
  const std::uint64_t commits = commits_ + 1;
  const Eigen::Vector3d noise = window_lambda_;
  *this = plain;
  options_ = options;
  commits_ = commits;
  // The prediction-error variances: the plain RPEM's include the errors of its first samples
  // after the change; the held predictor's at the start of this window do not.
  lambda_ = lambda_.cwiseMin(noise);
  theta_ = estimate();
  pending_.setZero();
  if (!linearise_at_theta()) {  // cannot be: the plain estimator checks its predictor
    ++projections_;
    theta_ = checked_;
    linearise_at_theta();
  }
  checked_ = theta_;
  reference_model_ = model_of(theta_);
  hold_ << reference_.Ad, reference_.Bd;
  start_window(1.0);
}

void Amb1dofRecursivePem::start_window(double carry) {
  window_origin_ = theta_;
  window_step_ = pending_;
  window_ud_ = ud_;
  window_ud_.scale(1.0 / carry);
  window_prior_ = estimate();
  window_prior_ud_ = window_ud_;
  window_lambda_ = lambda_;
}

void Amb1dofRecursivePem::relax(double carry) {
  if (!(carry > 0.0 && carry <= 1.0))
    throw Error(kRecursivePemWho + ": carry must be in (0, 1], got " + std::to_string(carry));
  // v and w only: the predictor gain K keeps its covariance (relaxed too, it let one window's
  // step make the predictor unstable).
  const Eigen::VectorXd variances = ud_.variances();
  for (int k = 0; k < kThetaGain; ++k) {
    Theta along = Theta::Unit(k);
    ud_.add((1.0 / carry - 1.0) * variances(k), along);
  }
  s1_ *= carry;
  s2_ *= carry * carry;
}

Eigen::Matrix<double, 9, 1> Amb1dofRecursivePem::window_v() const {
  return (window_origin_ + scale_.cwiseProduct(window_step_)).head<9>();
}

Eigen::Matrix<double, 9, 9> Amb1dofRecursivePem::window_covariance() const {
  const Eigen::Matrix<double, 9, 1> s = scale_.head<9>();
  return s.asDiagonal() * window_ud_.covariance().topLeftCorner<9, 9>() * s.asDiagonal();
}

void Amb1dofRecursivePem::detect_jump(const Eigen::Vector3d& e) {
  const double a = 1.0 / options_.jump_samples;
  // Per coil: the coil's v (R and kw: v5, v8 resp. v7, v9) and its offset c.
  constexpr int kCoilParameters[2][3] = {{4, 7, 10}, {6, 8, 11}};
  if (quiet_ > 0) {
    --quiet_;
    return;
  }
  for (int coil = 0; coil < 2; ++coil) {
    double& drift = drift_(coil);
    drift += a * (e(coil + 1) / std::sqrt(lambda_(coil + 1)) - drift);
    if (!(std::abs(drift) > options_.jump_threshold)) continue;
    // A jump: the coil's parameters get back at least the start's variance, so that the data
    // after it fix the new balance of the coil equation before anything else moves.
    for (UdCovariance* factor : {&ud_, &window_ud_}) {
      const Eigen::VectorXd variances = factor->variances();
      for (const int k : kCoilParameters[coil]) {
        const double prior = k < 9 ? options_.prior_relative_sigma * options_.prior_relative_sigma : 1.0;
        if (!(variances(k) < prior)) continue;
        Theta along = Theta::Unit(k);
        factor->add(prior - variances(k), along);
      }
    }
    drift = 0.0;
    ++jumps_;
  }
}

bool Amb1dofRecursivePem::linearise_at_theta() {
  const pem::Parameters batch = batch_parameters(model_of(theta_), theta_);
  reference_ = pem::zero_order_hold(batch, sample_time_, true);
  gain_ = pem::gain_of(batch);
  Eigen::Matrix4d F = reference_.Ad;
  for (int j = 0; j < 3; ++j) F.col(pem::kMeasured[std::size_t(j)]) -= gain_.col(j);
  predictor_radius_ = F.allFinite() ? linalg::spectral_radius(F) : 1.0;
  return F.allFinite() && predictor_radius_ < options_.max_predictor_radius;
}

void Amb1dofRecursivePem::relinearise() {
  since_relinearise_ = 0;
  if (!linearise_at_theta()) {
    // Ljung's projection: back to the last stable predictor, its state from the measurement.
    ++projections_;
    theta_ = checked_;
    restart({x_(0), x_(2), x_(3)});
    linearise_at_theta();
  }
  checked_ = theta_;
  reference_model_ = model_of(theta_);
  hold_ << reference_.Ad, reference_.Bd;
}

void Amb1dofRecursivePem::set_model() {
  hold_ << reference_.Ad, reference_.Bd;
  const Eigen::Matrix<double, 12, 1> change = model_of(theta_) - reference_model_;
  for (int k = 0; k < pem::kModel; ++k) hold_ += change(k) * reference_.derivative.block<4, 7>(4 * k, 0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) gain_(i, j) = theta_(kThetaGain + 3 * i + j);
}

void Amb1dofRecursivePem::update(const Eigen::Vector3d& y, const Eigen::Vector2d& u) {
  if (!started_) restart(y);
  const Eigen::Vector3d e(y(0) - x_(0), y(1) - x_(2), y(2) - x_(3));
  if (warmup_ < 0) warmup_ = warmup_samples();
  if (warmup_ > 0) {  // theta held: the state and sensitivities forget the restart first
    --warmup_;
    propagate(e, u);
    return;
  }
  const double lambda = forgetting_;
  const double approach = 1.0 / options_.startup_samples;
  forgetting_ += approach * (options_.forgetting - forgetting_);
  s1_ = lambda * s1_ + 1.0;
  s2_ = lambda * lambda * s2_ + 1.0;
  if (!options_.window_estimates) detect_jump(e);  // a change is followed by a plain RPEM (hold_at)
  lambda_ += (e.cwiseAbs2() - lambda_) / s1_;

  // The 3 outputs as scalar measurements of the linearised error e_j(theta) ~ e_j - psi_j' dtheta.
  ud_.forget(lambda);
  for (int k = 9; k < 12; ++k) {
    Theta along = Theta::Unit(k);
    ud_.add(options_.offset_random_walk, along);
  }

  // e(theta) ~ e - psi' (theta - theta_) about the predictor's theta_: the long-memory estimate
  // (pending_) and, with window_estimates, the window's (about window_origin_, which theta_ has
  // moved from by `moved` only if a projection put it back).
  Theta h, gain;
  const Theta moved = (theta_ - window_origin_).cwiseQuotient(scale_);
  for (int j = 0; j < 3; ++j) {
    h = w_.row(pem::kMeasured[std::size_t(j)]).transpose().cwiseProduct(scale_);
    const double innovation = e(j) - h.dot(pending_);
    ud_.update(h, lambda_(j), gain);
    pending_ += gain * innovation;
    if (!options_.window_estimates) continue;
    const double window_innovation = e(j) + h.dot(moved) - h.dot(window_step_);
    window_ud_.update(h, lambda_(j), gain);
    window_step_ += gain * window_innovation;
  }
  if (!options_.window_estimates) {  // the plain RPEM: theta_ follows at every sample
    theta_ += scale_.cwiseProduct(pending_);
    pending_.setZero();
    set_model();
  }
  propagate(e, u);
  ++samples_;
  if (!x_.allFinite() || !w_.allFinite() || !theta_.allFinite() || !pending_.allFinite() || !window_step_.allFinite()) {
    ++projections_;
    theta_ = checked_;
    pending_.setZero();
    relinearise();
    restart(y);
    start_window(1.0);
    return;
  }
  // With window_estimates theta_ moves at window starts only (begin_window relinearises then).
  if (!options_.window_estimates && ++since_relinearise_ >= options_.relinearise_samples) relinearise();
}

void Amb1dofRecursivePem::propagate(const Eigen::Vector3d& e, const Eigen::Vector2d& u) {
  // Sensitivities and state of the next sample with the current theta.
  Eigen::Matrix<double, 7, 1> z;
  z << x_, u, 1.0;
  Eigen::Matrix4d F = hold_.leftCols<4>();
  for (int j = 0; j < 3; ++j) F.col(pem::kMeasured[std::size_t(j)]) -= gain_.col(j);
  Eigen::Matrix<double, 4, kParameters> next;
  next.noalias() = F * w_;
  Eigen::Matrix<double, 4 * pem::kModel, 1> model_terms;
  model_terms.noalias() = reference_.derivative * z;
  // d/dv, d/dw of the hold's terms, then by the chain rule d/dv, d/dc.
  next.leftCols<pem::kModel>().noalias() +=
      Eigen::Map<const Eigen::Matrix<double, 4, pem::kModel>>(model_terms.data()) * model_map_;
  for (int i = 0; i < 4; ++i) next.block<1, 3>(i, kThetaGain + 3 * i) += e.transpose();
  w_ = next;
  x_ = hold_ * z + gain_ * e;
}

}  // namespace ambid::ident
