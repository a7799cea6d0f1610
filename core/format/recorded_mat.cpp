// MAT v5 records (and v7.3, which libmatio reads too): real numeric variables, either vectors
// named one per signal or a 2-D matrix whose columns are signals, addressed as "VAR(:,K)".
#include <matio.h>

#include <cmath>
#include <cstdint>
#include <regex>

#include "core/error.hpp"
#include "core/format/experiment_text.hpp"
#include "core/format/recorded_columns.hpp"

namespace ambid {
namespace {

// libmatio reports problems on stderr unless given a log function; a library prints nothing,
// and every failure is reported through the Error thrown below.
void silent(int, char*) {}

struct MatFileCloser {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};
struct MatVarFreer {
  void operator()(matvar_t* var) const { Mat_VarFree(var); }
};

template <typename T>
double element(const matvar_t& var, std::size_t i) {
  return static_cast<double>(static_cast<const T*>(var.data)[i]);
}

double element_as_double(const matvar_t& var, std::size_t i) {
  switch (var.class_type) {
    case MAT_C_DOUBLE:
      return element<double>(var, i);
    case MAT_C_SINGLE:
      return element<float>(var, i);
    case MAT_C_INT8:
      return element<std::int8_t>(var, i);
    case MAT_C_UINT8:
      return element<std::uint8_t>(var, i);
    case MAT_C_INT16:
      return element<std::int16_t>(var, i);
    case MAT_C_UINT16:
      return element<std::uint16_t>(var, i);
    case MAT_C_INT32:
      return element<std::int32_t>(var, i);
    case MAT_C_UINT32:
      return element<std::uint32_t>(var, i);
    case MAT_C_INT64:
      return element<std::int64_t>(var, i);
    case MAT_C_UINT64:
      return element<std::uint64_t>(var, i);
    default:
      throw Error("unsupported MAT class");  // excluded by the caller's check
  }
}

bool is_real_numeric(const matvar_t& var) {
  switch (var.class_type) {
    case MAT_C_DOUBLE:
    case MAT_C_SINGLE:
    case MAT_C_INT8:
    case MAT_C_UINT8:
    case MAT_C_INT16:
    case MAT_C_UINT16:
    case MAT_C_INT32:
    case MAT_C_UINT32:
    case MAT_C_INT64:
    case MAT_C_UINT64:
      return !var.isComplex && var.data != nullptr;
    default:
      return false;
  }
}

class MatColumns : public RecordedColumns {
 public:
  explicit MatColumns(const std::filesystem::path& file) {
    Mat_LogInitFunc("ambid", silent);
    mat_.reset(Mat_Open(file.c_str(), MAT_ACC_RDONLY));
    if (!mat_) throw Error("libmatio cannot open it as a MAT file (missing, unreadable or not MAT v5/v7.3)");
  }

  Eigen::VectorXd column(const std::string& source) const override {
    static const std::regex matrix_column(R"(^\s*([A-Za-z][A-Za-z0-9_]*)\s*\(\s*:\s*,\s*([0-9]+)\s*\)\s*$)");
    std::smatch m;
    const bool by_column = std::regex_match(source, m, matrix_column);
    const std::string name = by_column ? m[1].str() : source;
    const std::unique_ptr<matvar_t, MatVarFreer> var(Mat_VarRead(mat_.get(), name.c_str()));
    if (!var) throw Error("no variable '" + name + "' (the file has " + variable_list() + ")");
    if (!is_real_numeric(*var) || var->rank != 2)
      throw Error("variable '" + name + "' is not a real numeric 2-D array (complex, sparse, text, cell or struct)");
    const std::size_t rows = var->dims[0], cols = var->dims[1];
    const std::string shape = std::to_string(rows) + "x" + std::to_string(cols);
    std::size_t first = 0, count = 0;
    if (by_column) {
      const unsigned long k = std::stoul(m[2].str());
      if (k < 1 || k > cols)
        throw Error("'" + source + "': variable '" + name + "' is " + shape + ", it has no column " + m[2].str());
      first = (k - 1) * rows;  // column-major
      count = rows;
    } else {
      if (rows != 1 && cols != 1)
        throw Error("variable '" + name + "' is a " + shape + " matrix, not a vector; name one column as " + name +
                    "(:,K)");
      count = rows * cols;
    }
    Eigen::VectorXd values(static_cast<Eigen::Index>(count));
    for (std::size_t i = 0; i < count; ++i) {
      values(Eigen::Index(i)) = element_as_double(*var, first + i);
      if (!std::isfinite(values(Eigen::Index(i))))
        throw Error("'" + source + "': element " + std::to_string(i + 1) + " of " + std::to_string(count) + " is " +
                    number_text(values(Eigen::Index(i))) + "; expected a finite number");
    }
    return values;
  }

  std::string kind() const override {
    const mat_ft version = Mat_GetVersion(mat_.get());
    return version == MAT_FT_MAT73 ? "MAT v7.3" : version == MAT_FT_MAT4 ? "MAT v4" : "MAT v5";
  }

 private:
  std::string variable_list() const {
    std::size_t n = 0;
    char** names = Mat_GetDir(mat_.get(), &n);  // owned by the file
    std::string list;
    for (std::size_t i = 0; names && i < n; ++i) list += (list.empty() ? "'" : ", '") + std::string(names[i]) + "'";
    return n == 0 ? "no variables" : "variables " + list;
  }

  std::unique_ptr<mat_t, MatFileCloser> mat_;
};

}  // namespace

std::unique_ptr<RecordedColumns> open_mat_columns(const std::filesystem::path& file) {
  return std::make_unique<MatColumns>(file);
}

}  // namespace ambid
