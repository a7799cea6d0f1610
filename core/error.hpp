#pragma once
// The one exception type of ambid libraries. Messages say what was wrong and with which value;
// callers (the command line, the daemons) decide how to report it.
#include <stdexcept>
#include <string>

namespace ambid {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Thrown when the data cannot support the requested result (too short, not exciting enough,
// rank deficient). Separate from Error so callers can tell "bad input" from "weak data".
class InsufficientData : public Error {
 public:
  using Error::Error;
};

// "RxC": the size of a matrix (anything with rows() and cols()) in error messages.
template <class Matrix>
std::string dims(const Matrix& m) {
  return std::to_string(m.rows()) + "x" + std::to_string(m.cols());
}

}  // namespace ambid
