#pragma once
// A small deterministic mutation fuzzer for the readers (issue 18): valid inputs are mutated
// (bit flips, bytes that matter to the grammar, deletions, duplications, truncation, numbers
// replaced by extreme ones) with a fixed seed, and each reader must either accept the result
// or refuse it with ambid::Error — never crash, hang or throw anything else. The default suite
// runs a few hundred inputs per reader; the slow label runs many more; the `sanitize` preset
// runs the default ones under ASan and UBSan (scripts/test.sh).
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace ambid::fuzz {

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : random_(seed) {}
  // One to eight mutations of `input`.
  std::string mutate(const std::string& input);

 private:
  std::size_t position(std::size_t size);
  std::mt19937_64 random_;
};

struct FuzzCount {
  int accepted = 0, refused = 0;
};

// Runs `reader` on `iterations` mutations of inputs drawn from `corpus`. An exception that is
// not ambid::Error fails the test with the input that caused it (escaped, first 300 bytes).
FuzzCount fuzz(const std::vector<std::string>& corpus, int iterations, std::uint64_t seed,
               const std::function<void(const std::string&)>& reader);

}  // namespace ambid::fuzz
