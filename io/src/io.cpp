#include "stereo_io/io.hpp"
#include "decode_guard.hpp"
#include "quoted.hpp"
#include "stereo_io/limits.hpp"
#include "stereo_io/output.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace stereo::io {

namespace fs = std::filesystem;

namespace {

using detail::quoted;

std::string size_text(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

std::string format_text(const cv::Mat& mat) {
    const int bits = mat.depth() == CV_8U ? 8 : mat.depth() == CV_16U ? 16 : 0;
    const std::string depth = bits > 0 ? std::to_string(bits) + "-bit" : "non-integer";
    return depth + " " + std::to_string(mat.channels()) + "-channel";
}

// Reading the bytes ourselves (instead of cv::imread) gives a precise message for a missing
// or unreadable file and keeps OpenCV from printing its own warnings about it.
std::vector<uchar> read_bytes(const fs::path& path) {
    check_image_file(path);
    note_input_read(path);  // no output may replace it (stereo_io/output.hpp)
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw std::runtime_error("cannot read " + quoted(path) + ": " + std::strerror(errno));
    }
    std::vector<uchar> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) {
        throw std::runtime_error("cannot read " + quoted(path) + ": read error");
    }
    return bytes;
}

// libpng and libjpeg print their own diagnostics for a corrupt file straight to stderr (file
// descriptor 2, out of OpenCV's control). The caller reports the failure itself, in one line, so
// descriptor 2 points at /dev/null while a file is decoded.
class SilencedStderr {
  public:
    SilencedStderr() {
        std::fflush(stderr);
        saved_ = ::dup(STDERR_FILENO);
        const int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (saved_ >= 0 && null_fd >= 0) {
            ::dup2(null_fd, STDERR_FILENO);
        }
        if (null_fd >= 0) {
            ::close(null_fd);
        }
    }
    ~SilencedStderr() {
        std::fflush(stderr);
        if (saved_ >= 0) {
            ::dup2(saved_, STDERR_FILENO);
            ::close(saved_);
        }
    }
    SilencedStderr(const SilencedStderr&) = delete;
    SilencedStderr& operator=(const SilencedStderr&) = delete;

  private:
    int saved_ = -1;
};

std::string limit_text(std::int64_t limit) {
    return "more than the limit of " + std::to_string(limit) +
           " (--max-pixels or STEREO_MAX_IMAGE_PIXELS)";
}

