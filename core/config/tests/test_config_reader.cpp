// Strict JSON reading: the input checks of issue 12 (numbers no double holds, fractional integers,
// duplicate keys, a directory given as a file), each with a message naming the file and key.
#include "core/base/error.hpp"
#include "core/config/config_reader.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include <sys/stat.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>

namespace tmlab {
namespace {

namespace fs = std::filesystem;

class ConfigReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tmlab_reader_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& text) const {
    const std::string file = (dir_ / "c.json").string();
    std::ofstream(file) << text;
    return file;
  }
  /// The message of parsing `text` (and reading key `key` of it as T), or "" when it succeeds.
  template <class T>
  std::string error_of(const std::string& text, const std::string& key) const {
    try {
      const nlohmann::json j = ConfigReader::parse_file(write(text));
      ConfigReader r(j, "c.json");
      (void)r.require<T>(key);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(ConfigReaderTest, NumberBeyondDoubleNamesFileAndNumber) {
  const std::string m = error_of<double>(R"({"E": 1e999})", "E");
  EXPECT_NE(m.find("c.json"), std::string::npos) << m;
  EXPECT_NE(m.find("1e999"), std::string::npos) << m;
  EXPECT_NE(m.find("fit a double"), std::string::npos) << m;
}

TEST_F(ConfigReaderTest, FractionalIntegerIsRefusedWholeFloatAccepted) {
  const std::string m = error_of<int>(R"({"steps": 2.5})", "steps");
  EXPECT_NE(m.find("key 'steps' must be a whole number (got 2.5)"), std::string::npos) << m;
  EXPECT_EQ(error_of<int>(R"({"steps": 10.0})", "steps"), "");
  EXPECT_NE(error_of<int>(R"({"steps": 1e10})", "steps").find("whole number"), std::string::npos);
  EXPECT_NE(error_of<int>(R"({"steps": 10000000000})", "steps").find("out of range"), std::string::npos);
  EXPECT_NE(error_of<int>(R"({"steps": -10000000000})", "steps").find("out of range"), std::string::npos);
  EXPECT_EQ(error_of<int>(R"({"steps": -3})", "steps"), "");  // range checks belong to the caller
}

TEST_F(ConfigReaderTest, DuplicateKeyIsRefusedWithItsPath) {
  std::string m = error_of<double>(R"({"E": 1, "E": 2})", "E");
  EXPECT_NE(m.find("key 'E' is given twice"), std::string::npos) << m;
  m = error_of<double>(R"({"solver": {"steps": 1, "dt": 2, "steps": 3}})", "x");
  EXPECT_NE(m.find("key 'solver.steps' is given twice"), std::string::npos) << m;
  m = error_of<double>(R"({"loads": [{"name": "a"}, {"name": "b", "name": "c"}]})", "x");
  EXPECT_NE(m.find("key 'loads[].name' is given twice"), std::string::npos) << m;
  // The same key in sibling objects is fine.
  EXPECT_EQ(error_of<double>(R"({"a": {"x": 1}, "b": {"x": 2}, "x": 3})", "x"), "");
}

TEST_F(ConfigReaderTest, DirectoryIsNotAJsonFile) {
  try {
    (void)ConfigReader::parse_file(dir_.string());
    FAIL() << "a directory was parsed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
}

TEST_F(ConfigReaderTest, FifoAndDeepNestingAreRefusedAtOnce) {
  // Issue 26: a FIFO would block the reader; 100k nested arrays took tens of seconds (the duplicate-key
  // guard copied the key path at every level).
  const std::filesystem::path fifo = dir_ / "pipe.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    (void)ConfigReader::parse_file(fifo.string());
    FAIL() << "a FIFO was parsed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is not a regular file"), std::string::npos) << e.what();
  }
  const std::filesystem::path deep = dir_ / "deep.json";
  std::ofstream(deep) << "{\"a\": " << std::string(100000, '[') << std::string(100000, ']') << "}";
  try {
    (void)ConfigReader::parse_file(deep.string());
    FAIL() << "100000 levels were parsed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nested deeper than 64 levels (key 'a[][]"), std::string::npos)
        << e.what();
  }
}

TEST_F(ConfigReaderTest, SyntaxErrorNamesFileLineAndColumn) {
  const std::string m = error_of<double>("{\n  \"E\": 1,\n  \"nu\" 0.3\n}", "E");
  EXPECT_NE(m.find("c.json: invalid JSON"), std::string::npos) << m;
  EXPECT_NE(m.find("line 3"), std::string::npos) << m;
}

TEST(ConfigReader, Vec3ReadsThreeFiniteNumbersOrNamesTheKey) {
  nlohmann::json j = nlohmann::json::parse(
      R"({"p": [1, -2.5, 3e-3], "short": [1, 2], "text": [1, "a", 2], "big": [1, 1e308, 0], "none": 4})");
  j["inf"] = {1.0, std::numeric_limits<double>::infinity(), 0.0};
  ConfigReader r(j, "case.json", "load");
  EXPECT_EQ(r.vec3("p"), Eigen::Vector3d(1.0, -2.5, 3e-3));
  const auto message = [&](const std::string& key) {
    try {
      r.vec3(key);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("short").find("case.json: key 'load.short' must be a list of 3 numbers"),
            std::string::npos)
      << message("short");
  EXPECT_NE(message("text").find("load.text"), std::string::npos);
  EXPECT_NE(message("none").find("load.none"), std::string::npos);
  EXPECT_NE(message("missing").find("is required"), std::string::npos);
  EXPECT_NE(message("inf").find("key 'load.inf' must be finite"), std::string::npos) << message("inf");
  EXPECT_EQ(r.vec3("big"), Eigen::Vector3d(1.0, 1e308, 0.0));
}

}  // namespace
}  // namespace tmlab
