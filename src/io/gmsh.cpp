// Gmsh .msh 2.2 and 4.1, ASCII and binary.  See gmsh.hpp for the mapping to
// MeshData.  The reader holds the whole file in memory and walks it with one
// cursor: tokens for the ASCII parts (with line numbers), raw values for the
// binary parts (with byte offsets).
#include "io/gmsh.hpp"

#include "io/output_file.hpp"
#include "io/text_scanner.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <algorithm>
#include <cstdarg>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string_view>
#include <unordered_set>
#include <utility>
#include <vector>

namespace bodt {

namespace {

// ---------------------------------------------------------------- element types

struct ElementType {
    int type;
    int nodes;
    int dim;
    const char* name;
};

// Gmsh's fixed-size element types 1..31 (GmshDefines.h).
constexpr ElementType kElementTypes[] = {
    {1, 2, 1, "2-node line"},
    {2, 3, 2, "3-node triangle"},
    {3, 4, 2, "4-node quadrangle"},
    {4, 4, 3, "4-node tetrahedron"},
    {5, 8, 3, "8-node hexahedron"},
    {6, 6, 3, "6-node prism"},
    {7, 5, 3, "5-node pyramid"},
    {8, 3, 1, "3-node line"},
    {9, 6, 2, "6-node triangle"},
    {10, 9, 2, "9-node quadrangle"},
    {11, 10, 3, "10-node (second-order) tetrahedron"},
    {12, 27, 3, "27-node hexahedron"},
    {13, 18, 3, "18-node prism"},
    {14, 14, 3, "14-node pyramid"},
    {15, 1, 0, "point"},
    {16, 8, 2, "8-node quadrangle"},
    {17, 20, 3, "20-node hexahedron"},
    {18, 15, 3, "15-node prism"},
    {19, 13, 3, "13-node pyramid"},
    {20, 9, 2, "9-node triangle"},
    {21, 10, 2, "10-node triangle"},
    {22, 12, 2, "12-node triangle"},
    {23, 15, 2, "15-node triangle"},
    {24, 15, 2, "15-node triangle"},
    {25, 21, 2, "21-node triangle"},
    {26, 4, 1, "4-node line"},
    {27, 5, 1, "5-node line"},
    {28, 6, 1, "6-node line"},
    {29, 20, 3, "20-node (third-order) tetrahedron"},
    {30, 35, 3, "35-node (fourth-order) tetrahedron"},
    {31, 56, 3, "56-node (fifth-order) tetrahedron"},
};

constexpr int kLine = 1, kTriangle = 2, kTet = 4, kPoint = 15;

const ElementType* find_element_type(int64_t type) {
    for (const ElementType& t : kElementTypes)
        if (t.type == type) return &t;
    return nullptr;
}

// ---------------------------------------------------------------- input cursor

std::string printable(std::string_view s) {
    std::string out;
    for (char c : s.substr(0, 24)) out += (c >= 32 && c < 127) ? c : '?';
    if (s.size() > 24) out += "...";
    return out;
}

class Input {
public:
    explicit Input(const std::string& path) : path_(path), buf_(read_file_text(path)) {}

    // From here on, messages give byte offsets instead of line numbers.
    void set_binary() { binary_ = true; }
    bool binary() const { return binary_; }

    [[noreturn]] void fail(const std::string& message) const {
        if (binary_)
            throw Error(BODT_ERR_IO, path_ + ": at byte " + std::to_string(mark_) + ": " + message);
        throw Error(BODT_ERR_IO, path_ + ":" + std::to_string(line_) + ": " + message);
    }

    size_t remaining() const { return buf_.size() - pos_; }

    // ---- text
    bool next(std::string_view& token) {
        while (pos_ < buf_.size() && is_space(buf_[pos_])) {
            if (buf_[pos_] == '\n') ++line_;
            ++pos_;
        }
        mark_ = pos_;
        if (pos_ >= buf_.size()) return false;
        const size_t start = pos_;
        while (pos_ < buf_.size() && !is_space(buf_[pos_])) ++pos_;
        token = std::string_view(buf_).substr(start, pos_ - start);
        return true;
    }

    std::string_view expect(const char* what) {
        std::string_view token;
        if (!next(token)) fail(std::string("unexpected end of file while reading ") + what);
        return token;
    }

    void expect_keyword(const char* keyword) {
        std::string_view token;
        if (!next(token)) fail(std::string("unexpected end of file: missing ") + keyword);
        if (token != keyword) fail(std::string("expected ") + keyword + ", found '" + printable(token) + "'");
    }

    int64_t read_int(const char* what) {
        std::string_view token = expect(what);
        if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
        int64_t value = 0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (ec != std::errc() || end != token.data() + token.size())
            fail(std::string("expected an integer for ") + what + ", found '" + printable(token) + "'");
        return value;
    }

    int64_t read_int_in(const char* what, int64_t lo, int64_t hi) {
        const int64_t v = read_int(what);
        if (v < lo || v > hi)
            fail(std::string(what) + " " + std::to_string(v) + " is out of range [" + std::to_string(lo) + ", " +
                 std::to_string(hi) + "]");
        return v;
    }

    double read_double(const char* what, bool finite = true) {
        std::string_view token = expect(what);
        if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
        double value = 0.0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (ec != std::errc() || end != token.data() + token.size())
            fail(std::string("expected a number for ") + what + ", found '" + printable(token) + "'");
        if (finite && !std::isfinite(value)) fail(std::string(what) + " is not finite ('" + printable(token) + "')");
        return value;
    }

    // A count: >= 0 and at most what the rest of the file can hold at
    // `min_bytes_each` bytes per item.
    int64_t read_count(const char* what, int64_t min_bytes_each) {
        const int64_t n = read_int(what);
        check_count(n, min_bytes_each, what);
        return n;
    }

