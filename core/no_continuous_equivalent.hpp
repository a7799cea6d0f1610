#pragma once
// The error d2c_zoh (state_space.hpp) throws when a discrete model has no continuous
// zero-order-hold equivalent (an eigenvalue on the closed negative real axis): the discrete
// model itself may still be valid, and callers that can keep it catch this type.
#include "core/error.hpp"

namespace ambid {

class NoContinuousEquivalent : public InsufficientData {
 public:
  using InsufficientData::InsufficientData;
};

}  // namespace ambid
