// Puts each element to be written into a Gmsh entity; see gmsh_layout.hpp.
#include "io/gmsh_layout.hpp"

#include "mesh/element_keys.hpp"

#include <algorithm>
#include <climits>
#include <memory>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>

namespace bodt {

namespace {

constexpr int32_t kNone = -1;

// The input vertices a vertex stands for, with weights: an input vertex is
// its own, a made vertex has its parents (MeshData::Origins); without
// origins every vertex is an input vertex.
class Parentage {
public:
    explicit Parentage(const MeshData::Origins& o) : o_(o) {}

    template <class F>
    void each(int32_t v, F&& f) const {
        if (o_.parent_offsets.empty()) {
            f(v, 1.0);
            return;
        }
        const auto k = static_cast<size_t>(v);
        for (int64_t i = o_.parent_offsets[k]; i < o_.parent_offsets[k + 1]; ++i)
            f(o_.parents[static_cast<size_t>(i)], o_.weights[static_cast<size_t>(i)]);
    }

private:
    const MeshData::Origins& o_;
};

// Which model entities of one dimension hold each input vertex in their
// input elements (`per` vertices each): sorted lists, CSR.
class Membership {
public:
    Membership(const std::vector<int32_t>& vertices, int per, const std::vector<int32_t>& entity, size_t nv) {
        std::vector<std::pair<int32_t, int32_t>> pairs;
        for (size_t k = 0; k < entity.size(); ++k)
            if (entity[k] != kNone)
                for (int i = 0; i < per; ++i) pairs.push_back({vertices[per * k + i], entity[k]});
        std::sort(pairs.begin(), pairs.end());
        pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
        offsets_.assign(nv + 1, 0);
        for (const auto& p : pairs) ++offsets_[static_cast<size_t>(p.first) + 1];
        for (size_t v = 0; v < nv; ++v) offsets_[v + 1] += offsets_[v];
        for (const auto& p : pairs) entities_.push_back(p.second);
    }

    bool holds(int32_t v, int32_t e) const {
        if (v < 0 || static_cast<size_t>(v) + 1 >= offsets_.size()) return false;
        const auto first = entities_.begin() + static_cast<std::ptrdiff_t>(offsets_[static_cast<size_t>(v)]);
        const auto last = entities_.begin() + static_cast<std::ptrdiff_t>(offsets_[static_cast<size_t>(v) + 1]);
        return std::binary_search(first, last, e);
    }

private:
    std::vector<size_t> offsets_;
    std::vector<int32_t> entities_;
};

class Builder {
public:
    explicit Builder(const MeshData& d) : d_(d), parentage_(d.origins) {
        nv_ = d.xyz.size() / 3;
        const size_t input = d.origins.parent_offsets.empty() ? nv_ : static_cast<size_t>(d.origins.input_vertices);
        if (!d.gmsh || !d.gmsh->fits(input)) return;
        m_ = d.gmsh.get();
        used_.assign(nv_, 0);
        for (const int32_t v : d.tets) used_[vertex(v)] = 1;
    }

    GmshLayout build() {
        take_model();
        place_tets();
        place_triangles();
        place_lines();
        place_points();
        order_by_dimension();
        keep_known_bounding();
        fill_physical_zero();
        fill_boxes();
        place_nodes();
        name_groups();
        return std::move(out_);
    }

private:
    size_t vertex(int32_t v) const { return static_cast<size_t>(v - d_.base); }

    // ---- entities
    int32_t add_entity(int dim, int32_t tag, std::vector<int32_t> physicals, bool computed_box) {
        GmshLayout::Entity e;
        e.dim = dim;
        e.tag = tag;
        e.physicals = std::move(physicals);
        out_.entities.push_back(std::move(e));
        computed_box_.push_back(computed_box);
        tags_[dim].insert(tag);
        return static_cast<int32_t>(out_.entities.size() - 1);
    }

