#pragma once
// Test messages of every topic: `largest` sets every field, every string at its bound and every
// sequence at its bound (what a truncation, a bound mismatch or a layout slip would show);
// `small(k)` is a short message, distinct for each k, on one instance per type.
#include "services/bus/messages.hpp"

namespace ambid::bus::test {

template <class Message>
Message largest();
template <class Message>
Message small(int k);

// A string of exactly n characters that differs at every position from its neighbours'.
std::string text_of_length(std::size_t n, char first = 'a');

}  // namespace ambid::bus::test
