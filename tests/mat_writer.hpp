#pragma once
// Writes MAT v5 files with libmatio for the import tests: each variable a real double matrix.
#include <matio.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace ambid::test {

inline void write_mat(const std::filesystem::path& path,
                      const std::vector<std::pair<std::string, Eigen::MatrixXd>>& variables) {
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5);
  if (!mat) throw std::runtime_error("cannot create " + path.string());
  for (const auto& [name, value] : variables) {
    Eigen::MatrixXd data = value;  // column-major, as MAT stores it
    std::size_t dims[2] = {std::size_t(data.rows()), std::size_t(data.cols())};
    matvar_t* var = Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, data.data(), MAT_F_DONT_COPY_DATA);
    const int failed = !var || Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE) != 0;
    if (var) Mat_VarFree(var);
    if (failed) {
      Mat_Close(mat);
      throw std::runtime_error("cannot write variable " + name + " to " + path.string());
    }
  }
  Mat_Close(mat);
}

}  // namespace ambid::test
