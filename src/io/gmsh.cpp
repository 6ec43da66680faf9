// Gmsh .msh 2.2 and 4.1, ASCII and binary.  See gmsh.hpp for the mapping to
// MeshData.  The reader holds the whole file in memory and walks it with one
// cursor: tokens for the ASCII parts (with line numbers), raw values for the
// binary parts (with byte offsets).
#include "io/gmsh.hpp"

#include "io/gmsh_layout.hpp"
#include "io/gmsh_model.hpp"
#include "io/output_file.hpp"
#include "io/text_scanner.hpp"

#include "bodt.h"
#include "common/error.hpp"
#include "mesh/element_keys.hpp"

#include <algorithm>
#include <array>
#include <cstdarg>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <string_view>
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

    // A string in double quotes on the current line (no quote or line break
    // inside), after blanks.
    std::string quoted(const char* what) {
        while (pos_ < buf_.size() && (buf_[pos_] == ' ' || buf_[pos_] == '\t')) ++pos_;
        mark_ = pos_;
        if (pos_ >= buf_.size() || buf_[pos_] != '"') fail(std::string("expected ") + what + " in double quotes");
        const size_t close = buf_.find_first_of("\"\n", pos_ + 1);
        if (close == std::string::npos || buf_[close] != '"')
            fail(std::string(what) + " without its closing double quote on the line");
        std::string s = buf_.substr(pos_ + 1, close - pos_ - 1);
        pos_ = close + 1;
        return s;
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
            } else if (token == "$PhysicalNames") {
                if (names_read_) in_.fail("a second $PhysicalNames section");
                read_physical_names();
                in_.expect_keyword("$EndPhysicalNames");
                names_read_ = true;
            } else if (token == "$MeshFormat") {
                in_.fail("a second $MeshFormat section");
            } else {
                in_.skip_section(token.substr(1));
            }
        }
        if (!nodes_read_) in_.fail("no $Nodes section");
        if (!elements_read_) in_.fail("no $Elements section");
        if (elements_[kTetDim].entity.empty()) in_.fail("no 4-node tetrahedra (element type 4) in the file");
        finish();
        return std::move(d_);
    }