    void check_count(int64_t n, int64_t min_bytes_each, const char* what) const {
        if (n < 0) fail(std::string(what) + " is negative (" + std::to_string(n) + ")");
        if (n > static_cast<int64_t>(remaining()) / std::max<int64_t>(min_bytes_each, 1))
            fail(std::string(what) + " " + std::to_string(n) + " is more than the rest of the file can hold");
    }

    // Skips the rest of the current line and then `lines` more lines.
    void skip_lines(int64_t lines, const char* what) {
        for (int64_t k = 0; k <= lines; ++k) {
            const size_t nl = buf_.find('\n', pos_);
            if (nl == std::string::npos) {
                pos_ = buf_.size();
                fail(std::string("unexpected end of file while skipping ") + what);
            }
            pos_ = nl + 1;
            ++line_;
        }
    }

    // The end of a text line before binary data: blanks, then '\n'.
    void end_line() {
        while (pos_ < buf_.size() && (buf_[pos_] == ' ' || buf_[pos_] == '\t' || buf_[pos_] == '\r')) ++pos_;
        mark_ = pos_;
        if (pos_ >= buf_.size()) fail("unexpected end of file: expected binary data");
        if (buf_[pos_] != '\n') fail("expected the end of the line before binary data");
        ++pos_;
        ++line_;
    }

    // Skips a section up to and including its $End line; `name` is the
    // section's keyword without '$'.
    void skip_section(std::string_view name) {
        const std::string end = "$End" + std::string(name);
        size_t at = pos_;
        for (;;) {
            at = buf_.find(end, at);
            if (at == std::string::npos) fail("missing " + end + " for $" + std::string(name));
            const bool line_start = at > 0 && (buf_[at - 1] == '\n' || buf_[at - 1] == '\r');
            const size_t after = at + end.size();
            const bool line_end = after >= buf_.size() || is_space(buf_[after]);
            if (line_start && line_end) break;
            at += 1;
        }
        if (!binary_) line_ += std::count(buf_.begin() + static_cast<std::ptrdiff_t>(pos_), buf_.begin() + static_cast<std::ptrdiff_t>(at), '\n');
        pos_ = at + end.size();
        mark_ = at;
    }

    // ---- binary
    // Checks that `n` items of `bytes_each` bytes are left.
    void need(uint64_t n, uint64_t bytes_each, const char* what) {
        mark_ = pos_;
        if (bytes_each > 0 && n > remaining() / bytes_each)
            fail(std::string("the file ends before ") + std::to_string(n) + " " + what + " (" +
                 std::to_string(bytes_each) + " bytes each; " + std::to_string(remaining()) + " bytes left)");
    }

    template <class T>
    T raw(const char* what) {
        mark_ = pos_;
        if (remaining() < sizeof(T))
            fail(std::string("unexpected end of file while reading ") + what);
        T v;
        std::memcpy(&v, buf_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    int32_t bin_int(const char* what) { return raw<int32_t>(what); }
    int64_t bin_int_in(const char* what, int64_t lo, int64_t hi) {
        const int32_t v = bin_int(what);
        if (v < lo || v > hi)
            fail(std::string(what) + " " + std::to_string(v) + " is out of range [" + std::to_string(lo) + ", " +
                 std::to_string(hi) + "]");
        return v;
    }
    // A size_t count, checked as read_count does.
    int64_t bin_count(const char* what, int64_t min_bytes_each) {
        const uint64_t v = raw<uint64_t>(what);
        if (v > static_cast<uint64_t>(INT64_MAX)) fail(std::string(what) + " " + std::to_string(v) + " is too large");
        const size_t at = mark_;
        const auto n = static_cast<int64_t>(v);
        check_count(n, min_bytes_each, what);
        mark_ = at;
        return n;
    }
    uint64_t bin_size(const char* what) { return raw<uint64_t>(what); }
    double bin_double(const char* what) {
        const double v = raw<double>(what);
        if (!std::isfinite(v)) fail(std::string(what) + " is not finite");
        return v;
    }

    // ---- either, by mode
    int64_t count(const char* what, int64_t min_ascii, int64_t min_binary) {
        return binary_ ? bin_count(what, min_binary) : read_count(what, min_ascii);
    }
    // An int (4 bytes in binary files).
    int64_t int_in(const char* what, int64_t lo, int64_t hi) {
        return binary_ ? bin_int_in(what, lo, hi) : read_int_in(what, lo, hi);
    }
    // A size_t in binary 4.1 files: tags.
    int64_t tag(const char* what) {
        if (!binary_) return read_int_in(what, 1, INT64_MAX);
        const uint64_t v = bin_size(what);
        if (v < 1 || v > static_cast<uint64_t>(INT64_MAX))
            fail(std::string(what) + " " + std::to_string(v) + " is out of range");
        return static_cast<int64_t>(v);
    }
    double coord(const char* what) { return binary_ ? bin_double(what) : read_double(what); }

private:
    static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == '\v' || c == '\f'; }

    std::string path_;
    std::string buf_;
    size_t pos_ = 0;
    size_t mark_ = 0;  // byte offset of the item being read, for messages
    int64_t line_ = 1;
    bool binary_ = false;
};

[[noreturn]] void unsupported_volume_element(Input& in, const ElementType* t, int64_t type) {
    if (t)
        in.fail("element type " + std::to_string(type) + " (" + t->name +
                ") is not supported: bodt reads only 4-node tetrahedra (type 4) as volume elements");
    in.fail("unknown element type " + std::to_string(type) + " in a volume");
}

// ---------------------------------------------------------------- node tags

// Node tag -> vertex index (0-based, file order).
class NodeMap {
public:
    // `tags` in file order; false (and `dup` set) when a tag repeats.
    bool build(const std::vector<int64_t>& tags, int64_t& dup) {
        const int64_t n = static_cast<int64_t>(tags.size());
        int64_t max_tag = 0;
        for (int64_t t : tags) max_tag = std::max(max_tag, t);
        dense_mode_ = max_tag <= 2 * n + 1024;
        if (dense_mode_) {
            dense_.assign(static_cast<size_t>(max_tag) + 1, -1);
            for (int64_t i = 0; i < n; ++i) {
                int32_t& slot = dense_[static_cast<size_t>(tags[i])];
                if (slot >= 0) {
                    dup = tags[i];
                    return false;
                }
                slot = static_cast<int32_t>(i);
            }
        } else {
            sorted_.resize(tags.size());
            for (int64_t i = 0; i < n; ++i) sorted_[i] = {tags[i], static_cast<int32_t>(i)};
            std::sort(sorted_.begin(), sorted_.end());
            for (size_t i = 1; i < sorted_.size(); ++i)
                if (sorted_[i].first == sorted_[i - 1].first) {
                    dup = sorted_[i].first;
                    return false;
                }
        }
        return true;
    }

