// Medit binary .meshb, the layout of Loic Marechal's libMeshb (INRIA Gamma;
// https://github.com/LoicMarechal/libMeshb, sources/libmeshb7.c: GmfOpenMesh,
// GmfSetKwd, GmfCloseMesh, ScaKwdTab, ScaKwdHdr, ExpFmt, GetPos/SetPos):
//
//   int32 code     1, written in the writer's byte order: a reader that sees
//                  0x01000000 swaps every word (4- and 8-byte values alike)
//   int32 version  1: 32-bit reals, ints and positions
//                  2: 64-bit reals, 32-bit ints and positions
//                  3: 64-bit reals, 32-bit ints, 64-bit positions
//                  4: 64-bit reals, 64-bit ints and positions
//   keywords, each
//     int32 code, then the absolute byte position of the next keyword
//     (int32 for versions 1-2, int64 for 3-4), then
//     - Dimension (3): the dimension as an int32 (4 bytes in every version:
//       GmfOpenMesh reads it with ScaWrd), and it is the first keyword;
//     - a data keyword: the record count (an "int": 32 or 64 bits by
//       version), then the records: Vertices (4) x y z ref, Edges (5)
//       a b ref, Triangles (6) a b c ref, Tetrahedra (8) a b c d ref,
//       Corners (13), Ridges (14), RequiredVertices (15) one int each;
//     - End (54): last; libMeshb writes its position as 0.
//
// The mapping to MeshData is that of the ASCII reader (medit.cpp): vertex
// ref -> vertex_refs, tet ref -> region, triangle ref -> marker, every edge
// of Edges -> a feature edge with its ref in edge_refs, Corners -> corners,
// RequiredVertices -> fixed.  Ridges adds nothing (every edge is a feature
// edge already) but its indices must name edges.  A write lists every edge
// in Ridges, for tools that take only ridges as feature lines.  Every other
// keyword, known to libMeshb or not, is skipped by its next-keyword
// position.  A data keyword other than Vertices may come more than once
// (meshio writes one per cell block): repeated keywords are appended in file
// order, and Ridges number the edges of all Edges keywords in that order.
// libMeshb keeps one position per keyword code (ScaKwdHdr overwrites it), so
// it reads only the last of each; appending reads meshio's files as meshio
// meant them.  A second Vertices keyword is an error: the indices after it
// would be ambiguous.  Nothing in the file is trusted: every position must
// move forward and stay inside the file, every count must fit in the bytes
// before the next keyword (checked before allocating), every index must name
// a vertex or edge, every coordinate must be finite.  A problem is
// Error(BODT_ERR_IO, "<path>: byte <offset>: ...").
#include "io/medit_binary.hpp"

#include "io/byte_order.hpp"
#include "io/output_file.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

namespace bodt {

namespace {

constexpr int32_t kDimension = 3;
constexpr int32_t kVertices = 4;
constexpr int32_t kEdges = 5;
constexpr int32_t kTriangles = 6;
constexpr int32_t kTetrahedra = 8;
constexpr int32_t kCorners = 13;
constexpr int32_t kRidges = 14;
constexpr int32_t kRequiredVertices = 15;
constexpr int32_t kEnd = 54;

const char* keyword_name(int32_t code) {
    switch (code) {
        case kDimension:
            return "Dimension";
        case kVertices:
            return "Vertices";
        case kEdges:
            return "Edges";
        case kTriangles:
            return "Triangles";
        case kTetrahedra:
            return "Tetrahedra";
        case kCorners:
            return "Corners";
        case kRidges:
            return "Ridges";
        case kRequiredVertices:
            return "RequiredVertices";
        case kEnd:
            return "End";
        default:
            return nullptr;
    }
}

// "Vertices (4)", or "keyword 200" for a code not read here.
std::string describe(int32_t code) {
    const char* name = keyword_name(code);
    return name ? std::string(name) + " (" + std::to_string(code) + ")" : "keyword " + std::to_string(code);
}

// ---------------------------------------------------------------- reading

// Sizes of the file's values, from its version.
struct Layout {
    bool big_endian = false;
    int version = 0;
    int int_size = 4;   // ints: vertex indices, refs, counts
    int real_size = 8;  // coordinates
    int pos_size = 4;   // next-keyword positions
};

// A signed int of 4 or 8 bytes.
int64_t load_int(const unsigned char* p, int size, bool big_endian) {
    const uint64_t v = load_uint(p, size, big_endian);
    if (size == 4) return static_cast<int32_t>(static_cast<uint32_t>(v));
    return static_cast<int64_t>(v);
}

double load_real(const unsigned char* p, int size, bool big_endian) {
    const uint64_t v = load_uint(p, size, big_endian);
    if (size == 4) {
        const uint32_t bits = static_cast<uint32_t>(v);
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return static_cast<double>(f);
    }
    double d;
    std::memcpy(&d, &v, sizeof d);
    return d;
}

// The file, read at given offsets with every read checked against its size.
class InputFile {
public:
    explicit InputFile(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "rb")) {
        if (!file_) throw Error(BODT_ERR_IO, path + ": cannot open for reading: " + std::strerror(errno));
        if (fseeko(file_, 0, SEEK_END) != 0 || (size_ = ftello(file_)) < 0) {
            std::fclose(file_);
            throw Error(BODT_ERR_IO, path + ": byte 0: cannot find the size of the file");
        }
    }
    ~InputFile() { std::fclose(file_); }
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    int64_t size() const { return size_; }