// Two bounds, both before any pixel is decoded: the size the header declares (declared_image,
// with the largest buffer it makes the decoder allocate, for a precise message at once), and the
// size the decoder itself computed, refused by decode_bounded's allocator whatever the header
// reader said (docs/reliability.md, "Bounded inputs").
cv::Mat decode(const fs::path& path, int flags = cv::IMREAD_UNCHANGED) {
    const std::vector<uchar> bytes = read_bytes(path);
    const auto declared =
        declared_image(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    if (!declared) {
        throw std::runtime_error("cannot read " + quoted(path) +
                                 ": not an image in a format whose size is checked before "
                                 "decoding (PNG, JPEG, PNM, BMP, TIFF, WebP), or its header is "
                                 "corrupt");
    }
    const std::int64_t limit = max_image_pixels();
    const std::string size =
        std::to_string(declared->width) + "x" + std::to_string(declared->height);
    if (declared->width > 0 && declared->height > limit / declared->width) {
        throw std::invalid_argument("image " + quoted(path) + " declares " + size + " pixels, " +
                                    limit_text(limit));
    }
    if (declared->largest_pixels > limit) {
        throw std::invalid_argument("image " + quoted(path) + " declares " + size + " pixels but " +
                                    declared->largest_what + " (" +
                                    std::to_string(declared->largest_pixels) + " pixels), " +
                                    limit_text(limit));
    }
    const cv::Mat mat = decode_bounded(bytes, flags, quoted(path));
    if (mat.empty()) {
        throw std::runtime_error("cannot read " + quoted(path) +
                                 ": not an image or a corrupt/unsupported format");
    }
    return mat;
}

// An 8-bit grey or BGR matrix of the file (alpha dropped).
cv::Mat read_colour_or_grey(const fs::path& path) {
    const cv::Mat mat = decode(path);
    const int channels = mat.channels();
    if (mat.depth() != CV_8U || (channels != 1 && channels != 3 && channels != 4)) {
        throw std::runtime_error("cannot use " + quoted(path) + ": it is " + format_text(mat) +
                                 ", expected an 8-bit grey, RGB or RGBA image");
    }
    if (channels == 4) {
        cv::Mat bgr;
        cv::cvtColor(mat, bgr, cv::COLOR_BGRA2BGR);
        return bgr;
    }
    return mat;
}

void check_downscale(int downscale) {
    if (downscale < 1) {
        throw std::invalid_argument("downscale factor must be >= 1, got " +
                                    std::to_string(downscale));
    }
}

// floor(W / F) x floor(H / F); throws when that is empty. `what` names the matrix in the message.
std::pair<int, int> downscaled_size(const cv::Mat& mat, int downscale, const char* what) {
    check_downscale(downscale);
    const int width = mat.cols / downscale;
    const int height = mat.rows / downscale;
    if (width < 1 || height < 1) {
        throw std::invalid_argument(std::string(what) + " (" + size_text(mat.cols, mat.rows) +
                                    ") is too small for downscale factor " +
                                    std::to_string(downscale));
    }
    return {width, height};
}

// shrink_area with the file named in the "too small" message.
cv::Mat shrink(const cv::Mat& mat, int downscale, const fs::path& path) {
    if (downscale > 1 && (mat.cols / downscale < 1 || mat.rows / downscale < 1)) {
        throw std::invalid_argument("image " + quoted(path) + " (" + size_text(mat.cols, mat.rows) +
                                    ") is too small for downscale factor " +
                                    std::to_string(downscale));
    }
    return shrink_area(mat, downscale);
}

// One channel of a grey file; a 3-channel file is accepted only when it is grey in fact, so that
// a colour view passed by mistake is refused rather than evaluated.
cv::Mat single_channel(const cv::Mat& mat, const fs::path& path) {
    if (mat.channels() == 1) {
        return mat;
    }
    if (mat.channels() == 3) {
        std::vector<cv::Mat> planes;
        cv::split(mat, planes);
        if (cv::countNonZero(planes[0] != planes[1]) == 0 &&
            cv::countNonZero(planes[0] != planes[2]) == 0) {
            return planes[0];
        }
    }
    throw std::runtime_error("cannot use " + quoted(path) + ": it is a " +
                             std::to_string(mat.channels()) +
                             "-channel colour image, expected a grey image");
}

}  // namespace

cv::Mat shrink_area(const cv::Mat& mat, int downscale) {
    if (downscale == 1) {
        check_downscale(downscale);
        return mat;
    }
    const auto [width, height] = downscaled_size(mat, downscale, "image");
    cv::Mat small;
    cv::resize(mat, small, cv::Size(width, height), 0.0, 0.0, cv::INTER_AREA);
    return small;
}

bool is_image_file(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm" || ext == ".pgm" ||
           ext == ".bmp" || ext == ".tif" || ext == ".tiff";
}

std::vector<std::string> image_file_names(const fs::path& folder) {
    if (!fs::is_directory(folder)) {
        throw std::runtime_error("cannot read image folder " + folder.string());
    }
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) {
        if (entry.is_regular_file() && is_image_file(entry.path())) {
            names.push_back(entry.path().filename().string());
        }
    }
    std::sort(names.begin(), names.end());
    return names;
}

Image crop(const Image& image, int x0, int y0, int width, int height) {
    // Written without x0 + width, which could overflow for hostile values.
    if (width < 1 || height < 1 || x0 < 0 || y0 < 0 || x0 > image.width - width ||
        y0 > image.height - height) {
        std::string text = "crop ";
        text += size_text(width, height) + "+" + std::to_string(x0) + "+" + std::to_string(y0);
        text += " does not fit the " + size_text(image.width, image.height) + " image";
        throw std::invalid_argument(text);
    }
    Image out(width, height, image.channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < image.channels; ++c) {
                out.at(x, y, c) = image.at(x0 + x, y0 + y, c);
            }
        }
    }
    return out;
}

