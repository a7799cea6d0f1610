#pragma once
// The columns of a foreign record for `ambid import`: named CSV columns or MAT variables.
#include <filesystem>
#include <memory>
#include <string>

#include <Eigen/Core>

namespace ambid {

class RecordedColumns {
 public:
  virtual ~RecordedColumns() = default;
  // The finite values of `source` (a CSV column name; a MAT vector variable or "VAR(:,K)").
  // Throws Error naming the source and what is wrong, without the file name.
  virtual Eigen::VectorXd column(const std::string& source) const = 0;
  virtual std::string kind() const = 0;  // "CSV", "MAT v5"
};

// Throws Error (without the file name) when the file cannot be read or has no header line.
std::unique_ptr<RecordedColumns> open_csv_columns(const std::filesystem::path& file);
// Throws Error (without the file name) when libmatio cannot open the file.
std::unique_ptr<RecordedColumns> open_mat_columns(const std::filesystem::path& file);

}  // namespace ambid