    void take_model() {
        if (!m_) return;
        for (const GmshEntity& e : m_->entities) {
            add_entity(e.dim, e.tag, e.physicals, !e.has_box);
            out_.entities.back().bounding = e.bounding;
            out_.entities.back().box = e.box;
        }
        const std::pair<const std::vector<int32_t>*, int> held[] = {
            {&m_->point_entity, 0}, {&m_->line_entity, 1}, {&m_->triangle_entity, 2}, {&m_->tet_entity, 3}};
        held_.assign(m_->entities.size(), 0);
        for (const auto& [entities, dim] : held)
            for (const int32_t e : *entities)
                if (e != kNone) held_[static_cast<size_t>(e)] = 1;
        for (size_t k = 0; k < m_->triangle_entity.size(); ++k) {
            const int32_t* v = &m_->triangles[3 * k];
            input_triangles_.emplace(FaceKey::of(v[0], v[1], v[2]), m_->triangle_entity[k]);
        }
        for (size_t k = 0; k < m_->line_entity.size(); ++k)
            input_lines_.emplace(edge_key(m_->lines[2 * k], m_->lines[2 * k + 1]), m_->line_entity[k]);
        index_candidates();
    }

    // Model entity e takes elements with value r (region, marker, ref): r
    // is its key, or one of its physical tags where those are the values.
    bool accepts(int32_t e, int32_t r) const {
        const GmshEntity& entity = m_->entities[static_cast<size_t>(e)];
        if (m_->key(entity) == r) return true;
        return !m_->entity_keyed[entity.dim] && r != 0 &&
               std::find(entity.physicals.begin(), entity.physicals.end(), r) != entity.physicals.end();
    }

    // The model entities of `dim` that take value r, in the model's order;
    // for r = 0 (no physical group) only those that held elements.
    const std::vector<int32_t>& candidates(int dim, int32_t r) const {
        static const std::vector<int32_t> none;
        const auto it = candidates_.find({dim, r});
        return it == candidates_.end() ? none : it->second;
    }

    void index_candidates() {
        for (size_t k = 0; k < m_->entities.size(); ++k) {
            const GmshEntity& e = m_->entities[k];
            const auto index = static_cast<int32_t>(k);
            std::set<int32_t> values{m_->key(e)};
            if (!m_->entity_keyed[e.dim])
                for (const int32_t p : e.physicals)
                    if (p != 0) values.insert(p);
            for (const int32_t r : values)
                if (r != 0 || held_[k]) candidates_[{e.dim, r}].push_back(index);
        }
    }

    // `wish` if it is a free tag of `dim`, else the one after the largest
    // (or the first free one when that is INT32_MAX).
    int32_t free_tag(int dim, int32_t wish) {
        if (wish > 0 && !tags_[dim].count(wish)) return wish;
        return next_free(tags_[dim]);
    }

    static int32_t next_free(const std::set<int32_t>& taken) {
        const int32_t largest = taken.empty() ? 0 : std::max(*taken.rbegin(), 0);
        if (largest < INT32_MAX) return largest + 1;
        int32_t t = 1;
        while (taken.count(t)) ++t;
        return t;
    }

    // The new entity of `dim` for the elements of value r that fit no model
    // entity (gmsh_layout.hpp).
    int32_t new_entity(int dim, int32_t r) {
        const auto [it, fresh] = made_.emplace(std::make_pair(dim, r), kNone);
        if (!fresh) return it->second;
        const bool keyed = m_ && m_->entity_keyed[dim];
        std::vector<int32_t> physicals;
        if (!keyed && r != 0) physicals.push_back(r);
        it->second = add_entity(dim, free_tag(dim, r), std::move(physicals), true);
        return it->second;
    }

    const Membership& membership(int dim) {
        std::unique_ptr<Membership>& m = membership_[dim];
        if (!m) {
            if (dim == 1)
                m = std::make_unique<Membership>(m_->lines, 2, m_->line_entity, nv_);
            else
                m = std::make_unique<Membership>(m_->triangles, 3, m_->triangle_entity, nv_);
        }
        return *m;
    }

    // Among `candidates`, the entity the element's vertices (`n`, from
    // base) lie on most; with `positive`, none unless they lie on it at all.
    int32_t lies_on(int dim, const std::vector<int32_t>& candidates, const int32_t* v, int n, bool positive) {
        if (candidates.size() == 1 && !positive) return candidates[0];
        const Membership& held = membership(dim);
        int32_t best = positive ? kNone : candidates.front();
        double most = 0.0;
        for (const int32_t e : candidates) {
            double score = 0.0;
            for (int i = 0; i < n; ++i)
                parentage_.each(static_cast<int32_t>(vertex(v[i])), [&](int32_t p, double w) {
                    if (held.holds(p, e)) score += w;
                });
            if (score > most) {
                most = score;
                best = e;
            }
        }
        return best;
    }