    // -1 if the tag is not a node.
    int32_t find(int64_t tag) const {
        if (dense_mode_) return tag >= 0 && tag < static_cast<int64_t>(dense_.size()) ? dense_[tag] : -1;
        const auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(tag, INT32_MIN));
        return it != sorted_.end() && it->first == tag ? it->second : -1;
    }

private:
    bool dense_mode_ = true;
    std::vector<int32_t> dense_;
    std::vector<std::pair<int64_t, int32_t>> sorted_;
};

// ---------------------------------------------------------------- reader

class Reader {
public:
    explicit Reader(const std::string& path) : in_(path) {}

    MeshData read() {
        read_format();
        std::string_view token;
        while (in_.next(token)) {
            if (token.size() < 2 || token[0] != '$' || token.substr(0, 4) == "$End")
                in_.fail("expected a section ($Name), found '" + printable(token) + "'");
            if (token == "$Nodes") {
                if (nodes_read_) in_.fail("a second $Nodes section");
                version_ == 41 ? read_nodes41() : read_nodes22();
                finish_nodes();
                in_.expect_keyword("$EndNodes");
                nodes_read_ = true;
            } else if (token == "$Elements") {
                if (!nodes_read_) in_.fail("$Elements before $Nodes");
                if (elements_read_) in_.fail("a second $Elements section");
                version_ == 41 ? read_elements41() : read_elements22();
                in_.expect_keyword("$EndElements");
                elements_read_ = true;
            } else if (token == "$Entities" && version_ == 41) {
                if (entities_read_) in_.fail("a second $Entities section");
                if (elements_read_) in_.fail("$Entities after $Elements");
                read_entities();
                in_.expect_keyword("$EndEntities");
                entities_read_ = true;
            } else if (token == "$MeshFormat") {
                in_.fail("a second $MeshFormat section");
            } else {
                in_.skip_section(token.substr(1));
            }
        }
        if (!nodes_read_) in_.fail("no $Nodes section");
        if (!elements_read_) in_.fail("no $Elements section");
        if (d_.tets.empty()) in_.fail("no 4-node tetrahedra (element type 4) in the file");
        regions_from_entities();
        markers_from_entities();
        return std::move(d_);
    }

private:
    void read_format() {
        std::string_view token;
        if (!in_.next(token) || token != "$MeshFormat")
            in_.fail("not a Gmsh mesh: it must start with $MeshFormat");
        const std::string_view v = in_.expect("the format version");
        if (v == "2.2")
            version_ = 22;
        else if (v == "4.1")
            version_ = 41;
        else
            in_.fail("unsupported Gmsh MSH format version '" + printable(v) +
                     "': only 2.2 and 4.1 are read (save with Gmsh's -format msh41 or msh22)");
        const int64_t file_type = in_.read_int("the file type");
        if (file_type != 0 && file_type != 1) in_.fail("file type " + std::to_string(file_type) + " is neither 0 (ASCII) nor 1 (binary)");
        const int64_t data_size = in_.read_int("the data size");
        if (data_size != 8) in_.fail("unsupported data size " + std::to_string(data_size) + ": only 8-byte doubles and size_t are read");
        if (file_type == 1) {
            in_.end_line();
            in_.set_binary();
            const int32_t one = in_.bin_int("the endianness check (int 1)");
            if (one != 1) {
                int32_t swapped = 0;
                for (int k = 0; k < 4; ++k)
                    swapped = static_cast<int32_t>(static_cast<uint32_t>(swapped) << 8 |
                                                   ((static_cast<uint32_t>(one) >> (8 * k)) & 0xffu));
                if (swapped == 1) in_.fail("binary file of the other byte order (endianness): not supported");
                in_.fail("the endianness check reads " + std::to_string(one) + " instead of 1");
            }
        }
        in_.expect_keyword("$EndMeshFormat");
    }

    // ---- $Entities (4.1)
    void read_entities() {
        if (in_.binary()) in_.end_line();
        int64_t n[4];
        const char* names[4] = {"the number of points", "the number of curves", "the number of surfaces",
                                "the number of volumes"};
        for (int dim = 0; dim < 4; ++dim) n[dim] = in_.count(names[dim], 6, 20);
        for (int dim = 0; dim < 4; ++dim) {
            for (int64_t e = 0; e < n[dim]; ++e) {
                const int64_t tag = in_.int_in("an entity tag", INT32_MIN, INT32_MAX);
                for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) {
                    if (in_.binary())
                        in_.raw<double>("an entity bounding box");
                    else
                        in_.read_double("an entity bounding box", false);
                }
                const int64_t nphys = in_.count("the number of physical tags", 2, 4);
                int32_t first = 0;
                for (int64_t p = 0; p < nphys; ++p) {
                    const auto phys = static_cast<int32_t>(in_.int_in("a physical tag", INT32_MIN, INT32_MAX));
                    if (p == 0) first = phys;
                }
                if (dim > 0) {
                    const int64_t nbound = in_.count("the number of bounding entities", 2, 4);
                    for (int64_t b = 0; b < nbound; ++b) in_.int_in("a bounding entity tag", INT32_MIN, INT32_MAX);
                }
                if (!physical_[dim].emplace(tag, first).second)
                    in_.fail("entity " + std::to_string(tag) + " of dimension " + std::to_string(dim) + " is listed twice");
            }
        }
    }

