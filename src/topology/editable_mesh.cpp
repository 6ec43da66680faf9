#include "topology/editable_mesh.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <string>

namespace bodt {

namespace {

constexpr int32_t kNoMarker = INT32_MIN;
constexpr double kUnknownSine = std::numeric_limits<double>::quiet_NaN();
constexpr double kNoSineFloor = -std::numeric_limits<double>::infinity();

// The two vertices of q other than a and b, ordered so that (a, b, c, d)
// is an even permutation of q: the positions of a, b, c, d in q have an
// even number of inversions.
std::array<int32_t, 2> other_two(const Tet& q, int32_t a, int32_t b) {
    int pa = 0, pb = 0, pc = -1, pd = -1;
    for (int i = 0; i < 4; ++i) {
        if (q[i] == a) pa = i;
        else if (q[i] == b) pb = i;
        else (pc < 0 ? pc : pd) = i;
    }
    const int pos[4] = {pa, pb, pc, pd};
    int inversions = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) inversions += pos[i] > pos[j];
    return inversions % 2 == 0 ? std::array<int32_t, 2>{q[pc], q[pd]} : std::array<int32_t, 2>{q[pd], q[pc]};
}

// Room for the tets and vertices the operations add, 1/32 of `size`: a
// per-tet or per-vertex array that had to grow would be copied whole at
// twice its size, and past glibc's mmap threshold (32 MB) the kernel zeroes
// the new block's pages (a 1e7-tet mesh's arrays are far past it).
size_t with_room(size_t size) { return size + size / 32; }

template <class T>
void copy_with_room(std::vector<T>& to, const std::vector<T>& from) {
    to.reserve(with_room(from.size()));
    to.assign(from.begin(), from.end());
}

template <class T>
void fill_with_room(std::vector<T>& to, size_t size, const T& value) {
    to.reserve(with_room(size));
    to.assign(size, value);
}

}  // namespace

EditableMesh::EditableMesh(const TetMesh& mesh, const VertexClasses& classes)
    : parents_(mesh.new_parents),
      markers_(mesh.face_markers),
      caller_features_(mesh.feature_edges),
      features_(classes.feature_edges),
      input_vertices_(mesh.num_input_vertices()) {
    if (classes.cls.size() != mesh.points.size())
        throw Error(BODT_ERR_NUMERIC, "internal error: " + std::to_string(classes.cls.size()) +
                                          " vertex classes for " + std::to_string(mesh.points.size()) + " vertices");
    copy_with_room(points_, mesh.points);
    copy_with_room(cls_, classes.cls);
    copy_with_room(tets_, mesh.tets);
    copy_with_room(regions_, mesh.regions);
    fill_with_room(sine_, tets_.size(), kUnknownSine);
    fill_with_room(stamp_, points_.size(), uint64_t{0});
    fill_with_room(pins_, points_.size(), uint8_t{0});
    fill_with_room(marked_at_, points_.size(), int32_t{0});
    for (const auto& [f, m] : markers_) count_marked(f, 1);
    for (size_t v = 0; v < points_.size(); ++v) pins_[v] = mesh.vflags[v] & kPinned;
    for (const auto& [key, ref] : caller_features_) features_.insert(key);
    if (mesh.tet_origin.empty()) {
        fill_with_room(origin_, tets_.size(), int32_t{0});
        for (size_t t = 0; t < tets_.size(); ++t) origin_[t] = static_cast<int32_t>(t);
    } else {
        copy_with_room(origin_, mesh.tet_origin);
    }
    // Room for a few more tets at each vertex: flips and splits add some.
    constexpr int32_t kSpare = 4;
    fill_with_room(vt_, points_.size(), TetSlot{});
    size_t at = 0;
    for (size_t v = 0; v < points_.size(); ++v) {
        const int32_t n = static_cast<int32_t>(mesh.star_end(static_cast<int32_t>(v)) - mesh.star_begin(static_cast<int32_t>(v)));
        vt_[v] = {at, 0, n + kSpare};
        at += static_cast<size_t>(n + kSpare);
    }
    // A little room for the lists that move: the first would otherwise
    // reallocate the whole pool at twice its size.
    vt_pool_.reserve(with_room(at));
    vt_pool_.resize(at);
    for (int32_t t = 0; t < tet_capacity(); ++t)
        for (int32_t v : tets_[t]) vt_pool_[vt_[v].at + static_cast<size_t>(vt_[v].size++)] = t;  // ascending
}