    // ---- elements
    void place_tets() {
        const size_t nt = d_.tets.size() / 4;
        std::vector<int32_t>& out = out_.element_entity[3];
        out.assign(nt, kNone);
        const std::vector<int32_t>& origins = d_.origins.tet_origins;
        for (size_t t = 0; t < nt; ++t) {
            const int32_t r = d_.regions.empty() ? 0 : d_.regions[t];
            int32_t e = kNone;
            if (m_) {
                const int64_t o = origins.empty() ? static_cast<int64_t>(t) : origins[t];
                if (o >= 0 && static_cast<size_t>(o) < m_->tet_entity.size()) {
                    const int32_t from = m_->tet_entity[static_cast<size_t>(o)];
                    if (from != kNone && accepts(from, r)) e = from;
                }
                if (e == kNone && !candidates(3, r).empty()) e = candidates(3, r).front();
            }
            out[t] = e != kNone ? e : new_entity(3, r);
        }
    }

    void place_triangles() {
        const size_t nf = d_.tri_markers.size();
        std::vector<int32_t>& out = out_.element_entity[2];
        out.assign(nf, kNone);
        // unmarked faces only where the model held triangles without a physical group
        const bool unmarked_surfaces = m_ && !candidates(2, 0).empty();
        for (size_t f = 0; f < nf; ++f) {
            const int32_t r = d_.tri_markers[f];
            if (r == 0 && !unmarked_surfaces) continue;
            const int32_t* v = &d_.triangles[3 * f];
            int32_t e = kNone;
            if (m_) {
                const auto it = input_triangles_.find(FaceKey::of(static_cast<int32_t>(vertex(v[0])),
                                                                 static_cast<int32_t>(vertex(v[1])),
                                                                 static_cast<int32_t>(vertex(v[2]))));
                if (it != input_triangles_.end() && it->second != kNone && accepts(it->second, r))
                    e = it->second;
                else if (!candidates(2, r).empty())
                    e = lies_on(2, candidates(2, r), v, 3, r == 0);
            }
            if (e == kNone && r != 0) e = new_entity(2, r);
            out[f] = e;
        }
    }

    void place_lines() {
        const size_t ne = d_.feature_edges.size() / 2;
        std::vector<int32_t>& out = out_.element_entity[1];
        out.assign(ne, kNone);
        for (size_t k = 0; k < ne; ++k) {
            const int32_t r = d_.edge_refs.empty() ? 0 : d_.edge_refs[k];
            const int32_t* v = &d_.feature_edges[2 * k];
            int32_t e = kNone;
            if (m_) {
                const auto it = input_lines_.find(
                    edge_key(static_cast<int32_t>(vertex(v[0])), static_cast<int32_t>(vertex(v[1]))));
                if (it != input_lines_.end() && it->second != kNone && accepts(it->second, r))
                    e = it->second;
                else if (!candidates(1, r).empty())
                    e = lies_on(1, candidates(1, r), v, 2, r == 0);
            }
            out[k] = e != kNone ? e : new_entity(1, r);
        }
    }

    // The physical group of the fixed vertices that had none in the model.
    int32_t fixed_group() {
        if (fixed_group_ != 0) return fixed_group_;
        std::set<int32_t> taken;
        if (m_) {
            for (const GmshEntity& e : m_->entities)
                if (e.dim == 0) taken.insert(e.physicals.begin(), e.physicals.end());
            for (const GmshPhysicalName& n : m_->names)
                if (n.dim == 0) taken.insert(n.tag);
        }
        fixed_group_ = next_free(taken);
        return fixed_group_;
    }

    void add_point(int32_t v, int32_t e) {
        out_.points.push_back(v);
        out_.element_entity[0].push_back(e);
    }

