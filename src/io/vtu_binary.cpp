// Binary DataArray data of .vtu files: see vtu_binary.hpp.
#include "io/vtu_binary.hpp"

#include "io/byte_order.hpp"

#include <zlib.h>

#include <algorithm>
#include <climits>
#include <cstring>

namespace bodt {

namespace {

// Deflate's largest compression ratio (a 258-byte match in at most 2 bits
// of code): no valid zlib stream inflates to more than 1032 times its size.
constexpr uint64_t kMaxInflateRatio = 1032;
// Output of inflate is added in pieces of at most this many bytes, so that
// a block claiming more than its stream holds costs no more than this.
constexpr size_t kInflateChunk = size_t{1} << 20;

// Inflates the zlib stream in[0, in_size) onto the end of `out`: it must
// give exactly `size` bytes and end with the input.  Returns what is wrong,
// or an empty string.
std::string inflate_block(const uint8_t* in, uint32_t in_size, uint32_t size, std::vector<uint8_t>& out) {
    z_stream zs{};
    if (inflateInit(&zs) != Z_OK) return "zlib could not start (out of memory)";
    zs.next_in = const_cast<Bytef*>(in);  // zlib's API is not const; it only reads
    zs.avail_in = in_size;
    const size_t start = out.size();
    size_t done = 0;
    int rc = Z_OK;
    while (rc == Z_OK && done < size) {
        const size_t chunk = std::min<size_t>(size - done, kInflateChunk);
        out.resize(start + done + chunk);
        zs.next_out = out.data() + start + done;
        zs.avail_out = static_cast<uInt>(chunk);
        rc = inflate(&zs, Z_NO_FLUSH);
        done += chunk - zs.avail_out;
        out.resize(start + done);
    }
    bool longer = false;
    if (rc == Z_OK && done == size) {
        // All the bytes claimed: the stream must end here.
        uint8_t extra;
        zs.next_out = &extra;
        zs.avail_out = 1;
        rc = inflate(&zs, Z_NO_FLUSH);
        longer = zs.avail_out == 0;
    }
    const std::string zmsg = zs.msg ? zs.msg : "";
    const uInt trailing = zs.avail_in;
    inflateEnd(&zs);
    if (longer) return "inflates to more than the " + std::to_string(size) + " bytes it claims";
    if (rc == Z_STREAM_END) {
        if (done != size)
            return "inflates to " + std::to_string(done) + " bytes, not the " + std::to_string(size) + " it claims";
        if (trailing != 0) return "has " + std::to_string(trailing) + " bytes after the end of its zlib stream";
        return {};
    }
    if (rc == Z_DATA_ERROR) return "is not valid zlib data (" + zmsg + ")";
    if (rc == Z_NEED_DICT) return "needs a preset zlib dictionary";
    if (rc == Z_MEM_ERROR) return "could not be inflated (out of memory)";
    return "ends before its zlib stream does (truncated)";  // Z_BUF_ERROR: no input left
}

}  // namespace

const uint8_t* VtuRawBytes::take(size_t n) {
    if (n > size_ - pos_)
        fail_(pos_, "the data ends after " + std::to_string(size_ - pos_) + " of the " + std::to_string(n) +
                        " bytes needed");
    const uint8_t* p = data_ + pos_;
    pos_ += n;
    return p;
}

bool VtuBase64Bytes::decode_group() {
    uint32_t group = 0;
    int n = 0, pad = 0;
    size_t group_start = pos_;
    for (; pos_ < text_.size() && n < 4; ++pos_) {
        const char c = text_[pos_];
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r') continue;
        int v = 0;
        if (c >= 'A' && c <= 'Z') v = c - 'A';
        else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
        else if (c >= '0' && c <= '9') v = c - '0' + 52;
        else if (c == '+') v = 62;
        else if (c == '/') v = 63;
        else if (c == '=') v = -1;
        else fail_(pos_, std::string("invalid character '") + c + "'");
        if (n == 0) group_start = pos_;
        if (v < 0) {
            if (n < 2) fail_(pos_, "misplaced '='");
            ++pad;
            v = 0;
        } else if (pad > 0) {
            fail_(pos_, "data after '=' within a group of 4");
        }
        group = (group << 6) | static_cast<uint32_t>(v);
        ++n;
    }
    if (n == 0) return false;
    if (n < 4) fail_(group_start, "truncated data (the length is not a multiple of 4)");
    buf_.push_back(static_cast<uint8_t>(group >> 16));
    if (pad < 2) buf_.push_back(static_cast<uint8_t>(group >> 8));
    if (pad < 1) buf_.push_back(static_cast<uint8_t>(group));
    return true;
}

const uint8_t* VtuBase64Bytes::take(size_t n) {
    buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(used_));
    used_ = 0;
    while (buf_.size() < n)
        if (!decode_group())
            fail_(pos_, "the data ends after " + std::to_string(buf_.size()) + " of the " + std::to_string(n) +
                            " bytes needed");
    used_ = n;
    return buf_.data();
}

