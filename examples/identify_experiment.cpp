// identifier: identify the open-loop plant of a closed-loop experiment file and print its
// physical parameters with their one-sigma uncertainty.
//   identify_experiment FILE [METHOD]     (METHOD default pem: consistent under sensor noise)
#include <iostream>

#include "core/error.hpp"
#include "core/experiment_io.hpp"
#include "identifier/identify_experiment.hpp"

int main(int argc, char** argv) try {
  if (argc < 2 || argc > 3) {
    std::cerr << "usage: identify_experiment FILE [METHOD]\n";
    return 2;
  }
  ambid::ident::IdentifyOptions options;
  options.method = argc == 3 ? argv[2] : "pem";
  options.skip_samples = 1000;  // the settling transient of the first 0.1 s
  const ambid::Model model = ambid::ident::identify_experiment(ambid::read_experiment(argv[1]).experiment, options);
  for (const auto& [name, value] : model.physical) {
    const auto sigma = model.uncertainty.find(name);
    std::cout << name << " = " << value << " +- " << (sigma == model.uncertainty.end() ? 0.0 : sigma->second) << "\n";
  }
} catch (const ambid::Error& error) {
  std::cerr << "identify_experiment: " << error.what() << "\n";
  return 1;
}
