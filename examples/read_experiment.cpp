// core: read an experiment file (experiment-format.md) and print what it holds.
//   read_experiment FILE     (the .csv or the .json of the pair)
#include <iostream>

#include "core/error.hpp"
#include "core/experiment_io.hpp"

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::cerr << "usage: read_experiment FILE\n";
    return 2;
  }
  const ambid::Experiment e = ambid::read_experiment(argv[1]).experiment;
  std::cout << e.name << ": plant " << e.plant.model << ", " << e.samples() << " samples at " << e.sample_time << " s, "
            << e.y_names.size() << " outputs, " << e.u_names.size() << " inputs, "
            << (e.controller ? "with" : "without") << " controller\n";
} catch (const ambid::Error& error) {
  std::cerr << "read_experiment: " << error.what() << "\n";
  return 1;
}