std::vector<int32_t> EditableMesh::write_to(TetMesh& mesh) const {
    // Vertex numbering: input vertices stay; made ones that are still used
    // follow in the order they were made.
    std::vector<int32_t> renumber(points_.size(), -1);
    int32_t next = input_vertices_;
    for (int32_t v = 0; v < num_vertices(); ++v)
        renumber[v] = v < input_vertices_ ? v : (vt_[v].size == 0 ? -1 : next++);
    // Reserved in full: a vector grown by doubling touches twice the pages,
    // and a block past glibc's mmap threshold (32 MB) is mapped afresh at
    // each growth, its pages zeroed by the kernel.
    mesh.points.reserve(static_cast<size_t>(next));
    mesh.points.assign(points_.begin(), points_.begin() + input_vertices_);
    mesh.new_parents.clear();
    std::vector<uint8_t> flags(static_cast<size_t>(next), 0);
    for (int32_t v = 0; v < num_vertices(); ++v) {
        if (renumber[v] < 0) continue;
        flags[renumber[v]] = pins_[v];
        if (v < input_vertices_) continue;
        mesh.points.push_back(points_[v]);
        mesh.new_parents.push_back(parents_[v - input_vertices_]);
    }
    mesh.vflags = std::move(flags);
    mesh.tets.clear();
    mesh.regions.clear();
    mesh.tet_origin.clear();
    // The slots, live or not: a bound for the live tets without a pass to count them.
    mesh.tets.reserve(tets_.size());
    mesh.regions.reserve(tets_.size());
    mesh.tet_origin.reserve(tets_.size());
    for (int32_t t = 0; t < tet_capacity(); ++t) {
        if (!alive(t)) continue;
        const Tet& q = tets_[t];
        mesh.tets.push_back({renumber[q[0]], renumber[q[1]], renumber[q[2]], renumber[q[3]]});
        mesh.regions.push_back(regions_[t]);
        mesh.tet_origin.push_back(origin_[t]);
    }
    mesh.face_markers.clear();
    for (const auto& [f, m] : markers_)
        mesh.face_markers.emplace(FaceKey::of(renumber[f.v[0]], renumber[f.v[1]], renumber[f.v[2]]), m);
    mesh.feature_edges.clear();
    for (const auto& [k, ref] : caller_features_)
        mesh.feature_edges.emplace(edge_key(renumber[edge_first(k)], renumber[edge_second(k)]), ref);
    mesh.reversed.clear();
    return renumber;
}

std::vector<int32_t> EditableMesh::written_tets() const {
    std::vector<int32_t> out(tets_.size(), -1);
    int32_t next = 0;
    for (int32_t t = 0; t < tet_capacity(); ++t)
        if (alive(t)) out[t] = next++;
    return out;
}

std::vector<Tet> EditableMesh::written_neighbors(const std::vector<Tet>& before,
                                                 const std::vector<int32_t>& written) const {
    std::vector<Tet> out;
    out.reserve(tets_.size());
    for (int32_t t = 0; t < tet_capacity(); ++t) {
        if (!alive(t)) continue;
        const Tet& q = tets_[t];
        const bool old = static_cast<size_t>(t) < before.size();
        Tet n;
        for (int i = 0; i < 4; ++i) {
            int32_t s = old ? before[t][i] : -1;
            if (!old || (s >= 0 && !alive(s))) {
                const auto& f = kFaceVertex[i];
                int32_t pair[2];
                const int k = face_tets(FaceKey::of(q[f[0]], q[f[1]], q[f[2]]), pair);
                s = -1;
                for (int j = 0; j < k; ++j)
                    if (pair[j] != t) s = pair[j];
            }
            n[i] = s < 0 ? -1 : written[s];
        }
        out.push_back(n);
    }
    return out;
}

void EditableMesh::write_shapes(const std::vector<int32_t>& written, std::vector<TetShape>& shapes,
                                const TetMesh& mesh) const {
    const size_t before = shapes.size(), count = mesh.tets.size();
    if (count > shapes.capacity()) shapes.reserve(with_room(count));  // as for the tets
    if (count > before) shapes.resize(count);
    // Slot t is written to written[t] <= t (the live slots before it), so
    // slot t is read before anything is written there.
    for (int32_t t = 0; t < tet_capacity(); ++t) {
        const int32_t w = written[t];
        if (w < 0) continue;
        const Tet& q = tets_[t];
        const bool kept = static_cast<size_t>(t) < before && stamp_[q[0]] == 0 && stamp_[q[1]] == 0 &&
                          stamp_[q[2]] == 0 && stamp_[q[3]] == 0;
        shapes[w] = kept ? shapes[t] : tet_shape(mesh.tet_points(w));
    }
    shapes.resize(count);
}