    [[noreturn]] void fail(int64_t offset, const std::string& message) const {
        throw Error(BODT_ERR_IO, path_ + ": byte " + std::to_string(offset) + ": " + message);
    }

    // `n` bytes at `offset`, or an error naming `what` if the file is shorter.
    void read(int64_t offset, int64_t n, unsigned char* out, const std::string& what) {
        if (offset < 0 || n < 0 || offset > size_ || n > size_ - offset)
            fail(offset, "the file is truncated: " + what + " needs " + std::to_string(n) +
                             " bytes here, the file has " + std::to_string(size_) + " bytes");
        if (n == 0) return;
        // Seeks only when not there already: the sections are read in
        // sequence, and each seek is a system call (a file of many small
        // sections would spend most of its time in them).
        if ((offset != at_ && fseeko(file_, static_cast<off_t>(offset), SEEK_SET) != 0) ||
            std::fread(out, 1, static_cast<size_t>(n), file_) != static_cast<size_t>(n))
            fail(offset, "reading " + what + " failed");  // the reader ends here: at_ is not needed again
        at_ = offset + n;
    }

    std::vector<unsigned char> read(int64_t offset, int64_t n, const std::string& what) {
        // Checked before allocating: n never exceeds what the file holds.
        if (offset < 0 || n < 0 || offset > size_ || n > size_ - offset) read(offset, n, nullptr, what);
        std::vector<unsigned char> bytes(static_cast<size_t>(n));
        read(offset, n, bytes.data(), what);
        return bytes;
    }

private:
    std::string path_;
    FILE* file_;
    int64_t size_ = 0;
    int64_t at_ = -1;  // the stream's position once a read has set it
};

// One keyword of the file.
struct Keyword {
    int32_t code;
    int64_t at;    // offset of its code
    int64_t data;  // offset just after its next-keyword position
    int64_t next;  // offset of the next keyword
};

// A data keyword's records, read at once.
struct Records {
    int64_t count = 0;
    int64_t first = 0;  // offset of the first record
    int64_t size = 0;   // bytes per record
    std::vector<unsigned char> bytes;

    const unsigned char* record(int64_t r) const { return bytes.data() + r * size; }
    int64_t offset(int64_t r, int64_t field_bytes) const { return first + r * size + field_bytes; }
};

class Reader {
public:
    explicit Reader(const std::string& path) : in_(path) {}

    MeshData read() {
        read_header();
        return read_sections();
    }

private:
    InputFile in_;
    Layout lay_;
    int64_t end_at_ = 0;

