/* The Eigen shim: least-squares contour fitting and simultaneous multi-point manipulation (fit.h).
 *
 * C++17 inside, the C API of include/rugo/fit.h outside. Nothing here lets an exception cross the C
 * boundary: every entry point catches everything and reports RUGO_ERR_OUT_OF_MEMORY (the only
 * exception Eigen and the standard library throw here is std::bad_alloc).
 *
 * Memory: the buffers rugo_fit_contour sizes itself (parameters, normal-equation band, scratch
 * output) go through the def's rugo_allocator; rugo_pyramid_move_points' bookkeeping goes through
 * the pyramid's own allocator. Eigen's
 * own containers (the sparse matrix and its factorisation, the small dense blocks of move_points)
 * allocate from the default C++ heap: Eigen has no per-call allocator hook.
 *
 * Determinism: fixed summation orders, Eigen's deterministic AMD ordering and Householder
 * factorisations; no threads (Eigen's sparse and small dense solvers used here are single-threaded).
 */
#include "rugo/fit.h"

#include "rugo/contour.h"
#include "rugo/multires.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

/* internal.h is a C header without its own linkage block; its standard headers are already in. */
#include "core/internal.h" /* declares its C functions with C linkage itself */

namespace {

/* "RFit" — marks a def that came from rugo_default_fit_def. */
constexpr int kFitCookie = 0x52466974;

/* Scaled pivots of the Jacobi-scaled normal matrix below this mean a rank-deficient (or so badly
 * conditioned that the answer would be noise: condition number >~ 1e11) fitting problem. */
constexpr double kFitPivotTolerance = 1e-11;

/* move_points: a pivot of the complete orthogonal decomposition below this fraction of the largest
 * counts as zero (two constraints that close together are the same constraint), and a residual above
 * this fraction of the largest requested displacement means the constraints conflict. */
constexpr double kMoveRankTolerance = 1e-10;
constexpr double kMoveResidualTolerance = 1e-8;

/* An array owned through the caller's allocator, freed on scope exit. Trivially copyable T only. */
template <class T> class AllocArray {
  public:
    explicit AllocArray(const rugo_allocator& a) : alloc_(a) {}
    ~AllocArray() { rugo__free(&alloc_, ptr_); }
    AllocArray(const AllocArray&) = delete;
    AllocArray& operator=(const AllocArray&) = delete;

    bool allocate(std::size_t count) {
        ptr_ = static_cast<T*>(rugo__alloc_array(&alloc_, count, sizeof(T)));
        return ptr_ != nullptr;
    }
    T* get() const { return ptr_; }
    T& operator[](std::size_t i) const { return ptr_[i]; }

  private:
    rugo_allocator alloc_;
    T* ptr_ = nullptr;
};

/* Reads a C enum argument as an int without a load of an out-of-range enum value, which C++ (and
 * UBSan's -fsanitize=enum) considers undefined; C callers may pass any int. */
template <class E> int enum_as_int(const E& e) {
    static_assert(sizeof(E) == sizeof(int), "C enums are int-sized on supported ABIs");
    int v;
    std::memcpy(&v, &e, sizeof v);
    return v;
}

/* Segment and local parameter of a global parameter u in [0, n]; u == n (only reachable by
 * rounding) stays on the last segment at t = 1, the same curve point as segment 0 at t = 0. */
void split_parameter(double u, int n, int* segment, double* t) {
    double f = std::floor(u);
    int s = static_cast<int>(f);
    if (s >= n) s = n - 1;
    if (s < 0) s = 0;
    *segment = s;
    *t = u - static_cast<double>(s);
}

rugo_status validate_fit(const rugo_fit_def* def, const rugo_vec2* control_points) {
    if (def == nullptr) return RUGO_ERR_NULL_ARGUMENT;
    if (def->cookie != kFitCookie) return RUGO_ERR_BAD_ARGUMENT;
    if (def->samples == nullptr || control_points == nullptr) return RUGO_ERR_NULL_ARGUMENT;
    const int n = def->control_count;
    if (n < 4) return RUGO_ERR_TOO_FEW_POINTS;
    if (n > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    if (!rugo__is_power_of_two(n)) return RUGO_ERR_NOT_POWER_OF_TWO;
    const int m = def->sample_count;
    if (m > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    if (m < n) return RUGO_ERR_BAD_ARGUMENT;
    const int param = enum_as_int(def->parameterization);
    if (param != RUGO_PARAM_CHORD_LENGTH && param != RUGO_PARAM_UNIFORM) return RUGO_ERR_BAD_ARGUMENT;
    for (int k = 0; k < m; ++k)
        if (!rugo__v2_finite(def->samples[k])) return RUGO_ERR_NOT_FINITE;
    if (param == RUGO_PARAM_CHORD_LENGTH) {
        for (int k = 0; k < m; ++k) {
            rugo_vec2 a = def->samples[k], b = def->samples[k + 1 < m ? k + 1 : 0];
            if (a.x == b.x && a.y == b.y) return RUGO_ERR_BAD_ARGUMENT;
        }
    }
    return RUGO_OK;
}

/* The fit, on validated input. The parameters come from the def's parameterization and stay fixed:
 * there is no parameter correction (re-projecting samples onto the fitted curve and refitting), so
 * max_error and rms_error measure the distance to the curve point at each sample's own parameter,
 * an upper bound on its distance to the curve.
 * Works in normalised coordinates q = (p - centre) / scale (the bounding box mapped to [-1, 1]^2):
 * the B-spline basis is a partition of unity, so the fit commutes with that affine map, and the
 * normalisation keeps sums and chord lengths finite and well scaled for any input (far from the
 * origin, tiny or huge). */
rugo_status fit_contour(const rugo_fit_def& def, rugo_vec2* control_points, rugo_fit_result* result) {
    const int n = def.control_count;
    const int m = def.sample_count;
    const rugo_vec2* p = def.samples;
    const rugo_allocator al = rugo__allocator_or_default(&def.allocator);

    rugo_vec2 lo = p[0], hi = p[0];
    for (int k = 1; k < m; ++k) {
        lo.x = std::fmin(lo.x, p[k].x);
        lo.y = std::fmin(lo.y, p[k].y);
        hi.x = std::fmax(hi.x, p[k].x);
        hi.y = std::fmax(hi.y, p[k].y);
    }
    /* Halves first so that nothing overflows for coordinates near DBL_MAX. */
    const rugo_vec2 centre = rugo_v2(0.5 * lo.x + 0.5 * hi.x, 0.5 * lo.y + 0.5 * hi.y);
    double scale = std::fmax(0.5 * hi.x - 0.5 * lo.x, 0.5 * hi.y - 0.5 * lo.y);
    if (!(scale > 0.0)) scale = 1.0; /* all samples equal (uniform parameters): any scale works */
    auto normalised = [&](int k) {
        return rugo_v2((p[k].x - centre.x) / scale, (p[k].y - centre.y) / scale);
    };

    /* Global parameters u_k in [0, n). */
    AllocArray<double> u(al);
    if (!u.allocate(static_cast<std::size_t>(m))) return RUGO_ERR_OUT_OF_MEMORY;
    if (enum_as_int(def.parameterization) == RUGO_PARAM_UNIFORM) {
        for (int k = 0; k < m; ++k)
            u[k] = static_cast<double>(k) * n / m;
    } else {
        double total = 0.0;
        for (int k = 0; k < m; ++k) {
            u[k] = total;
            rugo_vec2 a = normalised(k), b = normalised(k + 1 < m ? k + 1 : 0);
            total += std::hypot(b.x - a.x, b.y - a.y);
        }
        /* Every chord is > 0 (validated) and <= 2 sqrt(2) in normalised coordinates. */
        for (int k = 0; k < m; ++k)
            u[k] = u[k] / total * n;
    }

    /* Normal equations A^T A x = A^T q, A (m x n) holding each sample's four basis values. A^T A is a
     * cyclic band matrix: row i has entries at columns i-3..i+3 (mod n). Accumulate that band as
     * band[7 i + 3 + offset] and the right-hand sides as rhs[i]; for n = 4 several offsets name the
     * same column and are summed when the sparse matrix is assembled. */
    const std::size_t nn = static_cast<std::size_t>(n);
    AllocArray<double> band(al);
    AllocArray<rugo_vec2> rhs(al);
    if (!band.allocate(7 * nn) || !rhs.allocate(nn)) return RUGO_ERR_OUT_OF_MEMORY;
    for (std::size_t i = 0; i < 7 * nn; ++i)
        band[i] = 0.0;
    for (std::size_t i = 0; i < nn; ++i)
        rhs[i] = rugo_v2(0.0, 0.0);
    for (int k = 0; k < m; ++k) {
        int seg;
        double t, b[4];
        split_parameter(u[k], n, &seg, &t);
        rugo_bspline_basis(t, b);
        const rugo_vec2 q = normalised(k);
        for (int a = 0; a < 4; ++a) {
            const std::size_t i = static_cast<std::size_t>(rugo__wrap(seg - 1 + a, n));
            rhs[i].x += b[a] * q.x;
            rhs[i].y += b[a] * q.y;
            for (int c = 0; c < 4; ++c)
                band[7 * i + static_cast<std::size_t>(3 + c - a)] += b[a] * b[c];
        }
    }

    /* Jacobi scaling S G S with S = diag(1/sqrt(G_ii)): uneven sample density then does not look like
     * ill-conditioning, and the pivot test below is relative to a unit diagonal. A zero diagonal is a
     * control point that no sample depends on. */
    AllocArray<double> s(al);
    if (!s.allocate(nn)) return RUGO_ERR_OUT_OF_MEMORY;
    for (std::size_t i = 0; i < nn; ++i) {
        const double d = band[7 * i + 3];
        if (!(d > 0.0)) return RUGO_ERR_SINGULAR;
        s[i] = 1.0 / std::sqrt(d);
    }

    /* Sparse LDL^T (Eigen::SimplicialLDLT, AMD ordering): the matrix is SPD exactly when the problem
     * is well posed, the band keeps the factor O(n) even with the cyclic wrap, and the pivots D reveal
     * rank deficiency (each pivot is >= the smallest eigenvalue, so a tiny pivot proves a nearly
     * singular matrix). Dense QR would cost O(n^3); the normal equations square the condition number,
     * which the pivot test bounds. */
    typedef Eigen::SparseMatrix<double> SpMat;
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(4 * nn + 12);
    for (int i = 0; i < n; ++i) {
        const std::size_t ii = static_cast<std::size_t>(i);
        for (int off = -3; off <= 3; ++off) {
            const int j = rugo__wrap(i + off, n);
            const double v = band[7 * ii + static_cast<std::size_t>(3 + off)];
            /* SimplicialLDLT reads the lower triangle only; the cyclic wrap puts some of each row's
             * band above the diagonal, hence the test on j rather than on off. */
            if (v != 0.0 && j <= i) triplets.emplace_back(i, j, v * s[ii] * s[static_cast<std::size_t>(j)]);
        }
    }
    SpMat g(n, n);
    g.setFromTriplets(triplets.begin(), triplets.end());
    triplets.clear();
    triplets.shrink_to_fit();

    Eigen::SimplicialLDLT<SpMat> ldlt(g);
    if (ldlt.info() != Eigen::Success) return RUGO_ERR_SINGULAR;
    if (!(ldlt.vectorD().minCoeff() > kFitPivotTolerance)) return RUGO_ERR_SINGULAR;

    Eigen::MatrixX2d r(n, 2);
    for (std::size_t i = 0; i < nn; ++i) {
        const Eigen::Index ei = static_cast<Eigen::Index>(i);
        r(ei, 0) = rhs[i].x * s[i];
        r(ei, 1) = rhs[i].y * s[i];
    }
    const Eigen::MatrixX2d x = ldlt.solve(r);
    if (ldlt.info() != Eigen::Success || !x.allFinite()) return RUGO_ERR_SINGULAR;

    /* Back to the caller's coordinates, into scratch: the outputs change only on success. */
    AllocArray<rugo_vec2> out(al);
    if (!out.allocate(nn)) return RUGO_ERR_OUT_OF_MEMORY;
    for (std::size_t i = 0; i < nn; ++i) {
        const Eigen::Index ei = static_cast<Eigen::Index>(i);
        out[i] = rugo_v2(centre.x + scale * (x(ei, 0) * s[i]), centre.y + scale * (x(ei, 1) * s[i]));
        /* Control points can lie outside the samples' box; near DBL_MAX they may not be representable. */
        if (!rugo__v2_finite(out[i])) return RUGO_ERR_NOT_FINITE;
    }

    /* Errors at the samples' own parameters, in the caller's coordinates; the sum of squares is taken
     * relative to scale so that it cannot overflow. */
    rugo_contour c;
    c.points = out.get();
    c.count = n;
    double max_error = 0.0, sum_sq = 0.0;
    for (int k = 0; k < m; ++k) {
        int seg;
        double t;
        split_parameter(u[k], n, &seg, &t);
        const rugo_vec2 f = rugo_contour_point(c, seg, t);
        const double e = std::hypot(p[k].x - f.x, p[k].y - f.y);
        max_error = std::fmax(max_error, e);
        sum_sq += (e / scale) * (e / scale);
    }

    std::memcpy(control_points, out.get(), nn * sizeof(rugo_vec2));
    if (result != nullptr) {
        result->max_error = max_error;
        result->rms_error = scale * std::sqrt(sum_sq / m);
    }
    return RUGO_OK;
}

/* Disjoint sets over the constraints of move_points (path halving, union by index for determinism). */
int find_root(int* parent, int i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

void unite(int* parent, int a, int b) {
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a == b) return;
    if (a < b)
        parent[b] = a;
    else
        parent[a] = b;
}

rugo_status validate_move(rugo_pyramid* p, int level, int count, const int* segments, const rugo_real* ts,
                          const rugo_vec2* deltas, int mode) {
    if (p == nullptr || segments == nullptr || ts == nullptr || deltas == nullptr)
        return RUGO_ERR_NULL_ARGUMENT;
    if (mode != RUGO_DETAILS_FIXED && mode != RUGO_DETAILS_LOCAL) return RUGO_ERR_BAD_ARGUMENT;
    if (level < rugo_pyramid_coarsest_level(p) || level > rugo_pyramid_finest_level(p))
        return RUGO_ERR_BAD_LEVEL;
    if (count < 1) return RUGO_ERR_BAD_ARGUMENT;
    if (count > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    const int n = 1 << level;
    for (int i = 0; i < count; ++i) {
        if (segments[i] < 0 || segments[i] >= n) return RUGO_ERR_BAD_ARGUMENT;
        /* As rugo_pyramid_move_point: a NaN t is out of range too. */
        if (!(ts[i] >= 0.0 && ts[i] <= 1.0)) return RUGO_ERR_BAD_ARGUMENT;
        if (!rugo__v2_finite(deltas[i])) return RUGO_ERR_NOT_FINITE;
    }
    return RUGO_OK;
}

/* Least-norm control-point displacement for the constraints, then one rugo_pyramid_displace_level.
 *
 * Constraint i says N_i . dC = delta_i, N_i the four basis values of its point on control points
 * seg-1 .. seg+2 (cyclic). The least-norm solution dC = N^T (N N^T)^+ dF is zero on control points no
 * constraint touches, and constraints that share no control point are independent problems. So the
 * constraints are grouped into connected components (shared control points), and each component is
 * solved densely on just its own control points with Eigen::CompleteOrthogonalDecomposition: it is
 * rank revealing (column-pivoted QR, then an orthogonal step on the right) and returns the
 * minimum-norm least-squares solution even when the constraints are dependent, e.g. the same point
 * given twice. Whether dependent constraints agree is decided by the residual: a consistent system
 * is met to round-off, a conflicting one leaves a residual of the order of the conflict. Cost is
 * O(r k min(r, k)) per component of r constraints on k control points (k <= 4r): cheap for the
 * handful of points an editor moves, cubic for thousands of mutually overlapping constraints. */
rugo_status move_points(rugo_pyramid* p, int level, int count, const int* segments, const rugo_real* ts,
                        const rugo_vec2* deltas, rugo_detail_mode mode) {
    rugo_contour c;
    rugo_status st = rugo_pyramid_level(p, level, &c);
    if (st != RUGO_OK) return st;
    const int n = c.count;
    const std::size_t nn = static_cast<std::size_t>(n);
    const std::size_t nc = static_cast<std::size_t>(count);

    const rugo_allocator al = rugo_pyramid_allocator(p);
    AllocArray<rugo_vec2> delta(al);
    AllocArray<int> owner(al), parent(al), order(al), start(al), local(al), cols(al);
    if (!delta.allocate(nn) || !owner.allocate(nn) || !local.allocate(nn) || !parent.allocate(nc) ||
        !order.allocate(nc) || !start.allocate(nc + 1) || !cols.allocate(4 * nc))
        return RUGO_ERR_OUT_OF_MEMORY;
    for (std::size_t j = 0; j < nn; ++j) {
        delta[j] = rugo_v2(0.0, 0.0);
        owner[j] = -1;
        local[j] = -1;
    }
    for (int i = 0; i < count; ++i)
        parent[static_cast<std::size_t>(i)] = i;
    for (int i = 0; i < count; ++i) {
        for (int a = 0; a < 4; ++a) {
            const std::size_t j = static_cast<std::size_t>(rugo__wrap(segments[i] - 1 + a, n));
            if (owner[j] < 0)
                owner[j] = i;
            else
                unite(parent.get(), i, owner[j]);
        }
    }

    /* Counting sort of the constraints by component root (roots are each component's smallest
     * index), keeping index order inside a component. */
    for (std::size_t i = 0; i <= nc; ++i)
        start[i] = 0;
    for (int i = 0; i < count; ++i)
        ++start[static_cast<std::size_t>(find_root(parent.get(), i)) + 1];
    for (std::size_t i = 0; i < nc; ++i)
        start[i + 1] += start[i];
    {
        AllocArray<int> fill(al);
        if (!fill.allocate(nc)) return RUGO_ERR_OUT_OF_MEMORY;
        for (std::size_t i = 0; i < nc; ++i)
            fill[i] = start[i];
        for (int i = 0; i < count; ++i) {
            const std::size_t root = static_cast<std::size_t>(find_root(parent.get(), i));
            order[static_cast<std::size_t>(fill[root]++)] = i;
        }
    }

    for (std::size_t root = 0; root < nc; ++root) {
        const int first = start[root], last = start[root + 1];
        if (first == last) continue;
        const int rows = last - first;
        /* This component's control points, numbered in order of first use. */
        int k = 0;
        for (int r = first; r < last; ++r) {
            const int i = order[static_cast<std::size_t>(r)];
            for (int a = 0; a < 4; ++a) {
                const std::size_t j = static_cast<std::size_t>(rugo__wrap(segments[i] - 1 + a, n));
                if (local[j] < 0) {
                    local[j] = k;
                    cols[static_cast<std::size_t>(k++)] = static_cast<int>(j);
                }
            }
        }
        /* The deltas are solved for divided by their largest component, so that nothing overflows
         * and the residual test is relative to this component's own displacements. */
        double scale = 0.0;
        for (int r = first; r < last; ++r) {
            const int i = order[static_cast<std::size_t>(r)];
            scale = std::fmax(scale, std::fmax(std::fabs(deltas[i].x), std::fabs(deltas[i].y)));
        }
        if (scale == 0.0) { /* nothing to move here (delta is zero already) */
            for (int l = 0; l < k; ++l)
                local[static_cast<std::size_t>(cols[static_cast<std::size_t>(l)])] = -1;
            continue;
        }
        Eigen::MatrixXd nmat = Eigen::MatrixXd::Zero(rows, k);
        Eigen::MatrixX2d f(rows, 2);
        for (int r = 0; r < rows; ++r) {
            const int i = order[static_cast<std::size_t>(first + r)];
            double b[4];
            rugo_bspline_basis(ts[i], b);
            for (int a = 0; a < 4; ++a) {
                const std::size_t j = static_cast<std::size_t>(rugo__wrap(segments[i] - 1 + a, n));
                nmat(r, local[j]) += b[a]; /* += : on a 4-point level the window wraps onto itself */
            }
            f(r, 0) = deltas[i].x / scale;
            f(r, 1) = deltas[i].y / scale;
        }
        Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(rows, k);
        cod.setThreshold(kMoveRankTolerance);
        cod.compute(nmat);
        const Eigen::MatrixX2d dc = cod.solve(f);
        const double residual = (nmat * dc - f).cwiseAbs().maxCoeff();
        if (!dc.allFinite() || !(residual <= kMoveResidualTolerance)) return RUGO_ERR_SINGULAR;
        for (int l = 0; l < k; ++l) {
            const std::size_t j = static_cast<std::size_t>(cols[static_cast<std::size_t>(l)]);
            /* May overflow for deltas near DBL_MAX; rugo_pyramid_displace_level then refuses. */
            delta[j] = rugo_v2(dc(l, 0) * scale, dc(l, 1) * scale);
            local[j] = -1;
        }
    }

    return rugo_pyramid_displace_level(p, level, delta.get(), mode);
}

} // namespace

extern "C" {

rugo_fit_def rugo_default_fit_def(void) {
    rugo_fit_def def;
    std::memset(&def, 0, sizeof def);
    def.samples = nullptr;
    def.sample_count = 0;
    def.control_count = 0;
    def.parameterization = RUGO_PARAM_CHORD_LENGTH;
    def.allocator.alloc = nullptr; /* zeroed = malloc/free */
    def.allocator.free = nullptr;
    def.allocator.ctx = nullptr;
    def.cookie = kFitCookie;
    return def;
}

rugo_status rugo_fit_contour(const rugo_fit_def* def, rugo_vec2* control_points, rugo_fit_result* result) {
    try {
        const rugo_status st = validate_fit(def, control_points);
        if (st != RUGO_OK) return st;
        return fit_contour(*def, control_points, result);
    } catch (...) {
        /* std::bad_alloc from Eigen or std::vector; nothing else throws here. */
        return RUGO_ERR_OUT_OF_MEMORY;
    }
}

rugo_status rugo_pyramid_move_points(rugo_pyramid* p, int level, int count, const int* segments,
                                     const rugo_real* ts, const rugo_vec2* deltas, rugo_detail_mode mode) {
    try {
        const int m = enum_as_int(mode);
        const rugo_status st = validate_move(p, level, count, segments, ts, deltas, m);
        if (st != RUGO_OK) return st;
        return move_points(p, level, count, segments, ts, deltas, mode);
    } catch (...) {
        return RUGO_ERR_OUT_OF_MEMORY;
    }
}

} // extern "C"
