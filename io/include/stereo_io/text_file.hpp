// Small text inputs (calibrations, pose files, frame lists) read whole and bounded, so that a
// device such as /dev/zero, a FIFO or a huge file named as a calibration fails with one line
// instead of being read without end (docs/reliability.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace stereo::io {

// The largest text input read: calibration, pose and list files are kilobytes to megabytes.
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t{64} << 20;

// The bytes of the regular file `path`. `what` names the file in messages ("calibration file").
// Throws std::runtime_error when it is missing, not a regular file (directory, device, FIFO) or
// unreadable, std::invalid_argument when it is larger than `max_bytes`.
std::string read_text_file(const std::filesystem::path& path, const std::string& what,
                           std::uintmax_t max_bytes = kMaxTextFileBytes);

}  // namespace stereo::io
