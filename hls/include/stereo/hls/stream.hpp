// stereo::hls::stream<T>: the FIFO between the kernels and their caller.
//
// It has the shape of the vendor's hls::stream (read(), write(), empty(), full(), size()), so
// the kernels are written once for both:
//   * Under Vitis HLS (__SYNTHESIS__ defined, or <hls_stream.h> on the include path, as in the
//     vendor's C simulation) stereo::hls::stream<T> is an alias of ::hls::stream<T>.
//   * Otherwise (plain g++ here) it is the class below, an unbounded std::deque: a model of a
//     FIFO for C simulation only, never part of the hardware. Define STEREO_HLS_OWN_STREAM to
//     force it even where the vendor header exists.
// Reading an empty stream throws std::runtime_error here, where the vendor's C simulation would
// warn and hang or return garbage: a test then fails at once with the stream's name.
#pragma once

#if !defined(STEREO_HLS_OWN_STREAM)
#if defined(__SYNTHESIS__)
#define STEREO_HLS_VENDOR_STREAM 1
#elif defined(__has_include)
#if __has_include(<hls_stream.h>)
#define STEREO_HLS_VENDOR_STREAM 1
#endif
#endif
#endif

#if defined(STEREO_HLS_VENDOR_STREAM)

#include <hls_stream.h>

namespace stereo::hls {
template <typename T>
using stream = ::hls::stream<T>;
}  // namespace stereo::hls

#else

#include <cstddef>
#include <deque>
#include <stdexcept>
#include <string>
#include <utility>

namespace stereo::hls {

template <typename T>
class stream {
  public:
    stream() = default;
    explicit stream(const char* name) : name_(name) {}
    stream(const stream&) = delete;  // a FIFO is a channel, not a value
    stream& operator=(const stream&) = delete;

    T read() {
        if (fifo_.empty()) {
            throw std::runtime_error("read from empty stream '" + name_ + "'");
        }
        T value = std::move(fifo_.front());
        fifo_.pop_front();
        return value;
    }
    void read(T& value) { value = read(); }
    bool read_nb(T& value) {
        if (fifo_.empty()) {
            return false;
        }
        value = read();
        return true;
    }

    void write(const T& value) { fifo_.push_back(value); }
    bool write_nb(const T& value) {
        write(value);
        return true;
    }

    bool empty() const { return fifo_.empty(); }
    bool full() const { return false; }  // unbounded in C simulation
    std::size_t size() const { return fifo_.size(); }

  private:
    std::string name_ = "stream";
    std::deque<T> fifo_;
};

}  // namespace stereo::hls

#endif
