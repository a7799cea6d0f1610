// ISO 14839-3 zones of the peak sensitivity, at, above and below each limit (9.5, 12, 14 dB),
// on the bare classification and on constructed loops whose sensitivity peak is known by
// construction.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>

#include "core/error.hpp"
#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/sensitivity_function.hpp"
#include "identifier/iso_14839.hpp"

namespace ambid::ident {
namespace iso_14839_test {

using test::kPi;

TEST(Iso14839, ZonesAtAboveAndBelowEachLimit) {
  EXPECT_EQ(iso14839_zone(0.0), IsoZone::A);
  EXPECT_EQ(iso14839_zone(-std::numeric_limits<double>::infinity()), IsoZone::A);
  EXPECT_EQ(iso14839_zone(std::nextafter(9.5, 0.0)), IsoZone::A);
  EXPECT_EQ(iso14839_zone(9.5), IsoZone::B);  // a limit belongs to the worse zone
  EXPECT_EQ(iso14839_zone(9.51), IsoZone::B);
  EXPECT_EQ(iso14839_zone(std::nextafter(12.0, 0.0)), IsoZone::B);
  EXPECT_EQ(iso14839_zone(12.0), IsoZone::C);
  EXPECT_EQ(iso14839_zone(12.01), IsoZone::C);
  EXPECT_EQ(iso14839_zone(std::nextafter(14.0, 0.0)), IsoZone::C);
  EXPECT_EQ(iso14839_zone(14.0), IsoZone::D);
  EXPECT_EQ(iso14839_zone(40.0), IsoZone::D);
  EXPECT_EQ(iso14839_zone(std::numeric_limits<double>::infinity()), IsoZone::D);
  EXPECT_THROW(iso14839_zone(std::nan("")), Error);
  EXPECT_THROW(iso14839_zone(10.0, IsoZoneLimits{12.0, 9.5, 14.0}), Error);
  EXPECT_EQ(to_string(IsoZone::C), "C");
  EXPECT_NEAR(magnitude_db(3.0), 9.5424250943932, 1e-12);
  EXPECT_THROW(magnitude_db(-1.0), Error);
}

// A SISO loop on a 1 Hz grid whose input sensitivity is S(f) = 1 + (P - 1) exp(-((f - f0)/w)^2)
// (peak exactly P at the line f0), made by the controller K = (1 - 1/S) / G around the Sales
// rotor plant G = 840 / (s^2 - 2800). The sensitivity is then recomputed from G and K.
Frf constructed_sensitivity(double peak_db) {
  const double P = std::pow(10.0, peak_db / 20.0), f0 = 137.0, w = 25.0;
  Frf S;
  S.frequency_hz.resize(500);
  for (Eigen::Index i = 0; i < 500; ++i) {
    const double f = static_cast<double>(i + 1);
    S.frequency_hz(i) = f;
    const std::complex<double> s(0.0, 2.0 * kPi * f);
    const std::complex<double> G = 840.0 / (s * s - 2800.0);
    const std::complex<double> target = 1.0 + (P - 1.0) * std::exp(-std::pow((f - f0) / w, 2));
    const std::complex<double> K = (1.0 - 1.0 / target) / G;
    S.value.push_back(input_sensitivity(Eigen::MatrixXcd::Constant(1, 1, G), Eigen::MatrixXcd::Constant(1, 1, K)));
  }
  return S;
}

TEST(Iso14839, ConstructedLoopsAroundEachLimit) {
  struct Case {
    double db;
    IsoZone zone;
  };
  const Case cases[] = {{9.49, IsoZone::A},  {9.51, IsoZone::B},  {11.99, IsoZone::B}, {12.01, IsoZone::C},
                        {13.99, IsoZone::C}, {14.01, IsoZone::D}, {6.0, IsoZone::A},   {20.0, IsoZone::D}};
  for (const Case& c : cases) {
    const Frf S = constructed_sensitivity(c.db);
    const auto peaks = sensitivity_peaks(S, {"x"});
    ASSERT_EQ(peaks.size(), 1u);
    EXPECT_NEAR(peaks[0].magnitude_db, c.db, 1e-9) << c.db;
    EXPECT_DOUBLE_EQ(peaks[0].frequency_hz, 137.0);
    EXPECT_EQ(peaks[0].zone, c.zone) << c.db;
    EXPECT_EQ(peaks[0].loop, "x");
    const SensitivityPeak sigma = max_singular_sensitivity_peak(S);
    EXPECT_NEAR(sigma.magnitude_db, c.db, 1e-9);
    EXPECT_EQ(sigma.zone, c.zone);
  }
}

TEST(Iso14839, PerLoopPeaksOfATwoLoopSensitivity) {
  // S = diag(S_a, S_b) rotated by a unitary U: the diagonal loops see mixed peaks, sigma_max
  // sees the larger one exactly.
  const Frf Sa = constructed_sensitivity(10.0), Sb = constructed_sensitivity(13.0);
  const double c = std::cos(0.3), s = std::sin(0.3);
  Eigen::Matrix2cd U;
  U << c, -s, s, c;
  Frf S;
  S.frequency_hz = Sa.frequency_hz;
  for (Eigen::Index l = 0; l < Sa.lines(); ++l) {
    Eigen::Matrix2cd D = Eigen::Matrix2cd::Zero();
    D(0, 0) = Sa.value[static_cast<std::size_t>(l)](0, 0);
    D(1, 1) = Sb.value[static_cast<std::size_t>(l)](0, 0);
    S.value.push_back(U * D * U.adjoint());
  }
  const auto peaks = sensitivity_peaks(S, {"u1", "u2"});
  ASSERT_EQ(peaks.size(), 2u);
  const double pa = std::pow(10.0, 0.5), pb = std::pow(10.0, 13.0 / 20.0);
  EXPECT_NEAR(peaks[0].magnitude, c * c * pa + s * s * pb, 1e-9);
  EXPECT_NEAR(peaks[1].magnitude, s * s * pa + c * c * pb, 1e-9);
  EXPECT_NEAR(max_singular_sensitivity_peak(S).magnitude_db, 13.0, 1e-9);
  EXPECT_EQ(max_singular_sensitivity_peak(S).zone, IsoZone::C);
  EXPECT_THROW(sensitivity_peaks(S, {"u1"}), Error);
}

}  // namespace iso_14839_test
}  // namespace ambid::ident
