// Image and disparity-map files for the host tools.
//
// Error convention: a file that is missing, unreadable or of an unsupported format raises
// std::runtime_error; inputs that are readable but do not fit together (sizes, scales) raise
// std::invalid_argument. Every message is one line and names the file.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "stereo/image.hpp"

namespace stereo::io {

struct ImagePair {
    Image left;
    Image right;
};

// Reads an 8-bit image with 1, 3 or 4 channels into RGB (or grey) order; alpha is dropped.
// `downscale` (>= 1) shrinks both sides by that integer factor with area averaging.
Image load_image(const std::filesystem::path& path, int downscale = 1);

// Loads both images and checks that they have the same size before any downscale.
ImagePair load_pair(const std::filesystem::path& left, const std::filesystem::path& right,
                    int downscale = 1);

// The width x height region of `image` whose top-left pixel is (x0, y0), copied. Throws
// std::invalid_argument when the region is empty or does not lie inside the image.
Image crop(const Image& image, int x0, int y0, int width, int height);

// The same region of both images of a pair.
ImagePair crop(const ImagePair& pair, int x0, int y0, int width, int height);

// Reads an 8-bit image file as BGR, OpenCV's channel order (grey replicated, alpha dropped):
// for figures and the OpenCV baselines. Same errors as load_image.
cv::Mat load_bgr(const std::filesystem::path& path);

// The checks every image load makes before reading a byte: `path` exists, is a regular file
// (not a folder, device or FIFO) and is at most kMaxImageFileBytes; std::runtime_error naming the
// file otherwise. For sequences, to refuse a bad frame before the first one is processed.
void check_image_file(const std::filesystem::path& path);

// Reads an image file as 8-bit grey, converted as cv::imread(IMREAD_GRAYSCALE) does, with the
// checks and errors of load_image (regular file, size from the header, one-line messages).
cv::Mat load_grey(const std::filesystem::path& path);

// Decodes an image file's bytes with cv::imdecode(`flags`) under the pixel limit, enforced inside
// the decode: while it runs, every matrix allocated on this thread (the image, which the decoder
// sizes from its own reading of the header, and any temporary) is refused above
// max_image_pixels() before its memory is reserved. Throws std::invalid_argument naming `name`
// ("image NAME decodes to WxH pixels, more than the limit ...") for such a file; returns an empty
// matrix when OpenCV cannot decode the bytes. Reads no header itself: the loaders above check
// declared_image() first, for an early message and for the buffers that are no matrix (TIFF tiles).
cv::Mat decode_bounded(const std::vector<unsigned char>& bytes, int flags, const std::string& name);

// Converts an 8-bit OpenCV matrix (grey, BGR or BGRA) into an Image; `name` is for messages.
Image to_image(const cv::Mat& mat, const std::string& name);

// The inverse for drawing: an Image (grey or RGB) as an 8-bit BGR matrix.
cv::Mat to_bgr(const Image& image);

// Area averaging (OpenCV INTER_AREA) to floor(W/F) x floor(H/F); F = 1 returns `mat` itself.
// Throws std::invalid_argument when F < 1 or the result would be empty. The host's input
// shrink, not the model's bit-exact integer mean (stereo::hierarchical::downscale_area).
cv::Mat shrink_area(const cv::Mat& mat, int downscale);

// Whether the extension names an image file the tools read (png, jpg, ppm, ...; any case).
bool is_image_file(const std::filesystem::path& path);

// Names (not paths) of the image files directly inside `folder`, sorted. Throws
// std::runtime_error "cannot read image folder ..." when `folder` is not a directory.
std::vector<std::string> image_file_names(const std::filesystem::path& folder);

// Throws std::invalid_argument unless disparities 0..ndisp-1 times `scale` fit a 16-bit PNG.
void check_disparity_scale(int ndisp, int scale);

// The stored form of a disparity map: disparity * scale, 0 where invalid. The matrix is 8-bit
// when (ndisp - 1) * scale <= 255, else 16-bit.
cv::Mat disparity_to_mat(const DisparityMap& map, int ndisp, int scale);

// A colour view for people: disparity spread over 0..255 by ndisp - 1, colour-mapped (turbo),
// invalid pixels black. Returned in OpenCV's BGR order, ready for write_png.
cv::Mat disparity_to_colour(const DisparityMap& map, int ndisp);

// The same view of a float disparity map (ground truth, OpenCV output) where 0 means none.
cv::Mat float_disparity_to_colour(const cv::Mat& disparity, int ndisp);

// Our map as float disparities, 0 where invalid: the form evaluate() and the figures take.
cv::Mat to_float_disparity(const DisparityMap& map);

// Reads a disparity or ground-truth PNG (8 or 16 bit, grey or 3 equal channels) as float
// disparity = value / scale; 0 stays 0 and means invalid (ours) or unknown (ground truth).
cv::Mat load_disparity(const std::filesystem::path& path, double scale);

// The bytes of an input file: a regular file of at most kMaxImageFileBytes, with a one-line
// error naming it otherwise.
std::vector<unsigned char> read_input_file(const std::filesystem::path& path);

// Brings a full-size ground truth (CV_32FC1) or mask (CV_8UC1) to the grid of an image loaded
// with `downscale` F: floor(W/F) x floor(H/F), each pixel sampled at the centre of its F x F
// block, (F*x + F/2, F*y + F/2). Ground-truth disparities are divided by F (unknown stays 0);
// mask values are kept. Sampling, not averaging, so that unknown pixels and mask labels never
// blend with their neighbours.
cv::Mat downscale_ground_truth(const cv::Mat& ground_truth, int downscale);
cv::Mat downscale_mask(const cv::Mat& mask, int downscale);

// Reads an 8-bit evaluation mask (grey or 3 equal channels) as CV_8UC1.
cv::Mat load_mask(const std::filesystem::path& path);

// Encodes `mat` as PNG in memory, then writes it with write_file_atomic (stereo_io/output.hpp):
// a failure never leaves a partial file behind nor harms an existing one.
void write_png(const std::filesystem::path& path, const cv::Mat& mat);

// `mat` as PNG bytes; std::runtime_error naming `path` when it cannot be encoded.
std::string encode_png(const cv::Mat& mat, const std::filesystem::path& path);

// Several PNGs, all or nothing (write_files_atomic): a set of figures or a distorted scene.
void write_pngs(const std::vector<std::pair<std::filesystem::path, cv::Mat>>& files);

// Throws std::runtime_error when `path` could not be created because its folder is missing;
// used to fail before a long computation rather than after it.
void check_writable_location(const std::filesystem::path& path);

// The same for an output folder a command creates (figure sets, level maps): std::runtime_error
// unless `folder` is an existing folder or does not exist and its parent folder does.
void check_output_folder(const std::filesystem::path& folder);

}  // namespace stereo::io
