// io::mjpeg_avi (the overlay videos of `stereo avoid --overlay NAME.avi`): the file's RIFF
// structure read back field by field, the frames decoded by OpenCV's own AVI reader
// (cv::VideoCapture, an independent implementation) equal to the same JPEG decoded directly,
// and the bad requests refused.
#include "stereo_io/mjpeg_avi.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "stereo_io/output.hpp"

namespace {

namespace fs = std::filesystem;
using stereo::io::mjpeg_avi;

std::vector<cv::Mat> random_frames(int count, cv::Size size, unsigned seed) {
    std::mt19937 random(seed);
    std::vector<cv::Mat> frames;
    for (int i = 0; i < count; ++i) {
        cv::Mat frame(size, CV_8UC3);
        // Smooth content (JPEG keeps it close) with a per-frame offset so frames differ.
        for (int y = 0; y < size.height; ++y) {
            for (int x = 0; x < size.width; ++x) {
                frame.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<unsigned char>(x * 3 + i * 20),
                                                      static_cast<unsigned char>(y * 5),
                                                      static_cast<unsigned char>(random() % 8));
            }
        }
        frames.push_back(frame);
    }
    return frames;
}

std::uint32_t u32_at(const std::string& bytes, std::size_t at) {
    std::uint32_t value = 0;
    for (int i = 3; i >= 0; --i) {
        value = (value << 8) | static_cast<unsigned char>(bytes.at(at + i));
    }
    return value;
}