    void read_header() {
        unsigned char b[8];
        if (in_.size() < 8)
            in_.fail(in_.size(), "the file is truncated: a .meshb file starts with 8 bytes (code and version)");
        in_.read(0, 8, b, "the header");
        if (load_uint(b, 4, false) == 1)
            lay_.big_endian = false;
        else if (load_uint(b, 4, true) == 1)
            lay_.big_endian = true;
        else {
            char hex[16];
            std::snprintf(hex, sizeof hex, "0x%08llx", static_cast<unsigned long long>(load_uint(b, 4, false)));
            in_.fail(0,
                     std::string("not a Medit binary mesh: the first word is ") + hex + ", not 1 in either byte order");
        }
        const int64_t version = load_int(b + 4, 4, lay_.big_endian);
        if (version < 1 || version > 4) in_.fail(4, "unknown .meshb version " + std::to_string(version) + " (1 to 4)");
        lay_.version = static_cast<int>(version);
        lay_.real_size = version == 1 ? 4 : 8;
        lay_.int_size = version == 4 ? 8 : 4;
        lay_.pos_size = version >= 3 ? 8 : 4;
    }

    // Walks the keyword chain from byte 8 to End, calling visit(keyword) for
    // each keyword before End.  Each position must lie past the keyword's
    // header and inside the file, so the walk moves forward at every step
    // and ends.  Nothing is kept per keyword: memory does not grow with
    // their number.
    template <class Visit>
    void walk_keywords(Visit&& visit) {
        int64_t at = 8;
        for (;;) {
            if (at == in_.size()) in_.fail(at, "no End keyword: the file ends after the last keyword");
            unsigned char b[12];
            in_.read(at, 4, b, "a keyword code");
            const int32_t code = static_cast<int32_t>(load_int(b, 4, lay_.big_endian));
            if (at == 8 && code != kDimension)
                in_.fail(at, "the first keyword is " + std::to_string(code) + ", not Dimension (3)");
            if (code == kEnd) {
                // libMeshb writes a position 0 after End; nothing after End is read.
                end_at_ = at;
                return;
            }
            in_.read(at + 4, lay_.pos_size, b + 4, "the next-keyword position of " + describe(code));
            const int64_t next = load_int(b + 4, lay_.pos_size, lay_.big_endian);
            const int64_t data = at + 4 + lay_.pos_size;
            if (next == 0)
                in_.fail(at + 4,
                         describe(code) + " has next-keyword position 0 but is not End: the file has no End keyword");
            if (next < data)
                in_.fail(at + 4, describe(code) + " has next-keyword position " + std::to_string(next) +
                                     ", which does not move forward (its data starts at byte " + std::to_string(data) +
                                     ")");
            if (next > in_.size())
                in_.fail(at + 4, describe(code) + " has next-keyword position " + std::to_string(next) +
                                     ", past the end of the file (" + std::to_string(in_.size()) + " bytes)");
            if (code == kDimension) {
                if (next - data < 4) in_.fail(data, "the Dimension keyword has no room for its value");
                in_.read(data, 4, b, "the dimension");
                const int64_t dim = load_int(b, 4, lay_.big_endian);
                if (dim != 3)
                    in_.fail(data, "only 3-D meshes are supported, the file has Dimension " + std::to_string(dim));
            }
            visit(Keyword{code, at, data, next});
            at = next;
        }
    }

    // The count and records of a data keyword with `fields` ints and `reals`
    // reals per record.
    Records records(const Keyword& k, int fields, int reals) {
        const char* name = keyword_name(k.code);
        Records r;
        const int64_t room = k.next - k.data;
        if (room < lay_.int_size)
            in_.fail(k.data, std::string(name) + " has no room for its count before the next keyword (byte " +
                                 std::to_string(k.next) + ")");
        unsigned char b[8];
        in_.read(k.data, lay_.int_size, b, std::string("the count of ") + name);
        r.count = load_int(b, lay_.int_size, lay_.big_endian);
        r.size = int64_t{fields} * lay_.int_size + int64_t{reals} * lay_.real_size;
        r.first = k.data + lay_.int_size;
        const int64_t available = (room - lay_.int_size) / r.size;
        if (r.count < 0) in_.fail(k.data, std::string(name) + " has a negative count " + std::to_string(r.count));
        if (r.count > available)
            in_.fail(k.data, std::string(name) + " count " + std::to_string(r.count) + " does not fit: " +
                                 std::to_string(r.size) + "-byte records, room for " + std::to_string(available) +
                                 " before the next keyword at byte " + std::to_string(k.next));
        r.bytes = in_.read(r.first, r.count * r.size, std::string("the records of ") + name);
        return r;
    }

