#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/no_continuous_equivalent.hpp"
#include "core/state_space.hpp"

namespace ambid {
namespace state_space_test {

TEST(StateSpace, FirstOrderZohMatchesAnalytic) {
  // x' = -a x + b u  ->  Ad = exp(-aT), Bd = b/a (1 - exp(-aT))
  const double a = 3.0, b = 2.0, T = 0.1;
  ContinuousSystem sys{Eigen::MatrixXd::Constant(1, 1, -a), Eigen::MatrixXd::Constant(1, 1, b),
                       Eigen::MatrixXd::Identity(1, 1), Eigen::MatrixXd::Zero(1, 1)};
  const DiscreteSystem d = c2d_zoh(sys, T);
  EXPECT_NEAR(d.A(0, 0), std::exp(-a * T), 1e-15);
  EXPECT_NEAR(d.B(0, 0), b / a * (1 - std::exp(-a * T)), 1e-15);
}

TEST(StateSpace, UnstableDoubleIntegratorRoundTrip) {
  // The Sales rotor (seed 003 eq. 8): an unstable pole at +sqrt(2800).
  ContinuousSystem sys;
  sys.A.resize(2, 2);
  sys.A << 0, 1, 2.8e3, 0;
  sys.B.resize(2, 1);
  sys.B << 0, 4.2;
  sys.C.resize(1, 2);
  sys.C << 0.2e3, 0;
  sys.D = Eigen::MatrixXd::Zero(1, 1);
  const DiscreteSystem d = c2d_zoh(sys, 1e-3);
  const ContinuousSystem back = d2c_zoh(d);
  EXPECT_LT((back.A - sys.A).norm() / sys.A.norm(), 1e-10);
  EXPECT_LT((back.B - sys.B).norm() / sys.B.norm(), 1e-10);
  const Eigen::VectorXcd p = poles(d);
  const double zmax = std::max(p(0).real(), p(1).real());
  EXPECT_NEAR(zmax, std::exp(std::sqrt(2.8e3) * 1e-3), 1e-12);
}

TEST(StateSpace, LogarithmRefusedOnNegativeRealAxis) {
  DiscreteSystem d{Eigen::MatrixXd::Constant(1, 1, -0.5), Eigen::MatrixXd::Ones(1, 1), Eigen::MatrixXd::Ones(1, 1),
                   Eigen::MatrixXd::Zero(1, 1), 0.01};
  try {
    d2c_zoh(d);
    FAIL() << "expected an error";
  } catch (const NoContinuousEquivalent& e) {  // callers that keep the discrete model catch this type
    EXPECT_NE(std::string(e.what()).find("negative real axis"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("-0.5"), std::string::npos) << e.what();
  }
}

TEST(StateSpace, DimensionMismatchNamed) {
  ContinuousSystem sys{Eigen::MatrixXd::Zero(2, 2), Eigen::MatrixXd::Zero(3, 1), Eigen::MatrixXd::Zero(1, 2),
                       Eigen::MatrixXd::Zero(1, 1)};
  EXPECT_THROW(c2d_zoh(sys, 0.1), Error);
  ContinuousSystem ok{Eigen::MatrixXd::Zero(1, 1), Eigen::MatrixXd::Zero(1, 1), Eigen::MatrixXd::Zero(1, 1),
                      Eigen::MatrixXd::Zero(1, 1)};
  EXPECT_THROW(c2d_zoh(ok, -1.0), Error);
  EXPECT_THROW(c2d_zoh(ok, std::nan("")), Error);
}

TEST(StateSpace, SimulateImpulseGivesMarkovParameters) {
  DiscreteSystem d{Eigen::MatrixXd(2, 2), Eigen::MatrixXd(2, 1), Eigen::MatrixXd(1, 2), Eigen::MatrixXd::Zero(1, 1),
                   0.1};
  d.A << 0.5, 0.2, -0.1, 0.9;
  d.B << 1.0, 0.5;
  d.C << 1.0, -1.0;
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(5, 1);
  u(0, 0) = 1.0;
  const Eigen::MatrixXd y = simulate(d, u);
  Eigen::MatrixXd Ak = Eigen::MatrixXd::Identity(2, 2);
  EXPECT_DOUBLE_EQ(y(0, 0), 0.0);
  for (int k = 1; k < 5; ++k) {
    EXPECT_NEAR(y(k, 0), (d.C * Ak * d.B)(0, 0), 1e-15);
    Ak = Ak * d.A;
  }
}

}  // namespace state_space_test
}  // namespace ambid