ImagePair crop(const ImagePair& pair, int x0, int y0, int width, int height) {
    return {crop(pair.left, x0, y0, width, height), crop(pair.right, x0, y0, width, height)};
}

cv::Mat load_bgr(const fs::path& path) {
    const cv::Mat mat = read_colour_or_grey(path);
    if (mat.channels() == 1) {
        cv::Mat bgr;
        cv::cvtColor(mat, bgr, cv::COLOR_GRAY2BGR);
        return bgr;
    }
    return mat;
}

cv::Mat to_bgr(const Image& image) {
    const int type = image.channels == 1 ? CV_8UC1 : CV_8UC3;
    // A read-only view: cvtColor below writes a new matrix and never the Image's pixels.
    const cv::Mat wrapped(image.height, image.width, type,
                          const_cast<std::uint8_t*>(image.pixels.data()));
    cv::Mat bgr;
    if (image.channels == 1) {
        cv::cvtColor(wrapped, bgr, cv::COLOR_GRAY2BGR);
    } else {
        cv::cvtColor(wrapped, bgr, cv::COLOR_RGB2BGR);
    }
    return bgr;
}

Image to_image(const cv::Mat& mat, const std::string& name) {
    if (mat.empty() || mat.depth() != CV_8U || (mat.channels() != 1 && mat.channels() != 3)) {
        throw std::invalid_argument(
            "image " + name + " must be 8-bit grey or BGR, got " +
            (mat.empty() ? std::string("an empty matrix") : format_text(mat)));
    }
    cv::Mat ordered;  // RGB for colour: the model's channel order
    if (mat.channels() == 3) {
        cv::cvtColor(mat, ordered, cv::COLOR_BGR2RGB);
    } else {
        ordered = mat;
    }
    Image image(ordered.cols, ordered.rows, ordered.channels());
    const std::size_t row_bytes = static_cast<std::size_t>(image.width) * image.channels;
    for (int y = 0; y < image.height; ++y) {
        std::copy_n(ordered.ptr<std::uint8_t>(y), row_bytes,
                    image.pixels.begin() + static_cast<std::ptrdiff_t>(y * row_bytes));
    }
    return image;
}

cv::Mat decode_bounded(const std::vector<unsigned char>& bytes, int flags,
                       const std::string& name) {
    const std::int64_t limit = max_image_pixels();
    cv::Mat mat;
    std::optional<std::pair<std::int64_t, std::int64_t>> refused;
    {
        const detail::PixelBudget budget(limit);
        try {
            const SilencedStderr quiet;
            mat = cv::imdecode(bytes, flags);
        } catch (const cv::Exception&) {
            mat.release();  // reported by the caller, with the file name, as one line
        }
        refused = budget.refused();
    }
    if (refused) {
        mat.release();
        throw std::invalid_argument(
            "image " + name + " decodes to " + std::to_string(refused->first) + "x" +
            std::to_string(refused->second) + " pixels, " + limit_text(limit));
    }
    return mat;
}

void check_image_file(const fs::path& path) {
    std::error_code error;
    if (!fs::exists(path, error)) {
        throw std::runtime_error("cannot read " + quoted(path) + ": no such file");
    }
    if (fs::is_directory(path, error)) {
        throw std::runtime_error("cannot read " + quoted(path) + ": is a directory");
    }
    // Devices and pipes could be read without end (/dev/zero); images are regular files.
    if (!fs::is_regular_file(path, error)) {
        throw std::runtime_error("cannot read " + quoted(path) + ": not a regular file");
    }
    const auto size = fs::file_size(path, error);
    if (!error && static_cast<std::int64_t>(size) > kMaxImageFileBytes) {
        throw std::runtime_error("cannot read " + quoted(path) + ": " + std::to_string(size) +
                                 " bytes is larger than the " + std::to_string(kMaxImageFileBytes) +
                                 "-byte limit");
    }
}

cv::Mat load_grey(const fs::path& path) {
    return decode(path, cv::IMREAD_GRAYSCALE);
}

Image load_image(const fs::path& path, int downscale) {
    check_downscale(downscale);
    return to_image(shrink(read_colour_or_grey(path), downscale, path), quoted(path));
}