    int32_t physical_of(int dim, int64_t entity) const {
        const auto it = physical_[dim].find(entity);
        return it == physical_[dim].end() ? 0 : it->second;
    }

    // ---- $Nodes
    void read_nodes41() {
        if (in_.binary()) in_.end_line();
        const int64_t nblocks = in_.count("the number of node blocks", 8, 20);
        const int64_t total = in_.count("the number of nodes", 8, 32);
        if (total > INT32_MAX) in_.fail("more than 2^31 - 1 nodes");
        const int64_t min_tag = in_.binary() ? static_cast<int64_t>(in_.bin_size("the minimum node tag"))
                                             : in_.read_int("the minimum node tag");
        const int64_t max_tag = in_.binary() ? static_cast<int64_t>(in_.bin_size("the maximum node tag"))
                                             : in_.read_int("the maximum node tag");
        tags_.reserve(static_cast<size_t>(total));
        d_.xyz.reserve(static_cast<size_t>(3 * total));
        int64_t seen = 0;
        for (int64_t b = 0; b < nblocks; ++b) {
            const auto dim = static_cast<int>(in_.int_in("the entity dimension of a node block", 0, 3));
            in_.int_in("the entity tag of a node block", INT32_MIN, INT32_MAX);
            const auto parametric = static_cast<int>(in_.int_in("the parametric flag of a node block", 0, 1));
            const int extra = parametric ? dim : 0;
            const int64_t n = in_.count("the number of nodes in a block", 8, 32 + 8 * extra);
            if (n > total - seen)
                in_.fail("the node blocks hold more than the " + std::to_string(total) + " nodes of the $Nodes header");
            if (in_.binary()) in_.need(static_cast<uint64_t>(n), static_cast<uint64_t>(8 * (4 + extra)), "nodes");
            for (int64_t i = 0; i < n; ++i) {
                const int64_t tag = in_.tag("a node tag");
                if (tag < min_tag || tag > max_tag)
                    in_.fail("node tag " + std::to_string(tag) + " is outside the range [" + std::to_string(min_tag) +
                             ", " + std::to_string(max_tag) + "] of the $Nodes header");
                tags_.push_back(tag);
            }
            for (int64_t i = 0; i < n; ++i) {
                for (int k = 0; k < 3; ++k) d_.xyz.push_back(in_.coord("a node coordinate"));
                for (int k = 0; k < extra; ++k) in_.coord("a node parametric coordinate");
            }
            seen += n;
        }
        if (seen != total)
            in_.fail("the node blocks hold " + std::to_string(seen) + " nodes, the $Nodes header says " +
                     std::to_string(total));
    }

    void read_nodes22() {
        const int64_t n = in_.read_count("the number of nodes", 8);
        if (n > INT32_MAX) in_.fail("more than 2^31 - 1 nodes");
        if (in_.binary()) {
            in_.end_line();
            in_.need(static_cast<uint64_t>(n), 28, "nodes");
        }
        tags_.reserve(static_cast<size_t>(n));
        d_.xyz.reserve(static_cast<size_t>(3 * n));
        for (int64_t i = 0; i < n; ++i) {
            tags_.push_back(in_.int_in("a node tag", 1, INT32_MAX));
            for (int k = 0; k < 3; ++k) d_.xyz.push_back(in_.coord("a node coordinate"));
        }
    }

    void finish_nodes() {
        int64_t dup = 0;
        if (!map_.build(tags_, dup)) in_.fail("node tag " + std::to_string(dup) + " appears twice in $Nodes");
        bool in_order = true;
        for (size_t i = 0; i < tags_.size() && in_order; ++i) in_order = tags_[i] == static_cast<int64_t>(i) + 1;
        d_.base = in_order ? 1 : 0;
        tags_.clear();
        tags_.shrink_to_fit();
    }

    int32_t vertex(int64_t tag, int64_t element) {
        const int32_t v = tag >= 1 ? map_.find(tag) : -1;
        if (v < 0)
            in_.fail("element " + std::to_string(element) + ": node tag " + std::to_string(tag) + " is not in $Nodes");
        return v + d_.base;
    }

    // ---- $Elements
    // Stores one element of a known type whose vertices are in v_, from
    // the geometric entity `entity` (0 when a 2.2 file gives none).
    void add_element(int type, int32_t physical, int32_t entity) {
        switch (type) {
            case kTet:
                if (d_.tets.size() / 4 >= static_cast<size_t>(INT32_MAX)) in_.fail("more than 2^31 - 1 tets");
                d_.tets.insert(d_.tets.end(), v_, v_ + 4);
                d_.regions.push_back(physical);
                tet_entities_.push_back(entity);
                break;
            case kTriangle:
                if (physical != 0) {
                    d_.triangles.insert(d_.triangles.end(), v_, v_ + 3);
                    d_.tri_markers.push_back(physical);
                } else if (entity != 0) {
                    entity_triangles_.insert(entity_triangles_.end(), v_, v_ + 3);
                    triangle_entities_.push_back(entity);
                }
                break;
            case kLine:
                add_line(physical);
                break;
            case kPoint:
                if (physical != 0) d_.fixed.push_back(v_[0]);
                break;
            default:
                break;
        }
    }

    // Every line is a feature edge, also without a physical tag (ref 0), as
    // every tet is kept (region 0).  A 2.2 file lists a line once per
    // physical group: the first listing gives the ref, as the first physical
    // tag of a 4.1 entity does, and the others are dropped (an edge has one
    // ref).
    void add_line(int32_t physical) {
        const auto [lo, hi] = std::minmax(v_[0], v_[1]);
        const uint64_t key = uint64_t{static_cast<uint32_t>(lo)} << 32 | static_cast<uint32_t>(hi);
        if (!lines_.insert(key).second) return;
        d_.feature_edges.insert(d_.feature_edges.end(), v_, v_ + 2);
        d_.edge_refs.push_back(physical);
    }

