// `prt completions bash|zsh` and `prt manpage`: generated from the command line's own tree, so
// these tests drive the generated bash function the way bash does (COMP_WORDS in, COMPREPLY out)
// and typeset the man page with groff's warnings on.

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "cli_harness.hpp"

namespace prt::testing {
namespace {

bool have(const char* tool) {
  return std::system((std::string("command -v ") + tool + " > /dev/null 2>&1").c_str()) == 0;
}

class CompletionsCli : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    const Result r = prt("completions bash");
    ASSERT_EQ(r.rc, 0) << r.err;
    write("prt.bash", r.out);
  }
  /// COMPREPLY for the command line `words`, the cursor on its last word.
  std::string complete(const std::string& words) const {
    write("complete.sh", "source ./prt.bash\nCOMP_WORDS=(" + words +
                             ")\nCOMP_CWORD=$(( ${#COMP_WORDS[@]} - 1 ))\n_prt\n"
                             "(( ${#COMPREPLY[@]} == 0 )) || printf '%s\\n' \"${COMPREPLY[@]}\"\n");
    const std::string cmd = "cd '" + dir_.string() + "' && bash complete.sh > reply.txt 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
    return slurp(dir_ / "reply.txt");
  }
};

TEST_F(CompletionsCli, BashCompletesVerbsOptionsAndTheirValues) {
  EXPECT_EQ(complete("prt ba"), "bake\n");
  EXPECT_EQ(complete("prt bake --mo"), "--mode\n");
  const std::string modes = complete("prt bake --mode ''");
  for (const char* m : {"unshadowed", "shadowed", "interreflected"})
    EXPECT_NE(modes.find(std::string(m) + "\n"), std::string::npos) << modes;
  // Options belong to their verb: render has --exposure, bake does not.
  EXPECT_EQ(complete("prt render --expo"), "--exposure\n");
  EXPECT_EQ(complete("prt bake --expo"), "");
  // A value that is a file completes as a file name.
  write("scene.obj", "");
  EXPECT_EQ(complete("prt bake sce"), "scene.obj\n");
}

TEST_F(CompletionsCli, ZshScriptDefinesEveryVerb) {
  const Result r = prt("completions zsh");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out.rfind("#compdef prt\n", 0), 0u);
  for (const char* verb : {"bake", "light", "render", "validate", "web", "compress", "info"})
    EXPECT_NE(r.out.find(std::string("    ") + verb + ")\n"), std::string::npos) << verb;
  if (!have("zsh")) GTEST_SKIP() << "zsh is not installed: the script's syntax is not checked";
  write("_prt", r.out);
  EXPECT_EQ(std::system(("zsh -n '" + path("_prt") + "'").c_str()), 0);
}

TEST_F(CompletionsCli, UnknownShellIsOneLineError) {
  const Result r = prt("completions fish");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("fish"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST_F(CompletionsCli, ManPageTypesetsWithoutWarningsAndNamesEveryVerb) {
  const Result r = prt("manpage");
  ASSERT_EQ(r.rc, 0) << r.err;
  for (const char* verb : {"bake", "light", "render", "validate", "reference", "web", "view",
                           "compress", "merge", "export", "info", "demo"})
    EXPECT_NE(r.out.find(std::string(".SS prt ") + verb + "\n"), std::string::npos) << verb;
  for (unsigned char c : r.out) EXPECT_LT(c, 0x80) << "roff source must be ASCII (\\[uXXXX])";
  if (!have("groff")) GTEST_SKIP() << "groff is not installed: the page is not typeset";
  write("prt.1", r.out);
  const std::string cmd = "cd '" + dir_.string() +
                          "' && groff -man -Tutf8 -ww prt.1 > page.txt 2> warnings.txt";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(slurp(dir_ / "warnings.txt"), "");
  EXPECT_NE(slurp(dir_ / "page.txt").find("samples"), std::string::npos);
}

}  // namespace
}  // namespace prt::testing