    int64_t int_at(const Records& r, int64_t rec, int field) const {
        return load_int(r.record(rec) + field * lay_.int_size, lay_.int_size, lay_.big_endian);
    }

    // Int `field` of record `rec` (a record of ints only): a 1-based vertex
    // index.
    int32_t vertex_at(const Records& r, int64_t rec, int field, int64_t nverts, const char* what) const {
        const int64_t v = int_at(r, rec, field);
        if (v < 1 || v > nverts)
            in_.fail(r.offset(rec, int64_t{field} * lay_.int_size),
                     std::string(what) + " " + std::to_string(v) + " is out of range: the file has " +
                         std::to_string(nverts) + " vertices (numbered from 1)");
        return static_cast<int32_t>(v);
    }

    // The int `byte` bytes into record `rec`: a reference number.
    int32_t ref_at_byte(const Records& r, int64_t rec, int64_t byte, const char* what) const {
        const int64_t v = load_int(r.record(rec) + byte, lay_.int_size, lay_.big_endian);
        if (v < INT32_MIN || v > INT32_MAX)
            in_.fail(r.offset(rec, byte), std::string(what) + " " + std::to_string(v) + " does not fit in 32 bits");
        return static_cast<int32_t>(v);
    }

    // Int `field` of record `rec` (a record of ints only): a reference number.
    int32_t ref_at(const Records& r, int64_t rec, int field, const char* what) const {
        return ref_at_byte(r, rec, int64_t{field} * lay_.int_size, what);
    }

    // Vertices first, found by a first walk: the other sections are checked
    // against their count.  Then the others in file order, by a second walk.
    MeshData read_sections() {
        MeshData d;
        d.base = 1;
        Keyword vk{};
        walk_keywords([&](const Keyword& k) {
            if (k.code != kVertices) return;
            if (vk.code == kVertices)
                in_.fail(k.at, "a second Vertices section (the first at byte " + std::to_string(vk.at) +
                                   "): the vertex indices would be ambiguous");
            vk = k;
        });
        if (vk.code != kVertices) in_.fail(end_at_, "no Vertices section before End");
        const int64_t nverts = read_vertices(vk, d);

        bool saw_tets = false;
        std::vector<std::pair<int64_t, int64_t>> ridges;  // 1-based index into all edges, offset
        walk_keywords([&](const Keyword& k) {
            switch (k.code) {
                case kTetrahedra: {
                    saw_tets = true;
                    const Records r = records(k, 5, 0);
                    if (r.count > INT32_MAX - static_cast<int64_t>(d.regions.size()))
                        in_.fail(k.data, "more than 2^31 - 1 tets");
                    for (int64_t t = 0; t < r.count; ++t) {
                        for (int c = 0; c < 4; ++c) d.tets.push_back(vertex_at(r, t, c, nverts, "tet vertex"));
                        d.regions.push_back(ref_at(r, t, 4, "tet reference"));
                    }
                    break;
                }
                case kTriangles: {
                    const Records r = records(k, 4, 0);
                    for (int64_t f = 0; f < r.count; ++f) {
                        for (int c = 0; c < 3; ++c)
                            d.triangles.push_back(vertex_at(r, f, c, nverts, "triangle vertex"));
                        d.tri_markers.push_back(ref_at(r, f, 3, "triangle reference"));
                    }
                    break;
                }
                case kCorners:
                case kRequiredVertices: {
                    const Records r = records(k, 1, 0);
                    std::vector<int32_t>& to = k.code == kCorners ? d.corners : d.fixed;
                    for (int64_t i = 0; i < r.count; ++i)
                        to.push_back(vertex_at(r, i, 0, nverts, keyword_name(k.code)));
                    break;
                }
                case kEdges: {
                    const Records r = records(k, 3, 0);
                    for (int64_t e = 0; e < r.count; ++e) {
                        d.feature_edges.push_back(vertex_at(r, e, 0, nverts, "edge vertex"));
                        d.feature_edges.push_back(vertex_at(r, e, 1, nverts, "edge vertex"));
                        d.edge_refs.push_back(ref_at(r, e, 2, "edge reference"));
                    }
                    break;
                }
                case kRidges: {
                    const Records r = records(k, 1, 0);
                    for (int64_t i = 0; i < r.count; ++i) ridges.emplace_back(int_at(r, i, 0), r.offset(i, 0));
                    break;
                }
                default:
                    break;  // Vertices (read), Dimension (checked) and every other keyword: skipped
            }
        });
        if (!saw_tets) in_.fail(end_at_, "no Tetrahedra section before End");
        // Checked once every Edges section is read: Ridges may come first.
        const int64_t nedges = static_cast<int64_t>(d.edge_refs.size());
        for (const auto& [e, offset] : ridges)
            if (e < 1 || e > nedges)
                in_.fail(offset,
                         "ridge " + std::to_string(e) + " is not one of the " + std::to_string(nedges) + " edges");
        return d;
    }

