#include "features/shape_fit.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bodt {

namespace {

using Vec2 = Eigen::Vector2d;
using Mat3 = Eigen::Matrix3d;

// A point set is flat in a direction when its variance there is below this
// fraction of the largest variance (an aspect ratio of 1e-6).  Well above
// the eigensolver's absolute error (~1e-16 of the largest eigenvalue), so
// exactly collinear or coplanar input is always caught.
constexpr double kFlat = 1e-12;
// A circle or cylinder wider than this many times the points' extent is a
// line or a plane in disguise: its centre is not determined by the points.
constexpr double kMaxRadius = 1e6;

// The points moved to their centroid and scaled to unit RMS distance from
// it: every fit then works with O(1) numbers, whatever the pose and scale.
struct Normalized {
    Vec3 centroid = Vec3::Zero();
    double scale = 0.0;            // RMS distance from the centroid
    double extent = 0.0;           // max distance from the centroid / scale
    std::vector<Vec3> q;           // (p - centroid) / scale
    Eigen::Vector3d eigenvalues;   // of sum q q^T, ascending
    Mat3 eigenvectors;             // columns, matching
};

// False when the points all coincide (up to round-off of their coordinates).
bool normalize(const std::vector<Vec3>& points, Normalized& n) {
    const size_t count = points.size();
    if (count == 0) return false;
    Vec3 sum = Vec3::Zero();
    double magnitude = 0.0;
    for (const Vec3& p : points) {
        sum += p;
        magnitude = std::max(magnitude, p.cwiseAbs().maxCoeff());
    }
    n.centroid = sum / static_cast<double>(count);
    double ss = 0.0, far = 0.0;
    for (const Vec3& p : points) {
        const double d2 = (p - n.centroid).squaredNorm();
        ss += d2;
        far = std::max(far, d2);
    }
    far = std::sqrt(far);
    // Spread at the level of the coordinates' rounding is no spread.
    if (!(far > 64.0 * std::numeric_limits<double>::epsilon() * magnitude) || !std::isfinite(ss)) return false;
    n.scale = std::sqrt(ss / static_cast<double>(count));
    n.extent = far / n.scale;
    n.q.resize(count);
    Mat3 cov = Mat3::Zero();
    for (size_t i = 0; i < count; ++i) {
        n.q[i] = (points[i] - n.centroid) / n.scale;
        cov.noalias() += n.q[i] * n.q[i].transpose();
    }
    Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);
    n.eigenvalues = eig.eigenvalues();
    n.eigenvectors = eig.eigenvectors();
    return true;
}

// Levenberg-Marquardt over a Model with
//   double linearize(Mat& JtJ, Vec& Jtf) const   (returns sum f^2)
//   Model moved(const Vec& delta) const
// Parameters are O(1) (normalised coordinates), so a fixed step threshold
// is scale-free.  Zero-residual problems converge quadratically (plain
// Gauss-Newton once lambda has shrunk).
template <class Model>
Model levenberg_marquardt(Model m, int max_evaluations) {
    using Mat = typename Model::Mat;
    using Vec = typename Model::Vec;
    Mat jtj;
    Vec jtf;
    double cost = m.linearize(jtj, jtf);
    double lambda = 1e-3;
    for (int k = 0; k < max_evaluations && cost > 0.0; ++k) {
        // Marquardt's scaling, floored so that a parameter the data do not
        // constrain (a zero column) gets a finite, tiny step.
        const double least = 1e-12 * std::max(jtj.diagonal().maxCoeff(), 1e-300);
        Mat a = jtj;
        a.diagonal() += lambda * jtj.diagonal().cwiseMax(least);
        const Vec delta = a.ldlt().solve(-jtf);
        if (!delta.allFinite()) break;
        Mat jtj2;
        Vec jtf2;
        Model trial = m.moved(delta);
        const double cost2 = trial.linearize(jtj2, jtf2);
        if (cost2 < cost) {
            m = trial;
            jtj = jtj2;
            jtf = jtf2;
            cost = cost2;
            lambda = std::max(lambda * 0.1, 1e-15);
            if (delta.norm() < 1e-14) break;
        } else {
            lambda *= 10.0;
            if (lambda > 1e10 || delta.norm() < 1e-14) break;  // at the minimum up to round-off
        }
    }
    return m;
}

// Geometric circle in the plane: residuals |q - c| - r.
struct Circle2 {
    using Mat = Eigen::Matrix3d;
    using Vec = Eigen::Vector3d;
    const std::vector<Vec2>* q = nullptr;
    Vec2 c = Vec2::Zero();
    double r = 0.0;

