#include "diagnostics/synthetic_estimates.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <set>
#include <system_error>

#include "core/error.hpp"

namespace ambid::diag::testing {

const std::vector<std::pair<std::string, double>>& nominal_parameters() {
  static const std::vector<std::pair<std::string, double>> p = {
      {"R1", 17.5}, {"R2", 17.5}, {"kw1", 1.0}, {"kw2", 1.0}, {"kr1", 490.0}, {"kr2", 490.0}, {"ks", 7e5}};
  return p;
}

double nominal(const std::string& parameter) {
  for (const auto& [name, value] : nominal_parameters())
    if (name == parameter) return value;
  throw Error("no nominal value for " + parameter);
}

SyntheticPlant::SyntheticPlant(std::string plant, std::uint64_t seed, double sigma)
    : plant_id(std::move(plant)), relative_sigma(sigma), rng(seed) {
  for (const auto& [name, value] : nominal_parameters()) parameters.push_back(name);
}

EstimateWindow SyntheticPlant::window(std::size_t n) {
  EstimateWindow w;
  w.time = static_cast<double>(n) * period;
  w.plant_id = plant_id;
  w.source = Source::sim;
  std::normal_distribution<double> noise;
  for (const std::string& name : parameters) {
    const double v0 = nominal(name);
    w.estimates.push_back({name, v0 * (1.0 + change(name, n)) + relative_sigma * v0 * noise(rng), relative_sigma * v0});
  }
  return w;
}

std::vector<EstimateWindow> SyntheticPlant::windows(std::size_t from, std::size_t to) {
  std::vector<EstimateWindow> result;
  for (std::size_t n = from; n < to; ++n) result.push_back(window(n));
  return result;
}

namespace synthetic_estimates_support {

void remove_store(const std::filesystem::path& path) {
  std::error_code ignored;
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path.string() + suffix, ignored);
}

// Removes the stores of this test program when it exits (forked writers leave with _exit).
struct StoreCleanup {
  ~StoreCleanup() {
    for (const auto& path : paths) remove_store(path);
  }
  std::set<std::filesystem::path> paths;
};

}  // namespace synthetic_estimates_support
using namespace synthetic_estimates_support;

std::filesystem::path fresh_store_path(const std::string& name) {
  static StoreCleanup cleanup;
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) /
                                     ("ambid_diag_" + name + "_" + std::to_string(::getpid()) + ".sqlite");
  remove_store(path);
  cleanup.paths.insert(path);
  return path;
}

}  // namespace ambid::diag::testing
