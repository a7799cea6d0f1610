#pragma once
// Locale-independent number text for experiment files and messages: the shortest text that
// reads back to the same double, and a strict parser for CSV cells.
#include <optional>
#include <string>
#include <string_view>

namespace ambid {

// Shortest round-trip text (std::to_chars), e.g. "0.001", "1e-4", "1.5e+300", "-0", "inf".
std::string number_text(double value);

// The value of `text` if it is a whole decimal number ('.' point, optional sign and
// exponent), nullopt otherwise. Does not judge finiteness: "nan" and "inf" parse.
std::optional<double> parse_number(std::string_view text);

// `text` shortened to at most `limit` characters for quoting in a message.
std::string quote_excerpt(std::string_view text, std::size_t limit = 40);

}  // namespace ambid
