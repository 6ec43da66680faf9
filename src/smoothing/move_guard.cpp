#include "smoothing/move_guard.hpp"

#include <algorithm>

namespace bodt {

namespace {

Vec3 face_normal(const TetMesh& mesh, const FaceKey& f) {
    const Vec3& a = mesh.points[f.v[0]];
    return (mesh.points[f.v[1]] - a).cross(mesh.points[f.v[2]] - a);
}

// A star tet of this kernel and shape passes the guard.
BODT_KERNEL bool shape_passes(const TetKernel& k, const TetShape& shape, double floor, const CosineRange& before,
                              bool never_worse) {
    return (k.positive > 0.0) & !(shape.stretch < floor) &
           !(never_worse & ((shape.cosines.of_min > before.of_min) | (shape.cosines.of_max < before.of_max)));
}

// Star tet s with the vertex at x (star_tet_kernel); its stretch and
// cosines go to column s of `after` (3 rows of n).  Returns whether it
// passes the guard.
BODT_KERNEL bool tet_check(const double* opposite, const double* at, size_t n, size_t s, const Coords& x, double floor,
                           const CosineRange& before, bool never_worse, double* after) {
    const TetKernel k = star_tet_kernel(opposite, at, n, s, x);
    const TetShape shape = shape_of(k);
    after[s] = shape.stretch;
    after[n + s] = shape.cosines.of_min;
    after[2 * n + s] = shape.cosines.of_max;
    return shape_passes(k, shape, floor, before, never_worse);
}

// Every star tet at once, in a loop the compiler vectorises; returns the
// first tet that failed, n when none did.  `failed` is scratch for a flag
// per tet: a double, since an array of bytes would make GCC take 32 tets
// a time, more than most stars have; and a search after the loop, since a
// reduction in it would keep GCC from vectorising it.  The search is a
// plain loop: a call out of the clone (std::find is one) leaves the upper
// halves of the vector registers dirty for the SSE code after it, which
// then runs a third slower (the flip pass after a sweep did).
BODT_VECTOR_CLONES
size_t first_failing(const double* opposite, const double* at, size_t n, Coords x, const double* floor,
                     CosineRange before, bool never_worse, double* after, double* failed) {
#pragma omp simd
    for (size_t s = 0; s < n; ++s)
        failed[s] = tet_check(opposite, at, n, s, x, floor[s], before, never_worse, after) ? 0.0 : 1.0;
    size_t first = 0;
    while (first < n && failed[first] == 0.0) ++first;
    return first;
}

// The cached shapes of the n star tets `star`: each tet's stretch floor
// (min(min_stretch, its stretch)) and extreme cosines, in rows of n.
BODT_VECTOR_CLONES
void read_shapes(const int32_t* star, size_t n, const TetShape* cache, double min_stretch, double* floor,
                 double* of_min, double* of_max) {
#pragma omp simd
    for (size_t k = 0; k < n; ++k) {
        const TetShape& shape = cache[star[k]];
        floor[k] = std::min(min_stretch, shape.stretch);
        of_min[k] = shape.cosines.of_min;
        of_max[k] = shape.cosines.of_max;
    }
}

// kPlaces trials of the guard, each a star tet (repeats allowed) with the
// vertex at a place of its own: the tets' columns copied out of the star
// table, so that one pass of the vectorised kernel checks them all for
// about what one costs alone.  The halvings of one move at one tet
// (failing_attempts), or the likeliest failures of one place (acceptable).
struct Trials {
    static constexpr size_t m = MoveGuard::kPlaces;
    double rows[9 * m];    // StarTable::opposite's rows for these columns
    double corner[m];      // StarTable::at
    double floor[m];       // the tets' stretch floors
    double places[3 * m];  // x, y, z