    // The elements lie in more than one entity.
    static bool several(const std::vector<int32_t>& entities) {
        return std::any_of(entities.begin(), entities.end(), [&](int32_t e) { return e != entities.front(); });
    }

    // Without physical volumes, Gmsh's volumes are the regions (gmsh.hpp).
    void regions_from_entities() {
        const auto physical = [](int32_t r) { return r != 0; };
        if (std::any_of(d_.regions.begin(), d_.regions.end(), physical)) return;
        if (several(tet_entities_)) d_.regions = std::move(tet_entities_);
        tet_entities_ = {};
    }

    // Without physical surfaces, Gmsh's surfaces are the face markers, as
    // its volumes are the regions: a solver can still find the faces of
    // each surface for its boundary conditions, and the surfaces between
    // them stay where they are.  One surface alone marks nothing.
    void markers_from_entities() {
        if (d_.triangles.empty() && several(triangle_entities_)) {
            d_.triangles = std::move(entity_triangles_);
            d_.tri_markers = std::move(triangle_entities_);
        }
        entity_triangles_ = {};
        triangle_entities_ = {};
    }

    static bool used(int type) { return type == kTet || type == kTriangle || type == kLine || type == kPoint; }

    void read_elements41() {
        if (in_.binary()) in_.end_line();
        const int64_t nblocks = in_.count("the number of element blocks", 8, 20);
        const int64_t total = in_.count("the number of elements", 4, 16);
        if (in_.binary()) {
            in_.bin_size("the minimum element tag");
            in_.bin_size("the maximum element tag");
        } else {
            in_.read_int("the minimum element tag");
            in_.read_int("the maximum element tag");
        }
        int64_t seen = 0;
        for (int64_t b = 0; b < nblocks; ++b) {
            const auto dim = static_cast<int>(in_.int_in("the entity dimension of an element block", 0, 3));
            const int64_t entity = in_.int_in("the entity tag of an element block", INT32_MIN, INT32_MAX);
            const int64_t type = in_.int_in("an element type", INT32_MIN, INT32_MAX);
            const ElementType* t = find_element_type(type);
            if (t && t->dim != dim)
                in_.fail("element type " + std::to_string(type) + " (" + t->name + ") in a block of dimension " +
                         std::to_string(dim));
            if (dim == 3 && type != kTet) unsupported_volume_element(in_, t, type);
            if (!t && in_.binary()) in_.fail("unknown element type " + std::to_string(type) + ": cannot skip it in a binary file");
            const int64_t nodes = t ? t->nodes : 1;
            const int64_t n = in_.count("the number of elements in a block", 2 * (1 + nodes), 8 * (1 + nodes));
            if (n > total - seen)
                in_.fail("the element blocks hold more than the " + std::to_string(total) +
                         " elements of the $Elements header");
            seen += n;
            if (!t) {  // ASCII: one element per line
                in_.skip_lines(n, "elements of an unknown type");
                continue;
            }
            const int32_t physical = physical_of(dim, entity);
            const bool keep = used(t->type);
            for (int64_t e = 0; e < n; ++e) {
                const int64_t tag = in_.tag("an element tag");
                for (int k = 0; k < t->nodes; ++k) {
                    const int64_t node = in_.tag("a node tag of an element");
                    if (keep) v_[k] = vertex(node, tag);
                }
                if (keep) add_element(t->type, physical, static_cast<int32_t>(entity));
            }
        }
        if (seen != total)
            in_.fail("the element blocks hold " + std::to_string(seen) + " elements, the $Elements header says " +
                     std::to_string(total));
    }

    // One 2.2 element after its type and tags.
    void element22(int64_t tag, const ElementType* t, int32_t physical, int32_t entity) {
        const bool keep = used(t->type);
        for (int k = 0; k < t->nodes; ++k) {
            const int64_t node = in_.int_in("a node tag of an element", INT32_MIN, INT32_MAX);
            if (keep) v_[k] = vertex(node, tag);
        }
        if (keep) add_element(t->type, physical, entity);
    }

    const ElementType* type22(int64_t type) {
        const ElementType* t = find_element_type(type);
        if (!t) in_.fail("unknown element type " + std::to_string(type));
        if (t->dim == 3 && t->type != kTet) unsupported_volume_element(in_, t, type);
        return t;
    }

    void read_elements22() {
        const int64_t n = in_.read_count("the number of elements", 8);
        if (!in_.binary()) {
            for (int64_t e = 0; e < n; ++e) {
                const int64_t tag = in_.read_int("an element number");
                const ElementType* t = type22(in_.read_int("an element type"));
                const int64_t ntags = in_.read_count("the number of element tags", 2);
                int32_t physical = 0, entity = 0;  // the first two tags
                for (int64_t k = 0; k < ntags; ++k) {
                    const auto v = static_cast<int32_t>(in_.read_int_in("an element tag", INT32_MIN, INT32_MAX));
                    if (k == 0) physical = v;
                    if (k == 1) entity = v;
                }
                element22(tag, t, physical, entity);
            }
            return;
        }
        in_.end_line();
        int64_t seen = 0;
        while (seen < n) {
            const ElementType* t = type22(in_.bin_int("an element type"));
            const int64_t follow = in_.bin_int_in("the number of elements following", 1, n - seen);
            const int64_t ntags = in_.bin_int_in("the number of element tags", 0, INT32_MAX);
            in_.need(static_cast<uint64_t>(follow), static_cast<uint64_t>(4 * (1 + ntags + t->nodes)), "elements");
            for (int64_t e = 0; e < follow; ++e) {
                const int64_t tag = in_.bin_int("an element number");
                int32_t physical = 0, entity = 0;
                for (int64_t k = 0; k < ntags; ++k) {
                    const int32_t v = in_.bin_int("an element tag");
                    if (k == 0) physical = v;
                    if (k == 1) entity = v;
                }
                element22(tag, t, physical, entity);
            }
            seen += follow;
        }
    }