bool VtuBase64Bytes::at_end() {
    return pending() == 0 && !decode_group();
}

std::vector<uint8_t> read_vtu_array_bytes(VtuByteSource& in, int header_size, VtkCompressor compressor,
                                          const std::function<void(const std::string&)>& fail) {
    const uint64_t hs = static_cast<uint64_t>(header_size);
    // `count` header values; the bytes that follow must hold them.
    auto header = [&](uint64_t count, const std::string& what) {
        if (count > in.max_left() / hs)
            fail(what + ": " + std::to_string(count) + " x " + std::to_string(hs) +
                 " bytes needed, but at most " + std::to_string(in.max_left()) + " follow");
        const uint8_t* p = in.take(static_cast<size_t>(count * hs));
        std::vector<uint64_t> v(static_cast<size_t>(count));
        for (size_t k = 0; k < v.size(); ++k) v[k] = load_uint(p + k * hs, header_size, false);
        return v;
    };

    if (compressor == VtkCompressor::None) {
        const uint64_t size = header(1, "the header")[0];
        if (size > in.max_left())
            fail("the header says " + std::to_string(size) + " bytes of data, but at most " +
                 std::to_string(in.max_left()) + " follow");
        const uint8_t* p = in.take(static_cast<size_t>(size));
        return std::vector<uint8_t>(p, p + size);
    }

    const std::vector<uint64_t> h = header(3, "the compression header's block count and sizes");
    const uint64_t blocks = h[0], block_size = h[1], last_size = h[2];
    if (last_size > block_size)
        fail("the compression header's last block size " + std::to_string(last_size) +
             " is larger than its block size " + std::to_string(block_size));
    const std::vector<uint64_t> csize =
        header(blocks, "the compressed sizes of the " + std::to_string(blocks) + " blocks");
    uint64_t total = 0;
    for (uint64_t c : csize) {
        if (c > in.max_left() - total)
            fail("the " + std::to_string(blocks) + " compressed blocks need more than the " +
                 std::to_string(in.max_left()) + " bytes that follow");
        total += c;
    }
    const uint8_t* data = in.take(static_cast<size_t>(total));
    std::vector<uint8_t> out;
    for (uint64_t k = 0; k < blocks; ++k) {
        const uint64_t claim = k + 1 == blocks && last_size != 0 ? last_size : block_size;
        const std::string block = "compressed block " + std::to_string(k + 1) + " of " + std::to_string(blocks);
        if (csize[k] > UINT32_MAX || claim > UINT32_MAX) fail(block + " is larger than 4 GiB");
        if (claim > kMaxInflateRatio * csize[k])
            fail(block + " claims " + std::to_string(claim) + " bytes from " + std::to_string(csize[k]) +
                 " compressed bytes, more than zlib can inflate (1032:1)");
        const std::string problem =
            inflate_block(data, static_cast<uint32_t>(csize[k]), static_cast<uint32_t>(claim), out);
        if (!problem.empty()) fail(block + " " + problem);
        data += csize[k];
    }
    return out;
}

}  // namespace bodt