    // Column j: star tet s, whose stretch floor is `floor_s`, with the vertex at p.
    void set(size_t j, const StarTable& star, size_t s, double floor_s, const Coords& p) {
        const size_t n = star.size();
        for (size_t r = 0; r < 9; ++r) rows[r * m + j] = star.opposite()[r * n + s];
        corner[j] = star.at()[s];
        floor[j] = floor_s;
        places[j] = p.x;
        places[m + j] = p.y;
        places[2 * m + j] = p.z;
    }
};

// failed[j] = 1 where trial j fails the guard.
BODT_VECTOR_CLONES
void trials_fail(const Trials& t, CosineRange before, bool never_worse, double* failed) {
    constexpr size_t m = Trials::m;
#pragma omp simd
    for (size_t j = 0; j < m; ++j) {
        const TetKernel k = star_tet_kernel(t.rows, t.corner, m, j, {t.places[j], t.places[m + j], t.places[2 * m + j]});
        failed[j] = shape_passes(k, shape_of(k), t.floor[j], before, never_worse) ? 0.0 : 1.0;
    }
}

}  // namespace

uint64_t MoveGuard::failing_attempts(size_t k, const Vec3& start, Vec3 step, int from) const {
    constexpr size_t m = kPlaces;
    uint64_t failing = 0;
    if (settings_.backtrack_steps >= 64) return failing;  // one bit per attempt (the parameter allows 50)
    for (int a0 = from; a0 <= settings_.backtrack_steps; a0 += static_cast<int>(m)) {
        // m places, halving as move_gathered does; those past the last attempt are not read.
        Trials trials;
        for (size_t j = 0; j < m; ++j, step *= 0.5) trials.set(j, star_, k, floor_[k], coords(start + step));
        const int count = std::min(static_cast<int>(m), settings_.backtrack_steps + 1 - a0);
        std::array<double, m> failed;
        trials_fail(trials, star_before_, settings_.never_worse, failed.data());
        for (int j = 0; j < count; ++j)
            if (failed[j] != 0.0) failing |= uint64_t{1} << (a0 + j);
    }
    return failing;
}

bool MoveGuard::acceptable(const TetMesh& mesh, const Vec3& at, const std::vector<FaceKey>& surface_faces) {
    const Coords x = coords(at);
    for (size_t k = 0; k < surface_faces.size(); ++k)
        if (!(face_normal(mesh, surface_faces[k]).dot(normals_[k]) > 0.0)) return false;
    // A shorter move mostly fails where the longer one did: that tet first;
    // then the tets that held the star's extreme angles, which fail most
    // often otherwise.  The order changes no verdict, only its cost.
    // All three in one pass of the vectorised kernel (the fourth trial
    // repeats the first).
    const size_t n = star_.size();
    if (n == 0) return true;  // no tet to check (extreme_ names none)
    const size_t first = last_failed_ < n ? last_failed_ : extreme_[0];
    constexpr size_t kLikely = 3;
    static_assert(kPlaces >= kLikely);
    const std::array<size_t, kLikely> likely{first, extreme_[0], extreme_[1]};
    Trials trials;
    for (size_t j = 0; j < kPlaces; ++j) {
        const size_t k = likely[j % kLikely];
        trials.set(j, star_, k, floor_[k], x);
    }
    std::array<double, kPlaces> failed;
    trials_fail(trials, star_before_, settings_.never_worse, failed.data());
    for (size_t j = 0; j < kLikely; ++j)
        if (failed[j] != 0.0) {
            last_failed_ = likely[j];
            return false;
        }
    const size_t failing = first_failing(star_.opposite(), star_.at(), n, x, floor_.data(), star_before_,
                                         settings_.never_worse, after_.data(), failed_.data());
    if (failing == n) return true;
    last_failed_ = failing;
    return false;
}

MoveOutcome MoveGuard::move(TetMesh& mesh, int32_t v, const Vec3& target, const std::vector<FaceKey>& surface_faces,
                            double& distance) {
    star_.gather(mesh, v);
    return move_gathered(mesh, v, target, surface_faces, distance);
}

MoveOutcome MoveGuard::move_gathered(TetMesh& mesh, int32_t v, const Vec3& target,
                                     const std::vector<FaceKey>& surface_faces, double& distance,
                                     double largest_cosine) {
    normals_.clear();
    for (const FaceKey& f : surface_faces) normals_.push_back(face_normal(mesh, f));
    const size_t n = star_.size();
    const int32_t* star = mesh.star_begin(v);
    floor_.resize(n);
    after_.resize(3 * n);
    failed_.resize(n);
    last_failed_ = n;
    star_before_ = {-1.0, 1.0};
    extreme_ = {0, 0};
    // Each star tet's cosines go to after_'s rows (scratch until a trial
    // fills them).
    double* of_min = after_.data() + n;
    double* of_max = after_.data() + 2 * n;
    if (cache_) {
        read_shapes(star, n, cache_->data(), settings_.min_stretch, floor_.data(), of_min, of_max);
    } else {
        for (size_t k = 0; k < n; ++k) {
            const TetShape shape = tet_shape(mesh.tet_points(star[k]));
            floor_[k] = std::min(settings_.min_stretch, shape.stretch);
            of_min[k] = shape.cosines.of_min;
            of_max[k] = shape.cosines.of_max;
        }
    }
    for (size_t k = 0; k < n; ++k) {
        if (of_min[k] > star_before_.of_min) {
            star_before_.of_min = of_min[k];
            extreme_[0] = k;
        }
        if (of_max[k] < star_before_.of_max) {
            star_before_.of_max = of_max[k];
            extreme_[1] = k;
        }
    }
    star_before_.of_max = std::min(star_before_.of_max, largest_cosine);
    const Vec3 start = mesh.points[v];
    Vec3 step = target - start;
    // Attempts known to fail: where a star tet that failed an earlier one
    // fails too (checked for all the later attempts at once).  Skipping
    // them changes no verdict, only its cost.
    uint64_t failing = 0;
    size_t screened = n;  // the last tet checked at every later attempt
    for (int attempt = 0; attempt <= settings_.backtrack_steps; ++attempt, step *= 0.5) {
        if (failing >> attempt & 1) continue;
        mesh.points[v] = start + step;
        if (acceptable(mesh, mesh.points[v], surface_faces)) {
            if (cache_)
                for (size_t k = 0; k < n; ++k)
                    (*cache_)[static_cast<size_t>(star[k])] = {after_[k], {after_[n + k], after_[2 * n + k]}};
            distance = step.norm();
            return attempt == 0 ? MoveOutcome::Moved : MoveOutcome::Shortened;
        }
        if (last_failed_ < n && last_failed_ != screened && attempt < settings_.backtrack_steps) {
            screened = last_failed_;
            failing |= failing_attempts(screened, start, 0.5 * step, attempt + 1);
        }
    }
    mesh.points[v] = start;
    distance = 0.0;
    return MoveOutcome::Rejected;
}

}  // namespace bodt
