// Image and disparity-map files of the host tools (io/include/stereo_io/io.hpp), and the
// data-folder rule (stereo_io/data_dir.hpp).
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <opencv2/imgproc.hpp>
#include "stereo_io/disparity_files.hpp"

#include "hostile_images.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/limits.hpp"
#include "stereo_io/output.hpp"
#include "temp_folder.hpp"

namespace stereo::io {
namespace {

namespace fs = std::filesystem;

using test::TempFolder;

// Expects `call` to throw `Exception` with a one-line message containing `part`.
template <typename Exception, typename Call>
void expect_error(Call&& call, const std::string& part) {
    try {
        call();
        FAIL() << "no exception, expected one mentioning: " << part;
    } catch (const Exception& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find(part), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

void write_text(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

DisparityMap sample_map(int ndisp) {
    // 4x3, one invalid pixel, and both the lowest and the highest label present.
    DisparityMap map(4, 3);
    for (int y = 0; y < 3; ++y) {
        for (int x = 0; x < 4; ++x) {
            const std::size_t i = map.index(x, y);
            map.disparity[i] = static_cast<std::uint8_t>((x + 4 * y) % ndisp);
            map.valid[i] = 1;
        }
    }
    map.disparity[map.index(3, 2)] = static_cast<std::uint8_t>(ndisp - 1);
    map.disparity[map.index(1, 1)] = 0;
    map.valid[map.index(1, 1)] = 0;
    return map;
}

void expect_round_trip(const DisparityMap& map, const cv::Mat& loaded) {
    ASSERT_EQ(loaded.type(), CV_32FC1);
    ASSERT_EQ(loaded.cols, map.width);
    ASSERT_EQ(loaded.rows, map.height);
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const std::size_t i = map.index(x, y);
            const float expected = map.valid[i] != 0 ? map.disparity[i] : 0.0F;
            EXPECT_FLOAT_EQ(loaded.at<float>(y, x), expected) << "at " << x << "," << y;
        }
    }
}

TEST(LoadImage, ConvertsBgrFileToRgbOrder) {
    const TempFolder dir;
    cv::Mat bgr(1, 2, CV_8UC3);
    bgr.at<cv::Vec3b>(0, 0) = cv::Vec3b(10, 20, 30);  // B, G, R
    bgr.at<cv::Vec3b>(0, 1) = cv::Vec3b(200, 100, 0);
    dir.write_image("rgb.png", bgr);

    const Image image = load_image(dir.file("rgb.png"));
    ASSERT_EQ(image.width, 2);
    ASSERT_EQ(image.height, 1);
    ASSERT_EQ(image.channels, 3);
    EXPECT_EQ(image.at(0, 0, 0), 30);  // R
    EXPECT_EQ(image.at(0, 0, 1), 20);  // G
    EXPECT_EQ(image.at(0, 0, 2), 10);  // B
    EXPECT_EQ(image.at(1, 0, 0), 0);
    EXPECT_EQ(image.at(1, 0, 2), 200);
}

TEST(LoadImage, DropsAlpha) {
    const TempFolder dir;
    const cv::Mat bgra(2, 2, CV_8UC4, cv::Scalar(1, 2, 3, 77));
    dir.write_image("rgba.png", bgra);

    const Image image = load_image(dir.file("rgba.png"));
    ASSERT_EQ(image.channels, 3);
    EXPECT_EQ(image.at(1, 1, 0), 3);
    EXPECT_EQ(image.at(1, 1, 1), 2);
    EXPECT_EQ(image.at(1, 1, 2), 1);
}

TEST(LoadImage, KeepsGreyAsOneChannel) {
    const TempFolder dir;
    const cv::Mat grey(3, 5, CV_8UC1, cv::Scalar(42));
    dir.write_image("grey.png", grey);

    const Image image = load_image(dir.file("grey.png"));
    EXPECT_EQ(image.channels, 1);
    EXPECT_EQ(image.width, 5);
    EXPECT_EQ(image.height, 3);
    EXPECT_EQ(image.at(4, 2, 0), 42);
}

TEST(LoadImage, Refuses16BitColour) {
    const TempFolder dir;
    const cv::Mat deep(2, 2, CV_16UC3, cv::Scalar(1000, 2000, 3000));
    dir.write_image("deep.png", deep);
    expect_error<std::runtime_error>([&] { (void)load_image(dir.file("deep.png")); },
                                     "deep.png': it is 16-bit 3-channel");
}

TEST(LoadImage, MissingFileNamesTheFile) {
    const TempFolder dir;
    expect_error<std::runtime_error>([&] { (void)load_image(dir.file("nope.png")); },
                                     "nope.png': no such file");
}

TEST(LoadImage, NotAnImageNamesTheFile) {
    const TempFolder dir;
    write_text(dir.file("text.png"), "this is not a PNG\n");
    expect_error<std::runtime_error>([&] { (void)load_image(dir.file("text.png")); },
                                     "text.png': not an image");
    write_text(dir.file("empty.png"), "");
    expect_error<std::runtime_error>([&] { (void)load_image(dir.file("empty.png")); },
                                     "empty.png': not an image");
}

TEST(LoadImage, DownscaleAveragesBlocks) {
    const TempFolder dir;
    // 4x2 grey: two 2x2 blocks with means 25 and 100.
    const cv::Mat grey = (cv::Mat_<std::uint8_t>(2, 4) << 10, 20, 100, 100,  //
                          30, 40, 100, 100);
    dir.write_image("blocks.png", grey);

    const Image image = load_image(dir.file("blocks.png"), 2);
    ASSERT_EQ(image.width, 2);
    ASSERT_EQ(image.height, 1);
    EXPECT_EQ(image.at(0, 0, 0), 25);
    EXPECT_EQ(image.at(1, 0, 0), 100);
}

TEST(LoadImage, RejectsBadDownscale) {
    const TempFolder dir;
    dir.write_image("small.png", cv::Mat(3, 3, CV_8UC1));
    expect_error<std::invalid_argument>([&] { (void)load_image(dir.file("small.png"), 0); },
                                        "downscale factor must be >= 1, got 0");
    expect_error<std::invalid_argument>([&] { (void)load_image(dir.file("small.png"), 4); },
                                        "(3x3) is too small for downscale factor 4");
}

TEST(LoadPair, SizeMismatchNamesBothSizes) {
    const TempFolder dir;
    dir.write_image("l.png", cv::Mat(3, 4, CV_8UC3));
    dir.write_image("r.png", cv::Mat(3, 5, CV_8UC3));
    expect_error<std::invalid_argument>(
        [&] { (void)load_pair(dir.file("l.png"), dir.file("r.png")); },
        "l.png' is 4x3 but right '" + dir.file("r.png").string() + "' is 5x3");
}

TEST(LoadPair, UnreadableRightNamesTheFile) {
    const TempFolder dir;
    dir.write_image("l.png", cv::Mat(3, 4, CV_8UC3));
    expect_error<std::runtime_error>(
        [&] { (void)load_pair(dir.file("l.png"), dir.file("missing.png")); }, "missing.png'");
}

TEST(LoadPair, PromotesGreyToColourWhenMixed) {
    const TempFolder dir;
    dir.write_image("l.png", cv::Mat(2, 2, CV_8UC1, cv::Scalar(9)));
    dir.write_image("r.png", cv::Mat(2, 2, CV_8UC3));
    const ImagePair pair = load_pair(dir.file("l.png"), dir.file("r.png"));
    EXPECT_EQ(pair.left.channels, 3);
    EXPECT_EQ(pair.right.channels, 3);
    EXPECT_EQ(pair.left.at(1, 1, 2), 9);
}

TEST(DisparityPng, RoundTrip8Bit) {
    const TempFolder dir;
    const int ndisp = 16;
    const int scale = 4;  // (16 - 1) * 4 = 60 fits 8 bits
    const DisparityMap map = sample_map(ndisp);
    write_png(dir.file("d8.png"), disparity_to_mat(map, ndisp, scale));

    const cv::Mat raw = cv::imread(dir.file("d8.png").string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(raw.type(), CV_8UC1);
    EXPECT_EQ(raw.at<std::uint8_t>(2, 3), (ndisp - 1) * scale);
    EXPECT_EQ(raw.at<std::uint8_t>(1, 1), 0);  // invalid
    expect_round_trip(map, load_disparity(dir.file("d8.png"), scale));
}

TEST(DisparityPng, RoundTrip16Bit) {
    const TempFolder dir;
    const int ndisp = 64;
    const int scale = 16;  // 63 * 16 = 1008 needs 16 bits
    const DisparityMap map = sample_map(ndisp);
    write_png(dir.file("d16.png"), disparity_to_mat(map, ndisp, scale));

    const cv::Mat raw = cv::imread(dir.file("d16.png").string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(raw.type(), CV_16UC1);
    EXPECT_EQ(raw.at<std::uint16_t>(2, 3), 1008);
    expect_round_trip(map, load_disparity(dir.file("d16.png"), scale));
}

TEST(DisparityPng, DepthFollowsLargestPossibleValue) {
    const DisparityMap map = sample_map(2);
    EXPECT_EQ(disparity_to_mat(sample_map(256), 256, 1).type(), CV_8UC1);  // 255
    EXPECT_EQ(disparity_to_mat(map, 2, 255).type(), CV_8UC1);              // 255
    EXPECT_EQ(disparity_to_mat(map, 2, 256).type(), CV_16UC1);             // 256
    EXPECT_EQ(disparity_to_mat(map, 2, 65535).type(), CV_16UC1);
}

TEST(DisparityPng, RejectsImpossibleScales) {
    const DisparityMap map = sample_map(16);
    expect_error<std::invalid_argument>([&] { (void)disparity_to_mat(map, 16, 0); },
                                        "scale must be >= 1, got 0");
    expect_error<std::invalid_argument>([&] { (void)disparity_to_mat(map, 0, 1); },
                                        "ndisp must be >= 1");
    expect_error<std::invalid_argument>([&] { check_disparity_scale(256, 258); },
                                        "values up to 65790");
    EXPECT_NO_THROW(check_disparity_scale(256, 257));  // 255 * 257 = 65535
}

TEST(DisparityPng, RejectsLabelsAboveNdisp) {
    const DisparityMap map = sample_map(16);
    expect_error<std::invalid_argument>([&] { (void)disparity_to_mat(map, 8, 1); },
                                        "is not below ndisp 8");
}

TEST(DisparityPng, ColourViewBlacksOutInvalidPixels) {
    const int ndisp = 16;
    const DisparityMap map = sample_map(ndisp);
    const cv::Mat colour = disparity_to_colour(map, ndisp);
    ASSERT_EQ(colour.type(), CV_8UC3);
    EXPECT_EQ(colour.at<cv::Vec3b>(1, 1), cv::Vec3b(0, 0, 0));

    // The highest label takes the top of the colour map, label 0 its bottom.
    const cv::Mat ends = (cv::Mat_<std::uint8_t>(1, 2) << 0, 255);
    cv::Mat expected;
    cv::applyColorMap(ends, expected, cv::COLORMAP_TURBO);
    EXPECT_EQ(colour.at<cv::Vec3b>(0, 0), expected.at<cv::Vec3b>(0, 0));
    EXPECT_EQ(colour.at<cv::Vec3b>(2, 3), expected.at<cv::Vec3b>(0, 1));
    EXPECT_NE(expected.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 0));  // valid 0 is not black
}

TEST(LoadDisparity, AppliesScaleAndTakesOneChannelOfGrey) {
    const TempFolder dir;
    const cv::Mat grey3(1, 2, CV_8UC3, cv::Scalar(40, 40, 40));
    dir.write_image("g3.png", grey3);
    const cv::Mat loaded = load_disparity(dir.file("g3.png"), 8.0);
    ASSERT_EQ(loaded.type(), CV_32FC1);
    EXPECT_FLOAT_EQ(loaded.at<float>(0, 1), 5.0F);
}

TEST(LoadDisparity, RefusesColourAndBadScale) {
    const TempFolder dir;
    dir.write_image("c.png", cv::Mat(1, 2, CV_8UC3, cv::Scalar(1, 2, 3)));
    expect_error<std::runtime_error>([&] { (void)load_disparity(dir.file("c.png"), 1.0); },
                                     "expected a grey image");
    expect_error<std::invalid_argument>([&] { (void)load_disparity(dir.file("c.png"), 0.0); },
                                        "must be a positive number");
}

TEST(LoadMask, Refuses16Bit) {
    const TempFolder dir;
    dir.write_image("m16.png", cv::Mat(2, 2, CV_16UC1));
    expect_error<std::runtime_error>([&] { (void)load_mask(dir.file("m16.png")); },
                                     "expected an 8-bit mask");
}

TEST(WritePng, MissingFolderFailsWithoutCreatingAFile) {
    const TempFolder dir;
    const fs::path target = dir.file("no_such_folder") / "out.png";
    expect_error<std::runtime_error>([&] { check_writable_location(target); },
                                     "no_such_folder' does not exist");
    expect_error<std::runtime_error>(
        [&] { write_png(target, cv::Mat(2, 2, CV_8UC1, cv::Scalar(0))); }, "cannot write");
    EXPECT_FALSE(fs::exists(target));
    EXPECT_NO_THROW(check_writable_location(dir.file("fine.png")));
}

TEST(Downscale, GroundTruthAndMasksSampleBlockCentres) {
    // 5x4 GT, factor 2: the small grid is 2x2 and samples (1,1), (3,1), (1,3), (3,3); the odd
    // last column and row are dropped as in the image downscale. Disparities halve.
    cv::Mat gt(4, 5, CV_32FC1, cv::Scalar(0));
    gt.at<float>(1, 1) = 10.0f;
    gt.at<float>(1, 3) = 7.0f;
    gt.at<float>(3, 1) = 0.0f;  // unknown stays unknown
    gt.at<float>(3, 3) = 3.0f;
    gt.at<float>(0, 0) = 99.0f;  // not a block centre: ignored
    const cv::Mat small = downscale_ground_truth(gt, 2);
    ASSERT_EQ(small.size(), cv::Size(2, 2));
    EXPECT_FLOAT_EQ(small.at<float>(0, 0), 5.0f);
    EXPECT_FLOAT_EQ(small.at<float>(0, 1), 3.5f);
    EXPECT_FLOAT_EQ(small.at<float>(1, 0), 0.0f);
    EXPECT_FLOAT_EQ(small.at<float>(1, 1), 1.5f);
    cv::Mat mask(4, 5, CV_8UC1, cv::Scalar(0));
    mask.at<std::uint8_t>(1, 3) = 255;
    mask.at<std::uint8_t>(3, 3) = 128;
    const cv::Mat small_mask = downscale_mask(mask, 2);
    EXPECT_EQ(small_mask.at<std::uint8_t>(0, 1), 255);
    EXPECT_EQ(small_mask.at<std::uint8_t>(1, 1), 128);
    EXPECT_EQ(small_mask.at<std::uint8_t>(0, 0), 0);
    EXPECT_EQ(downscale_ground_truth(gt, 1).size(), gt.size());
    EXPECT_THROW(downscale_ground_truth(gt, 0), std::invalid_argument);
    EXPECT_THROW(downscale_ground_truth(gt, 5), std::invalid_argument);
}

TEST(ShrinkArea, AveragesBlocksAndRejectsTooSmall) {
    const cv::Mat grey = (cv::Mat_<std::uint8_t>(2, 4) << 10, 20, 100, 100,  //
                          30, 40, 100, 100);
    const cv::Mat small = shrink_area(grey, 2);
    ASSERT_EQ(small.size(), cv::Size(2, 1));
    EXPECT_EQ(small.at<std::uint8_t>(0, 0), 25);
    EXPECT_EQ(small.at<std::uint8_t>(0, 1), 100);
    EXPECT_EQ(shrink_area(grey, 1).data, grey.data);  // factor 1: the same matrix
    EXPECT_THROW((void)shrink_area(grey, 3), std::invalid_argument);
    EXPECT_THROW((void)shrink_area(grey, 0), std::invalid_argument);
}

TEST(ImageFiles, ListsImagesSortedByName) {
    const TempFolder dir;
    const fs::path folder = dir.file("frames");
    fs::create_directories(folder / "folder.png");  // a folder is not an image file
    for (const char* name : {"b.PNG", "a.jpg", "notes.txt", "c.ppm"}) {
        std::ofstream(folder / name) << "x";
    }
    EXPECT_EQ(image_file_names(folder), (std::vector<std::string>{"a.jpg", "b.PNG", "c.ppm"}));
    expect_error<std::runtime_error>([&] { (void)image_file_names(dir.file("nope")); },
                                     "cannot read image folder");
}

TEST(ToBgr, InvertsToImage) {
    cv::Mat bgr(2, 3, CV_8UC3);
    cv::randu(bgr, 0, 256);
    EXPECT_EQ(cv::norm(to_bgr(to_image(bgr, "bgr")), bgr, cv::NORM_INF), 0.0);
    const TempFolder dir;
    dir.write_image("grey.png", cv::Mat(2, 2, CV_8UC1, cv::Scalar(7)));
    const cv::Mat loaded = load_bgr(dir.file("grey.png"));
    ASSERT_EQ(loaded.type(), CV_8UC3);
    EXPECT_EQ(loaded.at<cv::Vec3b>(1, 1), cv::Vec3b(7, 7, 7));
}

// Sets an environment variable for one scope and restores the previous value (or absence).
class ScopedEnv {
  public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) {
            old_ = old;
        }
        ::setenv(name, value, 1);
    }
    ~ScopedEnv() {
        if (old_) {
            ::setenv(name_, old_->c_str(), 1);
        } else {
            ::unsetenv(name_);
        }
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

  private:
    const char* name_;
    std::optional<std::string> old_;
};

TEST(DataDir, EnvironmentOverridesTheBuiltInFolder) {
    {
        const ScopedEnv unset("STEREO_DATA_DIR", "");  // empty counts as unset
        const fs::path built_in = data_dir();
        EXPECT_TRUE(built_in.is_absolute()) << built_in;
        const ScopedEnv env("STEREO_DATA_DIR", "/tmp/stereo_data_override");
        EXPECT_EQ(data_dir(), fs::path("/tmp/stereo_data_override"));
    }
    {
        const ScopedEnv unset("STEREO_ALOE_DIR", "");
        EXPECT_TRUE(aloe_dir().is_absolute()) << aloe_dir();
        const ScopedEnv env("STEREO_ALOE_DIR", "/tmp/stereo_aloe_override");
        EXPECT_EQ(aloe_dir(), fs::path("/tmp/stereo_aloe_override"));
    }
}

}  // namespace
}  // namespace stereo::io

namespace stereo::io {
namespace {

TEST(Limits, DeclaredSizeOfEncodedImages) {
    // Independent path: OpenCV's encoders write the headers that declared_size parses.
    const cv::Mat image(23, 37, CV_8UC3, cv::Scalar(10, 20, 30));
    for (const char* extension : {".png", ".jpg", ".ppm", ".bmp"}) {
        std::vector<uchar> bytes;
        ASSERT_TRUE(cv::imencode(extension, image, bytes));
        const auto size = declared_size(
            std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
        ASSERT_TRUE(size.has_value()) << extension;
        EXPECT_EQ(size->first, 37) << extension;
        EXPECT_EQ(size->second, 23) << extension;
    }
    EXPECT_FALSE(declared_size("BM not a png").has_value());
    EXPECT_FALSE(declared_size("\x89PNG").has_value());
    // PNM headers with comments, and sizes no decoder could allocate.
    const auto pnm = declared_size("P5\n# made by hand\n 640\t# width\n480\n255\n");
    ASSERT_TRUE(pnm.has_value());
    EXPECT_EQ(*pnm, std::make_pair(std::int64_t{640}, std::int64_t{480}));
    const auto huge_pnm = declared_size("P6 99999999999999 2 255 ");
    ASSERT_TRUE(huge_pnm.has_value());
    EXPECT_GT(huge_pnm->first, max_image_pixels());
}

// Found by fuzz_image_loaders: a JPEG with bytes that are no marker before its frame header.
// libjpeg skips them and decodes the 14884 x 65312 frame (2.9 GB); the header walk stopped at
// them and let the file through unchecked.
TEST(Limits, JpegFrameBehindGarbageIsFound) {
    std::vector<uchar> bytes;
    ASSERT_TRUE(cv::imencode(".jpg", cv::Mat(8, 8, CV_8UC1, cv::Scalar(7)), bytes));
    const std::string jpeg(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    const std::size_t frame = jpeg.find("\xFF\xC0");
    ASSERT_NE(frame, std::string::npos);
    std::string hostile = jpeg.substr(0, frame) + "garbage!" + jpeg.substr(frame);
    hostile[frame + 8 + 5] = '\xFF';  // height 0xFF20, width 0x3A24
    hostile[frame + 8 + 6] = '\x20';
    hostile[frame + 8 + 7] = '\x3A';
    hostile[frame + 8 + 8] = '\x24';
    const auto size = declared_size(hostile);
    ASSERT_TRUE(size.has_value());
    EXPECT_EQ(*size, std::make_pair(std::int64_t{0x3A24}, std::int64_t{0xFF20}));
}

// TIFF and WebP sizes, from OpenCV's encoders (both byte orders for TIFF by hand), and a file of
// a format whose size is not read is refused before it is decoded.
TEST(Limits, DeclaredSizeOfTiffAndWebp) {
    const cv::Mat image(23, 37, CV_8UC3, cv::Scalar(10, 20, 30));
    for (const char* extension : {".tiff", ".webp"}) {
        std::vector<uchar> bytes;
        if (!cv::haveImageWriter(extension)) {
            continue;
        }
        ASSERT_TRUE(cv::imencode(extension, image, bytes));
        const auto size = declared_size(
            std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
        ASSERT_TRUE(size.has_value()) << extension;
        EXPECT_EQ(*size, std::make_pair(std::int64_t{37}, std::int64_t{23})) << extension;
    }
    // Big-endian TIFF by hand: IFD at 8 with two entries, width SHORT 300, height LONG 70000.
    const std::string big(
        "MM\0*\0\0\0\x08\0\x02"
        "\x01\x00\0\x03\0\0\0\x01\x01\x2c\0\0"
        "\x01\x01\0\x04\0\0\0\x01\0\x01\x11\x70",
        34);
    const auto big_size = declared_size(big);
    ASSERT_TRUE(big_size.has_value());
    EXPECT_EQ(*big_size, std::make_pair(std::int64_t{300}, std::int64_t{70000}));
    EXPECT_FALSE(declared_size(big.substr(0, 30)).has_value());  // directory cut off
    EXPECT_FALSE(declared_size(std::string("II+\0\x08\0\0\0", 8)).has_value());  // header cut off
}

TEST(Limits, HugeTiffAndUnknownFormatsAreRefusedBeforeDecoding) {
    const TempFolder dir;
    // A little-endian TIFF directory declaring 40000 x 40000 (1.6 Gpixel) and nothing else.
    const std::string huge(
        "II*\0\x08\0\0\0\x02\0"
        "\x00\x01\x04\0\x01\0\0\0\x40\x9c\0\0"
        "\x01\x01\x04\0\x01\0\0\0\x40\x9c\0\0",
        34);
    std::ofstream(dir.file("huge.tif"), std::ios::binary) << huge;
    expect_error<std::invalid_argument>([&] { (void)load_image(dir.file("huge.tif")); },
                                        "declares 40000x40000 pixels");
    // Radiance HDR, a format OpenCV decodes but whose header is not read here.
    std::vector<uchar> hdr;
    ASSERT_TRUE(cv::imencode(".hdr", cv::Mat(4, 4, CV_32FC3, cv::Scalar(1, 1, 1)), hdr));
    std::ofstream(dir.file("a.hdr"), std::ios::binary)
        .write(reinterpret_cast<const char*>(hdr.data()), static_cast<std::streamsize>(hdr.size()));
    ASSERT_FALSE(cv::imdecode(hdr, cv::IMREAD_UNCHANGED).empty());  // OpenCV would decode it
    expect_error<std::runtime_error>([&] { (void)load_image(dir.file("a.hdr")); },
                                     "a.hdr': not an image in a format whose size is checked");
}

namespace hostile = test::hostile;

// Sets the pixel limit for one test and restores it.
class ScopedLimit {
  public:
    explicit ScopedLimit(std::int64_t pixels) { set_max_image_pixels(pixels); }
    ~ScopedLimit() { set_max_image_pixels(before_); }
    ScopedLimit(const ScopedLimit&) = delete;
    ScopedLimit& operator=(const ScopedLimit&) = delete;

  private:
    std::int64_t before_ = max_image_pixels();
};

constexpr std::int64_t kTestLimit = std::int64_t{1} << 20;

std::pair<std::int64_t, std::int64_t> size_pair(std::int64_t width, std::int64_t height) {
    return {width, height};
}

// Issue 51: a marker without a length (TEM, RSTn, a stuffed zero FF 00) before the frame header
// made the old walk read a length and land on a decoy frame declaring 16 x 16, while libjpeg
// decoded the real 12000 x 12000 frame (499 MB in `stereo match`).
TEST(Limits, JpegFrameBehindMarkersWithoutLengthIsFound) {
    for (const unsigned char marker : {0x01, 0xD0, 0xD3, 0xD7, 0x00}) {
        const std::string jpeg = hostile::jpeg_hidden_frame(12000, 9000, marker);
        EXPECT_EQ(declared_size(jpeg), size_pair(12000, 9000)) << static_cast<int>(marker);
        // Independent check: OpenCV decodes the real frame, not the decoy (at a size it can).
        const std::string small = hostile::jpeg_hidden_frame(40, 24, marker);
        EXPECT_EQ(declared_size(small), size_pair(40, 24));
        const cv::Mat decoded =
            cv::imdecode(std::vector<uchar>(small.begin(), small.end()), cv::IMREAD_UNCHANGED);
        EXPECT_EQ(decoded.cols, 40);
        EXPECT_EQ(decoded.rows, 24);
    }
    // Fill bytes before the frame header are skipped.
    std::string filled = hostile::jpeg_declaring(300, 200);
    const std::size_t frame = filled.find("\xFF\xC0");
    filled.insert(frame, "\xFF\xFF\xFF");
    EXPECT_EQ(declared_size(filled), size_pair(300, 200));
    // A second SOI, a scan or the end of the image before any frame header: libjpeg stops with an
    // error, and so does the walk (the file is refused, not read further).
    const std::string jpeg = hostile::jpeg_declaring(300, 200);
    EXPECT_FALSE(declared_size(jpeg.substr(0, 2) + "\xFF\xD8" + jpeg.substr(2)).has_value());
    EXPECT_FALSE(declared_size(jpeg.substr(0, 2) + "\xFF\xDA" + jpeg.substr(2)).has_value());
    EXPECT_FALSE(declared_size(jpeg.substr(0, 2) + "\xFF\xD9" + jpeg.substr(2)).has_value());
    // FF D8 without the third FF of OpenCV's JPEG signature goes to another decoder: refused.
    EXPECT_FALSE(declared_size(jpeg.substr(0, 2) + "x" + jpeg.substr(2)).has_value());
}

// OpenCV's PNM reader (ReadNumber) ends a number at ANY character and consumes it: "4096#65536"
// is width 4096, height 65536; leading zeros are fine; the magic needs white space after it.
TEST(Limits, PnmHeaderIsReadAsOpenCvReadsIt) {
    EXPECT_EQ(declared_size(hostile::pgm_comment_terminator()), size_pair(4096, 65536));
    const std::string zeros = "P5 0000000000000064 0032 255\n" + std::string(64 * 32, '\x40');
    EXPECT_EQ(declared_size(zeros), size_pair(64, 32));
    const cv::Mat decoded =
        cv::imdecode(std::vector<uchar>(zeros.begin(), zeros.end()), cv::IMREAD_UNCHANGED);
    EXPECT_EQ(decoded.size(), cv::Size(64, 32));  // what OpenCV makes of it
    EXPECT_EQ(declared_size("P6 99999999999999999999999 2 255 ")->first,
              std::numeric_limits<std::int64_t>::max());
    EXPECT_FALSE(declared_size("P512 12 255\n").has_value());  // no white space after "P5"
    EXPECT_FALSE(declared_size("P5 12 x 255\n").has_value());  // OpenCV: unexpected code
    EXPECT_FALSE(declared_size("P5 12 # no end").has_value());
}

// A TIFF's strip or tile buffer is sized by OpenCV from the tile (or RowsPerStrip), not the
// image: a 64 x 64 image in 12000 x 12000 tiles cleared 576 MB (640 MB peak in `stereo match`).
TEST(Limits, TiffTilesStripsPagesAndBigTiff) {
    hostile::TiffPage tiled;
    tiled.width = 64;
    tiled.height = 64;
    tiled.tile = 12000;
    tiled.pixels = false;
    for (const bool big : {false, true}) {
        const auto image = declared_image(hostile::tiff({tiled}, big));
        ASSERT_TRUE(image.has_value()) << big;
        EXPECT_EQ(image->width, 64);
        EXPECT_EQ(image->height, 64);
        EXPECT_EQ(image->largest_pixels, std::int64_t{12000} * 12000);
        EXPECT_EQ(image->largest_what, "12000x12000 tiles");
    }
    hostile::TiffPage strips;
    strips.width = 64;
    strips.height = 64;
    strips.rows_per_strip = 1U << 23;
    const auto striped = declared_image(hostile::tiff({strips}));
    ASSERT_TRUE(striped.has_value());
    EXPECT_EQ(striped->largest_pixels, std::int64_t{64} << 23);
    EXPECT_EQ(striped->largest_what, "64x8388608 strips");
    // Every page counts, and a tag given twice counts with its larger value.
    hostile::TiffPage small;
    small.width = 64;
    small.height = 32;
    hostile::TiffPage huge;
    huge.width = 40000;
    huge.height = 40000;
    huge.pixels = false;
    const auto pages = declared_image(hostile::tiff({small, huge}));
    ASSERT_TRUE(pages.has_value());
    EXPECT_EQ(pages->width, 64);
    EXPECT_EQ(pages->largest_pixels, std::int64_t{40000} * 40000);
    EXPECT_EQ(pages->largest_what, "page 2, 40000x40000");
    hostile::TiffPage twice = small;
    twice.extra = {{256, 40000}};
    EXPECT_EQ(declared_size(hostile::tiff({twice})), size_pair(40000, 32));
    // BigTIFF is read (OpenCV decodes it, through libtiff) and decodes like the classic file.
    const std::string classic = hostile::tiff({small});
    const std::string big = hostile::tiff({small}, true);
    EXPECT_EQ(declared_size(big), size_pair(64, 32));
    const cv::Mat a = cv::imdecode(std::vector<uchar>(classic.begin(), classic.end()), -1);
    const cv::Mat b = cv::imdecode(std::vector<uchar>(big.begin(), big.end()), -1);
    ASSERT_EQ(a.size(), cv::Size(64, 32));
    ASSERT_EQ(b.size(), cv::Size(64, 32));
    EXPECT_EQ(cv::countNonZero(a != b), 0);
    // A directory chain that loops, a size of another type (RATIONAL) or count: refused.
    std::string loop = classic;
    const std::size_t entries = static_cast<unsigned char>(classic[8]);
    loop.replace(8 + 2 + entries * 12, 4, hostile::little_endian(8, 4));  // next: itself
    EXPECT_FALSE(declared_size(loop).has_value());
    std::string rational = classic;
    rational.replace(8 + 2 + 2, 2, hostile::little_endian(5, 2));  // ImageWidth as RATIONAL
    EXPECT_FALSE(declared_size(rational).has_value());
    std::string counted = classic;
    counted.replace(8 + 2 + 4, 4, hostile::little_endian(2, 4));  // ImageWidth count 2
    EXPECT_FALSE(declared_size(counted).has_value());
    // BigTIFF's 8-byte fields with the top bit set (fuzz.image_loaders found the reader's signed
    // sum overflowing on them; the sanitizer build makes this case fail if it comes back).
    const std::size_t first = static_cast<unsigned char>(big[8]);
    const std::size_t big_entries = static_cast<unsigned char>(big[first]);
    std::string far_next = big;
    far_next.replace(first + 8 + big_entries * 20, 8, std::string(8, '\xFF'));
    EXPECT_EQ(declared_size(far_next), size_pair(64, 32));  // libtiff stops at a bad offset
    std::string huge_count = big;
    huge_count.replace(first + 8 + 4, 8, std::string(8, '\xFF'));  // ImageWidth count 2^64 - 1
    EXPECT_FALSE(declared_size(huge_count).has_value());
    std::string huge_entries = big;
    huge_entries.replace(first, 8, std::string(8, '\xFF'));
    EXPECT_FALSE(declared_size(huge_entries).has_value());
}

// A file that looks like one format here but that OpenCV hands to another decoder is refused.
TEST(Limits, FilesAnotherDecoderWouldTakeAreRefused) {
    if (cv::haveImageWriter(".webp")) {
        std::string webp = hostile::encoded(".webp", cv::Mat(16, 16, CV_8UC3, cv::Scalar(1)));
        ASSERT_TRUE(declared_size(webp).has_value());
        webp.resize(std::max<std::size_t>(webp.size(), 160), '\0');
        webp.replace(128, 4, "DICM");  // DICOM's magic: GDCM's decoder, should WebP refuse it
        EXPECT_FALSE(declared_size(webp).has_value());
    }
    EXPECT_FALSE(declared_size("#?RADIANCE\n").has_value());
    EXPECT_FALSE(declared_size("P7\nWIDTH 4\n").has_value());  // PAM
    EXPECT_FALSE(declared_size("Pf\n4 4\n-1\n").has_value());  // PFM: our own reader only
}

// Every crafted file is refused by every image loader, with one line naming the file.
TEST(Limits, CraftedFilesAreRefusedBeforeDecoding) {
    const ScopedLimit limit(kTestLimit);
    const TempFolder dir;
    hostile::TiffPage tiled;
    tiled.width = 64;
    tiled.height = 64;
    tiled.tile = 12000;
    tiled.pixels = false;
    hostile::TiffPage strips = tiled;
    strips.tile = 0;
    strips.rows_per_strip = 1U << 23;
    strips.pixels = true;
    hostile::TiffPage small;
    small.width = 64;
    small.height = 32;
    hostile::TiffPage huge = small;
    huge.width = 40000;
    huge.height = 40000;
    huge.pixels = false;
    const std::vector<std::pair<std::string, std::string>> files = {
        {"tem.jpg", hostile::jpeg_hidden_frame(12000, 12000, 0x01)},
        {"rst.jpg", hostile::jpeg_hidden_frame(12000, 12000, 0xD5)},
        {"ff00.jpg", hostile::jpeg_hidden_frame(12000, 12000, 0x00)},
        {"declared.jpg", hostile::jpeg_declaring(2048, 1024)},
        {"declared.png", hostile::png_declaring(12000, 12000)},
        {"comment.pgm", hostile::pgm_comment_terminator()},
        {"huge.ppm", "P6 99999999999999 2 255\n"},
        {"tiles.tif", hostile::tiff({tiled})},
        {"tiles_big.tif", hostile::tiff({tiled}, true)},
        {"strips.tif", hostile::tiff({strips})},
        {"pages.tif", hostile::tiff({small, huge})},
        {"huge_big.tif", hostile::tiff({huge}, true)},
    };
    for (const auto& file : files) {
        const std::string& name = file.first;  // no structured binding: clang 14 lambdas
        std::ofstream(dir.file(name), std::ios::binary) << file.second;
        std::string quoted_name = "'";  // appended: "'" + string trips GCC 12's -Wrestrict
        quoted_name += dir.file(name).string();
        quoted_name += '\'';
        const std::string limit_text = "more than the limit of 1048576";
        expect_error<std::invalid_argument>([&] { (void)load_image(dir.file(name)); }, quoted_name);
        expect_error<std::invalid_argument>([&] { (void)load_image(dir.file(name)); }, limit_text);
        expect_error<std::invalid_argument>([&] { (void)load_grey(dir.file(name)); }, limit_text);
        expect_error<std::invalid_argument>([&] { (void)load_mask(dir.file(name)); }, limit_text);
    }
    // A PFM declaring more than the limit, with a comment, with a number no decoder could hold,
    // and a PFM given as an image (OpenCV would decode it; its size is not checked there).
    std::ofstream(dir.file("huge.pfm"), std::ios::binary) << "Pf\n30000 30000\n-1\n";
    expect_error<std::runtime_error>(
        [&] { (void)load_disparity_file(dir.file("huge.pfm"), DisparityEncoding::pfm, 1.0); },
        "30000x30000 is above the image limit of 1048576");
    std::ofstream(dir.file("comment.pfm"), std::ios::binary) << "Pf\n# 1 1\n4 4\n-1\n";
    expect_error<std::runtime_error>(
        [&] { (void)load_disparity_file(dir.file("comment.pfm"), DisparityEncoding::pfm, 1.0); },
        "bad PFM size '#'");
    std::ofstream(dir.file("number.pfm"), std::ios::binary) << "Pf\n99999999999999 1\n-1\n";
    expect_error<std::runtime_error>(
        [&] { (void)load_disparity_file(dir.file("number.pfm"), DisparityEncoding::pfm, 1.0); },
        "bad PFM size '99999999999999'");
    std::ofstream(dir.file("image.pfm"), std::ios::binary) << "PF\n4000 4000\n-1\n"
                                                           << std::string(48, '\0');
    expect_error<std::runtime_error>([&] { (void)load_image(dir.file("image.pfm")); },
                                     "not an image in a format whose size is checked");
}

// The bound the decode itself enforces (decode_bounded): whatever a header reader says, the
// matrix the decoder sizes from its own parse is refused above the limit before it is allocated.
// Each file here declares 4096 x 4096 (16 Mpixel) to a limit of 1 Mpixel.
TEST(DecodeBound, RefusesWhatTheDecoderSizesAboveTheLimit) {
    const ScopedLimit limit(kTestLimit);
    hostile::TiffPage tiff_page;
    tiff_page.width = 4096;
    tiff_page.height = 4096;
    tiff_page.pixels = false;
    std::string bmp = hostile::encoded(".bmp", cv::Mat(8, 8, CV_8UC3, cv::Scalar(1, 2, 3)));
    bmp.replace(18, 4, hostile::little_endian(4096, 4));
    bmp.replace(22, 4, hostile::little_endian(4096, 4));
    std::vector<std::pair<std::string, std::string>> files = {
        {"jpeg", hostile::jpeg_declaring(4096, 4096)},
        {"jpeg behind TEM", hostile::jpeg_hidden_frame(4096, 4096, 0x01)},
        {"png", hostile::png_declaring(4096, 4096)},
        {"pgm", "P5 4096 4096 255\n" + std::string(64, '\0')},
        {"pgm behind '#'", "P5 4096#4096\n255 " + std::string(64, '\0')},
        {"tiff", hostile::tiff({tiff_page})},
        {"bigtiff", hostile::tiff({tiff_page}, true)},
        {"bmp", bmp},
    };
    if (cv::haveImageWriter(".webp")) {
        std::string webp = hostile::encoded(".webp", cv::Mat(16, 16, CV_8UC3, cv::Scalar(1)));
        if (webp.substr(12, 4) == "VP8L") {  // lossless: 14-bit sizes minus one at byte 21
            webp.replace(21, 4, hostile::little_endian(4095U | (4095U << 14), 4));
        } else {  // lossy: 14-bit sizes at bytes 26 and 28
            ASSERT_EQ(webp.substr(12, 4), "VP8 ");
            webp.replace(26, 2, hostile::little_endian(4096, 2));
            webp.replace(28, 2, hostile::little_endian(4096, 2));
        }
        files.emplace_back("webp", webp);
    }
    for (const auto& file : files) {
        const std::string& what = file.first;  // no structured binding: clang 14 lambdas
        const std::vector<unsigned char> data(file.second.begin(), file.second.end());
        for (const int flags : {cv::IMREAD_UNCHANGED, cv::IMREAD_GRAYSCALE, cv::IMREAD_COLOR}) {
            SCOPED_TRACE(what + " flags " + std::to_string(flags));
            expect_error<std::invalid_argument>(
                [&] { (void)decode_bounded(data, flags, "'" + what + "'"); },
                "image '" + what + "' decodes to 4096x4096 pixels, more than the limit of " +
                    std::to_string(kTestLimit));
        }
    }
}

TEST(DecodeBound, DecodesUpToTheLimitAndLeavesOtherMatricesAlone) {
    const ScopedLimit limit(kTestLimit);
    const std::string at_limit = hostile::encoded(".png", cv::Mat(1024, 1024, CV_8UC1, 7));
    const cv::Mat decoded = decode_bounded(
        std::vector<unsigned char>(at_limit.begin(), at_limit.end()), cv::IMREAD_COLOR, "'a'");
    EXPECT_EQ(decoded.size(), cv::Size(1024, 1024));
    const std::string above = hostile::encoded(".png", cv::Mat(1024, 1025, CV_8UC1, 7));
    expect_error<std::invalid_argument>(
        [&] {
            (void)decode_bounded(std::vector<unsigned char>(above.begin(), above.end()),
                                 cv::IMREAD_COLOR, "'b'");
        },
        "decodes to 1025x1024 pixels");
    // Outside a decode the same thread allocates any matrix, and a corrupt file is no refusal.
    const cv::Mat large(2048, 2048, CV_8UC3, cv::Scalar(1, 2, 3));
    EXPECT_EQ(large.total(), std::size_t{2048} * 2048);
    const std::string corrupt = "\x89PNG\r\n\x1a\n not a png";
    EXPECT_TRUE(decode_bounded(std::vector<unsigned char>(corrupt.begin(), corrupt.end()),
                               cv::IMREAD_UNCHANGED, "'c'")
                    .empty());
}

TEST(Limits, LimitIsSettableAndChecked) {
    const std::int64_t before = max_image_pixels();
    EXPECT_THROW(set_max_image_pixels(0), std::invalid_argument);
    set_max_image_pixels(12345);
    EXPECT_EQ(max_image_pixels(), 12345);
    set_max_image_pixels(before);
}

}  // namespace
}  // namespace stereo::io

namespace stereo::io {
namespace {

TEST(Crop, CopiesTheRegionAndRefusesWhatDoesNotFit) {
    Image image(5, 4, 1);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        image.pixels[i] = static_cast<std::uint8_t>(i);
    }
    const Image part = crop(image, 1, 2, 3, 2);
    ASSERT_EQ(part.width, 3);
    EXPECT_EQ(part.at(0, 0, 0), 2 * 5 + 1);  // by hand: row 2, column 1
    EXPECT_EQ(part.at(2, 1, 0), 3 * 5 + 3);
    EXPECT_THROW(crop(image, 1, 0, 5, 4), std::invalid_argument);
    EXPECT_THROW(crop(image, -1, 0, 2, 2), std::invalid_argument);
    // Offsets and sizes whose sum overflows an int.
    EXPECT_THROW(crop(image, 2147483647, 0, 10, 1), std::invalid_argument);
    EXPECT_THROW(crop(image, 1, 0, 2147483647, 1), std::invalid_argument);
}

}  // namespace
}  // namespace stereo::io

// ---- disparity files of stage 6: PFM and offset16 -------------------------------------------

namespace stereo {
namespace {

TEST(DisparityFiles, PfmRoundTripKeepsSignedZeroAndInvalid) {
    cv::Mat map(2, 3, CV_32FC1);
    map.at<float>(0, 0) = -3.25F;
    map.at<float>(0, 1) = 0.0F;
    map.at<float>(0, 2) = std::numeric_limits<float>::quiet_NaN();
    map.at<float>(1, 0) = 12.5F;
    map.at<float>(1, 1) = std::numeric_limits<float>::infinity();
    map.at<float>(1, 2) = 255.0625F;
    const std::string bytes = io::encode_pfm(map);
    // Header by hand, then the bottom row first.
    ASSERT_EQ(bytes.substr(0, 10), "Pf\n3 2\n-1\n");
    float first = 0.0F;
    std::memcpy(&first, bytes.data() + 10, sizeof first);
    EXPECT_EQ(first, 12.5F);
    const cv::Mat back = io::decode_pfm(bytes, "map");
    EXPECT_EQ(back.at<float>(0, 0), -3.25F);
    EXPECT_EQ(back.at<float>(0, 1), 0.0F);
    EXPECT_TRUE(std::isnan(back.at<float>(0, 2)));
    EXPECT_TRUE(std::isnan(back.at<float>(1, 1)));
    EXPECT_EQ(back.at<float>(1, 2), 255.0625F);
}

TEST(DisparityFiles, PfmBigEndianIsRead) {
    std::string bytes = "Pf\n1 1\n1.0\n";
    // 0x40490FDB: four different non-zero bytes, so that each lane of the byte swap is checked
    // (7.5 = 0x40F00000 left the two low lanes unchecked).
    const float value = std::numbers::pi_v<float>;
    std::uint32_t word = 0;
    std::memcpy(&word, &value, sizeof word);
    for (int shift = 24; shift >= 0; shift -= 8) {  // most significant byte first
        bytes += static_cast<char>((word >> shift) & 0xFFU);
    }
    EXPECT_EQ(io::decode_pfm(bytes, "big").at<float>(0, 0), value);
}

TEST(DisparityFiles, BadPfmIsRefusedWithItsName) {
    const auto refused = [](const std::string& bytes, const std::string& fragment) {
        try {
            (void)io::decode_pfm(bytes, "'x.pfm'");
        } catch (const std::runtime_error& error) {
            const std::string message = error.what();
            return message.find("'x.pfm'") != std::string::npos &&
                   message.find(fragment) != std::string::npos;
        }
        return false;
    };
    std::string colour = "PF\n1 1\n-1\n" + std::string(12, '\0');
    EXPECT_TRUE(refused(colour, "3-channel"));
    EXPECT_TRUE(refused("P5\n1 1\n255\n" + std::string(1, '\0'), "not a PFM"));
    EXPECT_TRUE(refused("Pf\n2 2\n-1\n" + std::string(12, '\0'), "expected 16"));  // truncated
    EXPECT_TRUE(refused("Pf\n0 2\n-1\n", "positive"));
    EXPECT_TRUE(refused("Pf\n99999 99999\n-1\n", "limit"));
    std::string nan_map = "Pf\n1 1\n-1\n";
    const float nan = std::numeric_limits<float>::quiet_NaN();
    nan_map.append(reinterpret_cast<const char*>(&nan), sizeof nan);
    EXPECT_TRUE(refused(nan_map, "NaN"));
}

TEST(DisparityFiles, Offset16HoldsSignedSubpixelDisparities) {
    ValidatedDisparity v(3, 1);
    v.fixed = {-35, 0, 4000};  // -2.1875, 0, 250
    v.reason = {fx::kReasonValid, fx::kReasonValid, fx::kReasonUniqueness};
    const cv::Mat codes = io::to_offset16(v);
    EXPECT_EQ(codes.at<std::uint16_t>(0, 0), 32768 - 35);
    EXPECT_EQ(codes.at<std::uint16_t>(0, 1), 32768);
    EXPECT_EQ(codes.at<std::uint16_t>(0, 2), 0);  // invalid
    const cv::Mat floats = io::to_float_disparity(v);
    EXPECT_EQ(floats.at<float>(0, 0), -2.1875F);
    EXPECT_EQ(floats.at<float>(0, 1), 0.0F);
    EXPECT_TRUE(std::isnan(floats.at<float>(0, 2)));
}

}  // namespace
}  // namespace stereo

namespace stereo::io {
namespace {

// ---- self-describing disparity PNGs (issue 47): a tEXt chunk before IEND --------------------

std::span<const unsigned char> as_bytes(const std::string& text) {
    return {reinterpret_cast<const unsigned char*>(text.data()), text.size()};
}

TEST(PngText, Crc32IsTheStandardOne) {
    // The check value of CRC-32/ISO-HDLC (zlib's crc32) for "123456789", and the CRC of the
    // IEND chunk every PNG ends with (its type, no data).
    EXPECT_EQ(png_crc32(as_bytes("123456789")), 0xCBF43926U);
    EXPECT_EQ(png_crc32(as_bytes("IEND")), 0xAE426082U);
}

TEST(PngText, ChunkRoundTripsAndKeepsThePixels) {
    cv::Mat mat(7, 5, CV_16UC1);
    cv::randu(mat, 0, 65535);
    const std::string plain = encode_png(mat, "m.png");
    const std::string tagged = with_png_text(plain, "stereo-disparity", "encoding=offset16");
    ASSERT_EQ(tagged.size(), plain.size() + 12 + 16 + 1 + 17);
    // Everything but the inserted chunk is the original file, IEND last.
    EXPECT_EQ(tagged.substr(0, plain.size() - 12), plain.substr(0, plain.size() - 12));
    EXPECT_EQ(tagged.substr(tagged.size() - 12), plain.substr(plain.size() - 12));
    EXPECT_EQ(png_text(as_bytes(tagged), "stereo-disparity"), "encoding=offset16");
    EXPECT_EQ(png_text(as_bytes(tagged), "stereo"), std::nullopt);
    EXPECT_EQ(png_text(as_bytes(plain), "stereo-disparity"), std::nullopt);
    EXPECT_EQ(png_text(as_bytes("not a png"), "stereo-disparity"), std::nullopt);
    // The chunk's CRC covers its type and data.
    const std::string chunk = tagged.substr(plain.size() - 12, 12 + 16 + 1 + 17);
    const std::uint32_t crc = png_crc32(as_bytes(chunk.substr(4, chunk.size() - 8)));
    const auto* end = reinterpret_cast<const unsigned char*>(chunk.data() + chunk.size() - 4);
    EXPECT_EQ(crc, (std::uint32_t{end[0]} << 24) | (std::uint32_t{end[1]} << 16) |
                       (std::uint32_t{end[2]} << 8) | end[3]);
    const std::vector<unsigned char> buffer(tagged.begin(), tagged.end());
    const cv::Mat decoded = cv::imdecode(buffer, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(decoded.type(), CV_16UC1);
    EXPECT_EQ(cv::norm(decoded, mat, cv::NORM_INF), 0.0);
    EXPECT_THROW((void)with_png_text("not a png", "k", "t"), std::invalid_argument);
    EXPECT_THROW((void)with_png_text(plain, "", "t"), std::invalid_argument);
}

TEST(PngText, DisparityTagsRoundTripAndBadOnesAreNamed) {
    for (const DisparityTag tag : {DisparityTag{DisparityEncoding::offset16, 1.0},
                                   DisparityTag{DisparityEncoding::scaled, 4.0},
                                   DisparityTag{DisparityEncoding::scaled, 0.25}}) {
        EXPECT_EQ(parse_disparity_tag(disparity_tag_text(tag), "f"), tag);
    }
    EXPECT_EQ(disparity_tag_text({DisparityEncoding::scaled, 4.0}), "encoding=scaled scale=4");
    for (const char* bad : {"", "encoding=pfm", "encoding=scaled scale=", "encoding=scaled scale=0",
                            "encoding=scaled scale=4x", "encoding=scaled scale=-1"}) {
        try {
            (void)parse_disparity_tag(bad, "'f.png'");
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const std::runtime_error& error) {
            EXPECT_NE(std::string(error.what()).find("'f.png'"), std::string::npos);
        }
    }
}

TEST(PngText, DisparityFilesCarryTheirTag) {
    const TempFolder folder;
    cv::Mat mat(4, 6, CV_8UC1, cv::Scalar(12));
    const auto path = folder.path() / "d.png";
    write_file_atomic(path, encode_disparity_png(mat, {DisparityEncoding::scaled, 4.0}, path));
    EXPECT_EQ(read_disparity_tag(path), (DisparityTag{DisparityEncoding::scaled, 4.0}));
    write_png(path, mat);  // another tool's PNG
    EXPECT_EQ(read_disparity_tag(path), std::nullopt);
}

}  // namespace
}  // namespace stereo::io
