// The byte protocol of the iCEBreaker build (rtl/stereo_board_top.sv, docs/board.md): the
// commands a host sends and the replies the board sends back, both ways (encode and decode), so
// that the host (`stereo board`), the board's co-simulation (testbench/) and the emulated board
// of the tests speak one definition. Pure bytes: no serial port here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/validated.hpp"

namespace stereo::board {

inline constexpr std::uint8_t kHeader = 0xA5;  // starts every command
inline constexpr std::uint8_t kReply = 0x5A;   // starts every reply but a frame's beats
inline constexpr std::uint8_t kOpIdentify = 'I';
inline constexpr std::uint8_t kOpConfigure = 'C';
inline constexpr std::uint8_t kOpFrame = 'F';
inline constexpr std::uint8_t kOpClear = 'R';
inline constexpr std::size_t kIdentifyReplyBytes = 18;
inline constexpr std::size_t kAckReplyBytes = 2;  // kReply, status
inline constexpr std::size_t kConfigBytes = 12;   // after kHeader, kOpConfigure
inline constexpr std::size_t kPixelBytes = 6;     // left R, G, B, right R, G, B
inline constexpr std::size_t kBeatBytes = 4;      // one output beat, least significant byte first

// Sticky status bits (the last byte of the identify and acknowledge replies).
enum StatusBit : unsigned {
    kStatusEolMisplaced = 0,   // stereo_top: tlast not at the row end
    kStatusSofMisplaced = 1,   // stereo_top: tuser inside a frame
    kStatusConfigClamped = 2,  // configuration out of range, clamped
    kStatusProtocolError = 3,  // not a command, unknown opcode, or a timeout inside one
    kStatusFramingError = 4,   // a UART stop bit was 0
    kStatusInputOverrun = 5,   // a pixel arrived while the one before still waited
};
// "configuration clamped, protocol error" for the set bits; "ok" for 0.
std::string describe_status(std::uint8_t status);

// The identify reply: the synthesised configuration and the status.
struct Identity {
    std::uint32_t id = 0;
    std::uint32_t version = 0;
    int width = 0;  // largest frame
    int height = 0;
    int ndisp = 0;   // labels
    int window = 0;  // the constant kernel's window
    int max_min_disp = 0;
    std::uint8_t status = 0;
    bool operator==(const Identity&) const = default;
};

// The configuration registers, as the configure command carries them.
struct Config {
    int width = 0;
    int height = 0;
    int ndisp = 0;   // bits 8:0 are sent
    int radius = 0;  // must equal window / 2 of the board
    bool use_ca = true;
    int min_disp = 0;  // 12-bit two's complement
    bool uniqueness = false;
    int uniqueness_ratio = 20;
    bool left_right = false;
    int lr_tolerance = 0;
    bool subpixel = false;
    bool operator==(const Config&) const = default;
};

// The registers that make the board compute match_validated(left, right, params) on a frame of
// width x height (params.window is the board's window; the radius sent is window / 2).
Config config_for(int width, int height, const MatchParams& params);
// The model's parameters of a configuration on a board with the given window (the kernel is
// the default one, sigma fx::kDefaultSigma, as the board's constant kernel).
MatchParams match_params(const Config& config, int window);

// ---- commands (host to board) ----
std::vector<std::uint8_t> identify_command();
std::vector<std::uint8_t> clear_command();
std::vector<std::uint8_t> configure_command(const Config& config);
// kHeader, kOpFrame and the pixel pairs in raster order (grey is sent as R = G = B). Throws
// std::invalid_argument when the images differ in size.
std::vector<std::uint8_t> frame_command(const Image& left, const Image& right);

// The 12 configuration bytes back into registers (the sign of min_disp from its bit 11).
Config decode_config(std::span<const std::uint8_t> bytes);
// Pixel bytes (after the frame command's two bytes) back into an RGB pair.
std::pair<Image, Image> decode_pixels(std::span<const std::uint8_t> bytes, int width, int height);

// ---- replies (board to host) ----
std::vector<std::uint8_t> identify_reply(const Identity& identity);
std::vector<std::uint8_t> ack_reply(std::uint8_t status);
// One 4-byte beat per pixel, raster order: fixed (2 bytes), reason, certainty.
std::vector<std::uint8_t> encode_beats(const ValidatedDisparity& result);

// Throw std::runtime_error on a reply of the wrong size or without kReply.
Identity decode_identity(std::span<const std::uint8_t> reply);
std::uint8_t decode_ack(std::span<const std::uint8_t> reply);
// width * height beats back into the validated result; throws std::runtime_error when the byte
// count is wrong or a beat's padding bits are set.
ValidatedDisparity decode_beats(std::span<const std::uint8_t> bytes, int width, int height);

}  // namespace stereo::board
