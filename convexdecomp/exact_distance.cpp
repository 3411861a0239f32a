// pxcd_exact_distance: exact distance between the convex hulls of two point
// sets, behind the C ABI of pxcd.h. Ground truth for tests and benchmarks.
//
// Algorithm and sources:
//   - CGAL::Polytope_distance_d (CGAL 5.5 manual, "Optimal Distances",
//     class Polytope_distance_d<Traits>), which solves the distance problem
//     as a quadratic program with CGAL's exact QP solver (Gärtner and
//     Schönherr's algorithm). Traits:
//     Polytope_distance_d_traits_3<Homogeneous<Gmpzf>, Gmpzf, Gmpzf>, i.e.
//     exact arithmetic for both the solver (ET) and the pricing (NT). The
//     manual's "fast exact" configuration (Homogeneous<double>, NT = double)
//     prices in doubles, which under- and overflow at extreme scales: on two
//     tetrahedra at gap s it returns an invalid result (is_valid() false) for
//     s = 1e-170 and fails an assertion (QP not optimal) for s = 1e150, so it
//     is deliberately not used.
//   - Gmpzf(double) is exact, and homogeneous points with w = 1 represent
//     the input doubles exactly.
//   - The result is the exact rational num/den. We convert it to double with
//     MPFR (https://www.mpfr.org/mpfr-current/mpfr.html) in a Ziv loop:
//     approximate at increasing precision until mpfr_can_round certifies that
//     rounding to the nearest double is correct. MPFR's exponent range is far
//     wider than double's, so num and den never overflow separately, and
//     mpfr_get_d rounds subnormal results correctly too. The distance itself
//     is sqrt(num/den) rounded once to double (not sqrt of the rounded
//     square), so it stays correctly rounded when the squared distance is
//     subnormal (distance below ~1.5e-154) or underflows to 0 (below ~2e-162).
//   - The result is certified with Polytope_distance_d::is_valid(), an exact
//     check that all of P and all of Q lie on the proper sides of the two
//     planes through the realizing points normal to their difference. It is
//     linear in the number of points and cheap next to the solve.

#include "pxcd.h"

#include <CGAL/Gmpzf.h>
#include <CGAL/Homogeneous.h>
#include <CGAL/Polytope_distance_d.h>
#include <CGAL/Polytope_distance_d_traits_3.h>
#include <CGAL/exceptions.h>

#include <gmp.h>
#include <mpfr.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <new>
#include <stdexcept>
#include <vector>

namespace {

using ET = CGAL::Gmpzf;
using Kernel = CGAL::Homogeneous<ET>;
using Point = Kernel::Point_3;
using Traits = CGAL::Polytope_distance_d_traits_3<Kernel, ET, ET>;
using Polytope_distance = CGAL::Polytope_distance_d<Traits>;

void set_msg(char *msg, size_t msg_len, const char *text) {
    if (msg != nullptr && msg_len > 0) std::snprintf(msg, msg_len, "%s", text);
}

struct Distance_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// RAII wrapper for an mpfr_t.
struct Mpfr {
    mpfr_t x;
    explicit Mpfr(mpfr_prec_t prec) { mpfr_init2(x, prec); }
    ~Mpfr() { mpfr_clear(x); }
    Mpfr(const Mpfr &) = delete;
    Mpfr &operator=(const Mpfr &) = delete;
};

// A Gmpzf is man * 2^exp; with as many bits as the mantissa it is exact.
void set_exact(Mpfr &dst, const ET &v) {
    const size_t bits = mpz_sizeinbase(v.man(), 2);
    mpfr_set_prec(dst.x, static_cast<mpfr_prec_t>(std::max<size_t>(bits, MPFR_PREC_MIN)));
    mpfr_set_z_2exp(dst.x, v.man(), static_cast<mpfr_exp_t>(v.exp()), MPFR_RNDN);
    if (!mpfr_number_p(dst.x)) throw Distance_error("exact value exceeds MPFR's exponent range");
}

// Correctly rounded (to nearest, ties to even) double of num/den, or of
// sqrt(num/den) when take_sqrt. Ziv's strategy: at working precision p the
// approximation is within 2^(EXP - p + 1) of the true value (one rounding
// for the quotient, one for the square root), so mpfr_can_round with
// err = p - 2 is a safe certificate. Rounding to 54 bits towards zero is the
// manual's recipe for a correct round-to-nearest at 53 bits; it also covers
// subnormal targets, whose rounding boundaries are a subset of those. If all
// steps were exact the value is exact and its rounding is trivially right.
// Precision doubles at each step; a value exactly on a rounding boundary is
// dyadic, so it becomes exact at some finite precision and the loop ends.
double round_quotient(const ET &num, const ET &den, bool take_sqrt) {
    if (CGAL::is_zero(den)) throw Distance_error("zero denominator");
    Mpfr n(MPFR_PREC_MIN), d(MPFR_PREC_MIN);
    set_exact(n, num);
    set_exact(d, den);
    for (mpfr_prec_t prec = 128;; prec *= 2) {
        Mpfr r(prec);
        bool exact = mpfr_div(r.x, n.x, d.x, MPFR_RNDN) == 0;
        if (take_sqrt) {
            if (mpfr_sgn(r.x) < 0) throw Distance_error("negative squared distance");
            exact = (mpfr_sqrt(r.x, r.x, MPFR_RNDN) == 0) && exact;
        }
        if (exact || mpfr_can_round(r.x, prec - 2, MPFR_RNDN, MPFR_RNDZ, 54))
            return mpfr_get_d(r.x, MPFR_RNDN);
        if (prec > (mpfr_prec_t(1) << 24)) throw Distance_error("cannot round the exact distance");
    }
}

std::vector<Point> to_points(const double *xyz, size_t n) {
    std::vector<Point> pts;
    pts.reserve(n);
    for (size_t i = 0; i < n; ++i)
        pts.emplace_back(ET(xyz[3 * i]), ET(xyz[3 * i + 1]), ET(xyz[3 * i + 2]), ET(1));
    return pts;
}

// Realizing point from homogeneous coordinates (x, y, z, w).
void realizing_point(Polytope_distance::Coordinate_iterator c, double *out) {
    const ET &w = c[3];
    for (int j = 0; j < 3; ++j) out[j] = round_quotient(c[j], w, false);
}

} // namespace

