// Gives every test process a scratch directory of its own, where testing::TempDir() points:
// ctest runs the cases of one test binary as parallel processes, and cases that wrote files of
// the same name in a shared /tmp read each other's half-written files. The directory is removed
// when every test passed, kept (and named) otherwise.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace
{

class ScratchDirectory : public ::testing::Environment
{
public:
  void SetUp() override
  {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/igaview-test-XXXXXX";
    if (mkdtemp(pattern.data()))
    {
      this->Path = pattern;
      setenv("TEST_TMPDIR", pattern.c_str(), 1); // what testing::TempDir() reads
    }
  }

  void TearDown() override
  {
    if (this->Path.empty())
    {
      return;
    }
    if (::testing::UnitTest::GetInstance()->Passed())
    {
      std::error_code ignored;
      std::filesystem::remove_all(this->Path, ignored);
    }
    else
    {
      std::fprintf(stderr, "the failed tests' files are in %s\n", this->Path.c_str());
    }
  }

private:
  std::string Path;
};

// GoogleTest owns and runs the environments it is given, before and after all tests.
::testing::Environment* const scratch = ::testing::AddGlobalTestEnvironment(new ScratchDirectory);

} // namespace