    // The coordinates and refs of the Vertices keyword `vk` into `d`; their
    // number.
    int64_t read_vertices(const Keyword& vk, MeshData& d) {
        const Records vr = records(vk, 1, 3);
        if (vr.count > INT32_MAX) in_.fail(vk.data, "more than 2^31 - 1 vertices");
        const int64_t nverts = vr.count;
        d.xyz.resize(static_cast<size_t>(3 * nverts));
        d.vertex_refs.resize(static_cast<size_t>(nverts));
        for (int64_t v = 0; v < nverts; ++v) {
            for (int c = 0; c < 3; ++c) {
                const double x = load_real(vr.record(v) + c * lay_.real_size, lay_.real_size, lay_.big_endian);
                if (!std::isfinite(x))
                    in_.fail(
                        vr.offset(v, int64_t{c} * lay_.real_size),
                        "coordinate " + std::to_string(c) + " of vertex " + std::to_string(v + 1) + " is not finite");
                d.xyz[static_cast<size_t>(3 * v + c)] = x;
            }
            d.vertex_refs[static_cast<size_t>(v)] = ref_at_byte(vr, v, 3 * lay_.real_size, "vertex reference");
        }
        return nverts;
    }
};

// ---------------------------------------------------------------- writing

// Little-endian output through a buffer, with the byte position.
class Writer {
public:
    Writer(const std::string& path, int pos_size) : out_(path), pos_size_(pos_size) { buf_.reserve(kChunk + 64); }

    void i32(int64_t v) { put(static_cast<uint64_t>(v), 4); }
    void real(double x) {
        uint64_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        put(bits, 8);
    }
    // A keyword's code and the position of the next one, `payload` bytes on.
    void keyword(int32_t code, int64_t payload) {
        const int64_t next = pos_ + 4 + pos_size_ + payload;
        i32(code);
        put(static_cast<uint64_t>(next), pos_size_);
    }
    void end() {
        i32(kEnd);
        put(0, pos_size_);  // as libMeshb's GmfCloseMesh
        flush();
        out_.close();
    }

private:
    static constexpr size_t kChunk = size_t{1} << 20;
    OutputFile out_;
    int pos_size_;
    int64_t pos_ = 0;
    std::vector<unsigned char> buf_;

    void put(uint64_t v, int size) {
        for (int k = 0; k < size; ++k) buf_.push_back(static_cast<unsigned char>(v >> (8 * k)));
        pos_ += size;
        if (buf_.size() >= kChunk) flush();
    }
    void flush() {
        if (!buf_.empty()) std::fwrite(buf_.data(), 1, buf_.size(), out_.get());  // errors: OutputFile::close
        buf_.clear();
    }
};

}  // namespace

MeshData read_medit_binary(const std::string& path) {
    Reader reader(path);
    return reader.read();
}