extern "C" pxcd_status pxcd_exact_distance(const double *p_xyz, size_t np, const double *q_xyz, size_t nq,
                                           double *distance, double *squared_distance, int *is_zero,
                                           double *realizing_p, double *realizing_q, char *msg,
                                           size_t msg_len) {
    if (np == 0 || nq == 0 || p_xyz == nullptr || q_xyz == nullptr) {
        set_msg(msg, msg_len, "pxcd_exact_distance: both point sets must be non-empty");
        return PXCD_ERROR;
    }
    // CGAL's QP solver indexes variables with int.
    if (np > 100000000 || nq > 100000000) {
        set_msg(msg, msg_len, "pxcd_exact_distance: too many points");
        return PXCD_ERROR;
    }
    try {
        const std::vector<Point> p = to_points(p_xyz, np);
        const std::vector<Point> q = to_points(q_xyz, nq);
        const Polytope_distance pd(p.begin(), p.end(), q.begin(), q.end());

        if (!pd.is_valid()) throw Distance_error("CGAL's result failed its exact validity check");

        const ET num = pd.squared_distance_numerator();
        const ET den = pd.squared_distance_denominator();
        const bool zero = pd.is_zero();
        double d2 = 0.0, d = 0.0;
        if (!zero) {
            d2 = round_quotient(num, den, false);
            d = round_quotient(num, den, true);
        }
        double rp[3], rq[3];
        if (realizing_p != nullptr) realizing_point(pd.realizing_point_p_coordinates_begin(), rp);
        if (realizing_q != nullptr) realizing_point(pd.realizing_point_q_coordinates_begin(), rq);

        // Write outputs only once everything succeeded.
        if (distance != nullptr) *distance = d;
        if (squared_distance != nullptr) *squared_distance = d2;
        if (is_zero != nullptr) *is_zero = zero ? 1 : 0;
        if (realizing_p != nullptr) std::copy(rp, rp + 3, realizing_p);
        if (realizing_q != nullptr) std::copy(rq, rq + 3, realizing_q);
        return PXCD_OK;
    } catch (const std::bad_alloc &) { // out of memory is told by the type, never by the text
        set_msg(msg, msg_len, "pxcd_exact_distance: out of memory");
        return PXCD_OUT_OF_MEMORY;
    } catch (const CGAL::Failure_exception &e) {
        char buf[512];
        std::snprintf(buf, sizeof buf, "pxcd_exact_distance: CGAL failure: %s", e.what());
        set_msg(msg, msg_len, buf);
    } catch (const std::exception &e) {
        char buf[512];
        std::snprintf(buf, sizeof buf, "pxcd_exact_distance: %s", e.what());
        set_msg(msg, msg_len, buf);
    } catch (...) {
        set_msg(msg, msg_len, "pxcd_exact_distance: unknown exception");
    }
    return PXCD_ERROR;
}
