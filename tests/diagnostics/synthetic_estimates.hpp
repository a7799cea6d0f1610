#pragma once
// Synthetic estimate windows for the diagnostics tests: the nominal physical parameters of
// amb1dof_voltage (seed 000) with seeded Gaussian noise of a given relative sigma, and a
// chosen relative change of any parameter in any window.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "diagnostics/estimate.hpp"

namespace ambid::diag::testing {

// R1, R2 [ohm], kw1, kw2 [-], kr1, kr2 [N/A], ks [N/m].
const std::vector<std::pair<std::string, double>>& nominal_parameters();
double nominal(const std::string& parameter);

struct SyntheticPlant {
  SyntheticPlant(std::string plant, std::uint64_t seed, double relative_sigma);

  // value = nominal * (1 + change(parameter, window)) + N(0, relative_sigma * nominal); the
  // reported sigma is relative_sigma * nominal. Window n is at time n * period.
  EstimateWindow window(std::size_t n);
  std::vector<EstimateWindow> windows(std::size_t from, std::size_t to);  // [from, to)

  std::string plant_id;
  double relative_sigma;
  double period = 1.0;
  std::function<double(const std::string&, std::size_t)> change = [](const std::string&, std::size_t) { return 0.0; };
  std::vector<std::string> parameters;  // which parameters a window carries (all by default)
  std::mt19937_64 rng;
};

// A fresh path for a store file in the test temp directory (old file, -wal and -shm removed);
// removed again when the test program exits.
std::filesystem::path fresh_store_path(const std::string& name);

}  // namespace ambid::diag::testing