private:
    static constexpr int kTetDim = 3;

    // The elements of one dimension read so far, in file order.
    struct Elements {
        std::vector<int32_t> vertices;  // nodes-per-element each, from base
        std::vector<int32_t> entity;    // an index in model_.entities, or -1
        std::vector<int32_t> physical;  // the first physical tag, 0 for none
        std::vector<int64_t> tag;       // the element tags (4.1)
    };

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

    // ---- $PhysicalNames (ASCII also in binary files)
    void read_physical_names() {
        const int64_t n = in_.read_count("the number of physical names", 6);
        for (int64_t k = 0; k < n; ++k) {
            GmshPhysicalName name;
            name.dim = static_cast<int>(in_.read_int_in("the dimension of a physical name", 0, 3));
            name.tag = static_cast<int32_t>(in_.read_int_in("the tag of a physical name", INT32_MIN, INT32_MAX));
            name.name = in_.quoted("a physical name");
            model_.names.push_back(std::move(name));
        }
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
                GmshEntity entity;
                entity.dim = dim;
                const int64_t tag = in_.int_in("an entity tag", INT32_MIN, INT32_MAX);
                entity.tag = static_cast<int32_t>(tag);
                const int nbox = dim == 0 ? 3 : 6;
                entity.has_box = true;
                for (int k = 0; k < nbox; ++k) {
                    const double x = in_.binary() ? in_.raw<double>("an entity bounding box")
                                                  : in_.read_double("an entity bounding box", false);
                    entity.box[k] = x;
                    entity.has_box = entity.has_box && std::isfinite(x);
                }
                if (dim == 0) std::copy(entity.box.begin(), entity.box.begin() + 3, entity.box.begin() + 3);
                const int64_t nphys = in_.count("the number of physical tags", 2, 4);
                for (int64_t p = 0; p < nphys; ++p)
                    entity.physicals.push_back(static_cast<int32_t>(in_.int_in("a physical tag", INT32_MIN, INT32_MAX)));
                if (dim > 0) {
                    const int64_t nbound = in_.count("the number of bounding entities", 2, 4);
                    for (int64_t b = 0; b < nbound; ++b)
                        entity.bounding.push_back(
                            static_cast<int32_t>(in_.int_in("a bounding entity tag", INT32_MIN, INT32_MAX)));
                }
                // A tag that is not positive names no Gmsh entity: its
                // elements get none (entity_of).
                const int32_t index = tag > 0 ? static_cast<int32_t>(model_.entities.size()) : -1;
                if (!index_.emplace(std::make_pair(dim, tag), index).second)
                    in_.fail("entity " + std::to_string(tag) + " of dimension " + std::to_string(dim) + " is listed twice");
                if (index >= 0) model_.entities.push_back(std::move(entity));
            }
        }
    }

    // The entity (dim, tag), made if `make` and it is not known; -1 for a tag
    // that is not positive (no entity: 2.2 elements without one, meshio's 0).
    int32_t entity_of(int dim, int64_t tag, bool make) {
        if (tag <= 0 || tag > INT32_MAX) return -1;
        const auto key = std::make_pair(dim, tag);
        if (key == last_key_) return last_entity_;
        const auto it = index_.find(key);
        int32_t e = -1;
        if (it != index_.end()) {
            e = it->second;
        } else if (make) {
            e = static_cast<int32_t>(model_.entities.size());
            GmshEntity entity;
            entity.dim = dim;
            entity.tag = static_cast<int32_t>(tag);
            model_.entities.push_back(std::move(entity));
            index_[key] = e;
        }
        if (e >= 0) {  // not a miss: a later call may make it
            last_key_ = key;
            last_entity_ = e;
        }
        return e;
    }

    int32_t first_physical(int32_t e) const {
        if (e < 0) return 0;
        const std::vector<int32_t>& p = model_.entities[static_cast<size_t>(e)].physicals;
        return p.empty() ? 0 : p.front();
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
        node_block_entity_.reserve(static_cast<size_t>(total));
        int64_t seen = 0;
        for (int64_t b = 0; b < nblocks; ++b) {
            const auto dim = static_cast<int>(in_.int_in("the entity dimension of a node block", 0, 3));
            const int64_t tag = in_.int_in("the entity tag of a node block", INT32_MIN, INT32_MAX);
            const auto parametric = static_cast<int>(in_.int_in("the parametric flag of a node block", 0, 1));
            const int extra = parametric ? dim : 0;
            const int64_t n = in_.count("the number of nodes in a block", 8, 32 + 8 * extra);
            if (n > total - seen)
                in_.fail("the node blocks hold more than the " + std::to_string(total) + " nodes of the $Nodes header");
            if (in_.binary()) in_.need(static_cast<uint64_t>(n), static_cast<uint64_t>(8 * (4 + extra)), "nodes");
            for (int64_t i = 0; i < n; ++i) {
                const int64_t node = in_.tag("a node tag");
                if (node < min_tag || node > max_tag)
                    in_.fail("node tag " + std::to_string(node) + " is outside the range [" + std::to_string(min_tag) +
                             ", " + std::to_string(max_tag) + "] of the $Nodes header");
                tags_.push_back(node);
            }
            for (int64_t i = 0; i < n; ++i) {
                for (int k = 0; k < 3; ++k) d_.xyz.push_back(in_.coord("a node coordinate"));
                for (int k = 0; k < extra; ++k) in_.coord("a node parametric coordinate");
            }
            node_block_entity_.insert(node_block_entity_.end(), static_cast<size_t>(n), entity_of(dim, tag, false));
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

    // Node tags 1..n in any order: vertex i is the node tagged i + 1, base 1
    // (the vertices in the writer's order, whatever blocks it put them in).
    // Other tags: vertices in file order, base 0.
    void finish_nodes() {
        int64_t dup = 0;
        if (!map_.build(tags_, dup)) in_.fail("node tag " + std::to_string(dup) + " appears twice in $Nodes");
        const auto n = static_cast<int64_t>(tags_.size());
        by_tag_ = std::all_of(tags_.begin(), tags_.end(), [&](int64_t t) { return t >= 1 && t <= n; });
        d_.base = by_tag_ ? 1 : 0;
        if (by_tag_ && !std::is_sorted(tags_.begin(), tags_.end())) {
            std::vector<double> xyz(d_.xyz.size());
            std::vector<int32_t> entity(node_block_entity_.size());
            for (size_t i = 0; i < tags_.size(); ++i) {
                const auto v = static_cast<size_t>(tags_[i] - 1);
                std::copy_n(&d_.xyz[3 * i], 3, &xyz[3 * v]);
                if (!entity.empty()) entity[v] = node_block_entity_[i];
            }
            d_.xyz = std::move(xyz);
            node_block_entity_ = std::move(entity);
        }
        tags_.clear();
        tags_.shrink_to_fit();
    }

    int32_t vertex(int64_t tag, int64_t element) {
        const int64_t nv = static_cast<int64_t>(d_.xyz.size() / 3);
        const int32_t v = by_tag_ ? (tag >= 1 && tag <= nv ? static_cast<int32_t>(tag - 1) : -1)
                                  : (tag >= 1 ? map_.find(tag) : -1);
        if (v < 0)
            in_.fail("element " + std::to_string(element) + ": node tag " + std::to_string(tag) + " is not in $Nodes");
        return v + d_.base;
    }

    // ---- $Elements
    static bool used(int type) { return type == kTet || type == kTriangle || type == kLine || type == kPoint; }

    // Keeps one element of a used type whose vertices are in v_.
    void add_element(const ElementType* t, int32_t physical, int32_t entity, int64_t tag) {
        Elements& e = elements_[t->dim];
        if (t->type == kTet && e.entity.size() >= static_cast<size_t>(INT32_MAX)) in_.fail("more than 2^31 - 1 tets");
        e.vertices.insert(e.vertices.end(), v_, v_ + t->nodes);
        e.entity.push_back(entity);
        e.physical.push_back(physical);
        if (version_ == 41) e.tag.push_back(tag);
    }

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
            const int64_t entity_tag = in_.int_in("the entity tag of an element block", INT32_MIN, INT32_MAX);
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
            const bool keep = used(t->type);
            const int32_t entity = keep ? entity_of(dim, entity_tag, true) : -1;
            const int32_t physical = first_physical(entity);
            for (int64_t e = 0; e < n; ++e) {
                const int64_t tag = in_.tag("an element tag");
                for (int k = 0; k < t->nodes; ++k) {
                    const int64_t node = in_.tag("a node tag of an element");
                    if (keep) v_[k] = vertex(node, tag);
                }
                if (keep) add_element(t, physical, entity, tag);
            }
        }
        if (seen != total)
            in_.fail("the element blocks hold " + std::to_string(seen) + " elements, the $Elements header says " +
                     std::to_string(total));
    }

    // One 2.2 element after its type and tags: its entity is made from the
    // elements that name it, with their physical tags.
    void element22(int64_t tag, const ElementType* t, int32_t physical, int32_t entity_tag) {
        const bool keep = used(t->type);
        for (int k = 0; k < t->nodes; ++k) {
            const int64_t node = in_.int_in("a node tag of an element", INT32_MIN, INT32_MAX);
            if (keep) v_[k] = vertex(node, tag);
        }
        if (!keep) return;
        const int32_t entity = entity_of(t->dim, entity_tag, true);
        const std::pair<int32_t, int32_t> pair{entity, physical};
        if (entity >= 0 && physical != 0 && pair != last_physical_ && entity_physicals_.insert(pair).second)
            model_.entities[static_cast<size_t>(entity)].physicals.push_back(physical);
        last_physical_ = pair;
        add_element(t, physical, entity, tag);
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

    // ---- the arrays and the model from the elements read
    // 4.1: the elements of a dimension in the order of their tags (stable),
    // which is the file order in files Gmsh writes and the order of the
    // arrays in files bodt writes.
    static void order_by_tag(Elements& e, int nodes) {
        if (std::is_sorted(e.tag.begin(), e.tag.end())) return;
        std::vector<size_t> order(e.tag.size());
        for (size_t k = 0; k < order.size(); ++k) order[k] = k;
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return e.tag[a] < e.tag[b]; });
        Elements sorted;
        for (const size_t k : order) {
            sorted.vertices.insert(sorted.vertices.end(), &e.vertices[k * nodes], &e.vertices[k * nodes] + nodes);
            sorted.entity.push_back(e.entity[k]);
            sorted.physical.push_back(e.physical[k]);
        }
        e = std::move(sorted);
    }

    // The elements lie in more than one entity.
    static bool several(const std::vector<int32_t>& entities) {
        return std::any_of(entities.begin(), entities.end(), [&](int32_t e) { return e != entities.front(); });
    }

    int32_t entity_tag(int32_t e) const { return e < 0 ? 0 : model_.entities[static_cast<size_t>(e)].tag; }

    // Vertex indices from 0, for the model.
    std::vector<int32_t> from_zero(const std::vector<int32_t>& vertices) const {
        std::vector<int32_t> out(vertices);
        for (int32_t& v : out) v -= d_.base;
        return out;
    }

    void finish() {
        static const int kNodes[4] = {1, 2, 3, 4};
        if (version_ == 41)
            for (int dim = 0; dim < 4; ++dim) order_by_tag(elements_[dim], kNodes[dim]);
        finish_tets();
        finish_triangles();
        finish_lines();
        finish_points();
        model_.node_entity = std::move(node_block_entity_);
        d_.gmsh = std::make_shared<const GmshModel>(std::move(model_));
    }

    // Region = the physical tag; without physical volumes, Gmsh's volumes
    // are the regions (gmsh.hpp).
    void finish_tets() {
        Elements& e = elements_[3];
        d_.tets = std::move(e.vertices);
        d_.regions = std::move(e.physical);
        const bool physical = std::any_of(d_.regions.begin(), d_.regions.end(), [](int32_t r) { return r != 0; });
        if (!physical && several(e.entity)) {
            model_.entity_keyed[3] = true;
            for (size_t t = 0; t < d_.regions.size(); ++t) d_.regions[t] = entity_tag(e.entity[t]);
        }
        model_.tet_entity = std::move(e.entity);
    }

    // Marked faces: the triangles with a physical tag.  Without physical
    // surfaces, Gmsh's surfaces are the face markers, as its volumes are the
    // regions: a solver can still find the faces of each surface for its
    // boundary conditions, and the surfaces between them stay where they
    // are.  One surface alone marks nothing.
    void finish_triangles() {
        Elements& e = elements_[2];
        const size_t n = e.entity.size();
        std::vector<int32_t> unmarked;  // the entities of triangles without a physical tag, but in an entity
        for (size_t k = 0; k < n; ++k)
            if (e.physical[k] != 0) {
                d_.triangles.insert(d_.triangles.end(), &e.vertices[3 * k], &e.vertices[3 * k] + 3);
                d_.tri_markers.push_back(e.physical[k]);
            } else if (e.entity[k] >= 0) {
                unmarked.push_back(e.entity[k]);
            }
        if (d_.triangles.empty() && several(unmarked)) {
            model_.entity_keyed[2] = true;
            for (size_t k = 0; k < n; ++k)
                if (e.entity[k] >= 0) {
                    d_.triangles.insert(d_.triangles.end(), &e.vertices[3 * k], &e.vertices[3 * k] + 3);
                    d_.tri_markers.push_back(entity_tag(e.entity[k]));
                }
        }
        model_.triangles = from_zero(e.vertices);
        model_.triangle_entity = std::move(e.entity);
        e = Elements{};
    }

    // Every line is a feature edge, also without a physical tag (ref 0), as
    // every tet is kept (region 0).  A 2.2 file lists a line once per
    // physical group: the first listing gives the ref, as the first physical
    // tag of a 4.1 entity does, and the others are dropped (an edge has one
    // ref).
    void finish_lines() {
        Elements& e = elements_[1];
        EdgeSet seen;
        for (size_t k = 0; k < e.entity.size(); ++k) {
            const int32_t* v = &e.vertices[2 * k];
            if (!seen.insert(edge_key(v[0], v[1])).second) continue;
            d_.feature_edges.insert(d_.feature_edges.end(), v, v + 2);
            d_.edge_refs.push_back(e.physical[k]);
            model_.line_entity.push_back(e.entity[k]);
        }
        model_.lines = from_zero(d_.feature_edges);
        e = Elements{};
    }

    // A point element with a physical tag fixes its vertex.
    void finish_points() {
        Elements& e = elements_[0];
        for (size_t k = 0; k < e.entity.size(); ++k)
            if (e.physical[k] != 0) d_.fixed.push_back(e.vertices[k]);
        model_.points = from_zero(e.vertices);
        model_.point_entity = std::move(e.entity);
        e = Elements{};
    }

    Input in_;
    MeshData d_;
    GmshModel model_;
    int version_ = 0;
    bool nodes_read_ = false, elements_read_ = false, entities_read_ = false, names_read_ = false;
    std::vector<int64_t> tags_;  // node tags in file order, while reading $Nodes
    NodeMap map_;
    bool by_tag_ = false;  // the node tags are 1..n: vertex = tag - 1
    std::vector<int32_t> node_block_entity_;  // per node, the entity of its block (4.1)
    std::map<std::pair<int, int64_t>, int32_t> index_;  // (dim, tag) -> entity index
    std::pair<int, int64_t> last_key_{-1, 0};           // the last entity_of() lookup
    int32_t last_entity_ = -1;
    std::set<std::pair<int32_t, int32_t>> entity_physicals_;  // 2.2: (entity, physical) pairs seen
    std::pair<int32_t, int32_t> last_physical_{-1, 0};       // and the last one
    Elements elements_[4];  // by dimension: points, lines, triangles, tets
    int32_t v_[64] = {};    // vertices of the element being read
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
    void str(const std::string& s) {
        buf_ += s;
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

// Element type and node count of the elements of each dimension.
constexpr int kTypeOfDim[4] = {kPoint, kLine, kTriangle, kTet};
constexpr int kNodesOfDim[4] = {1, 2, 3, 4};

// Writes the layout (gmsh_layout.hpp) of a mesh.  4.1: entities, nodes in a
// block per entity, elements in a block per entity, element tags numbering
// each dimension's elements in their order (points, lines, triangles, tets)
// so that a reader that orders elements by tag gets them back in that
// order.  2.2: elements in that order, each tagged with its entity's first
// physical tag (0 without one) and its entity.
class Writer {
public:
    Writer(const MeshData& d, int version, bool binary, Out& out)
        : d_(d), layout_(layout_gmsh(d)), version_(version), binary_(binary), out_(out) {
        nv_ = d.xyz.size() / 3;
        size_t next = 1;  // the element tags of each dimension follow the lower ones'
        for (int dim = 0; dim < 4; ++dim) {
            const std::vector<int32_t>& entity = layout_.element_entity[dim];
            tags_[dim].assign(entity.size(), 0);
            for (size_t k = 0; k < entity.size(); ++k)
                if (entity[k] >= 0) tags_[dim][k] = next++;
        }
        nelements_ = next - 1;
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
    // The node tags of element k of `dim`.
    void node_tags(int dim, size_t k, uint64_t* tags) const {
        if (dim == 0) {
            tags[0] = static_cast<uint64_t>(layout_.points[k]) + 1;
            return;
        }
        const int32_t* v = dim == 1 ? &d_.feature_edges[2 * k] : dim == 2 ? &d_.triangles[3 * k] : &d_.tets[4 * k];
        for (int j = 0; j < kNodesOfDim[dim]; ++j) tags[j] = static_cast<uint64_t>(int64_t{v[j]} - d_.base + 1);
    }

    void write_physical_names() {
        if (layout_.names.empty()) return;
        out_.text("$PhysicalNames\n%zu\n", layout_.names.size());
        for (const GmshPhysicalName& n : layout_.names) {
            out_.text("%d %d \"", n.dim, n.tag);
            out_.str(n.name);
            out_.text("\"\n");
        }
        out_.text("$EndPhysicalNames\n");
    }

    // ---- 4.1
    void write_entities41() {
        out_.text("$Entities\n");
        size_t counts[4] = {0, 0, 0, 0};
        for (const GmshLayout::Entity& e : layout_.entities) ++counts[e.dim];
        if (binary_)
            for (size_t c : counts) out_.u64(c);
        else
            out_.text("%zu %zu %zu %zu\n", counts[0], counts[1], counts[2], counts[3]);
        for (const GmshLayout::Entity& e : layout_.entities) {
            const int nbox = e.dim == 0 ? 3 : 6;
            if (binary_) {
                out_.i32(e.tag);
                for (int k = 0; k < nbox; ++k) out_.f64(e.box[k]);
            } else {
                out_.text("%d", e.tag);
                for (int k = 0; k < nbox; ++k) out_.text(" %.17g", e.box[k]);
            }
            tag_list(e.physicals);
            if (e.dim > 0) tag_list(e.bounding);
            if (!binary_) out_.text("\n");
        }
        out_.text("%s$EndEntities\n", binary_ ? "\n" : "");
    }

    // A count and the tags.
    void tag_list(const std::vector<int32_t>& tags) {
        if (binary_) {
            out_.u64(tags.size());
            for (int32_t t : tags) out_.i32(t);
        } else {
            out_.text(" %zu", tags.size());
            for (int32_t t : tags) out_.text(" %d", t);
        }
    }

    void block_header41(int dim, int tag, int type_or_parametric, size_t n) {
        if (binary_) {
            out_.i32(dim);
            out_.i32(tag);
            out_.i32(type_or_parametric);
            out_.u64(n);
        } else {
            out_.text("%d %d %d %zu\n", dim, tag, type_or_parametric, n);
        }
    }

    // A section header: number of blocks, of items, smallest and largest tag.
    void counts41(size_t blocks, size_t n) {
        if (binary_) {
            out_.u64(blocks);
            out_.u64(n);
            out_.u64(n ? 1 : 0);
            out_.u64(n);
        } else {
            out_.text("%zu %zu %zu %zu\n", blocks, n, n ? size_t{1} : size_t{0}, n);
        }
    }

    void write_nodes41() {
        out_.text("$Nodes\n");
        // the vertices of each entity's block, in their order (CSR)
        const size_t ne = layout_.entities.size();
        std::vector<size_t> first(ne + 1, 0);
        for (int32_t e : layout_.node_entity) ++first[static_cast<size_t>(e) + 1];
        size_t blocks = 0;
        for (size_t e = 0; e < ne; ++e) {
            blocks += first[e + 1] > 0;
            first[e + 1] += first[e];
        }
        std::vector<size_t> vertices(nv_), fill(first.begin(), first.end() - 1);
        for (size_t v = 0; v < nv_; ++v) vertices[fill[static_cast<size_t>(layout_.node_entity[v])]++] = v;
        counts41(blocks, nv_);
        for (size_t e = 0; e < ne; ++e) {
            if (first[e + 1] == first[e]) continue;
            const GmshLayout::Entity& entity = layout_.entities[e];
            block_header41(entity.dim, entity.tag, 0, first[e + 1] - first[e]);
            for (size_t k = first[e]; k < first[e + 1]; ++k) {
                if (binary_)
                    out_.u64(vertices[k] + 1);
                else
                    out_.text("%zu\n", vertices[k] + 1);
            }
            for (size_t k = first[e]; k < first[e + 1]; ++k) {
                const double* x = &d_.xyz[3 * vertices[k]];
                if (binary_)
                    for (int j = 0; j < 3; ++j) out_.f64(x[j]);
                else
                    out_.text("%.17g %.17g %.17g\n", x[0], x[1], x[2]);
            }
        }
        out_.text("%s$EndNodes\n", binary_ ? "\n" : "");
    }

    void write_elements41() {
        out_.text("$Elements\n");
        size_t blocks = 0;
        for (const GmshLayout::Entity& e : layout_.entities) blocks += !e.elements.empty();
        counts41(blocks, nelements_);
        uint64_t nodes[4];
        for (const GmshLayout::Entity& e : layout_.entities) {
            if (e.elements.empty()) continue;
            const int n = kNodesOfDim[e.dim];
            block_header41(e.dim, e.tag, kTypeOfDim[e.dim], e.elements.size());
            for (const int32_t el : e.elements) {
                const auto k = static_cast<size_t>(el);
                node_tags(e.dim, k, nodes);
                if (binary_) {
                    out_.u64(tags_[e.dim][k]);
                    for (int j = 0; j < n; ++j) out_.u64(nodes[j]);
                } else {
                    out_.text("%zu", tags_[e.dim][k]);
                    for (int j = 0; j < n; ++j) out_.text(" %llu", static_cast<unsigned long long>(nodes[j]));
                    out_.text("\n");
                }
            }
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

    void write_elements22() {
        out_.text("$Elements\n%zu\n", nelements_);
        uint64_t nodes[4];
        for (int dim = 0; dim < 4; ++dim) {
            const std::vector<int32_t>& entity = layout_.element_entity[dim];
            const size_t n = static_cast<size_t>(std::count_if(entity.begin(), entity.end(), [](int32_t e) { return e >= 0; }));
            if (binary_ && n > 0) {  // one header for the elements of a type with two tags
                out_.i32(kTypeOfDim[dim]);
                out_.i32(static_cast<int64_t>(n));
                out_.i32(2);
            }
            for (size_t k = 0; k < entity.size(); ++k) {
                if (entity[k] < 0) continue;
                const GmshLayout::Entity& e = layout_.entities[static_cast<size_t>(entity[k])];
                const int32_t physical = e.physicals.empty() ? 0 : e.physicals.front();
                node_tags(dim, k, nodes);
                if (binary_) {
                    out_.i32(static_cast<int64_t>(tags_[dim][k]));
                    out_.i32(physical);
                    out_.i32(e.tag);
                    for (int j = 0; j < kNodesOfDim[dim]; ++j) out_.i32(static_cast<int64_t>(nodes[j]));
                } else {
                    out_.text("%zu %d 2 %d %d", tags_[dim][k], kTypeOfDim[dim], physical, e.tag);
                    for (int j = 0; j < kNodesOfDim[dim]; ++j)
                        out_.text(" %llu", static_cast<unsigned long long>(nodes[j]));
                    out_.text("\n");
                }
            }
        }
        out_.text("%s$EndElements\n", binary_ ? "\n" : "");
    }

    const MeshData& d_;
    const GmshLayout layout_;
    int version_;
    bool binary_;
    Out& out_;
    size_t nv_ = 0, nelements_ = 0;
    std::array<std::vector<size_t>, 4> tags_;  // per dimension and element: its tag (0: not written)
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
    const MeshData::Origins& o = d.origins;
    if (!o.tet_origins.empty() && o.tet_origins.size() != d.tets.size() / 4) bad("one origin per tet expected");
    if (o.parent_offsets.empty()) return;
    if (o.input_vertices < 0 || o.input_vertices > nv ||
        o.parent_offsets.size() != static_cast<size_t>(nv) + 1 || o.parent_offsets.front() != 0 ||
        static_cast<size_t>(o.parent_offsets.back()) != o.parents.size() || o.weights.size() != o.parents.size() ||
        !std::is_sorted(o.parent_offsets.begin(), o.parent_offsets.end()))
        bad("vertex parents that do not fit the vertices");
    for (int32_t p : o.parents)
        if (p < 0 || p >= o.input_vertices) bad("a vertex parent " + std::to_string(p) + " is not an input vertex");
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
