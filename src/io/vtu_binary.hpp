// The binary data of a VTK XML DataArray (.vtu), as VTK's vtkXMLDataParser
// reads it, wherever it is: inline base64 text, or appended data (raw bytes
// or base64 text) from the array's offset.  Header values are UInt32 or
// UInt64 (the file's header_type), little-endian.
//
//   uncompressed  [size], then `size` bytes
//   compressed    [n, block_size, last_size, csize_1 .. csize_n], then the n
//                 blocks of csize_1 .. csize_n bytes, each one zlib stream;
//                 every block inflates to block_size bytes, the last to
//                 last_size (to block_size when last_size is 0)
//
// In base64 the header and the data may be encoded together or separately
// (padding may end any group of four characters).  Nothing is allocated
// from a size in the header before the bytes present are known to hold it:
// the header's sizes are checked against the bytes that follow, a block
// may claim no more than zlib can inflate from its size (1032:1), and the
// inflated data grows only as zlib produces it, never past the claim.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace bodt {

// The compressors of VTK's XML writers; only zlib's data is read.
enum class VtkCompressor { None, ZLib };

// Reports a problem at a position of the bytes (or text) read; must throw.
using VtuFail = std::function<void(size_t pos, const std::string& message)>;

// The bytes of one array, read front to back.
class VtuByteSource {
public:
    virtual ~VtuByteSource() = default;
    // At least as many bytes as are left.
    virtual uint64_t max_left() const = 0;
    // The next n bytes, valid until the next call; fails if fewer are left.
    virtual const uint8_t* take(size_t n) = 0;
};

// Bytes in memory (raw appended data).
class VtuRawBytes : public VtuByteSource {
public:
    VtuRawBytes(const uint8_t* data, size_t size, VtuFail fail) : data_(data), size_(size), fail_(std::move(fail)) {}
    uint64_t max_left() const override { return size_ - pos_; }
    const uint8_t* take(size_t n) override;

private:
    const uint8_t* data_;
    size_t size_, pos_ = 0;
    VtuFail fail_;
};

// Base64 text, decoded as it is read; whitespace is skipped, and the
// positions given to `fail` are those of the text.
class VtuBase64Bytes : public VtuByteSource {
public:
    VtuBase64Bytes(std::string_view text, VtuFail fail) : text_(text), fail_(std::move(fail)) {}
    uint64_t max_left() const override { return pending() + (text_.size() - pos_) / 4 * 3; }
    const uint8_t* take(size_t n) override;
    // Only whitespace is left (a group that follows is decoded: a bad one fails).
    bool at_end();

private:
    size_t pending() const { return buf_.size() - used_; }
    // Decodes the next group of four characters onto buf_; false at the end.
    bool decode_group();

    std::string_view text_;
    size_t pos_ = 0;
    std::vector<uint8_t> buf_;  // decoded; the first used_ bytes were taken
    size_t used_ = 0;
    VtuFail fail_;
};

// The data bytes of one array (header read and checked, blocks inflated),
// read from the front of `in`, which may hold more.  header_size is 4 or 8.
// `fail` reports a problem of the header or the blocks; it must throw.
std::vector<uint8_t> read_vtu_array_bytes(VtuByteSource& in, int header_size, VtkCompressor compressor,
                                          const std::function<void(const std::string&)>& fail);

}  // namespace bodt
