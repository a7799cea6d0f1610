#include "core/json_value.hpp"

#include <utility>

#include <nlohmann/json.hpp>

namespace ambid {

JsonValue::JsonValue() = default;

JsonValue::JsonValue(nlohmann::json value) : value_(std::make_unique<nlohmann::json>(std::move(value))) {}

JsonValue JsonValue::object() { return JsonValue(nlohmann::json::object()); }

JsonValue::JsonValue(const JsonValue& other)
    : value_(other.value_ ? std::make_unique<nlohmann::json>(*other.value_) : nullptr) {}

JsonValue::JsonValue(JsonValue&& other) noexcept = default;

JsonValue& JsonValue::operator=(const JsonValue& other) {
  if (this != &other) value_ = other.value_ ? std::make_unique<nlohmann::json>(*other.value_) : nullptr;
  return *this;
}

JsonValue& JsonValue::operator=(JsonValue&& other) noexcept = default;

JsonValue::~JsonValue() = default;

const nlohmann::json& JsonValue::json() const {
  static const nlohmann::json null_value;
  return value_ ? *value_ : null_value;
}

nlohmann::json& JsonValue::json() {
  if (!value_) value_ = std::make_unique<nlohmann::json>();
  return *value_;
}

bool operator==(const JsonValue& a, const JsonValue& b) { return a.json() == b.json(); }

}  // namespace ambid
