// model.json (experiment-format.md "Model file"): exact round trip, unknown keys kept, and one
// test per rule of the strict reader, each checking the message names file, key and expectation.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.hpp"
#include "core/experiment_file.hpp"
#include "core/model_file.hpp"

namespace ambid {
namespace model_file_test {

using nlohmann::json;
using ::testing::AllOf;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

// A model with awkward doubles (non-terminating binary fractions, tiny and huge magnitudes).
Model example_model() {
  std::mt19937_64 random(7);
  std::normal_distribution<double> normal;
  auto matrix = [&](Eigen::Index r, Eigen::Index c) {
    Eigen::MatrixXd m(r, c);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = normal(random) * std::pow(10.0, double(i % 7) - 3);
    return m;
  };
  Model m;
  m.plant_model = "amb1dof_voltage";
  m.method = "deadbeat";
  m.sample_time = 1e-4;
  m.discrete = {matrix(4, 4), matrix(4, 2), matrix(3, 4), Eigen::MatrixXd::Zero(3, 2), 1e-4};
  m.continuous = ContinuousSystem{matrix(4, 4), matrix(4, 2), matrix(3, 4), Eigen::MatrixXd::Zero(3, 2)};
  m.parameters = {{"v1", 777777.8}, {"v5", 40.79254079254079}, {"v8", 0.1 + 0.2}};
  m.physical = {{"R1", 17.5}, {"kw1", 1.0 / 3.0}};
  m.uncertainty = {{"v5", 0.02}, {"R1", 9e-3}};
  m.fit_nrmse = {{"x", 0.01}, {"i1", 2e-3}, {"i2", 2e-3}};
  return m;
}

class ModelFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("ambid-model-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write_text(const std::string& text) {
    fs::create_directories(dir_);
    const fs::path path = dir_ / "model.json";
    std::ofstream(path) << text;
    return path;
  }
  // The message of reading `j` as a model file; fails the test when it reads.
  std::string read_error(const json& j) { return read_error(j.dump()); }
  std::string read_error(const std::string& text) {
    const fs::path path = write_text(text);
    try {
      read_model(path);
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(path.string()));
      return e.what();
    }
    ADD_FAILURE() << "read a malformed model: " << text;
    return "";
  }

  fs::path dir_;
};

TEST_F(ModelFile, RoundTripIsExact) {
  const Model m = example_model();
  const fs::path path = dir_ / "sub" / "model.json";  // parent created by the writer
  write_model(m, path);
  const Model back = read_model(path);
  EXPECT_EQ(back.plant_model, m.plant_model);
  EXPECT_EQ(back.method, m.method);
  EXPECT_EQ(back.sample_time, m.sample_time);
  EXPECT_EQ(back.discrete.A, m.discrete.A);
  EXPECT_EQ(back.discrete.B, m.discrete.B);
  EXPECT_EQ(back.discrete.C, m.discrete.C);
  EXPECT_EQ(back.discrete.D, m.discrete.D);
  EXPECT_EQ(back.discrete.sample_time, m.sample_time);
  ASSERT_TRUE(back.continuous.has_value());
  EXPECT_EQ(back.continuous->A, m.continuous->A);
  EXPECT_EQ(back.continuous->B, m.continuous->B);
  EXPECT_EQ(back.parameters, m.parameters);
  EXPECT_EQ(back.physical, m.physical);
  EXPECT_EQ(back.uncertainty, m.uncertainty);
  EXPECT_EQ(back.fit_nrmse, m.fit_nrmse);
  // No temporary left beside the target.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "sub"), fs::directory_iterator()), 1);
}

