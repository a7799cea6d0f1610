// The per-window statistics of the prediction-error method at realistic noise, long version:
// 20 windows of 1 s under every controller of tests/support/amb1dof_records.hpp (the default
// suite checks 10 under the LQR loop, amb1dof_prediction_error_test.cpp).
#include <gtest/gtest.h>

#include "amb1dof_pem_checks.hpp"

namespace ambid::ident {
namespace amb1dof_prediction_error_slow_test {

class WindowScatter : public ::testing::TestWithParam<std::string> {};

TEST_P(WindowScatter, TwentyWindowsScatterAsTheReportedSigma) { testing::check_window_scatter(GetParam(), 20, 31); }

INSTANTIATE_TEST_SUITE_P(Controllers, WindowScatter, ::testing::ValuesIn(testing::amb1dof_record_controllers()));

}  // namespace amb1dof_prediction_error_slow_test
}  // namespace ambid::ident