    // Fixed vertices, then the model's point elements without a physical
    // group whose vertex is still in a tet.
    void place_points() {
        std::map<int32_t, int32_t> physical_points;  // vertex -> the first model point entity with a physical tag
        std::set<std::pair<int32_t, int32_t>> written;
        if (m_)
            for (size_t k = 0; k < m_->points.size(); ++k) {
                const int32_t e = m_->point_entity[k];
                if (e != kNone && m_->key(m_->entities[static_cast<size_t>(e)]) != 0)
                    physical_points.emplace(m_->points[k], e);
            }
        for (const int32_t f : d_.fixed) {
            const auto v = static_cast<int32_t>(vertex(f));
            const auto it = physical_points.find(v);
            const int32_t e = it != physical_points.end() ? it->second
                                                          : add_entity(0, free_tag(0, 0), {fixed_group()}, true);
            add_point(v, e);
            written.insert({v, e});
        }
        if (!m_) return;
        for (size_t k = 0; k < m_->points.size(); ++k) {
            const int32_t v = m_->points[k], e = m_->point_entity[k];
            if (e == kNone || m_->key(m_->entities[static_cast<size_t>(e)]) != 0 || !used_[static_cast<size_t>(v)])
                continue;
            if (written.insert({v, e}).second) add_point(v, e);
        }
    }

    // ---- after the elements
    // Entities by dimension (each dimension in the order they were added),
    // their element lists filled.
    void order_by_dimension() {
        const size_t n = out_.entities.size();
        std::vector<int32_t> order(n);
        for (size_t k = 0; k < n; ++k) order[k] = static_cast<int32_t>(k);
        std::stable_sort(order.begin(), order.end(),
                         [&](int32_t a, int32_t b) { return out_.entities[a].dim < out_.entities[b].dim; });
        std::vector<int32_t>& moved_to = model_to_layout_;
        moved_to.resize(n);
        std::vector<GmshLayout::Entity> entities(n);
        std::vector<uint8_t> computed(n);
        for (size_t k = 0; k < n; ++k) {
            moved_to[static_cast<size_t>(order[k])] = static_cast<int32_t>(k);
            entities[k] = std::move(out_.entities[static_cast<size_t>(order[k])]);
            computed[k] = computed_box_[static_cast<size_t>(order[k])];
        }
        out_.entities = std::move(entities);
        computed_box_ = std::move(computed);
        for (auto& of_dim : out_.element_entity)
            for (size_t k = 0; k < of_dim.size(); ++k) {
                int32_t& e = of_dim[k];
                if (e == kNone) continue;
                e = moved_to[static_cast<size_t>(e)];
                out_.entities[static_cast<size_t>(e)].elements.push_back(static_cast<int32_t>(k));
            }
    }

    void keep_known_bounding() {
        std::set<std::pair<int, int32_t>> known;
        for (const auto& e : out_.entities) known.insert({e.dim, e.tag});
        for (auto& e : out_.entities) {
            std::vector<int32_t> kept;
            for (const int32_t b : e.bounding)
                if (b != INT32_MIN && known.count({e.dim - 1, b < 0 ? -b : b})) kept.push_back(b);
            e.bounding = std::move(kept);
        }
    }

    void fill_physical_zero() {
        bool grouped = false;
        for (const auto& e : out_.entities) grouped = grouped || (!e.elements.empty() && !e.physicals.empty());
        if (!grouped) return;
        for (auto& e : out_.entities)
            if (!e.elements.empty() && e.physicals.empty()) e.physicals.push_back(0);
    }

    // The vertices (from base) of element k of `dim`.
    template <class F>
    void element_vertices(int dim, int32_t k, F&& f) const {
        const auto i = static_cast<size_t>(k);
        if (dim == 0) {
            f(out_.points[i]);
            return;
        }
        const int n = dim + 1;
        const int32_t* v = dim == 1 ? &d_.feature_edges[2 * i] : dim == 2 ? &d_.triangles[3 * i] : &d_.tets[4 * i];
        for (int j = 0; j < n; ++j) f(static_cast<int32_t>(vertex(v[j])));
    }

