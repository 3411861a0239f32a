/* Support (extreme vertex) queries: a cube-map direction table plus hill
 * climbing over the vertex graph.
 *
 * Sources: hill climbing on the 1-skeleton (Cameron, "Enhancing GJK", ICRA
 * 1997; any local maximum of d.x over a convex polytope's vertex graph is
 * global); the cube-map table follows the idea of PhysX's precomputed
 * "Gauss map" (REFERENCES §3): 6 faces x res x res cells, each storing the
 * vertex extreme along the cell's centre direction. A query looks up its cell
 * and climbs the few remaining steps, so its cost does not grow with the
 * number of vertices as long as a cell covers a bounded number of them.
 * Why not a Dobkin-Kirkpatrick hierarchy: see docs/lin-canny.md.
 */
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "core/core.h"
#include "math/vec3.h"

/* Greedy steepest ascent with strict improvement: terminates (d.x strictly
 * grows, so no vertex repeats) and stops at once on NaN directions. */
static uint32_t climb(const px_convex *c, px_vec3 d, uint32_t v) {
    double best = pxi_dot(c->v[v], d);
    for (;;) {
        uint32_t next = v;
        for (uint32_t k = c->v_first[v]; k < c->v_first[v + 1]; ++k) {
            uint32_t w = c->v_adj[k];
            double s = pxi_dot(c->v[w], d);
            if (s > best) {
                best = s;
                next = w;
            }
        }
        if (next == v) return v;
        v = next;
    }
}

/* Cell of a direction: the cube face is the axis of largest |component| and
 * its sign; the other two components divided by it give cell coordinates. */
static uint32_t cell_of(uint32_t res, px_vec3 d) {
    double ax = fabs(d.x), ay = fabs(d.y), az = fabs(d.z);
    uint32_t face;
    double a, b, m;
    if (ax >= ay && ax >= az) {
        face = d.x >= 0 ? 0 : 1;
        m = ax;
        a = d.y;
        b = d.z;
    } else if (ay >= az) {
        face = d.y >= 0 ? 2 : 3;
        m = ay;
        a = d.z;
        b = d.x;
    } else {
        face = d.z >= 0 ? 4 : 5;
        m = az;
        a = d.x;
        b = d.y;
    }
    if (!(m > 0)) return 0; /* zero or NaN direction: any cell will do */
    double h = 0.5 * res, k = h / m;
    double fa = a * k + h, fb = b * k + h;
    uint32_t ia = fa <= 0 ? 0 : fa >= res ? res - 1 : (uint32_t)fa;
    uint32_t ib = fb <= 0 ? 0 : fb >= res ? res - 1 : (uint32_t)fb;
    return (face * res + ia) * res + ib;
}

static px_vec3 cell_direction(uint32_t res, uint32_t face, uint32_t ia, uint32_t ib) {
    double a = (ia + 0.5) / res * 2.0 - 1.0, b = (ib + 0.5) / res * 2.0 - 1.0;
    double s = (face & 1) ? -1.0 : 1.0;
    switch (face >> 1) {
    case 0: return pxi_v(s, a, b);
    case 1: return pxi_v(b, s, a);
    default: return pxi_v(a, b, s);
    }
}

uint32_t pxi_lut_lookup(const px_convex *c, px_vec3 d) {
    if (!c->lut.cell) return 0;
    return c->lut.cell[cell_of(c->lut.res, pxi_rot(c->lut.map, d))];
}

/* Principal axes of the vertex cloud (Jacobi rotations on its covariance;
 * 3x3 symmetric, converges in a few sweeps) and the widths along them:
 * the lookup map diag(w) Q^T and its inverse Q diag(1/w) for the build. */
