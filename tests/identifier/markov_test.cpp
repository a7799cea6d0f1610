// The Markov-parameter recursions against directly computed C A^k B products (seed 002 notes
// sec. 8.3): ARX coefficients of a known innovation model with a fast predictor (rho = 0.25,
// q = 200 so the truncation is below 1e-120) give the exact sequences.
#include "identifier/time_domain/markov.hpp"

#include <random>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace markov_test {

using testing::markov_of;
using testing::matrix_with_eigenvalues;
using testing::max_relative_error;
using testing::random_matrix;
using C = std::complex<double>;

struct InnovationModel {
  Eigen::MatrixXd A, B, C, D, G, Abar;
};

// Plant with predictor gain G and Abar = A - G C of spectral radius 0.25; A itself unstable.
InnovationModel innovation_model(std::mt19937_64& rng, int n, int m, int p, bool feedthrough) {
  InnovationModel s;
  s.Abar = matrix_with_eigenvalues({C(0.25, 0.0), C(-0.2, 0.1), C(0.1, 0.0)}, rng);
  EXPECT_EQ(s.Abar.rows(), n);
  s.B = random_matrix(n, m, rng);
  s.C = random_matrix(p, n, rng);
  s.D = feedthrough ? random_matrix(p, m, rng) : Eigen::MatrixXd::Zero(p, m);
  s.G = random_matrix(n, p, rng);
  s.A = s.Abar + s.G * s.C;
  return s;
}

// ARX (predictor) coefficients a_i = C Abar^(i-1) G, b_0 = D, b_i = C Abar^(i-1) (B - G D).
void predictor_arx(const InnovationModel& s, int q, std::vector<Eigen::MatrixXd>& a, std::vector<Eigen::MatrixXd>& b) {
  a.clear();
  b.assign(1, s.D);
  Eigen::MatrixXd Ak = Eigen::MatrixXd::Identity(s.A.rows(), s.A.rows());
  for (int i = 1; i <= q; ++i) {
    a.push_back(s.C * Ak * s.G);
    b.push_back(s.C * Ak * (s.B - s.G * s.D));
    Ak = s.Abar * Ak;
  }
}

TEST(Markov, ArxRecursionGivesSystemAndKalmanMarkovParameters) {
  std::mt19937_64 rng(31);
  const InnovationModel s = innovation_model(rng, 4, 2, 3, true);
  ASSERT_GT(testing::spectral_radius(s.A), 1.0);  // an unstable plant
  std::vector<Eigen::MatrixXd> a, b;
  predictor_arx(s, 200, a, b);
  const int J = 30;
  const MarkovParameters mp = markov_from_arx(a, b, J);
  const auto Y = markov_of(s.A, s.B, s.C, s.D, J);
  const auto N = markov_of(s.A, s.G, s.C, Eigen::MatrixXd::Identity(3, 3), J);
  ASSERT_EQ(mp.system.size(), 31u);
  EXPECT_LT(max_relative_error(Y, mp.system, 0, J), 1e-9);  // (2.18) / (4.25)
  EXPECT_LT(max_relative_error(N, mp.gain, 0, J), 1e-9);    // (2.19) / (4.30)
  ::testing::Test::RecordProperty("system_error", testing::sci(max_relative_error(Y, mp.system, 0, J)));
}

TEST(Markov, SecondaryArxGivesFeedbackMarkovParameters) {
  std::mt19937_64 rng(32);
  const InnovationModel s = innovation_model(rng, 4, 2, 3, true);
  const Eigen::MatrixXd F = random_matrix(2, 4, rng);
  std::vector<Eigen::MatrixXd> a, b, c, d;
  predictor_arx(s, 200, a, b);
  // z = -F x: c_i = -F Abar^(i-1) G, d_0 = 0, d_i = -F Abar^(i-1) (B - G D).
  d.assign(1, Eigen::MatrixXd::Zero(2, 2));
  Eigen::MatrixXd Ak = Eigen::MatrixXd::Identity(4, 4);
  for (int i = 1; i <= 200; ++i) {
    c.push_back(-F * Ak * s.G);
    d.push_back(-F * Ak * (s.B - s.G * s.D));
    Ak = s.Abar * Ak;
  }
  const int J = 30;
  const MarkovParameters primary = markov_from_arx(a, b, J);
  const MarkovParameters fb = secondary_markov_from_arx(c, d, primary, J);
  const auto FB = markov_of(s.A, s.B, -F, Eigen::MatrixXd::Zero(2, 2), J);
  const auto FG = markov_of(s.A, s.G, -F, Eigen::MatrixXd::Zero(2, 3), J);
  EXPECT_LT(max_relative_error(FB, fb.system, 1, J), 1e-9);  // (4.26)
  EXPECT_LT(max_relative_error(FG, fb.gain, 1, J), 1e-9);    // (4.31)
  EXPECT_EQ(fb.gain[0].norm(), 0.0);
}