TetPoints EditableMesh::tet_points(int32_t t) const {
    const Tet& q = tets_[t];
    return {points_[q[0]], points_[q[1]], points_[q[2]], points_[q[3]]};
}

double EditableMesh::tet_sine(int32_t t) const {
    if (std::isnan(sine_[t])) sine_[t] = min_dihedral_sine(tet_points(t));
    return sine_[t];
}

void EditableMesh::bound_sines(const std::vector<TetShape>& shapes) {
    // The kernel's cosines and min_dihedral_sine's products differ by
    // round-off (about 1e-15 here); the margin keeps the bound below the
    // sine for every tet whose sine it could pass over.
    constexpr double kMargin = 1e-9;
    fill_with_room(sine_floor_, tets_.size(), kNoSineFloor);
    for (size_t t = 0; t < shapes.size() && t < sine_floor_.size(); ++t) {
        const TetShape& s = shapes[t];
        if (!(s.stretch > 0.0)) continue;
        const double c = worst_cosine(s.cosines);
        sine_floor_[t] = std::sqrt(std::max(0.0, 1.0 - c * c)) - kMargin;
    }
}

std::vector<int32_t> EditableMesh::tets_holding(std::initializer_list<int32_t> vs) const {
    std::vector<int32_t> out;
    for (int32_t t : tets_of(*vs.begin())) {
        const Tet& q = tets_[t];
        if (std::all_of(vs.begin(), vs.end(), [&q](int32_t v) { return holds(q, v); }))
            out.push_back(t);
    }
    return out;
}

bool EditableMesh::has_tet(const Tet& q) const {
    int32_t fewest = q[0];
    for (int32_t v : q)
        if (vt_[v].size < vt_[fewest].size) fewest = v;
    for (int32_t t : tets_of(fewest)) {
        const Tet& r = tets_[t];
        if (holds(r, q[0]) & holds(r, q[1]) & holds(r, q[2]) & holds(r, q[3])) return true;
    }
    return false;
}

int EditableMesh::face_tets(const FaceKey& f, int32_t out[2]) const {
    int n = 0;
    for (int32_t t : tets_of(f.v[0])) {
        const Tet& q = tets_[t];
        if (holds(q, f.v[1]) && holds(q, f.v[2]) && n < 2) out[n++] = t;
    }
    return n;
}

bool EditableMesh::is_surface_face(const FaceKey& f) const {
    int32_t t[2];
    const int n = face_tets(f, t);
    if (n == 1) return true;
    if (n == 2 && regions_[t[0]] != regions_[t[1]]) return true;
    return n == 2 && has_marker(f);
}

int32_t EditableMesh::marker(const FaceKey& f) const {
    if (!may_be_marked(f)) return 0;
    const auto it = markers_.find(f);
    return it == markers_.end() ? 0 : it->second;
}

bool EditableMesh::is_surface_edge(int32_t a, int32_t b) const {
    for (int32_t t : tets_of(a)) {
        const Tet& q = tets_[t];
        if (!holds(q, b)) continue;
        for (int32_t c : q)
            if (c != a && c != b && is_surface_face(FaceKey::of(a, b, c))) return true;
    }
    return false;
}

bool EditableMesh::has_edge(int32_t a, int32_t b) const {
    for (int32_t t : tets_of(a))
        if (holds(tets_[t], b)) return true;
    return false;
}

