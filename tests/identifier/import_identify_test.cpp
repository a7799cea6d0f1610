// A simulated SI experiment exported the ways other tools write records (MAT v5 matrix, MAT
// named vectors in um/mA, CSV in mm/mA/ms with other names and order), imported back: the
// identification of each equals the identification of the original.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <charconv>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/experiment_import.hpp"
#include "core/experiment_io.hpp"
#include "identifier/identify_experiment.hpp"
#include "mat_writer.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::ident {
namespace import_identify_test {

namespace fs = std::filesystem;

std::string shortest(double v) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
}

ImportMapping mapping(const std::string& t, const std::vector<std::string>& y, const std::vector<std::string>& u,
                      const std::vector<std::string>& r) {
  ImportMapping m;
  if (!t.empty()) m.t = parse_signal_source("t", t);
  for (const auto& s : y) m.y.push_back(parse_signal_mapping(s));
  for (const auto& s : u) m.u.push_back(parse_signal_mapping(s));
  for (const auto& s : r) m.r.push_back(parse_signal_mapping(s));
  return m;
}

void expect_same_parameters(const Model& imported, const Model& original, double relative, const std::string& how) {
  ASSERT_EQ(imported.parameters.size(), original.parameters.size()) << how;
  for (const auto& [name, value] : original.parameters)
    EXPECT_NEAR(imported.parameters.at(name), value, relative * std::abs(value)) << how << ": " << name;
  for (const auto& [name, value] : original.physical)
    EXPECT_NEAR(imported.physical.at(name), value, relative * std::abs(value)) << how << ": " << name;
}

TEST(ImportIdentify, MatAndCsvExportsIdentifyLikeTheSiOriginal) {
  sim::ScenarioOptions s;
  s.duration = 0.3;
  const Experiment e = sim::simulate_scenario(s);
  const fs::path dir = fs::temp_directory_path() / ("ambid-import-identify-" + std::to_string(std::random_device{}()));
  write_experiment(e, dir / "si");
  ImportOptions options;
  options.template_sidecar = read_sidecar(dir / "si.json");
  IdentifyOptions deadbeat;
  deadbeat.method = "deadbeat";
  const Model original = identify_experiment(read_experiment(dir / "si").experiment, deadbeat);
  const Eigen::Index n = e.samples();

  Eigen::MatrixXd matrix(n, 8);  // columns [r2, x, u1, t, i2, r1, u2, i1]
  matrix << e.r.col(1), e.y.col(0), e.u.col(0), e.t, e.y.col(2), e.r.col(0), e.u.col(1), e.y.col(1);
  ambid::test::write_mat(dir / "matrix.mat", {{"log", matrix}});
  const Model from_matrix =
      identify_experiment(import_experiment(dir / "matrix.mat",
                                            mapping("log(:,4)", {"x=log(:,2)", "i1=log(:,8)", "i2=log(:,5)"},
                                                    {"u1=log(:,3)", "u2=log(:,7)"}, {"r1=log(:,6)", "r2=log(:,1)"}),
                                            options)
                              .experiment,
                          deadbeat);
  expect_same_parameters(from_matrix, original, 0.0, "MAT matrix");

  ambid::test::write_mat(dir / "vectors.mat", {{"gap_um", e.y.col(0) * 1e6},
                                               {"coil1_mA", e.y.col(1) * 1e3},
                                               {"coil2_mA", e.y.col(2) * 1e3},
                                               {"cmd1", e.u.col(0)},
                                               {"cmd2", e.u.col(1)},
                                               {"exc1", e.r.col(0)},
                                               {"exc2", e.r.col(1)}});
  ImportOptions no_time = options;
  no_time.sample_time = e.sample_time;
  const Model from_vectors =
      identify_experiment(import_experiment(dir / "vectors.mat",
                                            mapping("", {"x=gap_um:um", "i1=coil1_mA:mA", "i2=coil2_mA:mA"},
                                                    {"u1=cmd1", "u2=cmd2"}, {"r1=exc1", "r2=exc2"}),
                                            no_time)
                              .experiment,
                          deadbeat);
  expect_same_parameters(from_vectors, original, 1e-9, "MAT vectors in um/mA");

  std::ofstream csv(dir / "logger.csv");
  csv << "ms,i2 (mA),u2,pos (mm),i1 (mA),u1,w2,w1\n";
  for (Eigen::Index k = 0; k < n; ++k)
    csv << shortest(e.t(k) * 1e3) << "," << shortest(e.y(k, 2) * 1e3) << "," << shortest(e.u(k, 1)) << ","
        << shortest(e.y(k, 0) * 1e3) << "," << shortest(e.y(k, 1) * 1e3) << "," << shortest(e.u(k, 0)) << ","
        << shortest(e.r(k, 1)) << "," << shortest(e.r(k, 0)) << "\n";
  csv.close();
  const Model from_csv = identify_experiment(
      import_experiment(
          dir / "logger.csv",
          mapping("ms:ms", {"x=pos (mm):mm", "i1=i1 (mA):mA", "i2=i2 (mA):mA"}, {"u1=u1", "u2=u2"}, {"r1=w1", "r2=w2"}),
          options)
          .experiment,
      deadbeat);
  expect_same_parameters(from_csv, original, 1e-9, "CSV in mm/mA/ms");
  fs::remove_all(dir);
}

}  // namespace import_identify_test
}  // namespace ambid::ident