// Lee's closed loop (2.7)-(2.9) with a controller u = Yd * y + r.
struct LeeLoop {
  InnovationModel plant;
  Eigen::MatrixXd Ad, Bd, Cd, Dd;
  Eigen::MatrixXd Ac, Bc, Kc, Cc;  // Kc is the block A_c K_c
};

LeeLoop lee_loop(std::mt19937_64& rng) {
  LeeLoop L;
  L.plant = innovation_model(rng, 4, 2, 3, false);
  L.Ad = matrix_with_eigenvalues({C(0.3, 0.0), C(-0.1, 0.0)}, rng);
  L.Bd = random_matrix(2, 3, rng, 0.3);
  L.Cd = random_matrix(2, 2, rng, 0.3);
  L.Dd = random_matrix(2, 3, rng, 0.3);
  const auto& P = L.plant;
  L.Ac.resize(6, 6);
  L.Ac << P.A + P.B * L.Dd * P.C, P.B * L.Cd, L.Bd * P.C, L.Ad;
  L.Bc.resize(6, 2);
  L.Bc << P.B, Eigen::MatrixXd::Zero(2, 2);
  L.Kc.resize(6, 3);
  L.Kc << P.G + P.B * L.Dd, L.Bd;
  L.Cc.resize(3, 6);
  L.Cc << P.C, Eigen::MatrixXd::Zero(3, 2);
  return L;
}

TEST(Markov, ClosedLoopArxRecursionMatchesTheClosedLoop) {
  std::mt19937_64 rng(33);
  const LeeLoop L = lee_loop(rng);
  const Eigen::MatrixXd Abar = L.Ac - L.Kc * L.Cc;
  // Block upper-triangular: eig(Abar) = eig(A - AKC) u eig(A_d) (notes 1.3).
  EXPECT_NEAR(testing::spectral_radius(Abar), 0.3, 1e-9);
  std::vector<Eigen::MatrixXd> a, b{Eigen::MatrixXd::Zero(3, 2)};
  Eigen::MatrixXd Ak = Eigen::MatrixXd::Identity(6, 6);
  for (int i = 1; i <= 300; ++i) {
    a.push_back(L.Cc * Ak * L.Kc);
    b.push_back(L.Cc * Ak * L.Bc);
    Ak = Abar * Ak;
  }
  const int J = 30;
  const MarkovParameters cl = markov_from_arx(a, b, J);
  EXPECT_LT(max_relative_error(markov_of(L.Ac, L.Bc, L.Cc, Eigen::MatrixXd::Zero(3, 2), J), cl.system, 1, J), 1e-9);
  EXPECT_LT(max_relative_error(markov_of(L.Ac, L.Kc, L.Cc, Eigen::MatrixXd::Identity(3, 3), J), cl.gain, 0, J), 1e-9);
}

TEST(Markov, LeeOpenLoopRecursionKeepsTheKEqualsJTerm) {
  std::mt19937_64 rng(34);
  const LeeLoop L = lee_loop(rng);
  const int J = 30;
  MarkovParameters cl;
  cl.system = markov_of(L.Ac, L.Bc, L.Cc, Eigen::MatrixXd::Zero(3, 2), J);
  cl.gain = markov_of(L.Ac, L.Kc, L.Cc, Eigen::MatrixXd::Identity(3, 3), J);
  const auto Yd = markov_of(L.Ad, L.Bd, L.Cd, L.Dd, J);
  const MarkovParameters ol = lee_open_loop_markov(cl, Yd);
  const auto Y = markov_of(L.plant.A, L.plant.B, L.plant.C, Eigen::MatrixXd::Zero(3, 2), J);
  const auto N = markov_of(L.plant.A, L.plant.G, L.plant.C, Eigen::MatrixXd::Identity(3, 3), J);
  const double ey = max_relative_error(Y, ol.system, 1, J), en = max_relative_error(N, ol.gain, 1, J);
  EXPECT_LT(ey, 1e-9);  // (2.24)
  EXPECT_LT(en, 1e-9);  // (2.25)
  ::testing::Test::RecordProperty("Y_error", testing::sci(ey));
  ::testing::Test::RecordProperty("N_error", testing::sci(en));

  // Appendix B clmarkov drops the k = j term of (2.25): that is badly wrong.
  std::vector<Eigen::MatrixXd> alpha{Eigen::MatrixXd::Zero(3, 3)}, Nbad{Eigen::MatrixXd::Identity(3, 3)};
  for (int j = 1; j <= J; ++j) {
    Eigen::MatrixXd aj = Eigen::MatrixXd::Zero(3, 3);
    for (int i = 1; i <= j; ++i) aj += Y[static_cast<std::size_t>(i)] * Yd[static_cast<std::size_t>(j - i)];
    alpha.push_back(aj);
    Eigen::MatrixXd nj = cl.gain[static_cast<std::size_t>(j)];
    for (int k = 1; k < j; ++k) nj -= alpha[static_cast<std::size_t>(k)] * cl.gain[static_cast<std::size_t>(j - k)];
    Nbad.push_back(nj);
  }
  const double ebad = max_relative_error(N, Nbad, 1, J);
  EXPECT_GT(ebad, 0.1);
  ::testing::Test::RecordProperty("N_error_without_k_eq_j", testing::sci(ebad));

  // The general form with Gu = 0 is the same recursion.
  ControllerMarkov cm;
  for (const auto& g : Yd) {
    cm.from_u.push_back(Eigen::MatrixXd::Zero(2, 2));
    cm.from_y.push_back(g);
  }
  const MarkovParameters general = open_loop_markov(cl, cm);
  EXPECT_LT(max_relative_error(ol.system, general.system, 1, J), 1e-9);  // summation order differs
  EXPECT_LT(max_relative_error(ol.gain, general.gain, 1, J), 1e-9);
}