    double linearize(Mat& jtj, Vec& jtf) const {
        jtj.setZero();
        jtf.setZero();
        double cost = 0.0;
        for (const Vec2& p : *q) {
            const Vec2 d = p - c;
            const double len = d.norm();
            const double f = len - r;
            Vec j;
            if (len > 0.0)
                j << -d.x() / len, -d.y() / len, -1.0;
            else
                j << 0.0, 0.0, -1.0;  // at the centre the direction is undefined
            jtj.noalias() += j * j.transpose();
            jtf += f * j;
            cost += f * f;
        }
        return cost;
    }
    Circle2 moved(const Vec& d) const {
        Circle2 m = *this;
        m.c += d.head<2>();
        m.r += d.z();
        return m;
    }
};

// Circle through 2-D points of O(1) size: Kasa's algebraic fit (linear least
// squares on x^2 + y^2 + D x + E y + F = 0) for the start, then the
// geometric fit, which Kasa's is biased from on short noisy arcs.  False when
// the points are collinear (no finite circle) or the result is not finite.
bool fit_circle_2d(const std::vector<Vec2>& q, Vec2& centre, double& radius) {
    const Eigen::Index n = static_cast<Eigen::Index>(q.size());
    if (n < 3) return false;
    Eigen::MatrixXd a(n, 3);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Vec2& p = q[static_cast<size_t>(i)];
        a.row(i) << p.x(), p.y(), 1.0;
        b(i) = -p.squaredNorm();
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
    qr.setThreshold(1e-10);
    if (qr.rank() < 3) return false;
    const Eigen::Vector3d def = qr.solve(b);
    Circle2 c;
    c.q = &q;
    c.c = -0.5 * def.head<2>();
    const double r2 = c.c.squaredNorm() - def.z();
    if (!(r2 > 0.0) || !std::isfinite(r2)) return false;
    c.r = std::sqrt(r2);
    c = levenberg_marquardt(c, 50);
    centre = c.c;
    radius = std::abs(c.r);
    return centre.allFinite() && std::isfinite(radius);
}

// Cylinder in normalised coordinates (centroid at the origin): residuals
// dist(q, axis) - r.  The axis point is kept at the foot of the origin, so
// tilting the axis pivots about the middle of the points and the tilt and
// shift parameters are nearly decoupled.  Step (alpha, beta, s, t, dr):
// axis += alpha u + beta w (then renormalised), point += s u + t w.
struct Cylinder5 {
    using Mat = Eigen::Matrix<double, 5, 5>;
    using Vec = Eigen::Matrix<double, 5, 1>;
    const std::vector<Vec3>* q = nullptr;
    Vec3 axis = Vec3::UnitZ(), u = Vec3::UnitX(), w = Vec3::UnitY();
    Vec3 point = Vec3::Zero();
    double r = 0.0;

    void set_axis(const Vec3& a) {
        axis = a.normalized();
        complete_frame(axis, u, w);
        point -= point.dot(axis) * axis;
    }
    double linearize(Mat& jtj, Vec& jtf) const {
        jtj.setZero();
        jtf.setZero();
        double cost = 0.0;
        for (const Vec3& p : *q) {
            const Vec3 d = p - point;
            const double h = d.dot(axis);
            const Vec3 rho = d - h * axis;
            const double len = rho.norm();
            const double f = len - r;
            // d dist / d alpha = -h (rho^.u); d dist / d s = -(rho^.u).
            const double ru = len > 0.0 ? rho.dot(u) / len : 0.0;
            const double rw = len > 0.0 ? rho.dot(w) / len : 0.0;
            Vec j;
            j << -h * ru, -h * rw, -ru, -rw, -1.0;
            jtj.noalias() += j * j.transpose();
            jtf += f * j;
            cost += f * f;
        }
        return cost;
    }
    Cylinder5 moved(const Vec& d) const {
        Cylinder5 m = *this;
        m.point += d(2) * u + d(3) * w;
        m.set_axis(axis + d(0) * u + d(1) * w);
        m.r += d(4);
        return m;
    }
};

