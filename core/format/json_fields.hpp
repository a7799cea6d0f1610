#pragma once
// Typed access to parsed JSON for the strict file readers (experiment sidecar, model file):
// each accessor throws Error naming the key path (`controller.A[1][2]`) and what was expected.
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>

namespace ambid::json_fields {

using nlohmann::json;

std::string path_of(const std::string& parent, const std::string& key);  // "parent.key"
std::string indexed(const std::string& path, std::size_t i);             // "path[i]"

[[noreturn]] void wrong_type(const json& value, const std::string& path, const std::string& expected);
const json& require_key(const json& object, const std::string& parent, const std::string& key,
                        const std::string& expected);
const json& as_object(const json& value, const std::string& path);
double as_number(const json& value, const std::string& path);
std::string as_string(const json& value, const std::string& path);
std::vector<std::string> as_names(const json& value, const std::string& path);
Eigen::VectorXd as_vector(const json& value, const std::string& path);
// An array of rows. `[]` has no rows to tell its width, so it gets `cols_if_empty` columns
// (a controller without states writes B as []).
Eigen::MatrixXd as_matrix(const json& value, const std::string& path, Eigen::Index cols_if_empty);

// Copies the keys of `object` that the format does not define into `extra`.
void keep_unknown(const json& object, const std::set<std::string>& known, json& extra);

// Puts the kept unknown keys back: an object in `extra` whose key names an object of `j` is
// merged into it, anything else set at the top.
void merge_unknown(json& j, const json& extra);

// Rows of numbers, the form as_matrix reads.
json matrix_json(const Eigen::MatrixXd& m);

}  // namespace ambid::json_fields