void write_medit_binary(const std::string& path, const MeshData& d) {
    const int64_t nv = static_cast<int64_t>(d.xyz.size() / 3), nt = static_cast<int64_t>(d.tets.size() / 4);
    const int64_t nf = static_cast<int64_t>(d.tri_markers.size()), nfix = static_cast<int64_t>(d.fixed.size());
    const int64_t ne = static_cast<int64_t>(d.feature_edges.size() / 2), nc = static_cast<int64_t>(d.corners.size());
    if (d.triangles.size() != static_cast<size_t>(3 * nf) ||
        (!d.regions.empty() && d.regions.size() != static_cast<size_t>(nt)) ||
        (!d.vertex_refs.empty() && d.vertex_refs.size() != static_cast<size_t>(nv)) ||
        (!d.edge_refs.empty() && d.edge_refs.size() != static_cast<size_t>(ne)))
        throw Error(BODT_ERR_INVALID_ARGUMENT,
                    path + ": the triangles, markers, regions, vertex refs and edge refs do not match in number");
    for (int64_t n : {nv, nt, nf, nfix, ne, nc})
        if (n > INT32_MAX) throw Error(BODT_ERR_IO, path + ": more than 2^31 - 1 records in one .meshb section");
    const int64_t shift = 1 - int64_t{d.base};  // Medit counts from 1

    // Payload bytes of each keyword after its header (version 2 and 3 alike:
    // 64-bit reals, 32-bit ints); -1 for a keyword not written.
    const int64_t dims = 4, verts = 4 + 28 * nv, tris = 4 + 16 * nf, tets = 4 + 20 * nt;
    const int64_t edges = ne > 0 ? 4 + 12 * ne : -1, ridges = ne > 0 ? 4 + 4 * ne : -1;
    const int64_t corners = nc > 0 ? 4 + 4 * nc : -1, fixed = nfix > 0 ? 4 + 4 * nfix : -1;
    int64_t total = 8 + 4 + 4;  // header and End
    for (int64_t p : {dims, verts, tris, tets, edges, ridges, corners, fixed})
        if (p >= 0) total += 4 + 4 + p;
    // Version 2 stores positions in signed 32 bits; version 3 in 64 bits.
    const int version = total <= INT32_MAX ? 2 : 3;
    const int pos_size = version == 2 ? 4 : 8;

    Writer w(path, pos_size);
    auto index = [&](int32_t v) {
        const int64_t i = v + shift;
        if (i < 1 || i > nv)
            throw Error(BODT_ERR_INVALID_ARGUMENT, path + ": vertex index " + std::to_string(v) +
                                                       " is not one of the " + std::to_string(nv) +
                                                       " vertices (numbered from " + std::to_string(d.base) + ")");
        w.i32(i);
    };
    // A list of vertices as a keyword of one int per record.
    auto vertex_list = [&](int32_t code, int64_t payload, const std::vector<int32_t>& vertices) {
        w.keyword(code, payload);
        w.i32(static_cast<int64_t>(vertices.size()));
        for (int32_t v : vertices) index(v);
    };
    w.i32(1);
    w.i32(version);
    w.keyword(kDimension, dims);
    w.i32(3);
    w.keyword(kVertices, verts);
    w.i32(nv);
    for (int64_t v = 0; v < nv; ++v) {
        for (int c = 0; c < 3; ++c) w.real(d.xyz[static_cast<size_t>(3 * v + c)]);
        w.i32(d.vertex_refs.empty() ? 0 : d.vertex_refs[static_cast<size_t>(v)]);
    }
    w.keyword(kTriangles, tris);
    w.i32(nf);
    for (int64_t f = 0; f < nf; ++f) {
        for (int c = 0; c < 3; ++c) index(d.triangles[static_cast<size_t>(3 * f + c)]);
        w.i32(d.tri_markers[static_cast<size_t>(f)]);
    }
    w.keyword(kTetrahedra, tets);
    w.i32(nt);
    for (int64_t t = 0; t < nt; ++t) {
        for (int c = 0; c < 4; ++c) index(d.tets[static_cast<size_t>(4 * t + c)]);
        w.i32(d.regions.empty() ? 0 : d.regions[static_cast<size_t>(t)]);
    }
    if (ne > 0) {
        w.keyword(kEdges, edges);
        w.i32(ne);
        for (int64_t e = 0; e < ne; ++e) {
            index(d.feature_edges[static_cast<size_t>(2 * e)]);
            index(d.feature_edges[static_cast<size_t>(2 * e + 1)]);
            w.i32(d.edge_refs.empty() ? 0 : d.edge_refs[static_cast<size_t>(e)]);
        }
        w.keyword(kRidges, ridges);
        w.i32(ne);
        for (int64_t e = 1; e <= ne; ++e) w.i32(e);
    }
    if (nc > 0) vertex_list(kCorners, corners, d.corners);
    if (nfix > 0) vertex_list(kRequiredVertices, fixed, d.fixed);
    w.end();
}

}  // namespace bodt
