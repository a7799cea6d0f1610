// write_files_atomically (core/experiment_file.hpp), issue 18 item 6: a failed set of outputs
// leaves every target as it was. A set whose second target cannot be replaced (a directory in
// its place) used to leave the first target new beside the error: a failed `ambid audit` or
// `ambid diagnose` then left an audit.json or diagnosis.json that looked complete.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "core/error.hpp"
#include "core/experiment_file.hpp"

namespace ambid {
namespace experiment_file_test {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class WriteFilesAtomically : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ambid_write_files_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string text(const std::string& name) const {
    std::ifstream in(dir_ / name);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  std::set<std::string> names() const {
    std::set<std::string> out;
    for (const auto& entry : fs::directory_iterator(dir_)) out.insert(entry.path().filename().string());
    return out;
  }

  fs::path dir_;
};

TEST_F(WriteFilesAtomically, ReplacesEveryTargetAndLeavesNoTemporary) {
  std::ofstream(dir_ / "a.json") << "old a";
  write_files_atomically({{dir_ / "a.json", "new a"}, {dir_ / "b.svg", "new b"}});
  EXPECT_EQ(text("a.json"), "new a");
  EXPECT_EQ(text("b.svg"), "new b");
  EXPECT_EQ(names(), (std::set<std::string>{"a.json", "b.svg"}));
}

TEST_F(WriteFilesAtomically, ATargetThatCannotBeReplacedLeavesTheOthersAsTheyWere) {
  std::ofstream(dir_ / "a.json") << "old a";
  fs::create_directories(dir_ / "c.svg" / "blocker");
  try {
    write_files_atomically({{dir_ / "a.json", "new a"}, {dir_ / "b.svg", "new b"}, {dir_ / "c.svg", "new c"}});
    FAIL() << "a directory in the place of c.svg was replaced";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot replace " + (dir_ / "c.svg").string()));
  }
  EXPECT_EQ(text("a.json"), "old a");                              // the previous output, not the new one
  EXPECT_EQ(names(), (std::set<std::string>{"a.json", "c.svg"}));  // no new b.svg, no temporary
  write_files_atomically({{dir_ / "a.json", "new a"}});            // the set without the blocked target
  EXPECT_EQ(text("a.json"), "new a");
}

}  // namespace experiment_file_test
}  // namespace ambid
