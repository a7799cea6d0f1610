#include "fleet_support.hpp"

#include <fstream>

namespace ambid::testing {

std::string bearing(int k) { return "bearing-" + std::to_string(k); }

std::string fleet_scenario(const Stack& stack, int k, const std::string& overrides) {
  const auto file = stack.dir() / ("scenario-" + std::to_string(k) + (overrides.empty() ? "" : "-hot") + ".json");
  std::ofstream(file) << R"({"name": "fleet-)" << k << R"(", "controller": "lqr", "excitation": "prbs",)"
                      << R"( "amplitude": 1.0, "position_noise": 1e-9, "current_noise": 1e-6, "duration": 1.0,)"
                      << overrides << R"( "seed": )" << 10 * k << "}";
  return file.string();
}

void start_plant(Stack& stack, int k, int domain) {
  const auto config = stack.dir() / ("plant-" + std::to_string(k) + ".json");
  // Real time: eight bearings are 80 k samples/s in all on a shared 2-core machine.
  std::ofstream(config) << R"({"source": "sim", "target": ")" << fleet_scenario(stack, k)
                        << R"(", "batch_samples": 500, "speed": 1})";
  stack.start_process("plant-" + std::to_string(k),
                      {"daemon", "plant", "--dds", "cyclone", "--domain", std::to_string(domain), "--plant-id",
                       bearing(k), "--config", config.string()});
}

void start_identifier(Stack& stack, const std::string& name, const std::string& plants, int domain,
                      const std::string& vendor) {
  const auto config = stack.dir() / (name + ".json");
  std::ofstream(config) << R"({"plants": )" << plants
                        << R"(, "window": 0.25, "settle": 0.25, "method": "closed-loop"})";
  stack.start_process(
      name, {"daemon", "identifier", "--dds", vendor, "--domain", std::to_string(domain), "--config", config.string()});
}

std::string plant_list(int first, int last) {
  std::string s = "[";
  for (int k = first; k <= last; ++k) s += (k > first ? ", \"" : "\"") + bearing(k) + "\"";
  return s + "]";
}

}  // namespace ambid::testing