    Input in_;
    MeshData d_;
    int version_ = 0;
    bool nodes_read_ = false, elements_read_ = false, entities_read_ = false;
    std::vector<int64_t> tags_;  // node tags in file order, while reading $Nodes
    NodeMap map_;
    std::map<int64_t, int32_t> physical_[4];  // entity tag -> first physical tag, per dimension
    std::unordered_set<uint64_t> lines_;      // the feature edges so far, (low, high) vertex
    std::vector<int32_t> tet_entities_;       // each tet's volume entity
    std::vector<int32_t> entity_triangles_;   // the triangles without a physical tag (3 vertices each)
    std::vector<int32_t> triangle_entities_;  // and their surface entities
    int32_t v_[64] = {};                      // vertices of the element being read
};

// ---------------------------------------------------------------- writer

// Buffered binary or text output to an OutputFile.
class Out {
public:
    explicit Out(FILE* f) : f_(f) {}
    ~Out() = default;
    void text(const char* fmt, ...) __attribute__((format(printf, 2, 3))) {
        char line[512];
        va_list args;
        va_start(args, fmt);
        const int len = std::vsnprintf(line, sizeof line, fmt, args);
        va_end(args);
        buf_.append(line, static_cast<size_t>(std::min<int>(std::max(len, 0), static_cast<int>(sizeof line) - 1)));
        maybe_flush();
    }
    template <class T>
    void raw(T v) {
        buf_.append(reinterpret_cast<const char*>(&v), sizeof v);
        maybe_flush();
    }
    void i32(int64_t v) { raw(static_cast<int32_t>(v)); }
    void u64(uint64_t v) { raw(v); }
    void f64(double v) { raw(v); }
    void flush() {
        if (!buf_.empty()) std::fwrite(buf_.data(), 1, buf_.size(), f_);
        buf_.clear();
    }

private:
    void maybe_flush() {
        if (buf_.size() > (1u << 20)) flush();
    }
    FILE* f_;
    std::string buf_;
};

// Runs of equal values: [begin, end) index ranges over `items` with `key`.
struct Run {
    size_t begin, end;
    int32_t key;
};

std::vector<Run> runs_of(const std::vector<int32_t>& keys, const std::vector<size_t>& items) {
    std::vector<Run> runs;
    for (size_t k = 0; k < items.size(); ++k) {
        const int32_t key = keys[items[k]];
        if (runs.empty() || runs.back().key != key)
            runs.push_back({k, k + 1, key});
        else
            runs.back().end = k + 1;
    }
    return runs;
}

// The distinct values of `keys` in increasing order: entity k + 1 (of one
// dimension) holds the elements with the k-th.
std::vector<int32_t> distinct(std::vector<int32_t> keys) {
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    return keys;
}

// The entity (from 1) of the elements with `key`, `ids` from distinct().
int entity_of(const std::vector<int32_t>& ids, int32_t key) {
    return static_cast<int>(std::lower_bound(ids.begin(), ids.end(), key) - ids.begin()) + 1;
}

class Writer {
public:
    Writer(const MeshData& d, int version, bool binary, Out& out)
        : d_(d), version_(version), binary_(binary), out_(out) {
        nv_ = d.xyz.size() / 3;
        nt_ = d.tets.size() / 4;
        // regions -> volume entities 1..k (sorted ids)
        tet_region_.assign(nt_, 0);
        if (!d.regions.empty()) tet_region_ = d.regions;
        volume_ids_ = distinct(tet_region_);
        if (volume_ids_.empty()) volume_ids_.push_back(0);
        for (size_t t = 0; t < nt_; ++t) tet_items_.push_back(t);
        tet_runs_ = runs_of(tet_region_, tet_items_);
        // nonzero markers -> surface entities 1..k
        for (size_t f = 0; f < d.tri_markers.size(); ++f)
            if (d.tri_markers[f] != 0) {
                tri_items_.push_back(f);
                surface_ids_.push_back(d.tri_markers[f]);
            }
        surface_ids_ = distinct(surface_ids_);
        tri_runs_ = runs_of(d.tri_markers, tri_items_);
        // edge refs -> curve entities 1..k, ref 0 without physical group
        nedges_ = d.feature_edges.size() / 2;
        edge_ref_.assign(nedges_, 0);
        if (!d.edge_refs.empty()) edge_ref_ = d.edge_refs;
        curve_ids_ = distinct(edge_ref_);
        for (size_t e = 0; e < nedges_; ++e) edge_items_.push_back(e);
        edge_runs_ = runs_of(edge_ref_, edge_items_);
        nfixed_ = d.fixed.size();
        nelements_ = nfixed_ + nedges_ + tri_items_.size() + nt_;
        // bounding box for the entities
        for (int k = 0; k < 3; ++k) {
            lo_[k] = nv_ ? d.xyz[k] : 0.0;
            hi_[k] = lo_[k];
        }
        for (size_t v = 0; v < nv_; ++v)
            for (int k = 0; k < 3; ++k) {
                lo_[k] = std::min(lo_[k], d.xyz[3 * v + k]);
                hi_[k] = std::max(hi_[k], d.xyz[3 * v + k]);
            }
    }

    void write() {
        out_.text("$MeshFormat\n%s %d 8\n", version_ == 41 ? "4.1" : "2.2", binary_ ? 1 : 0);
        if (binary_) {
            out_.i32(1);
            out_.text("\n");
        }
        out_.text("$EndMeshFormat\n");
        write_physical_names();
        if (version_ == 41) {
            write_entities41();
            write_nodes41();
            write_elements41();
        } else {
            write_nodes22();
            write_elements22();
        }
    }

private:
    int volume_entity(int32_t region) const { return entity_of(volume_ids_, region); }
    int surface_entity(int32_t marker) const { return entity_of(surface_ids_, marker); }
    int curve_entity(int32_t ref) const { return entity_of(curve_ids_, ref); }
    uint64_t node(int32_t v) const { return static_cast<uint64_t>(static_cast<int64_t>(v) - d_.base + 1); }

