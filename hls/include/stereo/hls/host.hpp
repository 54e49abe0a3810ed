// Host-side helpers around stereo_hls_top (C simulation only, never synthesised): the frame
// configuration from MatchParams, and an image pair to and from the beat streams.
#pragma once

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "stereo/hls/stream.hpp"
#include "stereo/hls/types.hpp"
#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"

namespace stereo::hls {

// The cfg_* values of a frame for a top synthesised with WINDOW taps: the model's integer
// Gaussian (stereo::gaussian_kernel) of params.window taps, centred in the WINDOW taps with
// zeros around it, as the RTL takes a smaller runtime window.
template <int WINDOW>
FrameConfig<WINDOW> frame_config(const MatchParams& params, int width, int height) {
    if (params.window > WINDOW) {
        throw std::invalid_argument("window " + std::to_string(params.window) +
                                    " is larger than the synthesised window " +
                                    std::to_string(WINDOW));
    }
    const std::vector<std::int32_t> taps = gaussian_kernel(params.window, params.sigma);
    FrameConfig<WINDOW> cfg;
    cfg.width = width;
    cfg.height = height;
    cfg.ndisp = params.ndisp;
    cfg.radius = params.window / 2;
    cfg.use_ca = params.use_ca;
    cfg.min_disp = params.min_disp;
    cfg.uniqueness = params.validation.uniqueness;
    cfg.uniqueness_ratio = params.validation.uniqueness_ratio;
    cfg.left_right = params.validation.left_right;
    cfg.lr_tolerance = params.validation.lr_tolerance;
    cfg.subpixel = params.validation.subpixel;
    const int first = (WINDOW - params.window) / 2;
    for (std::size_t i = 0; i < taps.size(); ++i) {
        cfg.kernel[first + static_cast<int>(i)] = static_cast<tap_t>(taps[i]);
    }
    return cfg;
}

// The pixel (x, y) as the kernels take it: a grey pixel g becomes (g, g, g), which is how the
// model matches grey input.
inline Rgb rgb(const Image& image, int x, int y) {
    const int c1 = image.channels == 3 ? 1 : 0;
    const int c2 = image.channels == 3 ? 2 : 0;
    return Rgb{image.at(x, y, 0), image.at(x, y, c1), image.at(x, y, c2)};
}

// Writes the pair as width*height beats in raster order (rgb()).
inline void push_frame(const Image& left, const Image& right, stream<InputBeat>& in) {
    check_pair(left, right);
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < left.width; ++x) {
            InputBeat beat;
            beat.left = rgb(left, x, y);
            beat.right = rgb(right, x, y);
            beat.sof = x == 0 && y == 0;
            beat.eol = x == left.width - 1;
            in.write(beat);
        }
    }
}

// Reads one frame of width*height beats; throws std::logic_error when a beat is missing or
// its sof/eol framing is wrong.
inline ValidatedDisparity collect_validated(stream<OutputBeat>& out, int width, int height) {
    ValidatedDisparity map(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (out.empty()) {
                throw std::logic_error("HLS top wrote " + std::to_string(y * width + x) +
                                       " output beats, expected " + std::to_string(width * height));
            }
            const OutputBeat beat = out.read();
            if (beat.sof != (x == 0 && y == 0) || beat.eol != (x == width - 1)) {
                throw std::logic_error("HLS top framing wrong at output (" + std::to_string(x) +
                                       ", " + std::to_string(y) + ")");
            }
            const std::size_t i = map.index(x, y);
            map.fixed[i] = beat.result.fixed;
            map.reason[i] = beat.result.reason;
            map.certainty[i] = beat.result.certainty;
        }
    }
    return map;
}

// The frame a top wrote for one pushed frame, after checking that it reported no status, read
// every input beat and wrote no beat beyond the frame; `top` names it in the errors.
inline ValidatedDisparity finish_frame(const std::string& top, status_t status,
                                       const stream<InputBeat>& in, stream<OutputBeat>& out,
                                       int width, int height) {
    if (status != 0 || !in.empty()) {
        throw std::logic_error(top + " reported status " + std::to_string(status) + " with " +
                               std::to_string(in.size()) + " input beats left");
    }
    ValidatedDisparity map = collect_validated(out, width, height);
    if (!out.empty()) {
        throw std::logic_error(top + " wrote " + std::to_string(out.size()) +
                               " output beats too many");
    }
    return map;
}

// Its 8-bit view (stereo::to_label_map).
inline DisparityMap collect_frame(stream<OutputBeat>& out, int width, int height) {
    return to_label_map(collect_validated(out, width, height));
}

}  // namespace stereo::hls
