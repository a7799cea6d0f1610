// plant_sim: simulate the amb1dof_voltage bearing with coil 1 20 % hot under its nominal LQR
// controller and write the experiment (CSV + JSON sidecar) the other tools read.
//   simulate_bearing OUT_STEM     (writes OUT_STEM.csv and OUT_STEM.json)
#include <iostream>

#include "core/experiment_io.hpp"
#include "plant_sim/scenario.hpp"

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::cerr << "usage: simulate_bearing OUT_STEM\n";
    return 2;
  }
  ambid::sim::ScenarioOptions options;
  options.duration = 2.0;
  options.true_parameters["R1"] = 21.0;  // nominal 17.5 ohm; the sidecar keeps the nominal value
  options.position_noise = 1e-7;         // 0.1 um
  options.current_noise = 1e-3;          // 1 mA
  options.amplitude = 1.0;               // PRBS level at each amplifier input (V), of 8.75 V
  const ambid::Experiment experiment = ambid::sim::simulate_scenario(options);
  ambid::write_experiment(experiment, argv[1]);
  std::cout << experiment.samples() << " samples written to " << argv[1] << ".csv/.json\n";
} catch (const std::exception& error) {  // ambid::Error, or a file that cannot be written
  std::cerr << "simulate_bearing: " << error.what() << "\n";
  return 1;
}