class MjpegAvi : public ::testing::Test {
  protected:
    void SetUp() override {
        folder_ = fs::temp_directory_path() /
                  ("stereo_mjpeg_avi_" +
                   std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(folder_);
        fs::create_directories(folder_);
    }
    void TearDown() override { fs::remove_all(folder_); }
    fs::path write(const std::string& bytes) {
        const fs::path path = folder_ / "v.avi";
        std::ofstream(path, std::ios::binary) << bytes;
        return path;
    }
    fs::path folder_;
};

TEST_F(MjpegAvi, HeaderFieldsAndIndexDescribeTheFrames) {
    const auto frames = random_frames(5, {37, 21}, 1);  // odd sizes: pad bytes in play
    const std::string avi = mjpeg_avi(frames, 12.5);
    ASSERT_EQ(avi.substr(0, 4), "RIFF");
    EXPECT_EQ(u32_at(avi, 4), avi.size() - 8);
    EXPECT_EQ(avi.substr(8, 4), "AVI ");
    EXPECT_EQ(avi.substr(12, 4), "LIST");
    EXPECT_EQ(avi.substr(20, 4), "hdrl");
    ASSERT_EQ(avi.substr(24, 4), "avih");
    EXPECT_EQ(u32_at(avi, 28), 56u);
    EXPECT_EQ(u32_at(avi, 32), 80000u);   // microseconds per frame at 12.5 frames/s
    EXPECT_EQ(u32_at(avi, 32 + 16), 5u);  // total frames
    EXPECT_EQ(u32_at(avi, 32 + 24), 1u);  // streams
    EXPECT_EQ(u32_at(avi, 32 + 32), 37u);
    EXPECT_EQ(u32_at(avi, 32 + 36), 21u);
    const std::size_t strh = avi.find("strh");
    ASSERT_NE(strh, std::string::npos);
    EXPECT_EQ(avi.substr(strh + 8, 8), "vidsMJPG");
    EXPECT_EQ(u32_at(avi, strh + 8 + 20), 1000u);   // scale
    EXPECT_EQ(u32_at(avi, strh + 8 + 24), 12500u);  // rate: 12.5 frames/s
    EXPECT_EQ(u32_at(avi, strh + 8 + 32), 5u);      // length

    // Every index entry points at a "00dc" chunk holding one whole JPEG (SOI ... EOI) of the
    // length it names; the chunks follow one another inside "movi".
    const std::size_t movi = avi.find("movi");
    const std::size_t idx1 = avi.find("idx1");
    ASSERT_NE(movi, std::string::npos);
    ASSERT_NE(idx1, std::string::npos);
    ASSERT_EQ(u32_at(avi, idx1 + 4), 5u * 16u);
    std::size_t expected_offset = 4;
    for (std::size_t i = 0; i < 5; ++i) {
        const std::size_t entry = idx1 + 8 + 16 * i;
        EXPECT_EQ(avi.substr(entry, 4), "00dc");
        EXPECT_EQ(u32_at(avi, entry + 4), 0x10u);
        const std::uint32_t offset = u32_at(avi, entry + 8);
        const std::uint32_t length = u32_at(avi, entry + 12);
        EXPECT_EQ(offset, expected_offset);
        const std::size_t chunk = movi + offset;
        EXPECT_EQ(avi.substr(chunk, 4), "00dc");
        EXPECT_EQ(u32_at(avi, chunk + 4), length);
        EXPECT_EQ(static_cast<unsigned char>(avi[chunk + 8]), 0xffu);
        EXPECT_EQ(static_cast<unsigned char>(avi[chunk + 9]), 0xd8u);  // SOI
        EXPECT_EQ(static_cast<unsigned char>(avi[chunk + 8 + length - 2]), 0xffu);
        EXPECT_EQ(static_cast<unsigned char>(avi[chunk + 8 + length - 1]), 0xd9u);  // EOI
        expected_offset += 8 + length + (length % 2);
    }
    EXPECT_EQ(movi + expected_offset, idx1);
    EXPECT_NO_THROW(stereo::io::check_avi_complete(write(avi), "v.avi"));
}

TEST_F(MjpegAvi, OpenCvReadsBackEveryFrame) {
    const auto frames = random_frames(7, {64, 48}, 2);
    const fs::path path = write(mjpeg_avi(frames, 10.0, 90));
    // OpenCV's own MJPEG AVI reader (FFmpeg's would decode the JPEGs with other rounding).
    cv::VideoCapture capture(path.string(), cv::CAP_OPENCV_MJPEG);
    ASSERT_TRUE(capture.isOpened());
    EXPECT_EQ(capture.get(cv::CAP_PROP_FRAME_COUNT), 7.0);
    EXPECT_DOUBLE_EQ(capture.get(cv::CAP_PROP_FPS), 10.0);
    for (const cv::Mat& frame : frames) {
        cv::Mat read;
        ASSERT_TRUE(capture.read(read));
        std::vector<unsigned char> jpeg;
        ASSERT_TRUE(cv::imencode(".jpg", frame, jpeg, {cv::IMWRITE_JPEG_QUALITY, 90}));
        const cv::Mat expected = cv::imdecode(jpeg, cv::IMREAD_COLOR);
        ASSERT_EQ(read.size(), expected.size());
        EXPECT_EQ(cv::norm(read, expected, cv::NORM_INF), 0.0);
    }
    cv::Mat past_end;
    EXPECT_FALSE(capture.read(past_end));
}

// Players read it too: FFmpeg (VLC's, mpv's and OpenCV's default backend) finds every frame at
// its size. (Its JPEG decoder rounds differently from libjpeg's, so the pixels are not compared.)
TEST_F(MjpegAvi, FfmpegFindsEveryFrame) {
    const auto frames = random_frames(6, {50, 30}, 4);
    const fs::path path = write(mjpeg_avi(frames, 29.97));
    cv::VideoCapture capture(path.string(), cv::CAP_FFMPEG);
    if (!capture.isOpened()) {
        GTEST_SKIP() << "OpenCV was built without FFmpeg";
    }
    EXPECT_NEAR(capture.get(cv::CAP_PROP_FPS), 29.97, 1e-9);
    int read_frames = 0;
    cv::Mat frame;
    while (capture.read(frame)) {
        EXPECT_EQ(frame.size(), cv::Size(50, 30));
        ++read_frames;
    }
    EXPECT_EQ(read_frames, 6);
}

TEST_F(MjpegAvi, BadRequestsAreRefused) {
    const auto frames = random_frames(2, {8, 8}, 3);
    EXPECT_THROW(mjpeg_avi({}, 10.0), std::invalid_argument);
    EXPECT_THROW(mjpeg_avi(frames, 0.0), std::invalid_argument);
    EXPECT_THROW(mjpeg_avi(frames, -1.0), std::invalid_argument);
    EXPECT_THROW(mjpeg_avi(frames, std::numeric_limits<double>::quiet_NaN()),
                 std::invalid_argument);
    EXPECT_THROW(mjpeg_avi(frames, 10.0, 0), std::invalid_argument);
    EXPECT_THROW(mjpeg_avi(frames, 10.0, 101), std::invalid_argument);
    auto mixed = frames;
    mixed.push_back(cv::Mat(9, 8, CV_8UC3, cv::Scalar(0, 0, 0)));
    EXPECT_THROW(mjpeg_avi(mixed, 10.0), std::invalid_argument);
    auto grey = frames;
    grey.push_back(cv::Mat(8, 8, CV_8UC1, cv::Scalar(0)));
    EXPECT_THROW(mjpeg_avi(grey, 10.0), std::invalid_argument);
}

}  // namespace
