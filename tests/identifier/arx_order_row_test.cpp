// One row of identifier/time_domain/ARX_ORDER.md held in the default suite (okid, LQR, 1 s at
// 0.1 um / 1 mA, 2 V PRBS), and the short windows of the service: closed-loop on 0.25 s windows
// gives a model (it used to fail with "d2c: discrete eigenvalue ... on the closed negative
// real axis": 30 Markov parameters did not determine a 4th state above the noise; now more are
// taken when they do not), and at a noise the window cannot carry it says so
// (InsufficientData) instead of realising the noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "arx_order_cases.hpp"
#include "core/error.hpp"
#include "identifier/identify_experiment.hpp"
#include "identifier/identify_window.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace arx_order_row_test {

TEST(ArxOrderRow, OkidOneSecondWindowAgainstTheOrder) {
  const testing::ArxCase c = testing::arx_case("lqr", 1.0, 1e-7, 1e-3);
  // Worst v1..v9 error of the table (percent); the row's value within 15 % of itself.
  const std::vector<std::pair<Eigen::Index, double>> row = {{8, 467}, {16, 175}, {32, 19.4}, {64, 29.0}, {0, 120}};
  for (const auto& [order, percent] : row) {
    const testing::ArxCaseResult r = testing::identify_case(c, "okid", order);
    ASSERT_TRUE(r.error.empty()) << r.error;
    ::testing::Test::RecordProperty("okid_q" + std::to_string(r.order) + "_worst", testing::sci(r.worst));
    EXPECT_NEAR(100 * r.worst, percent, 0.15 * percent) << "order " << r.order;
    if (order == 0) {
      EXPECT_EQ(r.order, 19);  // 2 ln 10000, rounded up
    }
  }
}

// Four consecutive 0.25 s windows of one record, the controller state carried (as the service
// cuts its stream), for both controllers.
TEST(ArxOrderRow, ClosedLoopGivesAModelOnEveryQuarterSecondWindow) {
  for (const std::string controller : {"lqr", "pid"}) {
    const testing::ArxCase c = testing::arx_case(controller, 1.0, 1e-7, 1e-3);
    const Eigen::Index settle = std::lround(testing::kArxCaseSettle / c.record.sample_time);
    const Eigen::Index window = std::lround(0.25 / c.record.sample_time);
    for (Eigen::Index w = 0; w < 4; ++w) {
      SCOPED_TRACE(controller + " window " + std::to_string(w));
      const Experiment part = experiment_segment(c.record, settle + w * window, settle + (w + 1) * window);
      const WindowIdentification id = identify_window(part, window_identify_options("closed-loop"));
      ASSERT_EQ(id.model.parameters.size(), 9u);
      for (const auto& [name, value] : id.model.parameters) EXPECT_TRUE(std::isfinite(value)) << name;
    }
  }
}

// At 100 times the sensors' noise a 0.25 s window rarely carries 4 states: each window gives a
// model with a continuous equivalent or InsufficientData that says why, never the d2c error.
TEST(ArxOrderRow, WindowTooNoisyForFourStatesSaysSo) {
  int refused = 0;
  for (const std::string controller : {"lqr", "pid"}) {
    const testing::ArxCase c = testing::arx_case(controller, 1.0, 1e-5, 1e-1);
    const Eigen::Index settle = std::lround(testing::kArxCaseSettle / c.record.sample_time);
    const Eigen::Index window = std::lround(0.25 / c.record.sample_time);
    for (Eigen::Index w = 0; w < 4; ++w) {
      SCOPED_TRACE(controller + " window " + std::to_string(w));
      const Experiment part = experiment_segment(c.record, settle + w * window, settle + (w + 1) * window);
      try {
        const WindowIdentification id = identify_window(part, window_identify_options("closed-loop"));
        EXPECT_EQ(id.model.parameters.size(), 9u);
      } catch (const InsufficientData& e) {
        const std::string what = e.what();
        std::printf("%s window %lld: %s\n", controller.c_str(), static_cast<long long>(w), what.c_str());
        // Either ERA finds no determined order, or the only determined ones keep a noise state
        // on the negative real axis (a valid discrete model without physical parameters).
        EXPECT_TRUE(what.find("the data do not determine") != std::string::npos ||
                    what.find("numerical rank") != std::string::npos ||
                    what.find("no continuous-time model") != std::string::npos)
            << what;
        ++refused;
      }
    }
  }
  EXPECT_GE(refused, 4);
}

}  // namespace arx_order_row_test
}  // namespace ambid::ident
