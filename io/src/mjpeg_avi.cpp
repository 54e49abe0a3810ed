#include "stereo_io/mjpeg_avi.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string_view>
#include <utility>

#include <opencv2/imgcodecs.hpp>

namespace stereo::io {
namespace {

// Little-endian fields and chunks of a RIFF file.
class RiffBuilder {
  public:
    void u16(std::uint16_t value) {
        bytes_.push_back(static_cast<char>(value & 0xff));
        bytes_.push_back(static_cast<char>(value >> 8));
    }
    void u32(std::uint32_t value) {
        for (int shift = 0; shift < 32; shift += 8) {
            bytes_.push_back(static_cast<char>((value >> shift) & 0xff));
        }
    }
    void fourcc(std::string_view code) { bytes_.append(code.substr(0, 4)); }
    void append(std::string_view data) { bytes_.append(data); }

    // Opens a chunk ("RIFF"/"LIST" with `form`, or a plain chunk with an empty form): returns
    // the position of its size field, filled in by close().
    std::size_t open(std::string_view id, std::string_view form = {}) {
        fourcc(id);
        const std::size_t size_at = bytes_.size();
        u32(0);
        if (!form.empty()) {
            fourcc(form);
        }
        return size_at;
    }
    // Closes the chunk whose size field is at `size_at`, padding its data to an even length
    // (the pad byte is not counted in the size).
    void close(std::size_t size_at) {
        const std::size_t size = bytes_.size() - size_at - 4;
        for (int i = 0; i < 4; ++i) {
            bytes_[size_at + i] = static_cast<char>((size >> (8 * i)) & 0xff);
        }
        if (size % 2 != 0) {
            bytes_.push_back('\0');
        }
    }
    std::size_t size() const { return bytes_.size(); }
    std::string take() { return std::move(bytes_); }