ImagePair load_pair(const fs::path& left, const fs::path& right, int downscale) {
    check_downscale(downscale);
    cv::Mat left_mat = read_colour_or_grey(left);
    cv::Mat right_mat = read_colour_or_grey(right);
    if (left_mat.size() != right_mat.size()) {
        throw std::invalid_argument(
            "left " + quoted(left) + " is " + size_text(left_mat.cols, left_mat.rows) +
            " but right " + quoted(right) + " is " + size_text(right_mat.cols, right_mat.rows));
    }
    // The model matches a grey pixel g exactly as (g, g, g), so a grey/colour mix is promoted
    // to colour rather than refused.
    if (left_mat.channels() != right_mat.channels()) {
        cv::Mat& grey = left_mat.channels() == 1 ? left_mat : right_mat;
        cv::cvtColor(grey, grey, cv::COLOR_GRAY2BGR);
    }
    return {to_image(shrink(left_mat, downscale, left), quoted(left)),
            to_image(shrink(right_mat, downscale, right), quoted(right))};
}

void check_disparity_scale(int ndisp, int scale) {
    if (ndisp < 1) {
        throw std::invalid_argument("ndisp must be >= 1, got " + std::to_string(ndisp));
    }
    if (scale < 1) {
        throw std::invalid_argument("disparity scale must be >= 1, got " + std::to_string(scale));
    }
    const long long largest = static_cast<long long>(ndisp - 1) * scale;
    if (largest > 65535) {
        throw std::invalid_argument("disparity scale " + std::to_string(scale) + " with ndisp " +
                                    std::to_string(ndisp) + " gives values up to " +
                                    std::to_string(largest) + ", more than a 16-bit PNG holds");
    }
}

cv::Mat disparity_to_mat(const DisparityMap& map, int ndisp, int scale) {
    check_disparity_scale(ndisp, scale);
    const std::size_t count = static_cast<std::size_t>(map.width) * map.height;
    if (map.width < 1 || map.height < 1 || map.disparity.size() != count ||
        map.valid.size() != count) {
        throw std::invalid_argument("disparity map is empty or inconsistent");
    }
    const bool fits_8bit = (ndisp - 1) * scale <= 255;
    cv::Mat out(map.height, map.width, fits_8bit ? CV_8UC1 : CV_16UC1);
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const std::size_t i = map.index(x, y);
            const int d = map.disparity[i];
            if (map.valid[i] != 0 && d >= ndisp) {
                throw std::invalid_argument("disparity " + std::to_string(d) + " at (" +
                                            std::to_string(x) + ", " + std::to_string(y) +
                                            ") is not below ndisp " + std::to_string(ndisp));
            }
            const int value = map.valid[i] != 0 ? d * scale : 0;
            if (fits_8bit) {
                out.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(value);
            } else {
                out.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(value);
            }
        }
    }
    return out;
}

namespace {

// Disparities 0..ndisp-1 spread over the TURBO colour map.
cv::Mat turbo(const cv::Mat& disparity, int ndisp) {
    cv::Mat spread;
    disparity.convertTo(spread, CV_8U, ndisp > 1 ? 255.0 / (ndisp - 1) : 0.0);
    cv::Mat colour;
    cv::applyColorMap(spread, colour, cv::COLORMAP_TURBO);
    return colour;
}

}  // namespace

cv::Mat disparity_to_colour(const DisparityMap& map, int ndisp) {
    cv::Mat colour = turbo(disparity_to_mat(map, ndisp, 1), ndisp);
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            if (map.valid[map.index(x, y)] == 0) {
                colour.at<cv::Vec3b>(y, x) = cv::Vec3b(0, 0, 0);
            }
        }
    }
    return colour;
}

cv::Mat float_disparity_to_colour(const cv::Mat& disparity, int ndisp) {
    cv::Mat colour = turbo(disparity, ndisp);
    colour.setTo(cv::Scalar::all(0), disparity <= 0);
    return colour;
}