bool EditableMesh::edge_ring(int32_t a, int32_t b, EdgeRing& out) const {
    out.ring.clear();
    out.tets.clear();
    out.closed = false;
    // Each tet (a, b, c, d) in positive order links c -> d.
    auto& links = ring_links_;  // c, d, tet
    links.clear();
    for (int32_t t : tets_of(a)) {
        const Tet& q = tets_[t];
        if (!holds(q, b)) continue;
        const std::array<int32_t, 2> cd = other_two(q, a, b);
        links.push_back({cd[0], cd[1], t});
    }
    if (links.empty()) return false;
    // Start where no link ends (an open fan), else anywhere.
    size_t start = 0;
    for (size_t i = 0; i < links.size(); ++i) {
        const bool has_pred = std::any_of(links.begin(), links.end(), [&](const auto& l) { return l[1] == links[i][0]; });
        if (!has_pred) {
            start = i;
            break;
        }
    }
    size_t cur = start;
    out.ring.push_back(links[cur][0]);
    for (size_t k = 0; k < links.size(); ++k) {
        links[cur][0] = -1;  // used: no vertex links from -1
        out.tets.push_back(links[cur][2]);
        const int32_t d = links[cur][1];
        size_t nxt = links.size();
        for (size_t i = 0; i < links.size(); ++i)
            if (links[i][0] == d) {
                if (nxt != links.size()) return false;  // two tets continue the fan
                nxt = i;
            }
        if (nxt == links.size()) {
            if (k + 1 != links.size()) return false;  // the fan ended early
            out.closed = d == out.ring.front();
            if (!out.closed) out.ring.push_back(d);
            break;
        }
        out.ring.push_back(d);
        cur = nxt;
    }
    return true;
}