TEST_F(ModelFile, WrittenKeysAreThoseOfTheContract) {
  const json j = model_json(example_model());
  EXPECT_EQ(j["format"], "ambid-model/1");
  for (const char* key : {"plant_model", "method", "sample_time", "discrete", "continuous", "parameters", "physical",
                          "uncertainty", "fit"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["discrete"]["A"].size(), 4u);
  EXPECT_EQ(j["discrete"]["A"][0].size(), 4u);
  EXPECT_EQ(j["fit"]["nrmse"]["x"], 0.01);
}

TEST_F(ModelFile, UnknownKeysAreKeptThroughARewrite) {
  json j = model_json(example_model());
  j["comment"] = "hand edited";
  j["fit"]["segment"] = {0.75, 1.0};
  j["discrete"]["note"] = 3;
  const Model m = read_model(write_text(j.dump()));
  EXPECT_EQ(m.extra.json()["comment"], "hand edited");
  const fs::path again = dir_ / "again.json";
  write_model(m, again);
  const json back = json::parse(read_text_file(again));
  EXPECT_EQ(back["comment"], "hand edited");
  EXPECT_EQ(back["fit"]["segment"], j["fit"]["segment"]);
  EXPECT_EQ(back["fit"]["nrmse"], j["fit"]["nrmse"]);
  EXPECT_EQ(back["discrete"]["note"], 3);
}

TEST_F(ModelFile, OptionalPartsMayBeAbsent) {
  json j = model_json(example_model());
  for (const char* key : {"continuous", "parameters", "physical", "uncertainty", "fit"}) j.erase(key);
  const Model m = read_model(write_text(j.dump()));
  EXPECT_FALSE(m.continuous.has_value());
  EXPECT_TRUE(m.parameters.empty());
  EXPECT_TRUE(m.fit_nrmse.empty());
}

TEST_F(ModelFile, ADiscreteOnlyModelSaysWhyItHasNoContinuousPart) {
  Model m = example_model();
  m.continuous.reset();
  m.parameters.clear();
  m.physical.clear();
  m.uncertainty.clear();
  m.no_continuous = "d2c: discrete eigenvalue -0.5 lies on the closed negative real axis";
  const fs::path path = dir_ / "model.json";
  write_model(m, path);
  const json j = json::parse(read_text_file(path));
  EXPECT_FALSE(j.contains("continuous"));
  EXPECT_EQ(j["no_continuous"], m.no_continuous);
  const Model back = read_model(path);
  EXPECT_FALSE(back.continuous.has_value());
  EXPECT_EQ(back.no_continuous, m.no_continuous);
  EXPECT_EQ(back.discrete.A, m.discrete.A);
  // A reason beside a continuous system contradicts itself.
  json both = model_json(example_model());
  both["no_continuous"] = "d2c failed";
  EXPECT_THAT(read_error(both), HasSubstr("`no_continuous`"));
  both["no_continuous"] = 3;
  EXPECT_THAT(read_error(both), HasSubstr("no_continuous"));
}

TEST_F(ModelFile, MissingRequiredKeyIsNamed) {
  for (const char* key : {"format", "plant_model", "method", "sample_time", "discrete"}) {
    json j = model_json(example_model());
    j.erase(key);
    EXPECT_THAT(read_error(j), AllOf(HasSubstr("missing required key"), HasSubstr(std::string("`") + key + "`")));
  }
  json j = model_json(example_model());
  j["discrete"].erase("C");
  EXPECT_THAT(read_error(j), HasSubstr("`discrete.C`"));
}

TEST_F(ModelFile, WrongFormatIsRefused) {
  json j = model_json(example_model());
  j["format"] = "ambid-model/2";
  EXPECT_THAT(read_error(j), AllOf(HasSubstr("`format`"), HasSubstr("ambid-model/1"), HasSubstr("ambid-model/2")));
}

TEST_F(ModelFile, WrongTypesAreNamedWithTheExpectation) {
  json j = model_json(example_model());
  j["sample_time"] = "1e-4";
  EXPECT_THAT(read_error(j), AllOf(HasSubstr("`sample_time`"), HasSubstr("a number")));
  j = model_json(example_model());
  j["parameters"]["v5"] = "big";
  EXPECT_THAT(read_error(j), AllOf(HasSubstr("`parameters.v5`"), HasSubstr("a number")));
  j = model_json(example_model());
  j["discrete"]["A"][1][2] = nullptr;
  EXPECT_THAT(read_error(j), HasSubstr("`discrete.A[1][2]`"));
  j = model_json(example_model());
  j["fit"]["nrmse"] = 0.1;
  EXPECT_THAT(read_error(j), AllOf(HasSubstr("`fit.nrmse`"), HasSubstr("an object")));
  EXPECT_THAT(read_error(std::string("[1, 2]")), HasSubstr("an object"));
}

TEST_F(ModelFile, RaggedAndMismatchedMatricesAreRefused) {
  json j = model_json(example_model());
  j["discrete"]["A"][2].erase(0);
  EXPECT_THAT(read_error(j), AllOf(HasSubstr("`discrete.A[2]`"), HasSubstr("same length")));
  j = model_json(example_model());
  j["continuous"]["B"].erase(0);  // 3 rows for 4 states
  EXPECT_THAT(read_error(j), HasSubstr("`continuous`"));
}

TEST_F(ModelFile, BadValuesAreRefused) {
  json j = model_json(example_model());
  j["sample_time"] = -1e-4;
  EXPECT_THAT(read_error(j), AllOf(HasSubstr("`sample_time`"), HasSubstr("positive")));
  j = model_json(example_model());
  j["uncertainty"]["v5"] = -0.1;
  EXPECT_THAT(read_error(j), AllOf(HasSubstr("`uncertainty.v5`"), HasSubstr(">= 0")));
  j = model_json(example_model());
  j["uncertainty"]["v9"] = 0.1;
  EXPECT_THAT(read_error(j), AllOf(HasSubstr("`uncertainty.v9`"), HasSubstr("names no entry")));
  EXPECT_THAT(read_error(model_json(example_model()).dump().substr(0, 50)), HasSubstr("malformed JSON"));
  EXPECT_THAT(read_error(std::string(R"({"format": "ambid-model/1", "format": "x"})")), HasSubstr("appears twice"));
}

TEST_F(ModelFile, WriterRefusesAnInvalidModelAndWritesNothing) {
  Model m = example_model();
  m.discrete.A(1, 1) = std::nan("");
  const fs::path path = dir_ / "model.json";
  EXPECT_THROW(write_model(m, path), Error);
  EXPECT_FALSE(fs::exists(path));
  m = example_model();
  m.discrete.sample_time = 2e-4;
  EXPECT_THROW(write_model(m, path), Error);
  m = example_model();
  m.method.clear();
  EXPECT_THROW(write_model(m, path), Error);
}

TEST_F(ModelFile, MissingFileIsNamed) {
  try {
    read_model(dir_ / "absent.json");
    FAIL() << "read a missing file";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("absent.json"));
  }
}

}  // namespace model_file_test
}  // namespace ambid