cv::Mat to_float_disparity(const DisparityMap& map) {
    cv::Mat out(map.height, map.width, CV_32FC1, cv::Scalar(0));
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const auto i = map.index(x, y);
            out.at<float>(y, x) = map.valid[i] != 0 ? static_cast<float>(map.disparity[i]) : 0.0f;
        }
    }
    return out;
}

std::vector<unsigned char> read_input_file(const fs::path& path) {
    return read_bytes(path);
}

cv::Mat load_disparity(const fs::path& path, double scale) {
    if (!(scale > 0.0) || !std::isfinite(scale)) {
        throw std::invalid_argument("disparity scale for " + quoted(path) +
                                    " must be a positive number, got " + std::to_string(scale));
    }
    const cv::Mat mat = decode(path);
    if (mat.depth() != CV_8U && mat.depth() != CV_16U) {
        throw std::runtime_error("cannot use " + quoted(path) + ": it is " + format_text(mat) +
                                 ", expected an 8- or 16-bit disparity image");
    }
    cv::Mat disparity;
    single_channel(mat, path).convertTo(disparity, CV_32F, 1.0 / scale);
    return disparity;
}

namespace {

template <typename T>
cv::Mat sample_block_centres(const cv::Mat& full, int downscale, double divide_by) {
    const auto [width, height] = downscaled_size(full, downscale, "ground truth");
    cv::Mat small(height, width, full.type());
    const int offset = downscale / 2;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const T value = full.at<T>(y * downscale + offset, x * downscale + offset);
            small.at<T>(y, x) = static_cast<T>(value / divide_by);
        }
    }
    return small;
}

}  // namespace

cv::Mat downscale_ground_truth(const cv::Mat& ground_truth, int downscale) {
    return sample_block_centres<float>(ground_truth, downscale, downscale);
}

cv::Mat downscale_mask(const cv::Mat& mask, int downscale) {
    return sample_block_centres<std::uint8_t>(mask, downscale, 1.0);
}

cv::Mat load_mask(const fs::path& path) {
    const cv::Mat mat = decode(path);
    if (mat.depth() != CV_8U) {
        throw std::runtime_error("cannot use " + quoted(path) + ": it is " + format_text(mat) +
                                 ", expected an 8-bit mask");
    }
    return single_channel(mat, path).clone();
}

std::string encode_png(const cv::Mat& mat, const fs::path& path) {
    std::vector<uchar> bytes;
    bool encoded = false;
    try {
        encoded = !mat.empty() && cv::imencode(".png", mat, bytes);
    } catch (const cv::Exception&) {
        encoded = false;
    }
    if (!encoded) {
        throw std::runtime_error("cannot encode " + quoted(path) + " as PNG (" + format_text(mat) +
                                 ")");
    }
    return {bytes.begin(), bytes.end()};
}

void write_png(const fs::path& path, const cv::Mat& mat) {
    write_file_atomic(path, encode_png(mat, path));
}

void write_pngs(const std::vector<std::pair<fs::path, cv::Mat>>& files) {
    std::vector<std::pair<fs::path, std::string>> encoded;
    encoded.reserve(files.size());
    for (const auto& [path, mat] : files) {
        encoded.emplace_back(path, encode_png(mat, path));
    }
    write_files_atomic(encoded);
}

void check_writable_location(const fs::path& path) {
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code error;
    if (!fs::is_directory(folder, error)) {
        throw std::runtime_error("cannot write " + quoted(path) + ": folder " + quoted(folder) +
                                 " does not exist");
    }
    // Outputs replace regular files only (write_file_atomic): not a folder, /dev/null, a FIFO or
    // a socket; the folder must take a temporary file (check_can_stage).
    check_can_stage(path);
}

void check_output_folder(const fs::path& folder) {
    std::error_code error;
    if (fs::exists(folder, error)) {
        if (!fs::is_directory(folder, error)) {
            throw std::runtime_error("cannot write into " + quoted(folder) + ": not a folder");
        }
        return;
    }
    const fs::path parent = folder.parent_path().empty() ? fs::path(".") : folder.parent_path();
    if (!fs::is_directory(parent, error)) {
        throw std::runtime_error("cannot create folder " + quoted(folder) + ": folder " +
                                 quoted(parent) + " does not exist");
    }
}

}  // namespace stereo::io