static void lut_map(const px_convex *c, double map[9], double inv[9]) {
    /* Three vertices or fewer (a triangle, a segment, a point: the model
     * queries build one per triangle leaf met with a convex leaf): any
     * start climbs to the answer at once, so the table needs no spreading
     * and the cells are indexed by d itself (the rotations below cost more
     * than the rest of such a polytope's construction). */
    if (c->nv <= 3) {
        for (int k = 0; k < 9; ++k) map[k] = inv[k] = k % 4 == 0 ? 1.0 : 0.0;
        return;
    }
    double a[3][3] = {{0}}, q[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    /* Second moments are squares of coordinates: formed at unit scale (a
     * power of two) outside the safe range, where they would overflow or
     * underflow (the axes do not depend on the scale). */
    int e = pxi_len_ok(c->radius) || !(c->radius > 0.0) || !isfinite(c->radius) ? 0 : -ilogb(c->radius);
    for (uint32_t i = 0; i < c->nv; ++i) {
        px_vec3 p = pxi_ldexp3(pxi_sub(c->v[i], c->center), e);
        double x[3] = {p.x, p.y, p.z};
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) a[r][k] += x[r] * x[k];
    }
    for (int sweep = 0; sweep < 16; ++sweep)
        for (int r = 0; r < 2; ++r)
            for (int k = r + 1; k < 3; ++k) {
                if (!(fabs(a[r][k]) > 1e-300)) continue;
                double th = 0.5 * atan2(2.0 * a[r][k], a[k][k] - a[r][r]);
                double cs = cos(th), sn = sin(th);
                for (int j = 0; j < 3; ++j) { /* A <- A J */
                    double ar = a[j][r], ak = a[j][k];
                    a[j][r] = cs * ar - sn * ak;
                    a[j][k] = sn * ar + cs * ak;
                }
                for (int j = 0; j < 3; ++j) { /* A <- J^T A */
                    double ar = a[r][j], ak = a[k][j];
                    a[r][j] = cs * ar - sn * ak;
                    a[k][j] = sn * ar + cs * ak;
                }
                for (int j = 0; j < 3; ++j) { /* Q <- Q J */
                    double qr = q[j][r], qk = q[j][k];
                    q[j][r] = cs * qr - sn * qk;
                    q[j][k] = sn * qr + cs * qk;
                }
            }
    double w[3], wmax = 0.0;
    for (int k = 0; k < 3; ++k) {
        px_vec3 axis = pxi_v(q[0][k], q[1][k], q[2][k]);
        double lo = INFINITY, hi = -INFINITY;
        for (uint32_t i = 0; i < c->nv; ++i) {
            double t = pxi_dot(axis, c->v[i]);
            if (t < lo) lo = t;
            if (t > hi) hi = t;
        }
        w[k] = hi - lo;
        if (w[k] > wmax) wmax = w[k];
    }
    for (int k = 0; k < 3; ++k) {
        w[k] = wmax > 0.0 && w[k] > 1e-3 * wmax ? w[k] / wmax : 1e-3; /* NaN-safe, bounded ratio */
        if (!(wmax > 0.0) || !isfinite(w[k])) w[k] = 1.0;
    }
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) {
            map[3 * r + k] = w[r] * q[k][r]; /* diag(w) Q^T */
            inv[3 * r + k] = q[r][k] / w[k]; /* Q diag(1/w) */
        }
}

uint32_t pxi_support(const px_convex *c, px_vec3 d, uint32_t start) {
    /* The climb compares v . d. Callers pass unit-scale directions and raw
     * ones (centre differences, as large as the bodies): for bodies below
     * 1e-154 or above 1e154 the products of raw ones would underflow to 0 or
     * overflow to inf, every vertex tie and the climb stop where it started.
     * A power of two changes no comparison otherwise, so d is brought to
     * max-abs [1, 2) when it is far from unit size. */
    double m = pxi_max_abs(d);
    if (!(m >= 0x1p-16 && m <= 0x1p16) && m > 0.0 && isfinite(m)) d = pxi_ldexp3(d, -ilogb(m));
    if (start >= c->nv) start = pxi_lut_lookup(c, d);
    return climb(c, d, start);
}

px_status pxi_lut_build(px_convex *c, uint32_t res) {
    c->lut.res = 0;
    c->lut.cell = NULL;
    if (res == 0) return PX_OK;
    size_t n = 6 * (size_t)res * res;
    uint32_t *cell = pxi_alloc_array(&c->alloc, n, sizeof *cell);
    if (!cell) return PX_ERR_OUT_OF_MEMORY;
    c->bytes += n * sizeof *cell;
    /* Neighbouring cells have neighbouring answers: start each climb from
     * the previous cell's vertex (boustrophedon order keeps them adjacent). */
    double inv[9];
    lut_map(c, c->lut.map, inv);
    uint32_t v = 0;
    for (uint32_t face = 0; face < 6; ++face)
        for (uint32_t ia = 0; ia < res; ++ia)
            for (uint32_t j = 0; j < res; ++j) {
                uint32_t ib = (ia & 1) ? res - 1 - j : j;
                v = climb(c, pxi_rot(inv, cell_direction(res, face, ia, ib)), v);
                cell[(face * res + ia) * res + ib] = v;
            }
    c->lut.res = res;
    c->lut.cell = cell;
    return PX_OK;
}

void pxi_lut_destroy(px_convex *c) {
    if (c->lut.cell)
        pxi_free(&c->alloc, c->lut.cell, 6 * (size_t)c->lut.res * c->lut.res * sizeof *c->lut.cell);
    c->lut.cell = NULL;
}
