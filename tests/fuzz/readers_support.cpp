#include "fuzz/readers.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/experiment_file.hpp"
#include "core/experiment_io.hpp"
#include "core/model_file.hpp"
#include "fuzz/scratch.hpp"
#include "plant_sim/scenario.hpp"
#include "services/daemons/scenario_json.hpp"
#include "services/rig/rig_frame.hpp"

namespace ambid::fuzz {
namespace readers_support {

namespace fs = std::filesystem;

const Scratch& scratch() {
  static const Scratch s("ambid-fuzz-");
  return s;
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

// A real experiment of 200 samples (the nominal bearing, its LQR, a PRBS) as files.
struct ExperimentTexts {
  std::string sidecar, csv;
};
const ExperimentTexts& experiment_texts() {
  static const ExperimentTexts texts = [] {
    sim::ScenarioOptions o;
    o.duration = 0.02;
    o.position_noise = 1e-7;
    o.current_noise = 1e-3;
    const fs::path stem = scratch().file("corpus");
    write_experiment(sim::simulate_scenario(o), stem);
    return ExperimentTexts{read_text_file(stem.string() + ".json"), read_text_file(stem.string() + ".csv")};
  }();
  return texts;
}

std::string model_text() {
  Model m;
  m.plant_model = "amb1dof_voltage";
  m.method = "pem";
  m.sample_time = 1e-4;
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(4, 4) * 0.99;
  A(0, 1) = 1e-4;
  m.discrete = {A, Eigen::MatrixXd::Constant(4, 2, 1e-3), Eigen::MatrixXd::Identity(3, 4), Eigen::MatrixXd::Zero(3, 2),
                1e-4};
  m.continuous = ContinuousSystem{A * 10.0, Eigen::MatrixXd::Constant(4, 2, 10.0), Eigen::MatrixXd::Identity(3, 4),
                                  Eigen::MatrixXd::Zero(3, 2)};
  m.parameters = {{"v1", 777777.8}, {"v5", 40.79}};
  m.physical = {{"R1", 17.5}, {"kw1", 1.0}};
  m.uncertainty = {{"v5", 0.02}, {"R1", 9e-3}};
  m.fit_nrmse = {{"x", 0.01}};
  const fs::path path = scratch().file("corpus-model.json");
  write_model(m, path);
  return read_text_file(path);
}

// One valid frame of every type.
std::vector<std::string> frame_corpus() {
  using namespace rig;
  SampleBatch batch;
  batch.record = 3;
  batch.first_index = 44;
  batch.sample_time = 1e-4;
  batch.model = "amb1dof_voltage";
  batch.ny = 3;
  batch.nu = 2;
  batch.nr = 2;
  for (int k = 0; k < 5; ++k) {
    batch.t.push_back(1.0 + k * 1e-4);
    for (int j = 0; j < 7; ++j) (j < 3 ? batch.y : j < 5 ? batch.u : batch.r).push_back(0.01 * (k + j));
  }
  RigStatus status;
  status.board_time = 12.5;
  status.sample_time = 1e-4;
  status.model = "amb1dof_voltage";
  status.y_names = {"x", "i1", "i2"};
  status.u_names = {"u1", "u2"};
  status.r_names = {"r1", "r2"};
  status.message = "record 3";
  std::vector<std::string> corpus;
  for (const Payload& p :
       std::vector<Payload>{Hello{"gateway"}, KeepAlive{}, status, batch, Excite{7, "prbs", 0.5, 1.0, 1000.0},
                            ExciteReply{7, false, "too much"}}) {
    const std::vector<std::uint8_t> bytes = encode(Frame{9, p});
    corpus.emplace_back(bytes.begin(), bytes.end());
  }
  return corpus;
}

}  // namespace readers_support
using namespace readers_support;

FuzzCount fuzz_experiment_csv(int iterations) {
  const ExperimentTexts& texts = experiment_texts();
  const fs::path stem = readers_support::scratch().file("csv");
  write(stem.string() + ".json", texts.sidecar);
  return fuzz({texts.csv}, iterations, 11, [&](const std::string& csv) {
    write(stem.string() + ".csv", csv);
    read_experiment(stem);
  });
}

FuzzCount fuzz_experiment_sidecar(int iterations) {
  const ExperimentTexts& texts = experiment_texts();
  const fs::path stem = readers_support::scratch().file("sidecar");
  write(stem.string() + ".csv", texts.csv);
  return fuzz({texts.sidecar}, iterations, 12, [&](const std::string& sidecar) {
    write(stem.string() + ".json", sidecar);
    read_experiment(stem);
  });
}

FuzzCount fuzz_model_json(int iterations) {
  const fs::path path = readers_support::scratch().file("model.json");
  return fuzz({model_text()}, iterations, 13, [&](const std::string& text) {
    write(path, text);
    read_model(path);
  });
}

FuzzCount fuzz_scenario_json(int iterations) {
  std::vector<std::string> corpus{read_text_file(fs::path(AMBID_SOURCE_DIR) / "deploy/config/nominal-bearing.json")};
  for (const auto& entry : fs::directory_iterator(fs::path(AMBID_SOURCE_DIR) / "tests/integration/scenarios"))
    if (entry.path().extension() == ".json") corpus.push_back(read_text_file(entry.path()));
  std::sort(corpus.begin(), corpus.end());  // the directory's order is the file system's
  const fs::path path = readers_support::scratch().file("scenario.json");
  return fuzz(corpus, iterations, 15, [&](const std::string& text) {
    write(path, text);
    daemons::read_scenario_file(path.string());
  });
}

FuzzCount fuzz_rig_frame(int iterations) {
  return fuzz(frame_corpus(), iterations, 14, [](const std::string& datagram) {
    const std::vector<std::uint8_t> bytes(datagram.begin(), datagram.end());
    const rig::Decoded decoded = rig::decode(bytes);  // never throws
    if (!decoded.frame) throw Error(decoded.reason);
    // What decodes is a frame the codec can write again, byte for byte.
    if (rig::encode(*decoded.frame) != bytes)
      throw std::logic_error("a decoded frame does not re-encode to its datagram");
  });
}

}  // namespace ambid::fuzz
