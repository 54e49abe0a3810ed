#include "stereo_io/point_cloud.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include <opencv2/core.hpp>

namespace stereo::io {
namespace {

static_assert(std::endian::native == std::endian::little, "binary PLY is written little-endian");

constexpr std::string_view kProperties =
    "property float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n";
constexpr std::size_t kBinaryVertexBytes = 3 * sizeof(float) + 3;

std::string header(std::size_t count, bool binary) {
    std::string out = "ply\nformat ";
    out += binary ? "binary_little_endian" : "ascii";
    out +=
        " 1.0\ncomment stereo cloud (docs/cli.md)\nelement vertex " + std::to_string(count) + "\n";
    out += kProperties;
    out += "end_header\n";
    return out;
}

[[noreturn]] void fail(const std::string& name, const std::string& what) {
    throw std::runtime_error(name + ": not a PLY file of stereo cloud's form (" + what + ")");
}

}  // namespace

void check_geometry(const CloudGeometry& g) {
    if (!std::isfinite(g.focal) || g.focal <= 0.0) {
        throw std::invalid_argument("the focal length must be a positive number of pixels");
    }
    if (!std::isfinite(g.baseline) || g.baseline <= 0.0) {
        throw std::invalid_argument("the baseline must be positive");
    }
    if (!std::isfinite(g.cx) || !std::isfinite(g.cy) || !std::isfinite(g.doffs)) {
        throw std::invalid_argument("the principal point and the disparity offset must be finite");
    }
}

std::vector<CloudPoint> disparity_to_points(const cv::Mat& disparity, const cv::Mat& bgr,
                                            const CloudGeometry& geometry) {
    check_geometry(geometry);
    if (disparity.type() != CV_32FC1 || (bgr.type() != CV_8UC3 && bgr.type() != CV_8UC1)) {
        throw std::invalid_argument("a cloud needs a float disparity map and an 8-bit image");
    }
    if (disparity.size() != bgr.size()) {
        throw std::invalid_argument("the disparity map is " + std::to_string(disparity.cols) + "x" +
                                    std::to_string(disparity.rows) + " but the image is " +
                                    std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows));
    }
    std::vector<CloudPoint> points;
    const double fb = geometry.focal * geometry.baseline;
    for (int y = 0; y < disparity.rows; ++y) {
        for (int x = 0; x < disparity.cols; ++x) {
            const double d = disparity.at<float>(y, x) + geometry.doffs;
            if (!std::isfinite(d) || d <= 0.0) {
                continue;
            }
            const double z = fb / d;
            CloudPoint p;
            p.x = static_cast<float>((x - geometry.cx) * z / geometry.focal);
            p.y = static_cast<float>((y - geometry.cy) * z / geometry.focal);
            p.z = static_cast<float>(z);
            // A derived check: the PLY stores 32-bit floats, so a focal length and baseline
            // whose depths overflow them (1e308 each gave a cloud of inf) are refused.
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                throw std::invalid_argument(
                    "the geometry gives points beyond 32-bit floats (f x B / d = " +
                    std::to_string(z) + " at pixel " + std::to_string(x) + "," + std::to_string(y) +
                    "): check the focal length and the baseline");
            }
            if (bgr.type() == CV_8UC3) {
                const auto& c = bgr.at<cv::Vec3b>(y, x);
                p.red = c[2];
                p.green = c[1];
                p.blue = c[0];
            } else {
                p.red = p.green = p.blue = bgr.at<std::uint8_t>(y, x);
            }
            points.push_back(p);
        }
    }
    return points;
}

std::string encode_ply(const std::vector<CloudPoint>& points, bool binary) {
    std::string out = header(points.size(), binary);
    if (binary) {
        out.reserve(out.size() + points.size() * kBinaryVertexBytes);
        for (const CloudPoint& p : points) {
            for (const float v : {p.x, p.y, p.z}) {
                char bytes[sizeof(float)];
                std::memcpy(bytes, &v, sizeof v);
                out.append(bytes, sizeof bytes);
            }
            out.push_back(static_cast<char>(p.red));
            out.push_back(static_cast<char>(p.green));
            out.push_back(static_cast<char>(p.blue));
        }
        return out;
    }
    std::ostringstream text;
    text.precision(9);  // enough digits for a float to read back exactly
    for (const CloudPoint& p : points) {
        text << p.x << ' ' << p.y << ' ' << p.z << ' ' << int{p.red} << ' ' << int{p.green} << ' '
             << int{p.blue} << '\n';
    }
    return out + text.str();
}

std::vector<CloudPoint> decode_ply(std::string_view bytes, const std::string& name) {
    const std::size_t end = bytes.find("end_header\n");
    if (!bytes.starts_with("ply\n") || end == std::string_view::npos) {
        fail(name, "no ply header");
    }
    const std::string head(bytes.substr(0, end));
    const bool binary = head.find("format binary_little_endian 1.0\n") != std::string::npos;
    if (!binary && head.find("format ascii 1.0\n") == std::string::npos) {
        fail(name, "format");
    }
    if (head.find(kProperties) == std::string::npos) {
        fail(name, "vertex properties");
    }
    const std::size_t at = head.find("element vertex ");
    if (at == std::string::npos) {
        fail(name, "no vertex element");
    }
    const long long count = std::stoll(head.substr(at + 15));
    if (count < 0) {
        fail(name, "vertex count");
    }
    const std::string_view body = bytes.substr(end + 11);
    std::vector<CloudPoint> points(static_cast<std::size_t>(count));
    if (binary) {
        if (body.size() != points.size() * kBinaryVertexBytes) {
            fail(name, "body length");
        }
        for (std::size_t i = 0; i < points.size(); ++i) {
            const char* v = body.data() + i * kBinaryVertexBytes;
            std::memcpy(&points[i].x, v, sizeof(float));
            std::memcpy(&points[i].y, v + 4, sizeof(float));
            std::memcpy(&points[i].z, v + 8, sizeof(float));
            points[i].red = static_cast<std::uint8_t>(v[12]);
            points[i].green = static_cast<std::uint8_t>(v[13]);
            points[i].blue = static_cast<std::uint8_t>(v[14]);
        }
        return points;
    }
    std::istringstream text{std::string(body)};
    for (CloudPoint& p : points) {
        int r = 0;
        int g = 0;
        int b = 0;
        if (!(text >> p.x >> p.y >> p.z >> r >> g >> b) || r < 0 || r > 255 || g < 0 || g > 255 ||
            b < 0 || b > 255) {
            fail(name, "vertex line");
        }
        p.red = static_cast<std::uint8_t>(r);
        p.green = static_cast<std::uint8_t>(g);
        p.blue = static_cast<std::uint8_t>(b);
    }
    return points;
}

}  // namespace stereo::io
