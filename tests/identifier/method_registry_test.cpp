// The method registry: one entry per method, found by name, an unknown name refused naming the
// known ones, and README.md carries the table the help shows verbatim (it cannot drift).
#include "identifier/methods.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"

namespace ambid::ident {
namespace method_registry_test {

using ::testing::HasSubstr;

TEST(MethodRegistry, EveryMethodOnceWithAFit) {
  const auto& names = identification_methods();
  ASSERT_EQ(names.size(), method_registry().size());
  for (const IdentificationMethod& m : method_registry()) {
    SCOPED_TRACE(m.name);
    EXPECT_EQ(std::count(names.begin(), names.end(), m.name), 1);
    EXPECT_NE(m.fit, nullptr);
    EXPECT_FALSE(m.description.empty());
    EXPECT_EQ(m.description.find('\n'), std::string::npos);
    EXPECT_EQ(&identification_method(m.name, "test"), &m);
  }
}

TEST(MethodRegistry, UnknownNameListsTheKnownOnes) {
  try {
    identification_method("n4sid", "who");
    FAIL() << "found n4sid";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("who: unknown method 'n4sid' (expected one of " + method_names(", ") + ")"));
  }
}

TEST(MethodRegistry, ReadmeCarriesTheTableVerbatim) {
  std::ifstream in(std::string(AMBID_SOURCE_DIR) + "/README.md");
  ASSERT_TRUE(in) << "cannot open README.md";
  std::ostringstream readme;
  readme << in.rdbuf();
  const std::string block = "```text\n" + method_table() + "```\n";
  EXPECT_THAT(readme.str(), HasSubstr(block)) << "README.md, section \"Using it\", should carry:\n" << block;
}

}  // namespace method_registry_test
}  // namespace ambid::ident