    void fill_boxes() {
        std::array<double, 6> all{};
        box_of(all, [&](auto&& f) {
            for (size_t v = 0; v < nv_; ++v) f(static_cast<int32_t>(v));
        });
        for (size_t k = 0; k < out_.entities.size(); ++k) {
            GmshLayout::Entity& e = out_.entities[k];
            if (!computed_box_[k]) continue;
            e.box = all;
            if (e.elements.empty()) continue;
            box_of(e.box, [&](auto&& f) {
                for (const int32_t el : e.elements) element_vertices(e.dim, el, f);
            });
        }
    }

    template <class Each>
    void box_of(std::array<double, 6>& box, Each&& each) const {
        bool first = true;
        each([&](int32_t v) {
            for (int k = 0; k < 3; ++k) {
                const double x = d_.xyz[3 * static_cast<size_t>(v) + k];
                if (first || x < box[k]) box[k] = x;
                if (first || x > box[3 + k]) box[3 + k] = x;
            }
            first = false;
        });
    }

    void place_nodes() {
        std::vector<int32_t>& node = out_.node_entity;
        node.assign(nv_, kNone);
        if (m_ && !m_->node_entity.empty())
            for (size_t v = 0; v < m_->node_entity.size(); ++v)
                if (m_->node_entity[v] != kNone) node[v] = model_to_layout_[static_cast<size_t>(m_->node_entity[v])];
        int32_t volume = kNone;
        for (size_t k = 0; k < out_.entities.size(); ++k) {
            const GmshLayout::Entity& e = out_.entities[k];
            if (e.dim == 3 && volume == kNone && !e.elements.empty()) volume = static_cast<int32_t>(k);
            for (const int32_t el : e.elements)
                element_vertices(e.dim, el, [&](int32_t v) {
                    if (node[static_cast<size_t>(v)] == kNone) node[static_cast<size_t>(v)] = static_cast<int32_t>(k);
                });
        }
        for (int32_t& e : node)
            if (e == kNone) e = volume;
    }

    void name_groups() {
        std::set<std::pair<int, int32_t>> known;
        if (m_) {
            out_.names = m_->names;
            for (const GmshPhysicalName& n : m_->names) known.insert({n.dim, n.tag});
            for (const GmshEntity& e : m_->entities)
                for (const int32_t p : e.physicals) known.insert({e.dim, p});
        }
        static const char* const kinds[] = {"", "edge ref ", "marker ", "region "};
        std::vector<GmshPhysicalName> made;
        for (const auto& e : out_.entities)
            for (const int32_t p : e.physicals)
                if (p != 0 && known.insert({e.dim, p}).second)
                    made.push_back({e.dim, p, e.dim == 0 ? std::string("fixed vertices") : kinds[e.dim] + std::to_string(p)});
        std::sort(made.begin(), made.end(), [](const GmshPhysicalName& a, const GmshPhysicalName& b) {
            return std::make_pair(a.dim, a.tag) < std::make_pair(b.dim, b.tag);
        });
        out_.names.insert(out_.names.end(), made.begin(), made.end());
    }

    const MeshData& d_;
    const GmshModel* m_ = nullptr;  // the file's model, if it fits the mesh
    Parentage parentage_;
    size_t nv_ = 0;
    std::vector<uint8_t> used_;  // per vertex: in a tet (with a model only: for its point elements)
    GmshLayout out_;
    std::vector<uint8_t> computed_box_;  // per entity: its box from its elements (not the model's)
    std::vector<uint8_t> held_;          // per model entity: it held elements in the model
    std::vector<int32_t> model_to_layout_;  // entity index before order_by_dimension (the model's first) -> after
    std::set<int32_t> tags_[4];             // the entity tags taken, per dimension
    std::map<std::pair<int, int32_t>, std::vector<int32_t>> candidates_;
    std::map<std::pair<int, int32_t>, int32_t> made_;  // (dim, value) -> new entity
    std::unordered_map<FaceKey, int32_t, FaceKeyHash> input_triangles_;  // input triangle -> its entity
    std::unordered_map<EdgeKey, int32_t> input_lines_;                  // input line -> its entity
    std::unique_ptr<Membership> membership_[3];
    int32_t fixed_group_ = 0;
};

}  // namespace

GmshLayout layout_gmsh(const MeshData& d) { return Builder(d).build(); }

}  // namespace bodt