  private:
    std::string bytes_;
};

constexpr std::uint32_t kAvifHasIndex = 0x10;   // AVIF_HASINDEX: idx1 follows movi
constexpr std::uint32_t kAviifKeyframe = 0x10;  // AVIIF_KEYFRAME: every JPEG frame stands alone

}  // namespace

std::string mjpeg_avi(const std::vector<cv::Mat>& frames, double fps, int jpeg_quality) {
    if (frames.empty()) {
        throw std::invalid_argument("an AVI video needs at least one frame");
    }
    if (!std::isfinite(fps) || fps <= 0.0 || fps > 1e6) {
        throw std::invalid_argument("an AVI video needs a frame rate above 0 and at most 1e6");
    }
    if (jpeg_quality < 1 || jpeg_quality > 100) {
        throw std::invalid_argument("a JPEG quality is 1 to 100");
    }
    const cv::Size size = frames.front().size();
    for (const cv::Mat& frame : frames) {
        if (frame.type() != CV_8UC3 || frame.size() != size || frame.empty()) {
            throw std::invalid_argument(
                "the frames of an AVI video must be non-empty 8-bit BGR "
                "images of one size");
        }
    }

    std::vector<std::string> jpegs;
    jpegs.reserve(frames.size());
    std::uint64_t total = 0;
    std::size_t largest = 0;
    const std::vector<int> params{cv::IMWRITE_JPEG_QUALITY, jpeg_quality};
    for (const cv::Mat& frame : frames) {
        std::vector<unsigned char> encoded;
        if (!cv::imencode(".jpg", frame, encoded, params)) {
            throw std::runtime_error("OpenCV cannot encode a video frame as JPEG");
        }
        jpegs.emplace_back(encoded.begin(), encoded.end());
        total += encoded.size() + 8 + 1 + 16;  // chunk header, pad byte, index entry
        largest = std::max(largest, encoded.size());
        if (total + 4096 > kMaxAviBytes) {
            throw std::runtime_error(
                "the video would exceed the 1 GiB of an AVI file: write "
                "fewer or smaller frames, or a contact sheet (.png)");
        }
    }

    // Time base: the rate as a fraction rate/scale with scale 1000 (29.97 frames/s is exact).
    constexpr std::uint32_t kScale = 1000;
    const auto rate = static_cast<std::uint32_t>(std::llround(fps * kScale));
    const auto micro_seconds_per_frame = static_cast<std::uint32_t>(std::llround(1e6 / fps));
    const auto count = static_cast<std::uint32_t>(frames.size());
    const auto width = static_cast<std::uint32_t>(size.width);
    const auto height = static_cast<std::uint32_t>(size.height);
    const auto buffer = static_cast<std::uint32_t>(largest + (largest % 2));
    const auto bytes_per_second =
        static_cast<std::uint32_t>(std::min<double>(std::ceil(buffer * fps), 0xffffffffu));

    RiffBuilder avi;
    const std::size_t riff = avi.open("RIFF", "AVI ");
    const std::size_t hdrl = avi.open("LIST", "hdrl");
    const std::size_t avih = avi.open("avih");  // AVIMAINHEADER
    avi.u32(micro_seconds_per_frame);
    avi.u32(bytes_per_second);
    avi.u32(0);  // padding granularity
    avi.u32(kAvifHasIndex);
    avi.u32(count);
    avi.u32(0);  // initial frames
    avi.u32(1);  // streams
    avi.u32(buffer);
    avi.u32(width);
    avi.u32(height);
    for (int i = 0; i < 4; ++i) {
        avi.u32(0);  // reserved
    }
    avi.close(avih);
    const std::size_t strl = avi.open("LIST", "strl");
    const std::size_t strh = avi.open("strh");  // AVISTREAMHEADER
    avi.fourcc("vids");
    avi.fourcc("MJPG");
    avi.u32(0);  // flags
    avi.u16(0);  // priority
    avi.u16(0);  // language
    avi.u32(0);  // initial frames
    avi.u32(kScale);
    avi.u32(rate);
    avi.u32(0);  // start
    avi.u32(count);
    avi.u32(buffer);
    avi.u32(0xffffffffu);  // quality: the default
    avi.u32(0);            // sample size: frames vary in size
    avi.u16(0);            // rcFrame: left, top, right, bottom
    avi.u16(0);
    avi.u16(static_cast<std::uint16_t>(std::min<std::uint32_t>(width, 0xffff)));
    avi.u16(static_cast<std::uint16_t>(std::min<std::uint32_t>(height, 0xffff)));
    avi.close(strh);
    const std::size_t strf = avi.open("strf");  // BITMAPINFOHEADER
    avi.u32(40);
    avi.u32(width);
    avi.u32(height);
    avi.u16(1);   // planes
    avi.u16(24);  // bits per pixel
    avi.fourcc("MJPG");
    avi.u32(width * height * 3);
    avi.u32(0);  // pixels per metre, x and y
    avi.u32(0);
    avi.u32(0);  // colours used, important
    avi.u32(0);
    avi.close(strf);
    avi.close(strl);
    avi.close(hdrl);

    const std::size_t movi = avi.open("LIST", "movi");
    const std::size_t movi_data = movi + 4;  // index offsets count from the "movi" code
    std::vector<std::pair<std::uint32_t, std::uint32_t>> index;  // offset, length
    index.reserve(jpegs.size());
    for (const std::string& jpeg : jpegs) {
        index.emplace_back(static_cast<std::uint32_t>(avi.size() - movi_data),
                           static_cast<std::uint32_t>(jpeg.size()));
        const std::size_t chunk = avi.open("00dc");  // stream 0, compressed video
        avi.append(jpeg);
        avi.close(chunk);
    }
    avi.close(movi);
    const std::size_t idx1 = avi.open("idx1");  // AVIOLDINDEX
    for (const auto& [offset, length] : index) {
        avi.fourcc("00dc");
        avi.u32(kAviifKeyframe);
        avi.u32(offset);
        avi.u32(length);
    }
    avi.close(idx1);
    avi.close(riff);
    return avi.take();
}

}  // namespace stereo::io
