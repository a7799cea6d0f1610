#include "fuzz/mutator.hpp"

#include <gtest/gtest.h>

#include <array>
#include <exception>
#include <string_view>
#include <typeinfo>

#include "core/error.hpp"

namespace ambid::fuzz {
namespace mutator {

// Bytes and tokens that change what a JSON, CSV or frame parser does.
constexpr std::string_view kBytes = "{}[]\",:\n\r\t\\0-+.eE9 \x00\xff\x80\xc3";
constexpr std::array<std::string_view, 12> kTokens = {
    "1e309", "-1e309",         "nan", "NaN", "-0", "1e-320", "18446744073709551616", "\"\\u0000\"", "\xc3\x28", "[[[[",
    "null",  "\"x\":1,\"x\":2"};

std::string printable(const std::string& input) {
  std::string out;
  for (char c : input.substr(0, 300)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 32 && byte < 127) {
      out += c;
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 15];
    }
  }
  return out;
}

}  // namespace mutator
using namespace mutator;

std::size_t Mutator::position(std::size_t size) {
  return size == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, size - 1)(random_);
}

std::string Mutator::mutate(const std::string& input) {
  std::string s = input;
  const int count = std::uniform_int_distribution<int>(1, 8)(random_);
  for (int k = 0; k < count; ++k) {
    const std::size_t at = position(s.size());
    switch (std::uniform_int_distribution<int>(0, 6)(random_)) {
      case 0:  // flip a bit
        if (!s.empty()) s[at] = char(s[at] ^ (1 << position(8)));
        break;
      case 1:  // a byte that matters to the grammar
        if (!s.empty()) s[at] = kBytes[position(kBytes.size())];
        break;
      case 2:  // delete a range
        s.erase(at, position(64) + 1);
        break;
      case 3:  // duplicate a range
        s.insert(at, s.substr(position(s.size()), position(256) + 1));
        break;
      case 4:  // truncate
        s.resize(at);
        break;
      case 5:  // an extreme token
        s.insert(at, kTokens[position(kTokens.size())]);
        break;
      default:  // a number's digits replaced
        if (const std::size_t d = s.find_first_of("0123456789", at); d != std::string::npos)
          s.replace(d, 1, kTokens[position(7)]);
        break;
    }
  }
  return s;
}

FuzzCount fuzz(const std::vector<std::string>& corpus, int iterations, std::uint64_t seed,
               const std::function<void(const std::string&)>& reader) {
  Mutator mutator(seed);
  FuzzCount count;
  for (int i = 0; i < iterations; ++i) {
    const std::string input = mutator.mutate(corpus[std::size_t(i) % corpus.size()]);
    try {
      reader(input);
      ++count.accepted;
    } catch (const Error&) {
      ++count.refused;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "iteration " << i << ": " << typeid(e).name() << ": " << e.what()
                    << "\ninput: " << printable(input);
    }
  }
  return count;
}

}  // namespace ambid::fuzz
