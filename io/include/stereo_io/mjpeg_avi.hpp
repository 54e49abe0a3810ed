// Motion-JPEG video in an AVI 1.0 file, built in memory (for io::write_file_atomic).
//
// Why not cv::VideoWriter: Debian's libopencv_videoio links about a hundred shared libraries
// (FFmpeg, GStreamer, their codecs) that every process linking it loads at start, about 80 ms per
// `stereo` run (0.2 s instead of 0.12 s for `stereo --version`; four times that under ASan),
// paid by every command although only `avoid --overlay NAME.avi` writes a video. An MJPG AVI is a
// RIFF list of JPEG frames with a small header and an index; the JPEG frames come from
// imgcodecs, which every command loads anyway. Its structure follows Microsoft's AVI RIFF
// reference (AVIMAINHEADER, AVISTREAMHEADER, BITMAPINFOHEADER, AVIOLDINDEX).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace stereo::io {

// The largest file this writer makes: an AVI 1.0 file (no OpenDML extension) is read by every
// player up to 1 GiB.
inline constexpr std::uint64_t kMaxAviBytes = std::uint64_t{1} << 30;

// The bytes of an MJPG AVI file holding `frames` (8-bit, 3-channel BGR, all of one size) at
// `fps` frames per second, each frame a baseline JPEG of `jpeg_quality` (1-100; 95 is OpenCV's
// VideoWriter default). Throws std::invalid_argument for no frames, a frame of another size or
// type, fps not finite and positive or a quality out of range, and std::runtime_error when the
// file would exceed kMaxAviBytes.
std::string mjpeg_avi(const std::vector<cv::Mat>& frames, double fps, int jpeg_quality = 95);

}  // namespace stereo::io
