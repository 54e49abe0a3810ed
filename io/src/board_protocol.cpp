#include "stereo_io/board_protocol.hpp"

#include <stdexcept>

#include "stereo/constants.hpp"

namespace stereo::board {
namespace {

void put16(std::vector<std::uint8_t>& out, unsigned value) {
    out.push_back(static_cast<std::uint8_t>(value & 0xFFU));
    out.push_back(static_cast<std::uint8_t>(value >> 8 & 0xFFU));
}

void put32(std::vector<std::uint8_t>& out, std::uint32_t value) {
    put16(out, value & 0xFFFFU);
    put16(out, value >> 16);
}

unsigned get16(std::span<const std::uint8_t> bytes, std::size_t at) {
    return bytes[at] | static_cast<unsigned>(bytes[at + 1]) << 8;
}

std::uint32_t get32(std::span<const std::uint8_t> bytes, std::size_t at) {
    return get16(bytes, at) | static_cast<std::uint32_t>(get16(bytes, at + 2)) << 16;
}

void check_reply(std::span<const std::uint8_t> reply, std::size_t size, const char* what) {
    if (reply.size() != size) {
        throw std::runtime_error(std::string(what) + " reply has " + std::to_string(reply.size()) +
                                 " bytes, expected " + std::to_string(size));
    }
    if (reply[0] != kReply) {
        throw std::runtime_error(std::string(what) + " reply starts with byte " +
                                 std::to_string(reply[0]) + ", expected " + std::to_string(kReply));
    }
}

std::uint8_t channel(const Image& image, int x, int y, int c) {
    return image.at(x, y, image.channels == 1 ? 0 : c);
}

}  // namespace

std::string describe_status(std::uint8_t status) {
    static constexpr const char* kNames[] = {
        "tlast misplaced",    "tuser misplaced", "configuration clamped", "protocol error",
        "UART framing error", "input overrun",   "reserved bit 6",        "reserved bit 7",
    };
    std::string out;
    for (unsigned bit = 0; bit < 8; ++bit) {
        if ((status >> bit & 1U) != 0) {
            out += (out.empty() ? "" : ", ") + std::string(kNames[bit]);
        }
    }
    return out.empty() ? "ok" : out;
}

Config config_for(int width, int height, const MatchParams& params) {
    const ValidationParams& v = params.validation;
    return {width,         height,          params.ndisp, params.window / 2,
            params.use_ca, params.min_disp, v.uniqueness, v.uniqueness_ratio,
            v.left_right,  v.lr_tolerance,  v.subpixel};
}

MatchParams match_params(const Config& config, int window) {
    MatchParams params{config.ndisp, window, fx::kDefaultSigma, config.use_ca};
    params.min_disp = config.min_disp;
    params.validation = {config.uniqueness, config.uniqueness_ratio, config.left_right,
                         config.lr_tolerance, config.subpixel};
    return params;
}

std::vector<std::uint8_t> identify_command() {
    return {kHeader, kOpIdentify};
}

std::vector<std::uint8_t> clear_command() {
    return {kHeader, kOpClear};
}

std::vector<std::uint8_t> configure_command(const Config& config) {
    std::vector<std::uint8_t> out{kHeader, kOpConfigure};
    put16(out, static_cast<unsigned>(config.width));
    put16(out, static_cast<unsigned>(config.height));
    put16(out, static_cast<unsigned>(config.ndisp) & 0x1FFU);
    out.push_back(static_cast<std::uint8_t>(config.radius & 0x1F));
    out.push_back(
        static_cast<std::uint8_t>((config.use_ca ? 1U : 0U) | (config.uniqueness ? 2U : 0U) |
                                  (config.left_right ? 4U : 0U) | (config.subpixel ? 8U : 0U)));
    put16(out, static_cast<unsigned>(config.min_disp) & 0xFFFU);
    out.push_back(static_cast<std::uint8_t>(config.uniqueness_ratio));
    out.push_back(static_cast<std::uint8_t>(config.lr_tolerance));
    return out;
}

std::vector<std::uint8_t> frame_command(const Image& left, const Image& right) {
    if (left.width != right.width || left.height != right.height) {
        throw std::invalid_argument(
            "the left image is " + std::to_string(left.width) + "x" + std::to_string(left.height) +
            ", the right " + std::to_string(right.width) + "x" + std::to_string(right.height));
    }
    std::vector<std::uint8_t> out{kHeader, kOpFrame};
    out.reserve(2 + kPixelBytes * static_cast<std::size_t>(left.width) * left.height);
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < left.width; ++x) {
            for (const Image* image : {&left, &right}) {
                for (int c = 0; c < 3; ++c) {
                    out.push_back(channel(*image, x, y, c));
                }
            }
        }
    }
    return out;
}