// A contract-form controller that also reads u (an observer-based controller): r enters the
// controller state too, so Lee's (2.24) does not apply as printed; the general form does.
TEST(Markov, OpenLoopRecoveryForAControllerThatReadsU) {
  std::mt19937_64 rng(35);
  const InnovationModel P = innovation_model(rng, 4, 2, 3, false);
  // Controller: xc+ = Ao xc + Bu u + By y, uf = Cc xc + Dy y.
  const Eigen::MatrixXd Ao = matrix_with_eigenvalues({C(0.2, 0.3), C(0.1, 0.0), C(-0.3, 0.0)}, rng);
  const Eigen::MatrixXd Bu = random_matrix(4, 2, rng, 0.3), By = random_matrix(4, 3, rng, 0.3);
  const Eigen::MatrixXd Cc = random_matrix(2, 4, rng, 0.3), Dy = random_matrix(2, 3, rng, 0.3);
  Eigen::MatrixXd Acl(8, 8), Bcl(8, 2), Kcl(8, 3), Ccl(3, 8);
  Acl << P.A + P.B * Dy * P.C, P.B * Cc, (Bu * Dy + By) * P.C, Ao + Bu * Cc;
  Bcl << P.B, Bu;
  Kcl << P.G + P.B * Dy, Bu * Dy + By;
  Ccl << P.C, Eigen::MatrixXd::Zero(3, 4);
  const int J = 30;
  MarkovParameters cl;
  cl.system = markov_of(Acl, Bcl, Ccl, Eigen::MatrixXd::Zero(3, 2), J);
  cl.gain = markov_of(Acl, Kcl, Ccl, Eigen::MatrixXd::Identity(3, 3), J);
  Eigen::MatrixXd Bk(4, 5), Dk(2, 5);
  Bk << Bu, By;
  Dk << Eigen::MatrixXd::Zero(2, 2), Dy;
  const ControllerMarkov cm = controller_markov(Ao, Bk, Cc, Dk, 2, J);
  const MarkovParameters ol = open_loop_markov(cl, cm);
  EXPECT_LT(max_relative_error(markov_of(P.A, P.B, P.C, Eigen::MatrixXd::Zero(3, 2), J), ol.system, 1, J), 1e-9);
  EXPECT_LT(max_relative_error(markov_of(P.A, P.G, P.C, Eigen::MatrixXd::Identity(3, 3), J), ol.gain, 1, J), 1e-9);
}

TEST(Markov, ControllerWithFeedthroughFromUIsRefused) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(2, 2) * 0.5, B = Eigen::MatrixXd::Ones(2, 3);
  Eigen::MatrixXd Cm = Eigen::MatrixXd::Ones(1, 2), D = Eigen::MatrixXd::Zero(1, 3);
  EXPECT_NO_THROW(controller_markov(A, B, Cm, D, 1, 5));
  D(0, 0) = 0.1;  // u -> uf directly
  try {
    controller_markov(A, B, Cm, D, 1, 5);
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("feedthrough"), std::string::npos) << e.what();
  }
}

TEST(Markov, StateSpaceMarkovAndErrorMeasure) {
  Eigen::MatrixXd A(2, 2), B(2, 1), Cm(1, 2);
  A << 0.5, 1.0, 0.0, 2.0;
  B << 0.0, 1.0;
  Cm << 1.0, 0.0;
  const MarkovSequence y = markov_parameters(A, B, Cm, Eigen::MatrixXd(), 3);
  ASSERT_EQ(y.size(), 4u);
  EXPECT_EQ(y[0](0, 0), 0.0);
  EXPECT_EQ(y[1](0, 0), 0.0);  // C B
  EXPECT_EQ(y[2](0, 0), 1.0);  // C A B
  EXPECT_EQ(y[3](0, 0), 2.5);  // C A^2 B = 0.5 + 2
  MarkovSequence est = y;
  est[3](0, 0) = 2.5 * 1.02;
  const auto e = markov_errors_percent(y, est, 2, 2);
  EXPECT_NEAR(e[0], 0.0, 1e-12);
  EXPECT_NEAR(e[1], 2.0, 1e-9);
  EXPECT_THROW(markov_errors_percent(y, est, 0, 2), Error);  // true Y_0 = 0
}

}  // namespace markov_test
}  // namespace ambid::ident