// Start from axis a: circle of the points projected along a, then the full
// 5-parameter fit.  False when the projection is degenerate.
bool fit_cylinder_from(const Normalized& n, const Vec3& a, Cylinder5& out) {
    Vec3 u, w;
    complete_frame(a.normalized(), u, w);
    std::vector<Vec2> flat(n.q.size());
    for (size_t i = 0; i < n.q.size(); ++i) flat[i] = Vec2(n.q[i].dot(u), n.q[i].dot(w));
    // Projected points on a line: the axis lies in the points' plane.
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const Vec2& p : flat) cov.noalias() += p * p.transpose();
    const Eigen::Vector2d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov).eigenvalues();
    if (!(ev(0) > kFlat * ev(1))) return false;
    Vec2 c;
    double r = 0.0;
    if (!fit_circle_2d(flat, c, r)) return false;
    Cylinder5 m;
    m.q = &n.q;
    m.point = c.x() * u + c.y() * w;
    m.set_axis(a);
    m.r = r;
    out = levenberg_marquardt(m, 100);
    Cylinder5::Mat jtj;
    Cylinder5::Vec jtf;
    return out.axis.allFinite() && out.point.allFinite() && std::isfinite(out.r) &&
           std::isfinite(out.linearize(jtj, jtf));
}

double max_distance(const Shape& s, const std::vector<Vec3>& points) {
    double e = 0.0;
    for (const Vec3& p : points) e = std::max(e, s.distance(p));
    return e;
}

// Unit radial direction of x about the shape's axis.  On the axis every
// direction is equally near: u, also when the radial part is round-off of
// x - point (then its direction is noise, and u keeps project() of a point
// computed on the axis deterministic).
Vec3 radial(const Shape& s, const Vec3& x) {
    const Vec3 d = x - s.point;
    const Vec3 rho = d - d.dot(s.axis) * s.axis;
    const double len = rho.norm();
    return len > 16.0 * std::numeric_limits<double>::epsilon() * d.norm() ? Vec3(rho / len) : s.u;
}

}  // namespace

void complete_frame(const Vec3& axis, Vec3& u, Vec3& w) {
    // The coordinate axis least aligned with `axis` gives the best
    // conditioned cross product; ties go to the lowest index.
    const Vec3 a = axis.cwiseAbs();
    int k = 0;
    if (a(1) < a(k)) k = 1;
    if (a(2) < a(k)) k = 2;
    u = axis.cross(Vec3::Unit(k)).normalized();
    w = axis.normalized().cross(u);
}

Vec3 Shape::project(const Vec3& x) const {
    switch (type) {
        case ShapeType::Plane:
            return x - (x - point).dot(axis) * axis;
        case ShapeType::Line:
            return point + (x - point).dot(axis) * axis;
        case ShapeType::Cylinder:
            return point + (x - point).dot(axis) * axis + radius * radial(*this, x);
        case ShapeType::Arc:
        case ShapeType::Circle:
            return point + radius * radial(*this, x);
        case ShapeType::None:
            break;
    }
    return x;
}

double Shape::distance(const Vec3& x) const {
    const Vec3 d = x - point;
    const double h = d.dot(axis);
    switch (type) {
        case ShapeType::Plane:
            return std::abs(h);
        case ShapeType::Line:
            return (d - h * axis).norm();
        case ShapeType::Cylinder:
            return std::abs((d - h * axis).norm() - radius);
        case ShapeType::Arc:
        case ShapeType::Circle:
            return std::hypot((d - h * axis).norm() - radius, h);
        case ShapeType::None:
            break;
    }
    return 0.0;
}

double Shape::angle(const Vec3& x) const {
    const Vec3 d = x - point;
    const double t = std::atan2(d.dot(w), d.dot(u));
    return t == -M_PI ? M_PI : t;  // atan2(-0, x < 0) = -pi: keep (-pi, pi]
}

double Shape::height(const Vec3& x) const { return (x - point).dot(axis); }

Vec3 Shape::at(double theta, double z) const {
    switch (type) {
        case ShapeType::Cylinder:
            return point + z * axis + radius * (std::cos(theta) * u + std::sin(theta) * w);
        case ShapeType::Arc:
        case ShapeType::Circle:
            return point + radius * (std::cos(theta) * u + std::sin(theta) * w);
        case ShapeType::Line:
            return point + z * axis;  // z: the coordinate along the line, as height()
        case ShapeType::Plane:
        case ShapeType::None:
            break;
    }
    return point;
}

Shape fit_plane(const std::vector<Vec3>& points) {
    Shape s;
    Normalized n;
    if (points.size() < 3 || !normalize(points, n)) return s;
    if (!(n.eigenvalues(1) > kFlat * n.eigenvalues(2))) return s;  // collinear
    s.type = ShapeType::Plane;
    s.point = n.centroid;
    s.axis = n.eigenvectors.col(0).normalized();
    complete_frame(s.axis, s.u, s.w);
    s.max_error = max_distance(s, points);
    return s;
}