    void write_physical_names() {
        size_t n = (nfixed_ ? 1 : 0) + surface_ids_.size();
        for (int32_t r : curve_ids_) n += r != 0;
        for (int32_t r : volume_ids_) n += r != 0;
        if (n == 0) return;
        out_.text("$PhysicalNames\n%zu\n", n);
        if (nfixed_) out_.text("0 1 \"fixed vertices\"\n");
        for (int32_t r : curve_ids_)
            if (r != 0) out_.text("1 %d \"edge ref %d\"\n", r, r);
        for (int32_t m : surface_ids_) out_.text("2 %d \"marker %d\"\n", m, m);
        for (int32_t r : volume_ids_)
            if (r != 0) out_.text("3 %d \"region %d\"\n", r, r);
        out_.text("$EndPhysicalNames\n");
    }

    // ---- 4.1
    void write_entities41() {
        out_.text("$Entities\n");
        const size_t counts[4] = {nfixed_, curve_ids_.size(), surface_ids_.size(), volume_ids_.size()};
        if (binary_)
            for (size_t c : counts) out_.u64(c);
        else
            out_.text("%zu %zu %zu %zu\n", counts[0], counts[1], counts[2], counts[3]);
        for (size_t p = 0; p < nfixed_; ++p) {
            const double* x = &d_.xyz[3 * static_cast<size_t>(d_.fixed[p] - d_.base)];
            if (binary_) {
                out_.i32(static_cast<int64_t>(p) + 1);
                for (int k = 0; k < 3; ++k) out_.f64(x[k]);
                out_.u64(1);
                out_.i32(1);
            } else {
                out_.text("%zu %.17g %.17g %.17g 1 1\n", p + 1, x[0], x[1], x[2]);
            }
        }
        for (size_t c = 0; c < curve_ids_.size(); ++c) entity41(static_cast<int>(c) + 1, curve_ids_[c]);
        for (size_t s = 0; s < surface_ids_.size(); ++s) entity41(static_cast<int>(s) + 1, surface_ids_[s]);
        for (size_t v = 0; v < volume_ids_.size(); ++v) entity41(static_cast<int>(v) + 1, volume_ids_[v]);
        out_.text("%s$EndEntities\n", binary_ ? "\n" : "");
    }

    // A curve, surface or volume entity with one physical tag (none if 0)
    // and no bounding entities.
    void entity41(int tag, int32_t physical) {
        if (binary_) {
            out_.i32(tag);
            for (int k = 0; k < 3; ++k) out_.f64(lo_[k]);
            for (int k = 0; k < 3; ++k) out_.f64(hi_[k]);
            out_.u64(physical != 0 ? 1 : 0);
            if (physical != 0) out_.i32(physical);
            out_.u64(0);
        } else {
            out_.text("%d %.17g %.17g %.17g %.17g %.17g %.17g ", tag, lo_[0], lo_[1], lo_[2], hi_[0], hi_[1], hi_[2]);
            if (physical != 0)
                out_.text("1 %d 0\n", physical);
            else
                out_.text("0 0\n");
        }
    }

    void write_nodes41() {
        out_.text("$Nodes\n");
        const size_t nblocks = nv_ ? 1 : 0;
        // every node in one block on the first volume
        if (binary_) {
            out_.u64(nblocks);
            out_.u64(nv_);
            out_.u64(nv_ ? 1 : 0);
            out_.u64(nv_);
            if (nv_) {
                out_.i32(3);
                out_.i32(1);
                out_.i32(0);
                out_.u64(nv_);
            }
            for (size_t v = 0; v < nv_; ++v) out_.u64(v + 1);
            for (size_t k = 0; k < 3 * nv_; ++k) out_.f64(d_.xyz[k]);
            out_.text("\n");
        } else {
            out_.text("%zu %zu %zu %zu\n", nblocks, nv_, nv_ ? size_t{1} : size_t{0}, nv_);
            if (nv_) out_.text("3 1 0 %zu\n", nv_);
            for (size_t v = 0; v < nv_; ++v) out_.text("%zu\n", v + 1);
            for (size_t v = 0; v < nv_; ++v)
                out_.text("%.17g %.17g %.17g\n", d_.xyz[3 * v], d_.xyz[3 * v + 1], d_.xyz[3 * v + 2]);
        }
        out_.text("$EndNodes\n");
    }

    void block_header41(int dim, int entity, int type, size_t n) {
        if (binary_) {
            out_.i32(dim);
            out_.i32(entity);
            out_.i32(type);
            out_.u64(n);
        } else {
            out_.text("%d %d %d %zu\n", dim, entity, type, n);
        }
    }

    void element41(const int32_t* v, int nodes) {
        ++tag_;
        if (binary_) {
            out_.u64(tag_);
            for (int k = 0; k < nodes; ++k) out_.u64(node(v[k]));
        } else {
            out_.text("%zu", tag_);
            for (int k = 0; k < nodes; ++k) out_.text(" %llu", static_cast<unsigned long long>(node(v[k])));
            out_.text("\n");
        }
    }

    void write_elements41() {
        out_.text("$Elements\n");
        const size_t nblocks = nfixed_ + edge_runs_.size() + tri_runs_.size() + tet_runs_.size();
        if (binary_) {
            out_.u64(nblocks);
            out_.u64(nelements_);
            out_.u64(nelements_ ? 1 : 0);
            out_.u64(nelements_);
        } else {
            out_.text("%zu %zu %zu %zu\n", nblocks, nelements_, nelements_ ? size_t{1} : size_t{0}, nelements_);
        }
        for (size_t p = 0; p < nfixed_; ++p) {
            block_header41(0, static_cast<int>(p) + 1, kPoint, 1);
            element41(&d_.fixed[p], 1);
        }
        for (const Run& r : edge_runs_) {
            block_header41(1, curve_entity(r.key), kLine, r.end - r.begin);
            for (size_t k = r.begin; k < r.end; ++k) element41(&d_.feature_edges[2 * edge_items_[k]], 2);
        }
        for (const Run& r : tri_runs_) {
            block_header41(2, surface_entity(r.key), kTriangle, r.end - r.begin);
            for (size_t k = r.begin; k < r.end; ++k) element41(&d_.triangles[3 * tri_items_[k]], 3);
        }
        for (const Run& r : tet_runs_) {
            block_header41(3, volume_entity(r.key), kTet, r.end - r.begin);
            for (size_t k = r.begin; k < r.end; ++k) element41(&d_.tets[4 * tet_items_[k]], 4);
        }
        out_.text("%s$EndElements\n", binary_ ? "\n" : "");
    }

