// A fresh folder per test, removed with everything in it when the test ends. Named after the
// running test, the process and a random number, so that tests running in parallel processes
// (ctest -j) never share one.
#pragma once

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <system_error>

#include <gtest/gtest.h>
#include <opencv2/core/mat.hpp>
#include <opencv2/imgcodecs.hpp>

namespace stereo::test {

class TempFolder {
  public:
    TempFolder() {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        const std::string test = info != nullptr
                                     ? std::string(info->test_suite_name()) + "_" + info->name()
                                     : std::string("no_test");
        path_ = std::filesystem::path(::testing::TempDir()) /
                ("stereo_" + test + "_" + std::to_string(std::random_device{}()));
        std::filesystem::create_directories(path_);
    }
    ~TempFolder() {
        std::error_code ignored;  // a test may have taken the write permission away
        std::filesystem::permissions(path_, std::filesystem::perms::owner_all,
                                     std::filesystem::perm_options::add, ignored);
        std::filesystem::remove_all(path_, ignored);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path file(const std::string& name) const { return path_ / name; }

    // Writes `text` to `name` (its folders created) and returns the path.
    std::filesystem::path write_text(const std::string& name, const std::string& text) const {
        const std::filesystem::path path = file(name);
        std::filesystem::create_directories(path.parent_path());
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }

    // Writes `image` with OpenCV (the format from the name's extension) and returns the path; a
    // failed write fails the test.
    std::filesystem::path write_image(const std::string& name, const cv::Mat& image) const {
        const std::filesystem::path path = file(name);
        EXPECT_TRUE(cv::imwrite(path.string(), image)) << "cannot write " << path;
        return path;
    }

  private:
    std::filesystem::path path_;
};

}  // namespace stereo::test
