// A test fixture for vmassd (and the other tools) as processes: a fresh folder per test (kept
// when the test fails), the service tests' drive as a samples CSV in it, the test config, and
// commands run in the foreground or started in the background with their exit code collected.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "test_drive.hpp"

namespace vmass::test {

namespace fs = std::filesystem;

class DaemonProcessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vmassd_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    csv_ = path("samples.csv");
    ASSERT_TRUE(test::write_samples_csv(csv_, test::make_drive(test::DriveSpec{})));
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write_config(const std::string& extra, const std::string& type = "bayes") {
    const std::string p = path("vmassd.yaml");
    EXPECT_TRUE(test::write_text(p, test::test_config_yaml(extra, type)));
    return p;
  }
  static int run(const std::string& command) {
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  /// Starts a command in the background; its pid and (later) exit code go to files.
  void start(const std::string& command, const std::string& name) {
    ASSERT_EQ(run("( " + command + " > " + path(name + ".log") + " 2>&1 & echo $! > " +
                  path(name + ".pid") + "; wait $!; echo $? > " + path(name + ".rc") + " ) &"),
              0);
    for (int i = 0; i < 100 && !fs::exists(path(name + ".pid")); ++i) sleep_s(0.02);
  }
  /// Exit code of a started command, or -1 when it did not finish within timeout_s.
  int wait_rc(const std::string& name, double timeout_s) {
    for (double t = 0.0; t < timeout_s; t += 0.05) {
      std::ifstream in(path(name + ".rc"));
      int rc = -1;
      if (in >> rc) return rc;
      sleep_s(0.05);
    }
    return -1;
  }
  std::string read(const std::string& name) const {
    std::ifstream in(path(name));
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static void sleep_s(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

  fs::path dir_;
  std::string csv_;
};

}  // namespace vmass::test
