// The pixel bound that the decode itself enforces (docs/reliability.md, "Bounded inputs").
//
// OpenCV's decoders size the image from their own header parse (libjpeg, libpng, libtiff,
// libwebp, OpenCV's BMP and PNM readers) and allocate it as a cv::Mat before decoding a pixel.
// While a PixelBudget lives on a thread, OpenCV's default matrix allocator refuses every matrix
// of more than the budget's elements allocated on that thread, so that no header reader of ours,
// however wrong, can let a larger image be decoded: the number checked is the decoder's own.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>

namespace stereo::io::detail {

class PixelBudget {
  public:
    // Installs the guarding allocator (once per process, or again when something replaced
    // OpenCV's default allocator since) and opens a budget of `pixels` on this thread.
    explicit PixelBudget(std::int64_t pixels);
    ~PixelBudget();
    PixelBudget(const PixelBudget&) = delete;
    PixelBudget& operator=(const PixelBudget&) = delete;

    // Width and height (columns x rows; elements of a matrix of other dimensions as width, 1) of
    // the first matrix refused under this budget, if one was.
    std::optional<std::pair<std::int64_t, std::int64_t>> refused() const;

  private:
    std::int64_t outer_pixels_;
};

}  // namespace stereo::io::detail