Config decode_config(std::span<const std::uint8_t> bytes) {
    if (bytes.size() != kConfigBytes) {
        throw std::runtime_error("configuration has " + std::to_string(bytes.size()) + " bytes");
    }
    const unsigned flags = bytes[7];
    const unsigned min_disp = get16(bytes, 8) & 0xFFFU;
    return {static_cast<int>(get16(bytes, 0)),
            static_cast<int>(get16(bytes, 2)),
            static_cast<int>(get16(bytes, 4) & 0x1FFU),
            bytes[6] & 0x1F,
            (flags & 1U) != 0,
            static_cast<int>(min_disp) - ((min_disp & 0x800U) != 0 ? 0x1000 : 0),
            (flags & 2U) != 0,
            bytes[10],
            (flags & 4U) != 0,
            bytes[11],
            (flags & 8U) != 0};
}

std::pair<Image, Image> decode_pixels(std::span<const std::uint8_t> bytes, int width, int height) {
    if (bytes.size() != kPixelBytes * static_cast<std::size_t>(width) * height) {
        throw std::runtime_error("frame has " + std::to_string(bytes.size()) + " pixel bytes");
    }
    Image left(width, height, 3);
    Image right(width, height, 3);
    std::size_t n = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (Image* image : {&left, &right}) {
                for (int c = 0; c < 3; ++c) {
                    image->at(x, y, c) = bytes[n++];
                }
            }
        }
    }
    return {std::move(left), std::move(right)};
}

std::vector<std::uint8_t> identify_reply(const Identity& identity) {
    std::vector<std::uint8_t> out{kReply};
    put32(out, identity.id);
    put32(out, identity.version);
    put16(out, static_cast<unsigned>(identity.width));
    put16(out, static_cast<unsigned>(identity.height));
    put16(out, static_cast<unsigned>(identity.ndisp));
    out.push_back(static_cast<std::uint8_t>(identity.window));
    out.push_back(static_cast<std::uint8_t>(identity.max_min_disp));
    out.push_back(identity.status);
    return out;
}

std::vector<std::uint8_t> ack_reply(std::uint8_t status) {
    return {kReply, status};
}

std::vector<std::uint8_t> encode_beats(const ValidatedDisparity& result) {
    std::vector<std::uint8_t> out;
    out.reserve(kBeatBytes * result.fixed.size());
    for (std::size_t i = 0; i < result.fixed.size(); ++i) {
        put16(out, static_cast<std::uint16_t>(result.fixed[i]));
        out.push_back(result.reason[i]);
        out.push_back(result.certainty[i]);
    }
    return out;
}

Identity decode_identity(std::span<const std::uint8_t> reply) {
    check_reply(reply, kIdentifyReplyBytes, "identify");
    return {get32(reply, 1),
            get32(reply, 5),
            static_cast<int>(get16(reply, 9)),
            static_cast<int>(get16(reply, 11)),
            static_cast<int>(get16(reply, 13)),
            reply[15],
            reply[16],
            reply[17]};
}

std::uint8_t decode_ack(std::span<const std::uint8_t> reply) {
    check_reply(reply, kAckReplyBytes, "acknowledge");
    return reply[1];
}

ValidatedDisparity decode_beats(std::span<const std::uint8_t> bytes, int width, int height) {
    ValidatedDisparity out(width, height);
    if (bytes.size() != kBeatBytes * out.fixed.size()) {
        throw std::runtime_error("frame reply has " + std::to_string(bytes.size()) +
                                 " bytes, expected " +
                                 std::to_string(kBeatBytes * out.fixed.size()));
    }
    for (std::size_t i = 0; i < out.fixed.size(); ++i) {
        const std::span<const std::uint8_t> beat = bytes.subspan(kBeatBytes * i, kBeatBytes);
        if ((beat[2] & ~((1U << fx::kReasonBits) - 1U)) != 0) {
            throw std::runtime_error("non-zero padding bits in output beat " + std::to_string(i));
        }
        out.fixed[i] = static_cast<std::int16_t>(static_cast<std::uint16_t>(get16(beat, 0)));
        out.reason[i] = beat[2];
        out.certainty[i] = beat[3];
    }
    return out;
}

}  // namespace stereo::board
