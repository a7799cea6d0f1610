#pragma once
// A JSON value kept behind a pointer, for data members of widely included types
// (Experiment::extra, Model::extra, Excitation::description): their headers then need only
// nlohmann/json_fwd.hpp, and copying such a type compiles no JSON code where it is copied.
// The files that build or read the value include <nlohmann/json.hpp> and use json().
#include <memory>

#include <nlohmann/json_fwd.hpp>

namespace ambid {

class JsonValue {
 public:
  JsonValue();  // null
  explicit JsonValue(nlohmann::json value);
  static JsonValue object();  // {}

  JsonValue(const JsonValue& other);
  JsonValue(JsonValue&& other) noexcept;  // moving leaves `other` null
  JsonValue& operator=(const JsonValue& other);
  JsonValue& operator=(JsonValue&& other) noexcept;
  ~JsonValue();

  const nlohmann::json& json() const;
  nlohmann::json& json();

  friend bool operator==(const JsonValue& a, const JsonValue& b);

 private:
  std::unique_ptr<nlohmann::json> value_;  // nullptr stands for null (no allocation)
};

}  // namespace ambid
