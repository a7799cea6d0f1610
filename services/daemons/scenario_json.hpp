#pragma once
// Scenario files: the simulated plant of the plant daemon's `sim` source, as JSON with the
// fields of sim::ScenarioOptions (plant_sim/scenario.hpp), every one optional:
//   {"name": "coil1-hot", "plant": "amb1dof_voltage", "true_parameters": {"R1": 21.6},
//    "controller": "lqr", "excitation": "prbs", "amplitude": 0.05, "f_min": 1, "f_max": 1000,
//    "duration": 1.0, "sample_time": 1e-4, "position_noise": 1e-7, "current_noise": 1e-4,
//    "force_noise": 0, "input_limit": 0, "seed": 1}
// `duration` is the length of one simulated record; the source runs record after record.
// Unknown keys are refused (a misspelt "true_parameters" must not give a healthy plant).
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "plant_sim/scenario.hpp"

namespace ambid::daemons {

// Throws Error naming the key and the value that is wrong.
sim::ScenarioOptions scenario_from_json(const nlohmann::json& j);
// The scenario in a file; errors name the file.
sim::ScenarioOptions read_scenario_file(const std::string& path);

}  // namespace ambid::daemons
