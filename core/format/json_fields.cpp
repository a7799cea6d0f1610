#include "core/format/json_fields.hpp"

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/format/experiment_text.hpp"

namespace ambid::json_fields {

std::string path_of(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string indexed(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

[[noreturn]] void wrong_type(const json& value, const std::string& path, const std::string& expected) {
  throw Error("key `" + path + "` must be " + expected + ", got " + value.type_name() + " " +
              quote_excerpt(value.dump()));
}

const json& require_key(const json& object, const std::string& parent, const std::string& key,
                        const std::string& expected) {
  const auto it = object.find(key);
  if (it == object.end())
    throw Error("missing required key `" + path_of(parent, key) + "` (expected " + expected + ")");
  return *it;
}

const json& as_object(const json& value, const std::string& path) {
  if (!value.is_object()) wrong_type(value, path, "an object");
  return value;
}

double as_number(const json& value, const std::string& path) {
  if (!value.is_number()) wrong_type(value, path, "a number");
  return value.get<double>();
}

std::string as_string(const json& value, const std::string& path) {
  if (!value.is_string()) wrong_type(value, path, "a string");
  return value.get<std::string>();
}

std::vector<std::string> as_names(const json& value, const std::string& path) {
  if (!value.is_array()) wrong_type(value, path, "an array of signal names");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < value.size(); ++i) names.push_back(as_string(value[i], indexed(path, i)));
  return names;
}

Eigen::VectorXd as_vector(const json& value, const std::string& path) {
  if (!value.is_array()) wrong_type(value, path, "an array of numbers");
  Eigen::VectorXd v(static_cast<Eigen::Index>(value.size()));
  for (std::size_t i = 0; i < value.size(); ++i)
    v(static_cast<Eigen::Index>(i)) = as_number(value[i], indexed(path, i));
  return v;
}

Eigen::MatrixXd as_matrix(const json& value, const std::string& path, Eigen::Index cols_if_empty) {
  if (!value.is_array()) wrong_type(value, path, "an array of rows (arrays of numbers)");
  if (value.empty()) return Eigen::MatrixXd(0, cols_if_empty);
  const auto rows = static_cast<Eigen::Index>(value.size());
  Eigen::MatrixXd m;
  for (Eigen::Index i = 0; i < rows; ++i) {
    const std::string row_path = indexed(path, static_cast<std::size_t>(i));
    const Eigen::VectorXd row = as_vector(value[static_cast<std::size_t>(i)], row_path);
    if (i == 0) m.resize(rows, row.size());
    if (row.size() != m.cols())
      throw Error("key `" + row_path + "` has " + std::to_string(row.size()) + " entries, but row 0 of `" + path +
                  "` has " + std::to_string(m.cols()) + "; every row must have the same length");
    m.row(i) = row.transpose();
  }
  return m;
}

void keep_unknown(const json& object, const std::set<std::string>& known, json& extra) {
  for (const auto& [key, value] : object.items())
    if (!known.count(key)) extra[key] = value;
}

void merge_unknown(json& j, const json& extra) {
  if (!extra.is_object()) return;
  for (const auto& [key, value] : extra.items()) {
    if (j.contains(key) && j[key].is_object())
      j[key].update(value);
    else
      j[key] = value;
  }
}

json matrix_json(const Eigen::MatrixXd& m) {
  json rows = json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(m(i, j));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace ambid::json_fields
