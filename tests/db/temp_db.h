// Test helper: a unique database path in the temp directory, removed (with its WAL and shared
// memory files) when the test ends.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace fibrenet::db::testing {

class TempDbPath {
 public:
  TempDbPath() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "fibrenet_db_";
    // Appended piece by piece: "_" + std::string trips a GCC 12 -Wrestrict false positive.
    if (info != nullptr) {
      name += info->test_suite_name();
      name += '_';
      name += info->name();
    }
    name += '_';
    name += std::to_string(::getpid());
    name += ".db";
    path_ = (std::filesystem::temp_directory_path() / name).string();
    Remove();
  }
  ~TempDbPath() { Remove(); }
  TempDbPath(const TempDbPath&) = delete;
  TempDbPath& operator=(const TempDbPath&) = delete;

  const std::string& str() const { return path_; }

 private:
  void Remove() {
    std::error_code ec;
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
      std::filesystem::remove(path_ + suffix, ec);
    }
  }
  std::string path_;
};

}  // namespace fibrenet::db::testing
