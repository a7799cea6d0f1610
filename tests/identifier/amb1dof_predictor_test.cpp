// The derivatives of the prediction-error method (amb1dof_predictor.hpp) against central
// differences: the Frechet derivative of the zero-order hold, and the whole Jacobian of the
// prediction errors from the forward sensitivity recursion, on a noisy closed-loop record.
#include "identifier/families/amb1dof_predictor.hpp"

#include <gtest/gtest.h>

#include "identifier/time_domain/loop_signals.hpp"
#include "plant_sim/lqr.hpp"
#include "support/amb1dof_records.hpp"

namespace ambid::ident::pem {
namespace amb1dof_predictor_test {

constexpr double kSampleTime = 1e-4;
// Relative step of the central differences: their truncation error is ~1e-6 relative, their
// round-off through the squarings of expm and the record far below.
constexpr double kStep = 1e-3;

struct Point {
  Eigen::MatrixXd y, u;
  Parameters theta, scale;  // scale: a natural size of each parameter (the finite-difference step)
};

// A short noisy record and a parameter vector near, not at, its truth: every derivative is
// exercised with non-zero errors, offsets and initial state.
Point point() {
  test_support::Amb1dofRecordOptions o;
  o.duration = 0.05;
  o.settle = 0.02;
  o.position_noise = 1e-7;
  o.current_noise = 1e-3;
  const test_support::Amb1dofRecord record = test_support::simulate_amb1dof_record(o);
  const LoopSignals s = loop_signals(record.experiment, {"x", "i1", "i2"}, {"u1", "u2"}, "test");
  Point out{s.y, s.u, {}, {}};
  Vector9 v;
  for (int i = 0; i < 9; ++i) v(i) = record.truth.at("v" + std::to_string(i + 1)) * (1.0 + 0.01 * (i - 4));
  const Eigen::Vector3d w(0.3 * std::abs(v(0)) * 1e-6, 2.0, -3.0);
  Parameters theta = pack(v, w, Eigen::Vector4d(1e-6, 1e-4, 0.01, -0.01), Gain::Zero());
  const ZeroOrderHold zoh = zero_order_hold(theta, kSampleTime, false);
  Eigen::Matrix<double, 3, 4> C = Eigen::Matrix<double, 3, 4>::Zero();
  C(0, 0) = C(1, 2) = C(2, 3) = 1.0;
  const Eigen::Vector4d W(1e-8, 1e-4, 1e-4, 1e-4);
  const Eigen::Vector3d V(1e-8, 1e-6, 1e-6);
  const Gain K = sim::predictor_gain(zoh.Ad, C, W.asDiagonal().toDenseMatrix(), V.asDiagonal().toDenseMatrix()).L;
  out.theta = pack(v, w, theta.segment<4>(kInitial), K);
  out.scale = pack(v.cwiseAbs(), Eigen::Vector3d(std::abs(v(0)) * 1e-6, 10.0, 10.0),
                   Eigen::Vector4d(1e-6, 1e-3, 0.01, 0.01), K.cwiseAbs().cwiseMax(1e-3));
  return out;
}

TEST(Amb1dofPredictor, ZeroOrderHoldDerivativeMatchesCentralDifferences) {
  const Point s = point();
  const ZeroOrderHold exact = zero_order_hold(s.theta, kSampleTime, true);
  for (int k = 0; k < kModel; ++k) {
    const double h = kStep * s.scale(k);
    Parameters plus = s.theta, minus = s.theta;
    plus(k) += h;
    minus(k) -= h;
    const ZeroOrderHold a = zero_order_hold(plus, kSampleTime, false), b = zero_order_hold(minus, kSampleTime, false);
    Eigen::Matrix<double, 4, 7> numeric;
    numeric << (a.Ad - b.Ad) / (2 * h), (a.Bd - b.Bd) / (2 * h);
    const Eigen::Matrix<double, 4, 7> analytic = exact.derivative.block<4, 7>(4 * k, 0);
    EXPECT_LT((analytic - numeric).norm(), 1e-5 * numeric.norm()) << "parameter " << k;
    EXPECT_GT(numeric.norm(), 0.0) << "parameter " << k;
  }
}

TEST(Amb1dofPredictor, SensitivityJacobianMatchesCentralDifferences) {
  const Point s = point();
  const Amb1dofPredictor predictor(s.y, s.u, kSampleTime);
  const Eigen::Vector3d weight(1e7, 1e3, 1e3);
  Eigen::MatrixXd J(0, kParameters);
  Eigen::VectorXd target(0);
  ASSERT_TRUE(predictor.linearise(s.theta, weight, s.scale, 64, [&](const auto& rows, const auto& t) {
    J.conservativeResize(J.rows() + rows.rows(), Eigen::NoChange);
    J.bottomRows(rows.rows()) = rows;
    target.conservativeResize(target.size() + t.size());
    target.tail(t.size()) = t;
  }));
  ASSERT_EQ(J.rows(), 3 * s.y.rows());
  // The targets are -weight e: their squares are the predictor's.
  const Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<1, 3>> e(target.data(), s.y.rows(), 3);
  const std::optional<Eigen::Vector3d> squares = predictor.squares(s.theta);
  ASSERT_TRUE(squares);
  for (int j = 0; j < 3; ++j)
    EXPECT_NEAR(e.col(j).squaredNorm() / (weight(j) * weight(j)), (*squares)(j), 1e-9 * (*squares)(j));
  // Central differences of the targets (d target / d p = -J with theta = theta0 + scale .* p).
  auto targets_at = [&](const Parameters& theta) {
    Eigen::VectorXd out(0);
    predictor.linearise(theta, weight, s.scale, 64, [&](const auto&, const auto& t) {
      out.conservativeResize(out.size() + t.size());
      out.tail(t.size()) = t;
    });
    return out;
  };
  double worst = 0.0;
  for (int k = 0; k < kParameters; ++k) {
    const double h = kStep;
    Parameters plus = s.theta, minus = s.theta;
    plus(k) += h * s.scale(k);
    minus(k) -= h * s.scale(k);
    const Eigen::VectorXd numeric = -(targets_at(plus) - targets_at(minus)) / (2 * h);
    EXPECT_LT((J.col(k) - numeric).norm(), 1e-5 * numeric.norm()) << "parameter " << k;
    worst = std::max(worst, (J.col(k) - numeric).norm() / numeric.norm());
    EXPECT_GT(numeric.norm(), 0.0) << "parameter " << k;
  }
  ::testing::Test::RecordProperty("worst_relative_error", std::to_string(worst));
}

}  // namespace amb1dof_predictor_test
}  // namespace ambid::ident::pem