void EditableMesh::neighbors(int32_t v, std::vector<int32_t>& out) const {
    out.clear();
    for (int32_t t : tets_of(v))
        for (int32_t w : tets_[t])
            if (w != v) out.push_back(w);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

// ------------------------------------------------------------------ changes

void EditableMesh::attach(int32_t t, const std::array<int32_t, 4>* at) {
    for (int i = 0; i < 4; ++i) {
        TetSlot& slot = vt_[tets_[t][i]];
        if (slot.size == slot.room) {
            const size_t moved = vt_pool_.size();
            const int32_t room = 2 * slot.room + 4;
            vt_pool_.resize(moved + static_cast<size_t>(room));
            std::copy_n(vt_pool_.begin() + static_cast<std::ptrdiff_t>(slot.at), slot.size,
                        vt_pool_.begin() + static_cast<std::ptrdiff_t>(moved));
            slot.at = moved;
            slot.room = room;
        }
        int32_t* list = vt_pool_.data() + slot.at;
        const int32_t k = at ? (*at)[i] : slot.size;
        std::copy_backward(list + k, list + slot.size, list + slot.size + 1);
        list[k] = t;
        ++slot.size;
        set_stamp(tets_[t][i], ++clock_);
    }
}

std::array<int32_t, 4> EditableMesh::detach(int32_t t) {
    std::array<int32_t, 4> at;
    for (int i = 0; i < 4; ++i) {
        TetSlot& slot = vt_[tets_[t][i]];
        int32_t* list = vt_pool_.data() + slot.at;
        const int32_t k = static_cast<int32_t>(std::find(list, list + slot.size, t) - list);
        at[i] = k;
        std::copy(list + k + 1, list + slot.size, list + k);
        --slot.size;
        set_stamp(tets_[t][i], ++clock_);
    }
    return at;
}

int32_t EditableMesh::add_vertex(const Vec3& p, VertexClass cls, Parents parents) {
    const int32_t v = num_vertices();
    points_.push_back(p);
    marked_at_.push_back(0);
    cls_.push_back(cls);
    pins_.push_back(0);
    parents_.push_back(std::move(parents));
    vt_.push_back({vt_pool_.size(), 0, 0});
    stamp_.push_back(++clock_);
    ++stamped_;
    journal_.push_back({Change::AddVertex, v, {}, 0, Vec3::Zero(), 0, {}});
    return v;
}

void EditableMesh::move_vertex(int32_t v, const Vec3& p) {
    journal_.push_back({Change::MoveVertex, v, {}, 0, points_[v], 0, {}});
    old_stamps_.push_back({stamp_[v], 0, 0, 0});
    place(v, p);
}

void EditableMesh::place(int32_t v, const Vec3& p) {
    points_[v] = p;
    set_stamp(v, ++clock_);
    for (int32_t t : tets_of(v)) {
        sine_[t] = kUnknownSine;
        if (!sine_floor_.empty()) sine_floor_[t] = kNoSineFloor;
    }
}

void EditableMesh::set_parents(int32_t v, Parents parents) {
    journal_.push_back({Change::SetParents, v, {}, 0, Vec3::Zero(), 0, {}});
    old_parents_.push_back(std::move(parents_[v - input_vertices_]));
    parents_[v - input_vertices_] = std::move(parents);
}

int32_t EditableMesh::add_tet(const Tet& q, int32_t region, int32_t origin) {
    const int32_t t = tet_capacity();
    tets_.push_back(q);
    sine_.push_back(kUnknownSine);
    if (!sine_floor_.empty()) sine_floor_.push_back(kNoSineFloor);
    regions_.push_back(region);
    origin_.push_back(origin);
    old_stamps_.push_back(stamps_of(q));
    attach(t);
    journal_.push_back({Change::AddTet, t, {}, 0, Vec3::Zero(), 0, {}});
    return t;
}

void EditableMesh::remove_tet(int32_t t) {
    old_stamps_.push_back(stamps_of(tets_[t]));
    removed_.push_back({tets_[t], detach(t)});
    tets_[t] = {-1, -1, -1, -1};
    journal_.push_back({Change::RemoveTet, t, {}, 0, Vec3::Zero(), 0, {}});
}

void EditableMesh::set_marker(const FaceKey& f, int32_t m) {
    const auto it = markers_.find(f);
    journal_.push_back({Change::SetMarker, 0, f, it == markers_.end() ? kNoMarker : it->second, Vec3::Zero(), 0, {}});
    if (it == markers_.end()) count_marked(f, 1);
    markers_[f] = m;
}

void EditableMesh::erase_marker(const FaceKey& f) {
    const auto it = markers_.find(f);
    if (it == markers_.end()) return;
    journal_.push_back({Change::EraseMarker, 0, f, it->second, Vec3::Zero(), 0, {}});
    markers_.erase(it);
    count_marked(f, -1);
}

void EditableMesh::add_feature_edge(int32_t a, int32_t b, CallerRef caller) {
    const EdgeKey k = edge_key(a, b);
    if (features_.count(k)) return;
    features_.insert(k);
    if (caller) caller_features_.emplace(k, *caller);
    journal_.push_back({Change::AddFeature, 0, {}, 0, Vec3::Zero(), k, caller});
}

CallerRef EditableMesh::erase_feature_edge(int32_t a, int32_t b) {
    const EdgeKey k = edge_key(a, b);
    if (!features_.erase(k)) return std::nullopt;
    CallerRef caller;
    if (const auto it = caller_features_.find(k); it != caller_features_.end()) {
        caller = it->second;
        caller_features_.erase(it);
    }
    journal_.push_back({Change::EraseFeature, 0, {}, 0, Vec3::Zero(), k, caller});
    return caller;
}

void EditableMesh::rollback(size_t mark) {
    while (journal_.size() > mark) {
        const Entry e = journal_.back();
        journal_.pop_back();
        switch (e.kind) {
            case Change::AddVertex:
                points_.pop_back();
                marked_at_.pop_back();
                cls_.pop_back();
                pins_.pop_back();
                parents_.pop_back();
                vt_.pop_back();
                set_stamp(static_cast<int32_t>(stamp_.size()) - 1, 0);
                stamp_.pop_back();
                break;
            case Change::MoveVertex:
                place(e.index, e.old_point);
                set_stamp(e.index, old_stamps_.back()[0]);
                old_stamps_.pop_back();
                break;
            case Change::SetParents:
                parents_[e.index - input_vertices_] = std::move(old_parents_.back());
                old_parents_.pop_back();
                break;
            case Change::AddTet:
                detach(e.index);
                restore_stamps(tets_[e.index], old_stamps_.back());
                old_stamps_.pop_back();
                tets_.pop_back();
                sine_.pop_back();
                if (!sine_floor_.empty()) sine_floor_.pop_back();
                regions_.pop_back();
                origin_.pop_back();
                break;
            case Change::RemoveTet:
                tets_[e.index] = removed_.back().tet;
                sine_[e.index] = kUnknownSine;
                if (!sine_floor_.empty()) sine_floor_[e.index] = kNoSineFloor;
                attach(e.index, &removed_.back().at);
                removed_.pop_back();
                restore_stamps(tets_[e.index], old_stamps_.back());
                old_stamps_.pop_back();
                break;
            case Change::SetMarker:
                if (e.old_marker == kNoMarker) {
                    markers_.erase(e.face);
                    count_marked(e.face, -1);
                } else {
                    markers_[e.face] = e.old_marker;
                }
                break;
            case Change::EraseMarker:
                markers_[e.face] = e.old_marker;
                count_marked(e.face, 1);
                break;
            case Change::AddFeature:
                features_.erase(e.edge);
                caller_features_.erase(e.edge);
                break;
            case Change::EraseFeature:
                features_.insert(e.edge);
                if (e.caller) caller_features_.emplace(e.edge, *e.caller);
                break;
        }
    }
}

}  // namespace bodt
