// The rig's records as the rig writes them (maglev-rig.md: MAT v5, either one N x 3 matrix
// [y_mm, u_V, I_mA] without a time column, or column vectors t, ref, y, u, i) through
// `import` with the simulated record's sidecar as template and r reconstructed from the
// board's PID (the sidecar `ambid sim` writes, read back as `ambid import --template` does):
// the grey-box identification and `frf`'s structure per settled level are those of the record
// itself.
#include <filesystem>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "core/experiment_import.hpp"
#include "core/experiment_io.hpp"
#include "core/model_file.hpp"
#include "identifier/frf_analysis.hpp"
#include "identifier/identify_experiment.hpp"
#include "mat_writer.hpp"
#include "support/maglev_records.hpp"

namespace ambid {
namespace maglev_rig_import_test {

namespace fs = std::filesystem;

Model greybox(const Experiment& e) {
  ident::IdentifyOptions o;
  o.method = "greybox";
  return ident::identify_experiment(e, o);
}

void expect_same_identification(const Model& imported, const Model& direct) {
  ASSERT_EQ(imported.physical.size(), direct.physical.size());
  for (const auto& [name, value] : direct.physical) {
    EXPECT_NEAR(imported.physical.at(name) / value, 1.0, 1e-9) << name;
    EXPECT_NEAR(imported.uncertainty.at(name) / direct.uncertainty.at(name), 1.0, 1e-9) << name;
  }
}

// The same settled levels, and at each the same unstable pole and sigma.
void expect_same_frf_levels(const ident::FrfReport& imported, const ident::FrfReport& direct) {
  ASSERT_TRUE(direct.levels.has_value());
  ASSERT_TRUE(imported.levels.has_value());
  ASSERT_EQ(imported.levels->levels.size(), direct.levels->levels.size());
  int fitted = 0;
  for (std::size_t l = 0; l < direct.levels->levels.size(); ++l) {
    const ident::LevelStructuredFit &a = imported.levels->levels[l], &b = direct.levels->levels[l];
    EXPECT_EQ(a.samples, b.samples);
    ASSERT_EQ(a.fit.has_value(), b.fit.has_value()) << l;
    if (!b.fit) continue;
    ++fitted;
    EXPECT_NEAR(a.fit->derived_value(0) / b.fit->derived_value(0), 1.0, 1e-6) << l;
    EXPECT_NEAR(a.fit->derived_sigma(0) / b.fit->derived_sigma(0), 1.0, 1e-6) << l;
  }
  EXPECT_GE(fitted, 2);
  EXPECT_EQ(imported.levels->at_operating_point, direct.levels->at_operating_point);
}

class MaglevRigImport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ =
        new fs::path(fs::temp_directory_path() / ("ambid-maglev-rig-import-" + std::to_string(std::random_device{}())));
    fs::create_directories(*dir_);
    write_experiment(test_support::maglev_record(sim::MaglevParameters::nominal(), sim::MaglevRig{},
                                                 test_support::maglev_run_options(1.5e-3, 3000, 5)),
                     *dir_ / "run");
    record_ = new Experiment(read_experiment(*dir_ / "run.json").experiment);
    direct_ = new Model(greybox(*record_));
    direct_frf_ = new ident::FrfReport(ident::analyse_frf(*record_));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete record_;
    delete direct_;
    delete direct_frf_;
  }
  static fs::path scratch(const std::string& name) { return *dir_ / name; }
  static ImportOptions rig_template() {
    ImportOptions o;
    o.template_sidecar = read_sidecar(*dir_ / "run.json");
    o.reconstruct_r = true;
    return o;
  }
  static fs::path* dir_;
  static Experiment* record_;
  static Model* direct_;
  static ident::FrfReport* direct_frf_;
};
fs::path* MaglevRigImport::dir_ = nullptr;
Experiment* MaglevRigImport::record_ = nullptr;
Model* MaglevRigImport::direct_ = nullptr;
ident::FrfReport* MaglevRigImport::direct_frf_ = nullptr;

TEST_F(MaglevRigImport, OneMatrixWithoutTimeColumnGivesTheSameIdentification) {
  const Experiment& e = *record_;
  Eigen::MatrixXd data(e.samples(), 3);
  data << e.y.col(0) * 1e3, e.u.col(0), e.y.col(1) * 1e3;  // [y_mm, u_V, I_mA]
  const fs::path file = scratch("matrix.mat");
  test::write_mat(file, {{"data", data}});
  ImportMapping mapping;
  mapping.y = {parse_signal_mapping("x=data(:,1):mm"), parse_signal_mapping("i=data(:,3):mA")};
  mapping.u = {parse_signal_mapping("u=data(:,2):V")};
  const ImportResult imported = import_experiment(file, mapping, rig_template());  // Ts from the template
  EXPECT_EQ(imported.file_kind, "MAT v5");
  EXPECT_EQ(imported.experiment.samples(), e.samples());
  EXPECT_DOUBLE_EQ(imported.experiment.sample_time, 1.5e-3);
  EXPECT_LT((imported.experiment.r - e.r).cwiseAbs().maxCoeff(), 1e-9);  // V
  expect_same_identification(greybox(imported.experiment), *direct_);
  expect_same_frf_levels(ident::analyse_frf(imported.experiment), *direct_frf_);
}

TEST_F(MaglevRigImport, ColumnVectorsWithTimeGiveTheSameIdentification) {
  const Experiment& e = *record_;
  const fs::path file = scratch("vectors.mat");
  const Eigen::VectorXd ref = Eigen::VectorXd::Constant(e.samples(), 14.0);  // the file's ref: not used
  test::write_mat(file,
                  {{"t", e.t}, {"ref", ref}, {"y", e.y.col(0) * 1e3}, {"u", e.u.col(0)}, {"i", e.y.col(1) * 1e3}});
  ImportMapping mapping;
  mapping.t = parse_signal_source("t", "t:s");
  mapping.y = {parse_signal_mapping("x=y:mm"), parse_signal_mapping("i=i:mA")};
  mapping.u = {parse_signal_mapping("u=u")};
  const ImportResult imported = import_experiment(file, mapping, rig_template());
  EXPECT_EQ(imported.experiment.samples(), e.samples());
  expect_same_identification(greybox(imported.experiment), *direct_);
  expect_same_frf_levels(ident::analyse_frf(imported.experiment), *direct_frf_);
}

}  // namespace maglev_rig_import_test
}  // namespace ambid
