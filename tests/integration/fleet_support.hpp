#pragma once
// A fleet of simulated bearings on one domain for the stack tests (fleet_stack*_test.cpp): one
// plant daemon per bearing (bearing-K, quiet-bearing.json with its own seed), identifiers
// serving lists of them.
#include <string>

#include "stack_support.hpp"

namespace ambid::testing {

std::string bearing(int k);  // "bearing-K"
// The scenario file of bearing k: quiet-bearing.json with seed 10 k; `overrides`: more keys,
// e.g. R"( "true_parameters": {"R1": 21.0},)" (then the file is scenario-K-hot.json).
std::string fleet_scenario(const Stack& stack, int k, const std::string& overrides = {});
// Process plant-K on cyclone at real time.
void start_plant(Stack& stack, int k, int domain);
// Process `name` on `vendor` serving `plants` (a JSON list), closed-loop on 0.25 s windows.
void start_identifier(Stack& stack, const std::string& name, const std::string& plants, int domain,
                      const std::string& vendor);
// ["bearing-first", ..., "bearing-last"]
std::string plant_list(int first, int last);

}  // namespace ambid::testing
