// Input and output sensitivity in the contract's sign (u = K y + d) against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "core/error.hpp"
#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/frequency_domain/frf_loop.hpp"
#include "identifier/frequency_domain/sensitivity_function.hpp"

namespace ambid::ident {
namespace sensitivity_function_test {

using test::kPi;

TEST(SensitivityFunction, SisoClosedForm) {
  // Negative PD u = -(kp + kd s) y on G = 840 / (s^2 - 2800): S = (s^2 - 2800) / (s^2 + 840 kd s + 840 kp - 2800).
  const double kp = 30.12, kd = 0.25;
  for (double f : {1.0, 10.0, 24.0, 100.0, 1000.0}) {
    const std::complex<double> s(0.0, 2.0 * kPi * f);
    const std::complex<double> G = 840.0 / (s * s - 2800.0), K = -(kp + kd * s);
    const std::complex<double> expected = (s * s - 2800.0) / (s * s + 840.0 * kd * s + 840.0 * kp - 2800.0);
    const Eigen::MatrixXcd S =
        input_sensitivity(Eigen::MatrixXcd::Constant(1, 1, G), Eigen::MatrixXcd::Constant(1, 1, K));
    EXPECT_LT(std::abs(S(0, 0) - expected), 1e-12 * std::abs(expected)) << f;
  }
}

TEST(SensitivityFunction, PushThroughAndShapes) {
  // G 3x2, K 2x3 (like amb1dof_voltage: x, i1, i2 from u1, u2): S_y G = G S_u.
  Eigen::MatrixXcd G(3, 2), K(2, 3);
  G << std::complex<double>(1, 0.5), 0.2, std::complex<double>(0.3, -0.1), std::complex<double>(-0.4, 0.2), 0.7, 0.1;
  K << -2.0, 0.3, 0.1, std::complex<double>(1.0, 1.0), -0.2, 0.4;
  const Eigen::MatrixXcd Su = input_sensitivity(G, K), Sy = output_sensitivity(G, K);
  EXPECT_EQ(Su.rows(), 2);
  EXPECT_EQ(Sy.rows(), 3);
  EXPECT_LT((Sy * G - G * Su).norm(), 1e-12);
  EXPECT_LT(((Eigen::MatrixXcd::Identity(2, 2) - K * G) * Su - Eigen::MatrixXcd::Identity(2, 2)).norm(), 1e-12);
  EXPECT_THROW(input_sensitivity(G, G), Error);
  // A loop gain of exactly 1 has no sensitivity.
  EXPECT_THROW(input_sensitivity(Eigen::MatrixXcd::Constant(1, 1, 1.0), Eigen::MatrixXcd::Constant(1, 1, 1.0)),
               InsufficientData);
}

TEST(SensitivityFunction, ControllerReadingThePlantInputIsFoldedIn) {
  // A controller uf = Ky y + Ku u (static, as an observer's direct path would look at one
  // frequency): u = (1 - Ku)^-1 Ky y + (1 - Ku)^-1 r.
  StateSpaceController c;
  c.sample_time = 1e-3;
  c.inputs = {"u", "y"};
  c.outputs = {"u"};
  c.A = Eigen::MatrixXd::Constant(1, 1, 0.5);
  c.B = (Eigen::MatrixXd(1, 2) << 0.2, 0.0).finished();  // the state integrates u (one sample late)
  c.C = Eigen::MatrixXd::Constant(1, 1, 1.0);
  c.D = (Eigen::MatrixXd(1, 2) << 0.0, -3.0).finished();  // zero in the u column
  const LoopSignalNames sig{{"y"}, {"u"}, {"r"}};
  const double w = 2.0 * kPi * 50.0;
  const std::complex<double> z = std::polar(1.0, w * 1e-3);
  const std::complex<double> Ku = 0.2 / (z - 0.5), Ky = -3.0;
  const LoopResponse loop = loop_response(c, sig, w);
  EXPECT_LT(std::abs(loop.K(0, 0) - Ky / (1.0 - Ku)), 1e-12);
  EXPECT_LT(std::abs(loop.M(0, 0) - 1.0 / (1.0 - Ku)), 1e-12);
  LoopSignalNames wrong = sig;
  wrong.y = {"x"};
  EXPECT_THROW(loop_response(c, wrong, w), Error);
}

}  // namespace sensitivity_function_test
}  // namespace ambid::ident