    // ---- 2.2
    void write_nodes22() {
        out_.text("$Nodes\n%zu\n", nv_);
        for (size_t v = 0; v < nv_; ++v) {
            if (binary_) {
                out_.i32(static_cast<int64_t>(v) + 1);
                for (int k = 0; k < 3; ++k) out_.f64(d_.xyz[3 * v + k]);
            } else {
                out_.text("%zu %.17g %.17g %.17g\n", v + 1, d_.xyz[3 * v], d_.xyz[3 * v + 1], d_.xyz[3 * v + 2]);
            }
        }
        out_.text("%s$EndNodes\n", binary_ ? "\n" : "");
    }

    // One element with tags (physical, elementary).
    void element22(int type, int32_t physical, int entity, const int32_t* v, int nodes) {
        ++tag_;
        if (binary_) {
            out_.i32(static_cast<int64_t>(tag_));
            out_.i32(physical);
            out_.i32(entity);
            for (int k = 0; k < nodes; ++k) out_.i32(static_cast<int64_t>(node(v[k])));
        } else {
            out_.text("%zu %d 2 %d %d", tag_, type, physical, entity);
            for (int k = 0; k < nodes; ++k) out_.text(" %llu", static_cast<unsigned long long>(node(v[k])));
            out_.text("\n");
        }
    }

    void header22(int type, size_t n) {
        if (binary_ && n > 0) {
            out_.i32(type);
            out_.i32(static_cast<int64_t>(n));
            out_.i32(2);
        }
    }

    void write_elements22() {
        out_.text("$Elements\n%zu\n", nelements_);
        header22(kPoint, nfixed_);
        for (size_t p = 0; p < nfixed_; ++p) element22(kPoint, 1, static_cast<int>(p) + 1, &d_.fixed[p], 1);
        header22(kLine, nedges_);
        for (size_t e = 0; e < nedges_; ++e)
            element22(kLine, edge_ref_[e], curve_entity(edge_ref_[e]), &d_.feature_edges[2 * e], 2);
        header22(kTriangle, tri_items_.size());
        for (size_t f : tri_items_) {
            const int32_t m = d_.tri_markers[f];
            element22(kTriangle, m, surface_entity(m), &d_.triangles[3 * f], 3);
        }
        header22(kTet, nt_);
        for (size_t t = 0; t < nt_; ++t)
            element22(kTet, tet_region_[t], volume_entity(tet_region_[t]), &d_.tets[4 * t], 4);
        out_.text("%s$EndElements\n", binary_ ? "\n" : "");
    }

    const MeshData& d_;
    int version_;
    bool binary_;
    Out& out_;
    size_t nv_ = 0, nt_ = 0, nedges_ = 0, nfixed_ = 0, nelements_ = 0;
    size_t tag_ = 0;  // the last element tag written
    std::vector<int32_t> tet_region_, volume_ids_, surface_ids_, edge_ref_, curve_ids_;
    std::vector<size_t> tet_items_, tri_items_, edge_items_;
    std::vector<Run> tet_runs_, tri_runs_, edge_runs_;
    double lo_[3] = {0, 0, 0}, hi_[3] = {0, 0, 0};
};

// The writer's input checks: sizes consistent and every index in range.
void check_for_writing(const MeshData& d) {
    auto bad = [](const std::string& m) { throw Error(BODT_ERR_INVALID_ARGUMENT, "write_gmsh: " + m); };
    if (d.xyz.size() % 3 || d.tets.size() % 4 || d.triangles.size() % 3 || d.feature_edges.size() % 2)
        bad("array sizes are not multiples of 3, 4, 3 and 2");
    if (!d.regions.empty() && d.regions.size() != d.tets.size() / 4) bad("one region per tet expected");
    if (d.tri_markers.size() != d.triangles.size() / 3) bad("one marker per triangle expected");
    if (!d.edge_refs.empty() && d.edge_refs.size() != d.feature_edges.size() / 2)
        bad("one ref per feature edge expected");
    const int64_t nv = static_cast<int64_t>(d.xyz.size() / 3);
    if (nv > INT32_MAX) bad("more than 2^31 - 1 vertices");
    auto check = [&](const std::vector<int32_t>& a, const char* what) {
        for (int32_t v : a)
            if (v < d.base || static_cast<int64_t>(v) - d.base >= nv)
                bad(std::string(what) + " vertex " + std::to_string(v) + " is out of range");
    };
    check(d.tets, "tet");
    check(d.triangles, "triangle");
    check(d.feature_edges, "feature edge");
    check(d.fixed, "fixed");
}

}  // namespace

MeshData read_gmsh(const std::string& path) {
    Reader reader(path);
    return reader.read();
}

void write_gmsh(const std::string& path, const MeshData& data, int version, bool binary) {
    if (version != 41 && version != 22)
        throw Error(BODT_ERR_INVALID_ARGUMENT,
                    "write_gmsh: version " + std::to_string(version) + " is neither 41 (MSH 4.1) nor 22 (MSH 2.2)");
    check_for_writing(data);
    OutputFile file(path);
    Out out(file.get());
    Writer(data, version, binary, out).write();
    out.flush();
    file.close();
}

}  // namespace bodt