Shape fit_line(const std::vector<Vec3>& points) {
    Shape s;
    Normalized n;
    if (points.size() < 2 || !normalize(points, n)) return s;
    s.type = ShapeType::Line;
    s.point = n.centroid;
    s.axis = n.eigenvectors.col(2).normalized();
    complete_frame(s.axis, s.u, s.w);
    s.max_error = max_distance(s, points);
    return s;
}

Shape fit_circle(const std::vector<Vec3>& points) {
    Shape s;
    Normalized n;
    if (points.size() < 3 || !normalize(points, n)) return s;
    if (!(n.eigenvalues(1) > kFlat * n.eigenvalues(2))) return s;  // collinear
    const Vec3 normal = n.eigenvectors.col(0).normalized();
    Vec3 u, w;
    complete_frame(normal, u, w);
    std::vector<Vec2> flat(n.q.size());
    for (size_t i = 0; i < n.q.size(); ++i) flat[i] = Vec2(n.q[i].dot(u), n.q[i].dot(w));
    Vec2 c;
    double r = 0.0;
    if (!fit_circle_2d(flat, c, r) || r > kMaxRadius * n.extent) return s;
    s.type = ShapeType::Arc;
    s.point = n.centroid + n.scale * (c.x() * u + c.y() * w);
    s.axis = normal;
    s.u = u;
    s.w = w;
    s.radius = n.scale * r;
    s.max_error = max_distance(s, points);
    return s;
}

Shape fit_cylinder(const std::vector<Vec3>& points, const std::vector<Vec3>& normals) {
    Shape s;
    Normalized n;
    if (points.size() < 5 || !normalize(points, n)) return s;

    // The axis is perpendicular to every normal: the least eigenvector of
    // sum n n^T (sign-free, so unoriented normals do).
    Mat3 nn = Mat3::Zero();
    int used = 0;
    for (const Vec3& v : normals) {
        const double len = v.norm();
        if (!(len > 0.0) || !std::isfinite(len)) continue;
        const Vec3 unit = v / len;
        nn.noalias() += unit * unit.transpose();
        ++used;
    }
    std::vector<Vec3> starts;
    if (used > 0) {
        Eigen::SelfAdjointEigenSolver<Mat3> eig(nn);
        // All normals parallel: a plane, no axis direction to find.
        if (!(eig.eigenvalues()(1) > kFlat * eig.eigenvalues()(2))) return s;
        starts.push_back(eig.eigenvectors().col(0));
    } else if (!(n.eigenvalues(0) > kFlat * n.eigenvalues(2))) {
        // No normals and coplanar points: no cylinder is determined (a
        // circle is fit_circle's).
        return s;
    }
    // The points' principal directions too (the long one for a tall
    // cylinder, the short one for a ring...): they rescue a narrow strip
    // whose noisy normals hardly fix the axis, and are all there is
    // without normals.  The best fit of all starts wins.
    for (int k = 0; k < 3; ++k) starts.push_back(n.eigenvectors.col(k));

    bool found = false;
    double best = std::numeric_limits<double>::infinity();
    Cylinder5 fit;
    for (const Vec3& a : starts) {
        Cylinder5 m;
        if (!fit_cylinder_from(n, a, m)) continue;
        Cylinder5::Mat jtj;
        Cylinder5::Vec jtf;
        const double cost = m.linearize(jtj, jtf);
        if (cost < best) {
            best = cost;
            fit = m;
            found = true;
        }
    }
    if (!found || !(std::abs(fit.r) <= kMaxRadius * n.extent)) return s;
    // Coplanar points meet a cylinder in a circle or an ellipse (the axis
    // crosses their plane) or in lines (the axis along it).  In the last
    // case a plane patch is no cylinder: the fit only drives r to infinity,
    // and stops, still finite, at the iteration limit.
    if (!(n.eigenvalues(0) > kFlat * n.eigenvalues(2)) && std::abs(fit.axis.dot(n.eigenvectors.col(0))) < 1e-2)
        return s;

    s.type = ShapeType::Cylinder;
    s.axis = fit.axis.normalized();
    // fit.point is the foot of the origin, i.e. of the centroid.
    s.point = n.centroid + n.scale * (fit.point - fit.point.dot(s.axis) * s.axis);
    complete_frame(s.axis, s.u, s.w);
    s.radius = n.scale * std::abs(fit.r);
    s.max_error = max_distance(s, points);
    return s;
}

}  // namespace bodt
