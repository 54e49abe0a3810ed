#include "stereo_io/test_vectors.hpp"

#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "stereo/catalogue.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_io/output.hpp"

namespace stereo::io {
namespace {

// `value` as `digits` hex digits and a newline.
void append_hex(std::string& out, std::uint64_t value, int digits) {
    std::array<char, 24> text{};
    std::snprintf(text.data(), text.size(), "%0*llx\n", digits,
                  static_cast<unsigned long long>(value));
    out += text.data();
}

constexpr int kInWordBits = table::kInBeatBits + 2;    // {tuser, tlast, tdata}
constexpr int kOutWordBits = table::kOutBeatBits + 2;  // {tuser, tlast, tdata}
constexpr int hex_digits(int bits) {
    return (bits + 3) / 4;
}

std::string config_text(const MatchParams& params, int width, int height, int frames) {
    const ValidationParams& v = params.validation;
    const unsigned min_disp =
        static_cast<unsigned>(params.min_disp) & ((1U << table::kCfgMinDispBits) - 1);
    const std::array<std::pair<std::uint32_t, const char*>, kVectorKernel> words = {{
        {kVectorMagicValue, "magic \"STV1\""},
        {static_cast<std::uint32_t>(catalogue::cost(params.cost).hardware_code),
         "cost: stereo_top's COST code"},
        {static_cast<std::uint32_t>(width), "width"},
        {static_cast<std::uint32_t>(height), "height"},
        {static_cast<std::uint32_t>(frames), "frames"},
        {static_cast<std::uint32_t>(params.ndisp), "ndisp"},
        {static_cast<std::uint32_t>(params.window), "window (cfg_radius = window / 2)"},
        {params.use_ca ? 1U : 0U, "use_ca"},
        {min_disp, "min_disp (two's complement)"},
        {v.uniqueness ? 1U : 0U, "uniqueness_en"},
        {static_cast<std::uint32_t>(v.uniqueness_ratio), "uniqueness ratio (percent)"},
        {v.left_right ? 1U : 0U, "lr_en"},
        {static_cast<std::uint32_t>(v.lr_tolerance), "lr_tolerance"},
        {v.subpixel ? 1U : 0U, "subpixel_en"},
    }};
    std::string out = "// stereo vectors: configuration words (testbench/sv/README.md)\n";
    for (std::size_t i = 0; i < words.size(); ++i) {
        std::array<char, 96> line{};
        std::snprintf(line.data(), line.size(), "%08x  // %zu %s\n", words[i].first, i,
                      words[i].second);
        out += line.data();
    }
    const auto taps = gaussian_kernel(params.window, params.sigma);
    for (std::size_t i = 0; i < taps.size(); ++i) {
        std::array<char, 64> line{};
        std::snprintf(line.data(), line.size(), "%08x  // %zu kernel tap %zu\n",
                      static_cast<unsigned>(taps[i]), kVectorKernel + i, i);
        out += line.data();
    }
    return out;
}

}  // namespace

VectorTexts make_vectors(const Image& left, const Image& right, const MatchParams& params,
                         const ValidatedDisparity& expected, int frames) {
    if (left.width != right.width || left.height != right.height || expected.width != left.width ||
        expected.height != left.height) {
        throw std::invalid_argument("test vectors: the images and the expected map differ in size");
    }
    if (frames < 1) {
        throw std::invalid_argument("test vectors: frames must be at least 1, got " +
                                    std::to_string(frames));
    }
    const int width = left.width;
    const int height = left.height;
    VectorTexts texts;
    texts.config = config_text(params, width, height, frames);
    const std::string size = std::to_string(width) + "x" + std::to_string(height) + ", " +
                             std::to_string(frames) + " frame(s)";
    texts.input = "// stereo vectors: {tuser, tlast, s_axis_tdata[47:0]} per beat, " + size + "\n";
    texts.expected =
        "// stereo vectors: {tuser, tlast, m_axis_tdata[31:0]} per beat, " + size + "\n";
    const std::uint64_t tlast = std::uint64_t{1} << 0;
    const std::uint64_t tuser = std::uint64_t{1} << 1;
    for (int f = 0; f < frames; ++f) {
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const std::uint64_t flags =
                    (x == width - 1 ? tlast : 0) | (x == 0 && y == 0 ? tuser : 0);
                append_hex(texts.input,
                           (flags << table::kInBeatBits) | table::in_beat_data(left, right, x, y),
                           hex_digits(kInWordBits));
                const std::size_t i = expected.index(x, y);
                append_hex(texts.expected,
                           (flags << table::kOutBeatBits) |
                               table::out_beat_data(expected.fixed[i], expected.reason[i],
                                                    expected.certainty[i]),
                           hex_digits(kOutWordBits));
            }
        }
    }
    return texts;
}

void write_vectors(const std::filesystem::path& folder, const VectorTexts& texts) {
    std::filesystem::create_directories(folder);
    write_file_atomic(folder / "config.hex", texts.config);
    write_file_atomic(folder / "input.hex", texts.input);
    write_file_atomic(folder / "expected.hex", texts.expected);
}

}  // namespace stereo::io
